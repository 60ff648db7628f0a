#!/usr/bin/env python3
"""Reproduces Tables 2 and 3 of Kraus et al. 2007 with weft.

For each data set (the aneurism, and the Gaffer smoke in place of the
abdomen, which is not public) it renders at 512x512:
  volume.preint                       (the paper's "tex.-based" column)
  volume.adaptive3d oracle=minimum    (worst-case overhead; must equal preint)
  volume.adaptive3d oracle=gradient_alpha
and prints sampling operations, oracle samples, syntheses, composites, the
render time (2 threads), and the RMSE against volume.preint at the same
slice spacing. Fragment counts come from hwsim replays (not in this table).

Usage: bench/kraus_tables.py [--data DIR] [--out DIR] [--res WxH] [--threads N]
DIR defaults to ../shared/data beside the project (aneurism.raw.gz, smoke.vdb).
"""
import argparse
import json
import os
import subprocess
import sys

from benchlib import ROOT, WEFT, headline, prepare_aneurism as convert_aneurism, rmse, run

# (label, file tag, technique, --set values)
COLUMNS = [
    ("tex.-based", "preint", "volume.preint", []),
    ("adaptive min.", "minimum", "volume.adaptive3d", ["oracle=minimum"]),
    ("adaptive |grad a|>eps", "gradient_alpha", "volume.adaptive3d", ["oracle=gradient_alpha"]),
    ("adaptive vdb_topology", "vdb_topology", "volume.adaptive3d", ["oracle=vdb_topology"]),
    ("adaptive majorant", "majorant", "volume.adaptive3d", ["oracle=majorant"]),
]
ROWS = ["volume.samples", "oracle.samples", "synthesis.ops", "composite.ops", "slices"]


def prepare_aneurism(data, out):
    convert_aneurism(data, out)
    scene = os.path.join(out, "aneurism.json")
    with open(os.path.join(ROOT, "scenes", "aneurism.json")) as src, open(scene, "w") as dst:
        dst.write(src.read())
    return scene


def render(scene, name, technique, sets, out, res, threads):
    exr = os.path.join(out, name + ".exr")
    stats = os.path.join(out, name + ".json")
    args = [WEFT, "render", scene, "--technique", technique, "--res", res, "--threads", str(threads),
            "-o", exr, "--preview", os.path.join(out, name + ".png"), "--stats", stats]
    for s in sets:
        args += ["--set", s]
    run(args)
    with open(stats) as f:
        return exr, json.load(f)


def speed_headline(what, base, fast, error, target):
    """adaptive3d's wall-clock speed-up over preint, which counts only at RMSE <= 1/255."""
    x = base["timings_ms"]["render"] / fast["timings_ms"]["render"]
    fewer = base["counters"]["volume.samples"] / max(1, fast["counters"]["volume.samples"])
    headline("volume.adaptive3d gradient_alpha vs volume.preint, %s" % what,
             "%.2fx wall, %.1fx fewer samples, RMSE %.5f" % (x, fewer, error),
             ">= %gx wall at RMSE <= 1/255" % target, x >= target and error <= 1 / 255)


def table(title, scene, tag, out, res, threads, target=None):
    results = []
    for label, name, technique, sets in COLUMNS:
        exr, stats = render(scene, tag + "_" + name, technique, sets, out, res, threads)
        results.append((label, exr, stats))
    ref = results[0][1]
    print("\n%s (%s, %d threads)" % (title, res, threads))
    print("%-22s" % "" + "".join("%23s " % r[0] for r in results))
    for row in ROWS:
        print("%-22s" % row + "".join("%24s" % "{:,}".format(r[2]["counters"].get(row, 0)) for r in results))
    print("%-22s" % "render time (s)" + "".join("%24.3f" % (r[2]["timings_ms"]["render"] / 1000) for r in results))
    oracle = [r[2]["timings_ms"].get("oracle", 0) / 1000 for r in results]
    print("%-22s" % "  of it oracle (s)" + "".join("%24.3f" % o for o in oracle))
    print("%-22s" % "RMSE vs tex.-based" + "".join("%24.6f" % rmse(r[1], ref) for r in results))
    base = results[0][2]
    last = results[2][2]
    print("gradient_alpha: %.1fx fewer volume samples, %.2fx the speed of tex.-based" % (
        base["counters"]["volume.samples"] / max(1, last["counters"]["volume.samples"]),
        base["timings_ms"]["render"] / last["timings_ms"]["render"]))
    if target:
        speed_headline("%s %s" % (tag, res), base, last, rmse(results[2][1], ref), target)


def bare_vdb_headline(vdb, out, res, threads):
    """The aneurism VDB as a user renders it first: no scene, the default transfer function."""
    preint_exr, preint = render(vdb, "bare_preint", "volume.preint", [], out, res, threads)
    exr, adaptive = render(vdb, "bare_gradient_alpha", "volume.adaptive3d", ["oracle=gradient_alpha"], out, res, threads)
    speed_headline("bare aneurism VDB %s" % res, preint, adaptive, rmse(exr, preint_exr), 10)


def sample_rate_headline(scene, out, res, threads):
    """Trilinear volume samples per second of volume.raymarch (its counter over its render time):
    as a user renders (empty space skipped, so few samples and the rays' walk dominate), and with
    every sample taken (skip_empty=false), as the rate was first measured, before raymarch skipped."""
    for name, sets, how in (("raymarch_rate", [], "default settings"),
                            ("raymarch_rate_every", ["skip_empty=false"], "every sample taken (skip_empty=false)")):
        _, st = render(scene, name, "volume.raymarch", sets, out, res, threads)
        rate = st["counters"]["volume.samples"] / (st["timings_ms"]["render"] / 1000)
        headline("volume.raymarch trilinear samples per second, aneurism %s, %d threads, %s" % (res, threads, how),
                 "%.0f M/s (%.1f M samples)" % (rate / 1e6, st["counters"]["volume.samples"] / 1e6), ">= 100 M/s",
                 rate >= 100e6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-kraus"))
    ap.add_argument("--res", default="512x512")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    for f in ("aneurism.raw.gz", "smoke.vdb"):
        if not os.path.exists(os.path.join(a.data, f)):
            sys.exit("bench: %s not found in %s (use --data DIR)" % (f, a.data))
    os.makedirs(a.out, exist_ok=True)
    aneurism = prepare_aneurism(a.data, a.out)
    table("Table 2: aneurism 256^3", aneurism, "aneurism", a.out, a.res, a.threads, target=10)
    table("Table 3: Gaffer smoke (abdomen not public)", os.path.join(a.data, "smoke.vdb"), "smoke", a.out, a.res, a.threads, target=3)
    bare_vdb_headline(convert_aneurism(a.data, a.out), a.out, a.res, a.threads)
    sample_rate_headline(aneurism, a.out, a.res, a.threads)


if __name__ == "__main__":
    main()
