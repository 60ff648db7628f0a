#!/usr/bin/env python3
"""Two builds of weft side by side: render time and counters of the
one-volume benchmark cases (bench/kraus_tables.py's columns and
bench/volume_vs_vdb_render.py's weft ladder), each case run by both builds
in turn, --repeat rounds, so both see the same machine load.

Prints per case the fastest render time (the stats' timings_ms.render) and
whole-process time of each build, their ratio (head / base) and whether the
counters are identical. A regression check before merging work that
reshapes shared code:

  /usr/bin/python3 bench/build_vs_build.py --base OTHER_CHECKOUT [--head .] [--repeat 5]
"""
import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
import time
import subprocess

from benchlib import ROOT

KRAUS = [
    ("preint", "volume.preint", []),
    ("adaptive3d minimum", "volume.adaptive3d", ["oracle=minimum"]),
    ("adaptive3d gradient_alpha", "volume.adaptive3d", ["oracle=gradient_alpha"]),
    ("adaptive3d vdb_topology", "volume.adaptive3d", ["oracle=vdb_topology"]),
    ("adaptive3d majorant", "volume.adaptive3d", ["oracle=majorant"]),
]
# bench/volume_vs_vdb_render.py's weft knobs (step, shadowstep, cache_voxel), a cheap and a fine one.
SCATTER = [(4, 4, 4), (1, 1, 2), (0.5, 1, 2)]
SMOKE_SCATTER = ["translate=0,40,160"]
ANEURISM_SCATTER = ["translate=120,130,640", "absorb=0.002,0.003,0.004", "scatter=0.012,0.01,0.008"]


def cases(data, tmp):
    aneurism_scene = os.path.join(tmp, "aneurism.json")
    shutil.copy(os.path.join(ROOT, "scenes", "aneurism.json"), aneurism_scene)
    smoke = os.path.join(data, "smoke.vdb")
    out = []
    for scene_name, scene in (("aneurism", aneurism_scene), ("smoke", smoke)):
        for label, technique, sets in KRAUS:
            out.append(("%s %s" % (scene_name, label), scene, technique, sets))
    for scene_name, scene, extra in (("smoke", smoke, SMOKE_SCATTER),
                                     ("aneurism", os.path.join(tmp, "aneurism.vdb"), ANEURISM_SCATTER)):
        for step, shadow, cache in SCATTER:
            sets = ["compat=vdb_render", "step=%g" % step, "shadowstep=%g" % shadow, "cache_voxel=%d" % cache] + extra
            out.append(("%s singlescatter step %g/%g/%d" % (scene_name, step, shadow, cache), scene,
                        "volume.singlescatter", sets))
    return out


def render(weft, scene, technique, sets, res, threads, tmp):
    exr, stats = os.path.join(tmp, "x.exr"), os.path.join(tmp, "x.json")
    args = [weft, "render", scene, "--technique", technique, "--res", res, "--threads", str(threads),
            "-o", exr, "--stats", stats]
    for s in sets:
        args += ["--set", s]
    start = time.perf_counter()
    proc = subprocess.run(args, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit("bench: %s failed:\n%s" % (" ".join(args), proc.stderr.strip()))
    with open(stats) as f:
        s = json.load(f)
    return s["timings_ms"]["render"] / 1000.0, wall, s["counters"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", required=True, help="checkout whose build/bin/weft is the baseline")
    ap.add_argument("--head", default=ROOT)
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--res", default="512x512")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--only", default="", help="run the cases whose label contains this text")
    a = ap.parse_args()
    builds = {name: os.path.join(path, "build", "bin", "weft") for name, path in (("base", a.base), ("head", a.head))}
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([builds["head"], "convert", os.path.join(a.data, "aneurism.raw.gz"), "--dims", "256,256,256",
                        "--type", "u8", "-o", os.path.join(tmp, "aneurism.vdb")], check=True, capture_output=True)
        print("| case | render base (s) | render head (s) | head / base | process base (s) | process head (s) | counters |")
        print("|---|---|---|---|---|---|---|")
        ratios = []
        for label, scene, technique, sets in cases(a.data, tmp):
            if a.only not in label:
                continue
            times = {"base": [], "head": []}
            counters = {}
            for _ in range(a.repeat):
                for name in ("base", "head"):
                    r, w, c = render(builds[name], scene, technique, sets, a.res, a.threads, tmp)
                    times[name].append((r, w))
                    counters[name] = c
            rb, rh = min(t[0] for t in times["base"]), min(t[0] for t in times["head"])
            wb, wh = min(t[1] for t in times["base"]), min(t[1] for t in times["head"])
            # Counters both builds have; one only one build counts is not a difference in work.
            common = set(counters["base"]) & set(counters["head"])
            same = all(counters["base"][k] == counters["head"][k] for k in common)
            ratios.append(rh / rb)
            print("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %s |" % (
                label, rb, rh, rh / rb, wb, wh, "identical" if same else "DIFFER: " + ", ".join(
                    "%s %s/%s" % (k, counters["base"][k], counters["head"][k]) for k in sorted(common)
                    if counters["base"][k] != counters["head"][k])), flush=True)
        if ratios:
            print("geometric mean head / base: %.3f" % statistics.geometric_mean(ratios))


if __name__ == "__main__":
    main()
