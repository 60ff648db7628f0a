#!/usr/bin/python3
"""Thread scaling: every technique's render time on 1 thread and on every
core of the machine (the `render` timing of --stats, median of --repeat
runs, side by side in one run), the speed-up, and whether the images are
identical (weft diff: max abs 0), as determinism requires.

    /usr/bin/python3 bench/thread_scaling.py [--res 256x256] [--repeat 3]

Target (issue "Speed"): >= 1.9x from 1 to 2 threads for every technique.
A machine busy with other work measures less; run it on an idle one.
"""
import argparse
import json
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, diff_all, headline, run  # noqa: E402

SMOKE = os.path.join(ROOT, "data", "smoke_small.vdb")
CORNELL = os.path.join(ROOT, "scenes", "cornell.json")
# Each technique on the shipped scene it is made for, with settings that
# make a render of a few hundred milliseconds at 256x256.
CASES = [
    ("volume.raymarch", SMOKE, ["--spp", "4"]),
    ("volume.preint", SMOKE, ["--spp", "4"]),
    ("volume.adaptive3d", SMOKE, []),
    ("volume.singlescatter", SMOKE, ["--spp", "4"]),
    ("mesh.pathtrace", CORNELL, ["--spp", "16"]),
    ("lighting.vpl_deferred", CORNELL, []),
    ("lighting.adaptive_indirect", CORNELL, []),
    ("analytic.2d", "builtin:zoneplate", ["--spp", "16"]),
]


def render_ms(work, tag, technique, scene, extra, res, threads, repeat):
    out, stats = os.path.join(work, tag + ".exr"), os.path.join(work, tag + ".json")
    times = []
    for _ in range(repeat):
        run([WEFT, "render", scene, "--technique", technique, "--res", res, "--threads", str(threads),
             "--seed", "1", "-o", out, "--stats", stats] + extra)
        with open(stats) as f:
            times.append(json.load(f)["timings_ms"]["render"])
    return statistics.median(times), out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", default="256x256")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    cores = os.cpu_count() or 2
    rows, held = [], 0
    with tempfile.TemporaryDirectory() as work:
        for technique, scene, extra in CASES:
            one, a = render_ms(work, "one", technique, scene, extra, args.res, 1, args.repeat)
            many, b = render_ms(work, "many", technique, scene, extra, args.res, cores, args.repeat)
            ratio = one / many if many > 0 else float("nan")
            held += ratio >= 1.9
            rows.append((technique, one, many, ratio, diff_all(a, b)[-1]))
    print("Render time at %s, 1 and %d threads, median of %d" % (args.res, cores, args.repeat))
    print("| technique | 1 thread (ms) | %d threads (ms) | speed-up | images max abs diff |" % cores)
    print("|---|---:|---:|---:|---:|")
    for technique, one, many, ratio, diff in rows:
        print("| %s | %.1f | %.1f | %.2fx | %g |" % (technique, one, many, ratio, diff))
    identical = sum(r[4] == 0 for r in rows)
    print("speed-up >= 1.9x: %d of %d techniques; identical images: %d of %d" % (held, len(rows), identical, len(rows)))
    slowest = min(rows, key=lambda r: r[3])
    headline("thread scaling 1 -> %d threads, %s, every technique" % (cores, args.res),
             "%d of %d >= 1.9x (lowest %.2fx, %s); images identical %d of %d" % (
                 held, len(rows), slowest[3], slowest[0], identical, len(rows)),
             ">= 1.9x each, identical", held == len(rows) and identical == len(rows))


if __name__ == "__main__":
    main()
