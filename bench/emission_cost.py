#!/usr/bin/python3
"""What emission costs: the fire scene (scenes/fire.json: procedural density
and temperature, blackbody emission) rendered with its emission and again
without it (the same density, no "emission" key), per volume technique that
renders emission, side by side in one run. Target: with emission at most
1.3x the render time without it, for each technique.

    /usr/bin/python3 bench/emission_cost.py [--res 512x512] [--repeat 3] [--techniques a,b]

The slice techniques' render time includes building their pre-integration
tables (with emission weights when the scene emits) and, for
volume.adaptive3d, its oracle field (with the emission's features).
"""
import argparse
import json
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, headline, run  # noqa: E402

TECHNIQUES = ["volume.raymarch", "volume.singlescatter", "mesh.pathtrace", "volume.preint", "volume.adaptive3d"]
TARGET = 1.3


def scene_files(tmp):
    with open(os.path.join(ROOT, "scenes", "fire.json")) as f:
        fire = json.load(f)
    dark = json.loads(json.dumps(fire))
    del dark["volumes"][0]["emission"]
    paths = {}
    for name, scene in (("emission", fire), ("none", dark)):
        paths[name] = os.path.join(tmp, name + ".json")
        with open(paths[name], "w") as f:
            json.dump(scene, f)
    return paths


def render_ms(scene, technique, res, tmp):
    """The render timing (ms) and the whole load + render of one run."""
    stats = os.path.join(tmp, "s.json")
    run([WEFT, "render", scene, "--technique", technique, "--res", res, "-o", os.path.join(tmp, "x.exr"),
         "--stats", stats])
    with open(stats) as f:
        t = json.load(f)["timings_ms"]
    return t["render"] + t.get("light_cache", 0.0), t["load"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--res", default="512x512")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--techniques", default=",".join(TECHNIQUES), help="comma-separated (default: every volume technique)")
    a = ap.parse_args()
    techniques = [t for t in a.techniques.split(",") if t]
    unknown = [t for t in techniques if t not in TECHNIQUES]
    if unknown:
        sys.exit("emission_cost.py: unknown technique %s (choose from %s)" % (unknown[0], ", ".join(TECHNIQUES)))
    with tempfile.TemporaryDirectory() as tmp:
        scenes = scene_files(tmp)
        print("%-22s %12s %12s %8s %10s %10s" % ("technique", "emission ms", "none ms", "ratio",
                                                 "load em ms", "load ms"))
        worst = 0.0
        for technique in techniques:
            runs = {name: [render_ms(path, technique, a.res, tmp) for _ in range(a.repeat)]
                    for name, path in scenes.items()}
            med = {name: statistics.median(r[0] for r in rs) for name, rs in runs.items()}
            load = {name: statistics.median(r[1] for r in rs) for name, rs in runs.items()}
            ratio = med["emission"] / med["none"]
            worst = max(worst, ratio)
            print("%-22s %12.1f %12.1f %7.2fx %10.0f %10.0f" % (technique, med["emission"], med["none"], ratio,
                                                              load["emission"], load["none"]))
        headline("emission cost, fire scene %s, worst of %d techniques (render time with / without)"
                 % (a.res, len(techniques)), "%.2fx" % worst, "<= %.1fx" % TARGET, worst <= TARGET)


if __name__ == "__main__":
    main()
