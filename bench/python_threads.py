#!/usr/bin/python3
"""Two renders in two Python threads through the weft module, against one:
the module releases the GIL while it renders, so two one-thread renders of
the Gaffer smoke run side by side in about the time of one (target: well
under twice one; with 2 cores, ideally 1x). Also the module's render time
against the weft command's own `render` timing for the same frame.

    /usr/bin/python3 bench/python_threads.py [--res 256x256] [--repeat 3]
"""
import argparse
import json
import os
import statistics
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, headline, run  # noqa: E402

sys.path.insert(0, os.path.join(ROOT, "build", "bin"))
try:
    import weft
except ImportError as e:
    sys.exit("bench: the weft module is not built (build/bin/weft*.so; pybind11-dev): %s" % e)

SMOKE = os.path.join(ROOT, "data", "smoke_small.vdb")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--res", default="256x256")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    w, h = (int(v) for v in a.res.split("x"))
    scene = weft.load_scene(SMOKE)
    scene.render(res=(w, h), threads=1)  # loads the scene for this framing

    def one():
        scene.render(res=(w, h), threads=1)

    alone, pair = [], []
    for _ in range(a.repeat):
        start = time.perf_counter()
        one()
        alone.append(time.perf_counter() - start)
        threads = [threading.Thread(target=one) for _ in range(2)]
        start = time.perf_counter()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        pair.append(time.perf_counter() - start)
    t1, t2 = statistics.median(alone), statistics.median(pair)
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "s.json")
        run([WEFT, "render", SMOKE, "--res", a.res, "--threads", "1", "-o", os.path.join(tmp, "x.exr"), "--stats", stats])
        with open(stats) as f:
            cli_ms = json.load(f)["timings_ms"]["render"]
    print("weft module, %s, data/smoke_small.vdb, one-thread renders (median of %d):" % (a.res, a.repeat))
    print("  one render            %.3f s   (the weft command's own render timing: %.3f s)" % (t1, cli_ms / 1000))
    print("  two in two threads    %.3f s   %.2fx one render (%d cores)" % (t2, t2 / t1, os.cpu_count()))
    headline("weft module: two renders in two Python threads / one render", "%.2fx" % (t2 / t1), "<= 1.5x", t2 / t1 <= 1.5)


if __name__ == "__main__":
    main()
