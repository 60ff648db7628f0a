#!/usr/bin/python3
"""The trade atlas (`make trade`): `weft sweep` over every technique's
speed/accuracy knobs (the grids `weft help NAME` lists) on the shipped
scenes, each technique measured against its family's converged reference
(--reference auto). Writes docs/trade/<scene>/ (sweep.csv, sweep.md,
sweep.png) and docs/trade/README.md: per scene and reference family, the
cheapest technique and setting whose RMSE is at most 0.01, 0.003 and 1/255.

    /usr/bin/python3 bench/trade_atlas.py [--scenes all|smoke,aneurism,...] [--res 128x128] [--threads 2] [--out docs/trade]

Scenes: smoke (data/smoke_small.vdb), aneurism (../shared/data, converted
once), cornell (scenes/cornell.json), bunny (../shared/data), and the
combined scenes of scenes/combined/. A scene whose data is missing is
skipped with a line saying so.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, prepare_aneurism, run_timed, write_mesh_scenes  # noqa: E402

THRESHOLDS = [("0.01", 0.01), ("0.003", 0.003), ("1/255", 1 / 255)]
VOLUME_TECHNIQUES = ["volume.raymarch", "volume.preint", "volume.adaptive3d", "volume.singlescatter"]
MESH_TECHNIQUES = ["mesh.pathtrace", "lighting.vpl_deferred", "lighting.adaptive_indirect"]


def knobs_of(technique):
    out = subprocess.run([WEFT, "help", technique], capture_output=True, text=True, check=True).stdout
    line = [l for l in out.splitlines() if l.startswith("speed/accuracy knobs")][0]
    return [part.split(" ", 1) for part in line.split(": ", 1)[1].split("; ")]


def family_of(technique):
    out = subprocess.run([WEFT, "help", technique], capture_output=True, text=True, check=True).stdout
    line = [l for l in out.splitlines() if l.startswith("converged reference")][0]
    return line.split(": ", 1)[1].split(" ")[0]


def scenes(data, work):
    found = {"smoke": (os.path.join(ROOT, "data", "smoke_small.vdb"), VOLUME_TECHNIQUES),
             "cornell": (os.path.join(ROOT, "scenes", "cornell.json"), MESH_TECHNIQUES)}
    if data and os.path.exists(os.path.join(data, "aneurism.raw.gz")):
        prepare_aneurism(data, work)
        with open(os.path.join(ROOT, "scenes", "aneurism.json")) as f:
            text = f.read()
        scene = os.path.join(work, "aneurism.json")
        with open(scene, "w") as f:
            f.write(text)
        found["aneurism"] = (scene, VOLUME_TECHNIQUES)
    if data and os.path.exists(os.path.join(data, "bunny.ply")):
        found["bunny"] = (write_mesh_scenes(data, work)["bunny"], MESH_TECHNIQUES)
    for name in sorted(os.listdir(os.path.join(ROOT, "scenes", "combined"))):
        found[name[:-5]] = (os.path.join(ROOT, "scenes", "combined", name), VOLUME_TECHNIQUES + MESH_TECHNIQUES)
    return found


def sweep(scene, techniques, out, res, threads):
    args = [WEFT, "sweep", scene, "--res", res, "--threads", threads, "--reference", "auto", "-o", out]
    for t in techniques:
        args += ["--technique", t] + sum((["--vary", "%s=%s" % (k, v)] for k, v in knobs_of(t)), [])
    seconds, _ = run_timed(args)
    shutil.rmtree(os.path.join(out, "references"), ignore_errors=True)  # rendered EXRs stay out of docs/
    for name in ("sweep.md", "sweep.json", "sweep.csv"):  # paths as a clone of the project names them
        path = os.path.join(out, name)
        with open(path) as f:
            text = f.read().replace(ROOT + os.sep, "").replace(os.path.dirname(scene) + os.sep, "")
        with open(path, "w") as f:
            f.write(text)
    with open(os.path.join(out, "sweep.csv")) as f:
        return seconds, list(csv.DictReader(f))


def cheapest(rows, technique_family, family, limit):
    # A refused run (a mesh technique on a scene without meshes) has no RMSE.
    ok = [r for r in rows if technique_family[r["technique"]] == family and r["rmse"] and float(r["rmse"]) <= limit]
    return min(ok, key=lambda r: float(r["median_ms"])) if ok else None


def label(row, keys):
    return " ".join("%s=%s" % (k, row[k]) for k in keys if row.get(k))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", default="all", help="comma-separated names, or all")
    ap.add_argument("--res", default="128x128")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--techniques", default=None, help="comma-separated: only these of each scene's techniques")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "trade"))
    ap.add_argument("--data", default=os.path.join(os.path.dirname(ROOT), "shared", "data"))
    ap.add_argument("--summarize", action="store_true",
                    help="rebuild cheapest.md and README.md from the sweep.csv files already there, rendering nothing")
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="weft-trade-")  # the converted aneurism and scene files
    available = scenes(args.data if os.path.isdir(args.data) else None, work)
    command = "/usr/bin/python3 bench/trade_atlas.py " + " ".join(a for a in sys.argv[1:] if a != "--summarize")
    for name in (list(available) if args.scenes == "all" else args.scenes.split(",")):
        if name not in available:
            print("trade: %s skipped (its data is not here)" % name)
            continue
        scene, techniques = available[name]
        if args.techniques:
            techniques = [t for t in techniques if t in args.techniques.split(",")]
        out = os.path.join(args.out, name)
        os.makedirs(out, exist_ok=True)
        if args.summarize:
            if not os.path.exists(os.path.join(out, "sweep.csv")):
                continue
            with open(os.path.join(out, "sweep.csv")) as f:
                rows = list(csv.DictReader(f))
            techniques = [t for t in techniques if any(r["technique"] == t for r in rows)]
        else:
            seconds, rows = sweep(scene, techniques, out, args.res, args.threads)
            print("trade: %s: %d runs in %.0f s -> %s" % (name, len(rows), seconds, out))
        families = {t: family_of(t) for t in techniques}
        keys = [k for k in rows[0].keys() if k not in ("run", "technique", "params") and not k.startswith("counters.")
                and k not in ("median_ms", "min_ms", "max_ms", "samples", "rmse", "relmse", "psnr", "ssim", "maxabs",
                              "flip", "front_time", "front_samples")]
        lines = ["<!-- %s: %s at %s, %s thread(s) -->" % (name, command, args.res, args.threads)]
        for family in dict.fromkeys(families.values()):
            for text, limit in THRESHOLDS:
                r = cheapest(rows, families, family, limit)
                lines.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                    name, family, text, r["technique"] if r else "none", label(r, keys) if r else "",
                    "%.3g" % (float(r["median_ms"]) / 1000) if r else "", "%.3g" % float(r["rmse"]) if r else ""))
        with open(os.path.join(out, "cheapest.md"), "w") as f:
            f.write("\n".join(lines) + "\n")
    write_index(args.out)


def write_index(folder):
    """docs/trade/README.md: every scene folder's cheapest settings, with the command that made them."""
    lines = ["# Trade atlas", "", "Each scene's folder holds the whole sweep (sweep.md, sweep.csv) and its Pareto plot "
             "(sweep.png): each technique's knob grid (`weft help NAME`) swept with `weft sweep --reference auto`. "
             "Below, per scene and reference family, the cheapest setting whose RMSE meets each threshold (median "
             "render time on the machine that ran it; the command is in the scene's `cheapest.md`).", "",
             "| scene | family (reference) | RMSE <= | technique | setting | time (s) | RMSE |", "|---|---|---|---|---|---:|---:|"]
    commands = []
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "cheapest.md")
        if os.path.exists(path):
            with open(path) as f:
                text = f.read().splitlines()
            commands.append("- %s" % text[0][5:-4])
            lines += text[1:]
    with open(os.path.join(folder, "README.md"), "w") as f:
        f.write("\n".join(lines + ["", "Commands:", ""] + commands) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
