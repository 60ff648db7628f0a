#!/usr/bin/env python3
"""Large scene files: the time from `weft render` to the first technique
work for a scene of 10,000 meshes and one of 20,000 lights, and the time to
refuse a 700 KB scene whose last number is out of range (the loader must be
linear in the file's size). Each is the whole process, rendered at 8x8 so
that loading is what is timed; the 1,000-light scene is timed beside the
20,000-light one to show the growth. Target: under 2 s for each large scene.

  /usr/bin/python3 bench/scene_load.py
"""
import json
import os
import subprocess
import sys
import tempfile
import time

from benchlib import WEFT, headline

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(args, expect_ok=True):
    best = None
    for _ in range(3):
        start = time.perf_counter()
        p = subprocess.run(args, capture_output=True, text=True)
        elapsed = time.perf_counter() - start
        if (p.returncode == 0) != expect_ok:
            sys.exit("bench: unexpected exit %d: %s\n%s" % (p.returncode, " ".join(args), p.stderr))
        best = elapsed if best is None else min(best, elapsed)
    return best


def lights_scene(n):
    return {"volumes": [{"procedural": "sphere", "resolution": 8}],
            "lights": [{"type": "point", "position": [i % 7, 3, i % 5], "intensity": 1e-4} for i in range(n)],
            "render": {"technique": "volume.raymarch"}}


def main():
    with tempfile.TemporaryDirectory() as d:
        tri = os.path.join(d, "tri.obj")
        with open(tri, "w") as f:
            f.write("v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n")
        meshes = {"meshes": [{"file": "tri.obj", "translate": [i % 100, i // 100, 0]} for i in range(10000)],
                  "render": {"technique": "mesh.pathtrace"}}
        paths = {}
        for name, scene in (("meshes10k", meshes), ("lights1k", lights_scene(1000)), ("lights20k", lights_scene(20000))):
            paths[name] = os.path.join(d, name + ".json")
            with open(paths[name], "w") as f:
                json.dump(scene, f, indent=1)
        bad = os.path.join(d, "numbers.json")
        with open(bad, "w") as f:
            f.write('{"volumes": [{"procedural": "sphere", "resolution": 8}],\n "lights": [')
            f.write(",\n".join('{"type": "directional", "direction": [0, -1, 0], "intensity": %d}' % (1 if i < 9999 else -1)
                               for i in range(10000)))
            f.write("]}\n")
        out = os.path.join(d, "out.exr")
        rows = []
        for name in ("meshes10k", "lights1k", "lights20k"):
            seconds = timed([WEFT, "render", paths[name], "--res", "8x8", "--spp", "1", "-o", out])
            rows.append((name, os.path.getsize(paths[name]), seconds))
        refuse = timed([WEFT, "render", bad, "--res", "8x8", "-o", out], expect_ok=False)
        rows.append(("numbers.json refused", os.path.getsize(bad), refuse))
        print("%-24s %10s %10s" % ("scene", "bytes", "seconds"))
        for name, size, seconds in rows:
            print("%-24s %10d %10.3f" % (name, size, seconds))
        worst = max(r[2] for r in rows if r[0] in ("meshes10k", "lights20k"))
        headline("10,000-mesh / 20,000-light scene, whole process at 8x8", "%.2f s" % worst, "< 2 s", worst < 2)


if __name__ == "__main__":
    main()
