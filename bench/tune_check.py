#!/usr/bin/python3
"""weft tune against an exhaustive sweep of the same knobs: tunes the Gaffer
smoke (data/smoke_small.vdb) for a target, renders the printed command line
again and measures it against the same reference, then sweeps each
technique's whole knob grid and reports the fastest point that meets the
target. Prints the tuned time against that best point, side by side.

    bench/tune_check.py [--target rmse=0.01] [--res 128x128] [--threads 2] [--out DIR]
"""
import argparse
import csv
import glob
import json
import os
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, rmse, run_timed  # noqa: E402

SCENE = os.path.join(ROOT, "data", "smoke_small.vdb")


def knobs_of(technique):
    """The knob grid `weft help` prints: [(key, [values])]."""
    out = subprocess.run([WEFT, "help", technique], capture_output=True, text=True, check=True).stdout
    line = [l for l in out.splitlines() if l.startswith("speed/accuracy knobs")][0]
    knobs = []
    for part in line.split(": ", 1)[1].split("; "):
        key, values = part.split(" ", 1)
        knobs.append((key, values.split(",")))
    return knobs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--target", default="rmse=0.01")
    ap.add_argument("--res", default="128x128")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="weft-tune-check-")
    os.makedirs(out, exist_ok=True)
    cache = os.path.join(out, "refs")
    common = ["--res", args.res, "--threads", args.threads]
    metric, value = args.target.split("=")
    choice_json = os.path.join(out, "choice.json")
    tune_s, printed = run_timed([WEFT, "tune", SCENE, "--target", args.target, "--cache", cache, "--json", choice_json] + common)
    with open(choice_json) as f:
        choice = json.load(f)
    if not choice["met"]:
        sys.exit("tune_check: no setting met %s\n%s" % (args.target, printed))
    refs = glob.glob(os.path.join(cache, "*.exr"))
    again = os.path.join(out, "again.exr")
    cmd = shlex.split(choice["choice"]["command"])[1:]
    cmd[cmd.index("-o") + 1] = again
    run_timed([WEFT] + cmd + ["--threads", args.threads])
    again_rmse = rmse(again, refs[0]) if metric == "rmse" else float("nan")
    best = None
    for t in choice["techniques"]:
        sweep = [WEFT, "sweep", SCENE, "--technique", t["technique"]]
        for key, values in knobs_of(t["technique"]):
            sweep += ["--vary", "%s=%s" % (key, ",".join(values))]
        d = os.path.join(out, "sweep-" + t["technique"])
        os.makedirs(d, exist_ok=True)
        run_timed(sweep + ["--reference", refs[0], "--no-plot", "-o", d] + common)  # the family's one reference
        for r in csv.DictReader(open(os.path.join(d, "sweep.csv"))):
            if float(r[metric]) <= float(value) and (best is None or float(r["median_ms"]) < best[0]):
                best = (float(r["median_ms"]), t["technique"], r)
    c = choice["choice"]
    print("weft tune %s on %s at %s (%s threads), %.1f s of tuning" % (args.target, os.path.basename(SCENE), args.res,
                                                                       args.threads, tune_s))
    print("  tuned:      %s  %.1f ms  %s %.5g" % (c["command"], c["time_ms"], metric, c["error"][metric]))
    print("  re-render:  %s %.5g against the same reference (meets: %s)" % (metric, again_rmse, again_rmse <= float(value)))
    if best:
        print("  exhaustive: best on the grid %s  %.1f ms; tuned/best time %.2f (target <= 1.10)" %
              (best[1], best[0], c["time_ms"] / best[0]))


if __name__ == "__main__":
    main()
