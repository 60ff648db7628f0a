"""What the benchmark scripts share: where weft is, running a command (a
failure ends the benchmark with its output), image RMSE through `weft diff`,
the aneurism converted to a VDB once, and the headline rows that `make bench`
gathers into one table (bench/headlines.py)."""
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WEFT = os.path.join(ROOT, "build", "bin", "weft")


def run_timed(args):
    """(seconds, stdout) of one run of args."""
    start = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit("bench: command failed: %s\n%s%s" % (" ".join(args), proc.stdout, proc.stderr.strip()))
    return elapsed, proc.stdout


def run(args):
    return run_timed(args)[1]


def diff_all(a, b):
    """The "all" row of `weft diff a b`: RMSE, relMSE, PSNR, SSIM, max abs."""
    for line in run([WEFT, "diff", a, b]).splitlines():
        if line.startswith("all "):
            return [float(v) for v in line.split()[1:]]
    return [float("nan")] * 5


def rmse(a, b):
    return diff_all(a, b)[0]


def headline(what, measured, target, holds):
    """One row of `make bench`'s headline table: a ratio or figure this bench
    measured side by side, its target and whether it holds. Appended as a JSON
    line to the file $WEFT_BENCH_HEADLINES names (bench/run.sh sets it); a
    bench run on its own just prints the row."""
    row = {"bench": os.path.basename(sys.argv[0]), "what": what, "measured": measured, "target": target,
           "holds": bool(holds)}
    print("headline: %s: %s (target %s: %s)" % (what, measured, target, "holds" if holds else "missed"))
    path = os.environ.get("WEFT_BENCH_HEADLINES")
    if path:
        with open(path, "a") as f:
            f.write(json.dumps(row) + "\n")


def prepare_aneurism(data, out):
    vdb = os.path.join(out, "aneurism.vdb")
    if not os.path.exists(vdb):
        run([WEFT, "convert", os.path.join(data, "aneurism.raw.gz"), "--dims", "256,256,256", "--type", "u8", "-o", vdb])
    return vdb


def write_mesh_scenes(data, out):
    """Scene files of the Cornell box, the glossy box and the bunny in the box."""
    cornell = os.path.join(ROOT, "data", "cornell", "CornellBox-Original.obj")
    camera = {"eye": [0, 1, 3.6], "target": [0, 1, 0], "up": [0, 1, 0], "fov": 40}
    scenes = {
        "cornell": {"camera": camera, "meshes": [{"file": cornell}]},
        "glossy": {"camera": camera, "meshes": [{"file": os.path.join(data, "cornell", "CornellBox-Glossy.obj")}]},
        "bunny": {"camera": camera, "meshes": [
            {"file": cornell},
            {"file": os.path.join(data, "bunny.ply"), "scale": 4, "translate": [0.358, 0.468, 0.37]}]},
    }
    paths = {}
    for name, scene in scenes.items():
        paths[name] = os.path.join(out, name + ".json")
        with open(paths[name], "w") as f:
            json.dump(scene, f, indent=1)
    return paths
