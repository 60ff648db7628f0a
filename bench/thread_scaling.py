#!/usr/bin/python3
"""Thread scaling: every technique's render time on 1 thread and on every
core of the machine (the `render` timing of --stats, side by side in one
run), the speed-up, and whether the images are identical (weft diff: max
abs 0), as determinism requires. The two thread counts run in turn, --repeat
times each, and the fastest run of each counts: load from other work on the
machine only ever adds time, and alternating spreads its drift over both.

    /usr/bin/python3 bench/thread_scaling.py [--res 256x256] [--repeat 5]

Target (issue "Speed"): >= 1.9x from 1 to 2 threads for every technique.
A machine busy with other work measures less; run it on an idle one.
"""
import argparse
import json
import os
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


def render_once(work, tag, technique, scene, extra, res, threads):
    out, stats = os.path.join(work, tag + ".exr"), os.path.join(work, tag + ".json")
    run([WEFT, "render", scene, "--technique", technique, "--res", res, "--threads", str(threads),
         "--seed", "1", "-o", out, "--stats", stats] + extra)
    with open(stats) as f:
        return json.load(f)["timings_ms"]["render"], out


def fastest_pair(work, technique, scene, extra, res, cores, repeat):
    """Fastest render on 1 thread and on `cores` threads, the two run in turn."""
    one, many = [], []
    for _ in range(repeat):
        t, a = render_once(work, "one", technique, scene, extra, res, 1)
        one.append(t)
        t, b = render_once(work, "many", technique, scene, extra, res, cores)
        many.append(t)
    return min(one), min(many), a, b


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--res", default="256x256")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    cores = os.cpu_count() or 2
    rows, held = [], 0
    with tempfile.TemporaryDirectory() as work:
        for technique, scene, extra in CASES:
            one, many, a, b = fastest_pair(work, technique, scene, extra, args.res, cores, args.repeat)
            ratio = one / many if many > 0 else float("nan")
            held += ratio >= 1.9
            rows.append((technique, one, many, ratio, diff_all(a, b)[-1]))
    print("Render time at %s, 1 and %d threads, fastest of %d each, run in turn" % (args.res, cores, args.repeat))
    print("| technique | 1 thread (ms) | %d threads (ms) | speed-up | images max abs diff |" % cores)
    print("|---|---:|---:|---:|---:|")
    for technique, one, many, ratio, diff in rows:
        print("| %s | %.1f | %.1f | %.3fx | %g |" % (technique, one, many, ratio, diff))
    identical = sum(r[4] == 0 for r in rows)
    print("speed-up >= 1.9x: %d of %d techniques; identical images: %d of %d" % (held, len(rows), identical, len(rows)))
    slowest = min(rows, key=lambda r: r[3])
    headline("thread scaling 1 -> %d threads, %s, every technique" % (cores, args.res),
             "%d of %d >= 1.9x (lowest %.3fx, %s); images identical %d of %d" % (
                 held, len(rows), slowest[3], slowest[0], identical, len(rows)),
             ">= 1.9x each, identical", held == len(rows) and identical == len(rows))


if __name__ == "__main__":
    main()
