#!/usr/bin/python3
"""What a sweep costs beyond its renders: a 20-point `weft sweep` of a short
render (about 0.06 s on 2 threads; 0.2 s when the bench was written, before
raymarch skipped empty space), timed as one process, against the sum of its
renders' own times (sweep.csv's median_ms) and against the same 20 settings
rendered by 20 `weft render` processes. Prints the ratios side by side.
What a sweep adds per run is the error against the reference (RMSE, SSIM,
FLIP on 384x384 pixels) and, once, the process start and the reference read.

    bench/sweep_overhead.py [--out DIR] [--threads N]
"""
import argparse
import csv
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, headline, run_timed  # noqa: E402

SCENE = os.path.join(ROOT, "data", "smoke_small.vdb")
STEPS = ["0.3", "0.35", "0.4", "0.45", "0.5", "0.6", "0.7", "0.8", "0.9", "1"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=None)
    ap.add_argument("--threads", default="2")
    ap.add_argument("--res", default="384x384")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="weft-sweep-bench-")
    common = ["--res", args.res, "--threads", args.threads]
    ref = os.path.join(out, "ref.exr")
    run_timed([WEFT, "render", SCENE, "--set", "step=0.1", "-o", ref] + common)
    sweep_dir = os.path.join(out, "sweep")
    sweep_s, _ = run_timed([WEFT, "sweep", SCENE, "--technique", "volume.raymarch", "--vary", "step=" + ",".join(STEPS),
                            "--vary", "jitter=false,true", "--reference", ref, "--no-plot", "-o", sweep_dir] + common)
    with open(os.path.join(sweep_dir, "sweep.csv")) as f:
        rows = list(csv.DictReader(f))
    renders_s = sum(float(r["median_ms"]) for r in rows) / 1000
    separate_s = 0.0
    for r in rows:
        s, _ = run_timed([WEFT, "render", SCENE, "--set", "step=" + r["step"], "--set", "jitter=" + r["jitter"],
                          "-o", os.path.join(out, "one.exr")] + common)
        separate_s += s
    print("sweep of %d renders of %s at %s (%s threads)" % (len(rows), os.path.basename(SCENE), args.res, args.threads))
    print("  mean render                    %8.3f s" % (renders_s / len(rows)))
    print("  sum of the renders' own times  %8.3f s" % renders_s)
    print("  weft sweep, one process        %8.3f s   %.2fx the renders (target <= 1.3x)" % (sweep_s, sweep_s / renders_s))
    print("  %d weft render processes       %8.3f s   %.2fx the renders" % (len(rows), separate_s, separate_s / renders_s))
    headline("weft sweep of %d renders of ~%.2f s against the sum of its renders" % (len(rows), renders_s / len(rows)),
             "%.2fx (%d processes: %.2fx)" % (sweep_s / renders_s, len(rows), separate_s / renders_s), "<= 1.3x",
             sweep_s / renders_s <= 1.3)


if __name__ == "__main__":
    main()
