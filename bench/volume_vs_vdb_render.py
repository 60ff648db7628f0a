#!/usr/bin/env python3
"""Time at equal error: weft's volume.singlescatter against vdb_render.

For each data set (the Gaffer smoke with the camera of docs/volumes.md, and the
aneurism) it renders one converged reference with vdb_render (step 0.125,
shadowstep 0.25), then vdb_render at steps 1, 0.5, 0.25, 0.125 (shadowstep
3, its default) and weft at a ladder of its own knobs (primary step, cache
march step and cache voxel size), each timed as a whole process on the same
number of threads in the same run. It prints the time-vs-RMSE table, writes
a CSV and a log-log plot, measures the strongest periodic peak of each error
image (rings along depth show up there), and ends with

    speedup_at_equal_rmse <x>

for the smoke: weft's time to reach the RMSE of vdb_render at step 1
(interpolated on weft's curve) over vdb_render's time at step 1.

Usage: /usr/bin/python3 bench/volume_vs_vdb_render.py [--data DIR] [--out DIR]
       [--res WxH] [--threads N] [--repeat N]
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

from benchlib import ROOT, WEFT, headline, prepare_aneurism, rmse, run_timed

VDB_STEPS = [1, 0.5, 0.25, 0.125]
# (step, shadowstep, cache_voxel), cheapest first.
WEFT_KNOBS = [(6, 6, 6), (4, 4, 4), (3, 3, 4), (2, 2, 3), (1, 1, 2), (0.5, 1, 2)]


def timed(args, repeat):
    return min(run_timed(args)[0] for _ in range(repeat))


def vdb_render(vdb, out, scene, step, shadowstep, a):
    args = ["vdb_render", vdb, out, "-res", a.res, "-cpus", str(a.threads), "-step", str(step),
            "-shadowstep", str(shadowstep)] + scene
    return timed(args, a.repeat)


def weft(vdb, out, scene, knobs, a):
    step, shadow, cache = knobs
    args = [WEFT, "render", vdb, "--technique", "volume.singlescatter", "--res", a.res, "--threads", str(a.threads),
            "-o", out, "--set", "compat=vdb_render", "--set", "step=%g" % step, "--set", "shadowstep=%g" % shadow,
            "--set", "cache_voxel=%d" % cache]
    for i in range(0, len(scene), 2):  # vdb_render's "-name value" pairs become --set name=value
        args += ["--set", "%s=%s" % (scene[i].lstrip("-"), scene[i + 1])]
    return timed(args, a.repeat)


def spectral_peak(image, reference):
    """Strongest non-DC peak of the error image's power spectrum over its mean."""
    import numpy as np
    import OpenImageIO as oiio
    err = oiio.ImageBuf(image).get_pixels(oiio.FLOAT)[..., :3].mean(axis=2) - \
        oiio.ImageBuf(reference).get_pixels(oiio.FLOAT)[..., :3].mean(axis=2)
    power = np.abs(np.fft.fftshift(np.fft.fft2(err - err.mean()))) ** 2
    cy, cx = power.shape[0] // 2, power.shape[1] // 2
    power[cy - 2:cy + 3, cx - 2:cx + 3] = 0  # DC and the lowest frequencies
    return float(power.max() / max(power.mean(), 1e-30))


def time_at_rmse(points, target):
    """Time at which the (time, rmse) curve reaches target, log-log interpolated."""
    pts = sorted(points)
    if pts[0][1] <= target:
        return pts[0][0], True  # already better at its cheapest: an upper bound on the time
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= target < e0:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), False
    return float("nan"), False


def plot(rows, path, title):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench: matplotlib missing, no plot (run with /usr/bin/python3)")
        return
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for who, marker in (("vdb_render", "o"), ("weft", "s")):
        pts = sorted((r["time_s"], r["rmse"]) for r in rows if r["renderer"] == who)
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=who)
    ax.set_xlabel("time (s, whole process)")
    ax.set_ylabel("RMSE vs converged reference")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def bench(name, vdb, scene, a):
    out = os.path.join(a.out, name)
    os.makedirs(out, exist_ok=True)
    ref = os.path.join(out, "reference.exr")
    t_ref = vdb_render(vdb, ref, scene, 0.125, 0.25, a)
    rows = []
    for s in VDB_STEPS:
        img = os.path.join(out, "vdb_render_step%g.exr" % s)
        t = vdb_render(vdb, img, scene, s, 3, a)
        rows.append(dict(renderer="vdb_render", setting="step %g shadowstep 3" % s, time_s=t, rmse=rmse(img, ref), image=img))
    for k in WEFT_KNOBS:
        img = os.path.join(out, "weft_step%g_shadow%g_cache%d.exr" % k)
        t = weft(vdb, img, scene, k, a)
        rows.append(dict(renderer="weft", setting="step %g shadowstep %g cache_voxel %d" % k, time_s=t, rmse=rmse(img, ref), image=img))
    print("\n%s (%s, %d threads; reference: vdb_render step 0.125 shadowstep 0.25, %.1f s)" % (name, a.res, a.threads, t_ref))
    print("%-11s %-36s %9s %10s %14s" % ("renderer", "setting", "time (s)", "RMSE", "spectral peak"))
    for r in rows:
        r["peak"] = spectral_peak(r["image"], ref)
        print("%-11s %-36s %9.3f %10.5f %14.1f" % (r["renderer"], r["setting"], r["time_s"], r["rmse"], r["peak"]))
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["renderer", "setting", "time_s", "rmse", "peak"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    plot(rows, os.path.join(out, "time_vs_rmse.png"), name)
    base = rows[0]
    t_weft, bound = time_at_rmse([(r["time_s"], r["rmse"]) for r in rows if r["renderer"] == "weft"], base["rmse"])
    speedup = base["time_s"] / t_weft
    print("%s: weft reaches vdb_render step 1's RMSE %.5f in %.3f s%s: %.2fx faster" % (
        name, base["rmse"], t_weft, " (its cheapest setting is already better)" if bound else "", speedup))
    return speedup, bound


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-vdb-render"))
    ap.add_argument("--res", default="512x512")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=2, help="runs per setting; the fastest counts")
    a = ap.parse_args()
    for f in ("smoke.vdb", "aneurism.raw.gz"):
        if not os.path.exists(os.path.join(a.data, f)):
            sys.exit("bench: %s not found in %s (use --data DIR)" % (f, a.data))
    os.makedirs(a.out, exist_ok=True)
    speedup, bound = bench("smoke", os.path.join(a.data, "smoke.vdb"), ["-translate", "0,40,160"], a)
    aneurism, aneurism_bound = bench("aneurism", prepare_aneurism(a.data, a.out),
                                     ["-translate", "120,130,640", "-absorb", "0.002,0.003,0.004", "-scatter", "0.012,0.01,0.008"], a)
    print("speedup_at_equal_rmse %s%.2f" % (">= " if bound else "", speedup))
    for name, x, at_least, target in (("smoke", speedup, bound, 10), ("aneurism", aneurism, aneurism_bound, 5)):
        headline("volume.singlescatter vs vdb_render at equal RMSE, %s %s" % (name, a.res),
                 "%s%.1fx" % (">= " if at_least else "", x), ">= %dx" % target, x >= target)


if __name__ == "__main__":
    main()
