#!/usr/bin/python3
"""EXR output: the time to write one render's frame with each compression
and pixel-type choice, on 1 thread and on every core, and the file size,
measured side by side in one run (the `write` timing of --stats).

    /usr/bin/python3 bench/exr_write.py [--res 1024x768] [--repeat 3]

The frame is lighting.vpl_deferred's Cornell box at interleave 8x6: RGBA
and 15 AOV channels, the largest frame a technique writes. The default
compression (core/base/options/exr_options.hpp) is the quickest lossless one on
every core, among those whose file is smaller than uncompressed.
"""
import argparse
import json
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, headline, run  # noqa: E402

LOSSLESS = ["none", "rle", "zips", "zip", "piz"]
LOSSY = ["pxr24", "b44", "b44a", "dwaa", "dwab"]
SCENE = os.path.join(ROOT, "data", "cornell", "CornellBox-Original.obj")


def write_ms(work, res, compression, types, threads, repeat):
    out, stats = os.path.join(work, "o.exr"), os.path.join(work, "s.json")
    times = []
    for _ in range(repeat):
        args = [WEFT, "render", SCENE, "--technique", "lighting.vpl_deferred", "--set", "interleave=8x6", "--res", res,
                "--threads", str(threads), "--compression", compression, "-o", out, "--stats", stats]
        for t in types:
            args += ["-d", t]
        run(args)
        with open(stats) as f:
            times.append(json.load(f)["timings_ms"]["write"])
    return statistics.median(times), os.path.getsize(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", default="1024x768")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    cores = os.cpu_count() or 1
    work = tempfile.mkdtemp(prefix="weft-exr-")
    rows = []
    for types, label in (([], "float"), (["aovs=half"], "AOVs half")):
        for c in LOSSLESS + LOSSY:
            one, size = write_ms(work, args.res, c, types, 1, args.repeat)
            many, _ = write_ms(work, args.res, c, types, cores, args.repeat)
            rows.append((c, label, one, many, size))
    base = [r for r in rows if r[0] == "zip" and r[1] == "float"][0]
    print("EXR write of %s, vpl_deferred Cornell box (19 channels), median of %d; ratios against zip float on 1 thread"
          % (args.res, args.repeat))
    print("| compression | lossless | pixel types | 1 thread (ms) | %d threads (ms) | size (MB) | speed-up 1 / %d threads vs zip |"
          % (cores, cores))
    print("|---|---|---|---:|---:|---:|---:|")
    for c, label, one, many, size in rows:
        print("| %s | %s | %s | %.0f | %.0f | %.2f | %.2fx / %.2fx |" % (
            c, "yes" if c in LOSSLESS else "no", label, one, many, size / 1e6, base[2] / one, base[2] / many))
    none_size = [r for r in rows if r[0] == "none" and r[1] == "float"][0][4]
    lossless = [r for r in rows if r[0] in LOSSLESS and r[1] == "float" and r[4] < none_size]
    best = min(lossless, key=lambda r: r[3])
    print("quickest lossless compression that compresses (float, %d threads): %s, %.0f ms, %.2f MB" % (cores, best[0], best[3], best[4] / 1e6))
    for label, column in (("1 thread", 2), ("%d threads" % cores, 3)):
        quickest = min(lossless, key=lambda r: r[column])
        headline("EXR write, vpl_deferred frame %s, 19 float channels, lossless, %s" % (args.res, label),
                 "%.0f ms (%s, %.1f MB; zip %.0f ms)" % (quickest[column], quickest[0], quickest[4] / 1e6, base[column]),
                 "<= 150 ms", quickest[column] <= 150)


if __name__ == "__main__":
    main()
