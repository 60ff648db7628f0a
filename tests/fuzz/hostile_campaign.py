#!/usr/bin/env python3
"""A campaign of hostile but realistic input against the weft executable.

Every run works in a folder of its own holding copies of the inputs it uses;
after the run, the campaign checks what a user would: the exit (a signal is
a crash), the time (past --hang seconds is a hang; a refusal past 2 s is
slow), the message (one line, in weft's words: no library's sentence), the
inputs (every file the run was given is unchanged: nothing lost), and the
outputs (a failed run leaves no file at an output name).

  /usr/bin/python3 tests/fuzz/hostile_campaign.py --runs 4000 [--seed 1] [--jobs 2]

Prints a table by input kind and writes the failing runs' commands to
hostile-failures.txt (none: an empty file). Exit 1 when any run crashed,
hung or lost a file.
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import random
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WEFT = os.path.join(ROOT, "build", "bin", "weft")
DATA = os.path.join(ROOT, "data")

# Sentences of the libraries under weft: a message holding one is not in weft's words.
LIBRARY_TEXT = ["json.exception", "while parsing", "last read:", "ArithmeticError", "IoError", "RuntimeError:", "ValueError:",
                "KeyError", "Use default material", "Iex::", "Imf::", "basic_string", "std::", "what():", "terminate called",
                "Assertion", "assimp", "Assimp", "embree", "TBB"]
EXTREMES = ["0", "-0", "1e-300", "1e-45", "5e-324", "1e300", "-1e300", "1e19", "-1", "4294967297", "9007199254740993",
            "nan", "inf", "-inf", "", "1,5", "0x10"]


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def flip_bytes(data, rng, count):
    b = bytearray(data)
    for _ in range(count):
        if not b:
            break
        b[rng.randrange(len(b))] = rng.randrange(256)
    return bytes(b)


def mutate_text(text, rng):
    choice = rng.randrange(6)
    if choice == 0 and text:  # drop a span
        i = rng.randrange(len(text))
        return text[:i] + text[i + rng.randrange(1, 20):]
    if choice == 1:  # a number becomes an extreme
        tokens = text.split(" ")
        idx = [i for i, t in enumerate(tokens) if any(c.isdigit() for c in t)]
        if idx:
            i = rng.choice(idx)
            tokens[i] = rng.choice(EXTREMES) + ("," if tokens[i].endswith(",") else "")
        return " ".join(tokens)
    if choice == 2:
        return flip_bytes(text.encode(), rng, rng.randrange(1, 4)).decode("latin-1")
    if choice == 3 and text:  # duplicate a span
        i = rng.randrange(len(text))
        return text[:i] + text[i:i + 30] * rng.randrange(1, 4) + text[i:]
    if choice == 4:
        return text[: rng.randrange(len(text) + 1)]  # cut short
    return text.replace("[", "[" * rng.randrange(1, 400), 1)


SCENES = [
    {"volumes": [{"file": "smoke_small.vdb"}], "render": {"technique": "volume.raymarch", "resolution": [24, 24]}},
    {"volumes": [{"procedural": "cloud", "resolution": 16, "translate": [0.5, 0, 0], "scale": 2}],
     "lights": [{"type": "point", "position": [1, 2, 3], "intensity": 2}],
     "render": {"technique": "volume.singlescatter", "resolution": [24, 24]}},
    {"camera": {"eye": [0, 1, 3.6], "target": [0, 1, 0], "up": [0, 1, 0], "fov": 40},
     "meshes": [{"file": "cornell/CornellBox-Original.obj"}], "render": {"technique": "mesh.pathtrace", "resolution": [16, 16]}},
    {"volumes": [{"procedural": "sphere", "resolution": 16}], "meshes": [{"file": "shapes/ground.obj", "translate": [0, -1, 0]}],
     "render": {"technique": "volume.preint", "resolution": [16, 16]}},
]
TECHNIQUES = ["volume.raymarch", "volume.singlescatter", "volume.preint", "volume.adaptive3d", "mesh.pathtrace"]


def copy_data(run_dir):
    for name in ("smoke_small.vdb",):
        shutil.copy(os.path.join(DATA, name), run_dir)
    shutil.copytree(os.path.join(DATA, "cornell"), os.path.join(run_dir, "cornell"))
    shutil.copytree(os.path.join(DATA, "shapes"), os.path.join(run_dir, "shapes"))


def ply_text(rng):
    verts = [[rng.uniform(-1, 1) for _ in range(3)] for _ in range(4)]
    head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n" \
           "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    body = "".join("%g %g %g\n" % tuple(v) for v in verts) + "3 0 1 2\n3 0 2 3\n"
    return head + body


# Each case writes its inputs into `d` and returns (kind, argv after weft, outputs it names).
def case_scene(d, rng):
    copy_data(d)
    text = json.dumps(rng.choice(SCENES), indent=1)
    for _ in range(rng.randrange(1, 3)):
        text = mutate_text(text, rng)
    with open(os.path.join(d, "scene.json"), "w", encoding="latin-1", errors="replace") as f:
        f.write(text)
    return "scene json", ["render", "scene.json", "-o", "out.exr", "--stats", "out.json", "--threads", "2"], ["out.exr", "out.json"]


def case_vdb(d, rng):
    data = open(os.path.join(DATA, "smoke_small.vdb"), "rb").read()
    if rng.random() < 0.2:
        data = data[: rng.randrange(len(data))]
    else:
        data = flip_bytes(data, rng, rng.randrange(1, 5)) if rng.random() < 0.5 else \
            (lambda i: data[:i] + bytes([rng.randrange(256)]) + data[i + 1:])(rng.randrange(min(len(data), 4096)))
    open(os.path.join(d, "x.vdb"), "wb").write(data)
    tech = rng.choice(TECHNIQUES[:4])
    return "vdb", ["render", "x.vdb", "--technique", tech, "--res", "32x32", "-o", "out.exr", "--threads", rng.choice(["1", "2"])], ["out.exr"]


def case_obj(d, rng):
    copy_data(d)
    obj = os.path.join(d, "cornell", "CornellBox-Original.obj")
    mtl = os.path.join(d, "cornell", "CornellBox-Original.mtl")
    target = obj if rng.random() < 0.6 else mtl
    text = open(target, encoding="latin-1").read()
    for _ in range(rng.randrange(1, 3)):
        text = mutate_text(text, rng)
    open(target, "w", encoding="latin-1").write(text)
    return "obj/mtl", ["render", "cornell/CornellBox-Original.obj", "--res", "16x16", "-o", "out.exr", "--technique",
                       rng.choice(["mesh.pathtrace", "lighting.vpl_deferred", "lighting.adaptive_indirect"])], ["out.exr"]


def case_ply(d, rng):
    text = ply_text(rng)
    for _ in range(rng.randrange(1, 3)):
        text = mutate_text(text, rng)
    open(os.path.join(d, "x.ply"), "w", encoding="latin-1").write(text)
    return "ply", ["render", "x.ply", "--res", "16x16", "-o", "out.exr"], ["out.exr"]


def case_exr(d, rng, good_exr):
    data = open(good_exr, "rb").read()
    data = flip_bytes(data, rng, rng.randrange(1, 6)) if rng.random() < 0.7 else data[: rng.randrange(len(data))]
    open(os.path.join(d, "in.exr"), "wb").write(data)
    shutil.copy(good_exr, os.path.join(d, "ref.exr"))
    cmd = rng.choice([["diff", "in.exr", "ref.exr"], ["filter", "atrous", "in.exr", "-o", "out.exr"], ["check", "in.exr"],
                      ["merge", "in.exr", "ref.exr", "-o", "out.exr"]])
    return "exr", cmd, ["out.exr"]


def case_convert(d, rng):
    dims = [rng.randrange(1, 9) for _ in range(3)]
    raw = bytes(rng.randrange(256) for _ in range(dims[0] * dims[1] * dims[2]))
    kind = rng.randrange(3)
    if kind == 0:
        open(os.path.join(d, "in.raw"), "wb").write(raw)
        args = ["convert", "in.raw", "--dims", ",".join(map(str, dims)), "--type", "u8"]
        if rng.random() < 0.5:
            args += [rng.choice(["--spacing", "--origin"]), ",".join(rng.choice(EXTREMES + ["1"]) for _ in range(3))]
        if rng.random() < 0.3:
            args[3] = ",".join(rng.choice(EXTREMES + ["2", "100000"]) for _ in range(3))
    elif kind == 1:
        header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: %d %d %d\nspacings: 1 1 1\nencoding: raw\n\n" % tuple(dims)
        text = mutate_text(header, rng).encode("latin-1", "replace")
        open(os.path.join(d, "in.nrrd"), "wb").write(text + raw)
        args = ["convert", "in.nrrd"]
    else:
        header = "{'descr': '|u1', 'fortran_order': False, 'shape': (%d, %d, %d), }" % tuple(dims)
        header = mutate_text(header, rng) if rng.random() < 0.7 else header
        h = header.encode("latin-1", "replace")
        h += b" " * ((64 - (10 + len(h) + 1) % 64) % 64) + b"\n"
        open(os.path.join(d, "in.npy"), "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(h)) + h + raw)
        args = ["convert", "in.npy"]
    if rng.random() < 0.3:  # a previous good output that must survive a failed convert
        open(os.path.join(d, "out.vdb"), "wb").write(open(os.path.join(DATA, "smoke_small.vdb"), "rb").read())
    return "convert", args + ["-o", "out.vdb"], ["out.vdb"]


def case_params(d, rng, params):
    tech = rng.choice(sorted(params))
    name = rng.choice(params[tech])
    copy_data(d)
    source = "smoke_small.vdb" if tech.startswith("volume") or tech.startswith("analytic") else "cornell/CornellBox-Original.obj"
    sets = ["--set", "%s=%s" % (name, rng.choice(EXTREMES + ["100000000", "-100000000"]))]
    return "--set extremes", ["render", source, "--technique", tech, "--res", "16x16", "-o", "out.exr"] + sets, ["out.exr"]


def case_outputs(d, rng):
    copy_data(d)
    json.dump(SCENES[0], open(os.path.join(d, "scene.json"), "w"))
    os.link(os.path.join(d, "smoke_small.vdb"), os.path.join(d, "hard.exr"))
    os.symlink("scene.json", os.path.join(d, "link.json"))
    os.mkfifo(os.path.join(d, "fifo.json"))
    names = ["scene.json", "smoke_small.vdb", "hard.exr", "link.json", "./scene.json", "fifo.json", "x" * 252 + ".exr", "ok.exr"]
    args = ["render", rng.choice(["scene.json", "smoke_small.vdb"]), "--res", "8x8"]
    outs = []
    for flag in rng.sample(["-o", "--stats", "--preview"], rng.randrange(1, 4)):
        name = rng.choice(names)
        if flag == "-o" and not name.endswith(".exr"):
            name += ".exr"
        if flag == "--preview":
            name = rng.choice(["scene.png", "hard.exr", "ok.png"])
        args += [flag, name]
        outs.append(name)
    return "output names", args, outs


def case_special(d, rng):
    copy_data(d)
    os.mkfifo(os.path.join(d, "pipe"))
    which = rng.randrange(4)
    if which == 0:
        open(os.path.join(d, "m.obj"), "w").write("mtllib pipe\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        return "special files", ["render", "m.obj", "--res", "8x8", "-o", "out.exr"], ["out.exr"]
    if which == 1:
        return "special files", ["batch", "pipe"], []
    if which == 2:
        shutil.copy(os.path.join(DATA, "smoke_small.vdb"), os.path.join(d, "a.vdb"))
        return "special files", ["diff", "a.vdb", "a.vdb", "--rule", "pipe"], []
    return "special files", ["render", "pipe", "--res", "8x8", "-o", "out.exr"], ["out.exr"]


def run_one(index, seed, good_exr, params, hang):
    rng = random.Random(seed * 1000003 + index)
    d = tempfile.mkdtemp(prefix="weft-hostile-")
    try:
        makers = [case_scene, case_vdb, case_obj, case_ply, lambda d, r: case_exr(d, r, good_exr), case_convert,
                  lambda d, r: case_params(d, r, params), case_outputs, case_special]
        kind, args, outputs = makers[index % len(makers)](d, rng)
        before = {}
        for base, _, files in os.walk(d):
            for f in files:
                p = os.path.join(base, f)
                if stat.S_ISREG(os.lstat(p).st_mode):
                    before[os.path.relpath(p, d)] = (sha(p), os.path.islink(p))
        kinds = {os.path.relpath(os.path.join(b, f), d): stat.S_IFMT(os.lstat(os.path.join(b, f)).st_mode)
                 for b, _, fs in os.walk(d) for f in fs}
        start = time.monotonic()
        try:
            p = subprocess.run([WEFT] + args, cwd=d, capture_output=True, timeout=hang, stdin=subprocess.DEVNULL)
            code, err = p.returncode, p.stderr.decode("utf-8", "replace")
        except subprocess.TimeoutExpired:
            code, err = None, ""
        seconds = time.monotonic() - start
        result = {"kind": kind, "cmd": "weft " + " ".join(args), "crash": code is not None and code < 0, "hang": code is None,
                  "slow_refusal": code not in (0, None) and seconds > 2, "library_text": any(t in err for t in LIBRARY_TEXT),
                  "lost": False, "partial": False, "err": err.strip()[-300:]}
        # An output replaces the file it names, through a link as cp writes: not a loss.
        named = {os.path.normpath(o) for o in outputs} | {os.path.relpath(os.path.realpath(os.path.join(d, o)), os.path.realpath(d))
                                                          for o in outputs}
        for rel, (digest, _) in before.items():
            p = os.path.join(d, rel)
            written = os.path.normpath(rel) in named
            if written:
                continue
            if not os.path.exists(p) or sha(p) != digest:
                result["lost"] = True
        for rel, mode in kinds.items():  # a special file or link stays what it was
            p = os.path.join(d, rel)
            if not os.path.lexists(p) or stat.S_IFMT(os.lstat(p).st_mode) != mode:
                result["lost"] = True
        if code not in (0, None):
            for o in outputs:
                p = os.path.join(d, o)
                if os.path.normpath(o) not in kinds and os.path.exists(p) and stat.S_ISREG(os.stat(p).st_mode):
                    result["partial"] = True
        return result
    finally:
        shutil.rmtree(d, ignore_errors=True)


def technique_params():
    out = {}
    for tech in TECHNIQUES + ["lighting.vpl_deferred", "lighting.adaptive_indirect", "analytic.2d"]:
        text = subprocess.run([WEFT, "help", tech], capture_output=True, text=True).stdout
        names = [line.split()[0] for line in text.splitlines() if line.startswith("  ") and line.split()]
        if names:
            out[tech] = names
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=4000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--hang", type=float, default=10.0, help="seconds after which a run counts as hung")
    ap.add_argument("--failures", default="hostile-failures.txt")
    a = ap.parse_args()
    if not os.access(WEFT, os.X_OK):
        sys.exit("hostile_campaign: build weft first (bash scripts/build.sh): no " + WEFT)
    work = tempfile.mkdtemp(prefix="weft-hostile-ref-")
    good = os.path.join(work, "good.exr")
    subprocess.run([WEFT, "render", "builtin:cloud", "--res", "16x16", "-o", good], check=True)
    params = technique_params()
    results = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = [pool.submit(run_one, i, a.seed, good, params, a.hang) for i in range(a.runs)]
        for n, f in enumerate(concurrent.futures.as_completed(futures), 1):
            results.append(f.result())
            if n % 500 == 0:
                print("hostile_campaign: %d of %d runs" % (n, a.runs), file=sys.stderr)
    shutil.rmtree(work, ignore_errors=True)
    cols = ["runs", "crash", "hang", "slow_refusal", "library_text", "lost", "partial"]
    kinds = sorted({r["kind"] for r in results})
    print("| input kind | " + " | ".join(cols) + " |")
    print("|---|" + "---:|" * len(cols))
    for k in kinds + ["all"]:
        rs = [r for r in results if k == "all" or r["kind"] == k]
        print("| %s | " % k + " | ".join(str(len(rs) if c == "runs" else sum(r[c] for r in rs)) for c in cols) + " |")
    bad = [r for r in results if any(r[c] for c in cols[1:])]
    with open(a.failures, "w") as f:
        for r in bad:
            f.write("%s\t%s\t%s\n" % (",".join(c for c in cols[1:] if r[c]), r["cmd"], r["err"].replace("\n", " | ")))
    return 1 if any(r["crash"] or r["hang"] or r["lost"] or r["partial"] for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
