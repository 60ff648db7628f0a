#!/usr/bin/python3
"""Reproduces the comparison and the overhead tables of Bauszat et al. 2011
with lighting.adaptive_indirect.

MSE table  MSE of the incident indirect illumination (the indirect.RGB AOV)
           against a high-sample reference (mode=uniform, unfiltered, --ref-spp
           samples per pixel) for the three modes at the same total number of
           indirect samples (--spp per surface pixel): uniform unfiltered,
           uniform + A-Trous, adaptive + A-Trous. The A-Trous level count is
           the one that minimises the uniform + A-Trous MSE (levels 2..6, two
           seeds), and
           the adaptive mode uses the same filter, as the paper does, with its
           taps weighted by their sample counts (count_weights, weft's
           default) and without (the paper's filter). The
           reference's own noise adds var/ref_spp to every MSE; it is estimated
           from the unfiltered uniform image (whose expected MSE is
           var/spp + var/ref_spp) and the "corrected" ratio takes it out.
Table 1/2  build/bin/weft_budget_overhead at 1024x768 (importance + counts
           per window size; sample generation and storage for 4/16/64 spp).

Scenes: the original Cornell box (data/ in the project), McGuire's glossy
Cornell box and the Stanford bunny on the short box of the original one
(both from the shared data folder, --data). The paper measured at 1024x768
with 1024-spp references; the defaults here (256x192, 1024-spp references)
run in a few minutes on two cores, --res 1024x768 in about 40 minutes
(--reuse-ref keeps the references for a second run).

Usage: bench/bauszat_tables.py [--data DIR] [--out DIR] [--res WxH] [--spp N] [--ref-spp N]
                               [--min-samples N] [--min-fraction F] [--seeds N] [--reuse-ref] [--threads N] [--scenes a,b] [--tables mse,overhead]
                               [--images DIR]
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

from benchlib import write_mesh_scenes as write_scenes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WEFT = os.path.join(ROOT, "build", "bin", "weft")
OVERHEAD = os.path.join(ROOT, "build", "bin", "weft_budget_overhead")
TECH = "lighting.adaptive_indirect"


def run(args):
    proc = subprocess.run(args, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit("bench: command failed: %s\n%s" % (" ".join(args), proc.stderr.strip()))
    return proc.stdout


def render(scene, path, res, spp, seed, threads, sets):
    stats = path[:-4] + ".json"
    args = [WEFT, "render", scene, "--technique", TECH, "--res", res, "--spp", str(spp), "--seed", str(seed),
            "--threads", str(threads), "-o", path, "--stats", stats]
    for s in sets:
        args += ["--set", s]
    run(args)
    with open(stats) as f:
        return read_layers(path), json.load(f)


def read_layers(path):
    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT)).reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    return {n: pixels[..., i] for i, n in enumerate(names)}


def indirect(layers, prefix="indirect"):
    return np.stack([layers[prefix + "." + c] for c in "RGB"], axis=-1)


def mse(a, b):
    return float(np.mean((a - b) ** 2))


_measured = {}  # image path -> (MSE, samples): a seed rendered once per run


def seed_mses(scene, name, tag, sets, args, ref_e, seeds=0):
    """MSE of indirect.RGB for seeds 1..seeds (--seeds), the path of seed 1's image, the sample totals."""
    errors, samples = [], set()
    path = lambda seed: os.path.join(args.out, "%s_%s_s%d.exr" % (name, tag, seed))
    for seed in range(1, (seeds or args.seeds) + 1):
        if path(seed) not in _measured:
            img, st = render(scene, path(seed), args.res, args.spp, seed, args.threads, sets)
            _measured[path(seed)] = (mse(indirect(img), ref_e), st["counters"]["samples.indirect"])
        errors.append(_measured[path(seed)][0])
        samples.add(_measured[path(seed)][1])
    return np.array(errors), path(1), samples


def mse_table(scenes, args):
    print("\nMSE of the incident indirect illumination (indirect.RGB) vs a %d-spp reference, %s, %d indirect samples per"
          " surface pixel (adaptive: the same total, at least max(%d, floor(%g x %d)) per pixel), mean of %d seeds, %d threads"
          % (args.ref_spp, args.res, args.spp, args.min_samples, args.min_fraction, args.spp, args.seeds, args.threads))
    print("%-8s %6s %10s %10s %12s %12s %10s %16s %16s %9s" % ("scene", "levels", "uniform", "uni+atrous", "adapt+atrous",
                                                             "adapt(plain)", "ref.noise", "corrected", "(plain)", "samples"))
    results = {}
    for name, scene in scenes.items():
        ref_path = os.path.join(args.out, "%s_ref_%s_%d.exr" % (name, args.res, args.ref_spp))
        if args.reuse_ref and os.path.exists(ref_path):
            ref = read_layers(ref_path)
        else:
            ref, _ = render(scene, ref_path, args.res, args.ref_spp, 1000, args.threads, ["mode=uniform", "direct_samples=0"])
        ref_e = indirect(ref)
        # The level count that minimises uniform + A-Trous on two seeds, then all seeds at it.
        uniform_atrous = lambda lv, n=0: seed_mses(scene, name, "uniform_atrous_%d" % lv,
                                                   ["mode=uniform_atrous", "levels=%d" % lv] + args.set, args, ref_e, n)
        levels = min(range(2, 7), key=lambda lv: uniform_atrous(lv, min(2, args.seeds))[0].mean())
        e_ua, ua, samples = uniform_atrous(levels)
        e_u, uni, s_u = seed_mses(scene, name, "uniform", ["mode=uniform"], args, ref_e)
        adaptive = ["mode=adaptive_atrous", "levels=%d" % levels, "min_samples=%d" % args.min_samples,
                    "min_fraction=%g" % args.min_fraction] + args.set
        e_a, ada, s_a = seed_mses(scene, name, "adaptive", adaptive + ["count_weights=true"], args, ref_e)
        e_p, _, s_p = seed_mses(scene, name, "adaptive_plain", adaptive + ["count_weights=false"], args, ref_e)
        assert len(samples | s_u | s_a | s_p) == 1, (samples, s_u, s_a, s_p)
        noise = e_u.mean() / (1.0 + args.ref_spp / args.spp)  # var / ref_spp
        base = e_ua.mean() - noise

        def corrected(e):  # percentage of uniform + A-Trous, +- two standard errors of the difference
            two_se = 2 * np.sqrt((e.var(ddof=1) + e_ua.var(ddof=1)) / len(e)) if len(e) > 1 else float("nan")
            return "%6.1f%% +- %4.1f" % (100 * (e.mean() - noise) / base, 100 * two_se / base)
        print("%-8s %6d %10.6f %10.6f %12.6f %12.6f %10.6f %16s %16s %9d"
              % (name, levels, e_u.mean(), e_ua.mean(), e_a.mean(), e_p.mean(), noise, corrected(e_a), corrected(e_p),
                 samples.pop()))
        results[name] = (ref, read_layers(uni), read_layers(ua), read_layers(ada))
    print("corrected: adaptive + A-Trous MSE as a percentage of uniform + A-Trous, both with the reference's own noise"
          " taken out, +- two standard errors over the seeds (below 100%: adaptive is better); adapt+atrous weights the"
          " filter's taps by their sample counts (count_weights, the default), adapt(plain) is the paper's filter")
    return results


def to_png(rgb, path, scale):
    # Incident irradiance shown linearly scaled, then sRGB-encoded (a display view, not a grade).
    v = np.clip(rgb * scale, 0, 1)
    v = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    out = oiio.ImageBuf(oiio.ImageSpec(v.shape[1], v.shape[0], 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(0, v.shape[1], 0, v.shape[0], 0, 1, 0, 3), (v * 255 + 0.5).astype(np.uint8))
    out.write(path)


def write_images(results, images):
    os.makedirs(images, exist_ok=True)
    ref, uni, ua, ada = results["cornell"]
    scale = 1.0 / np.percentile(indirect(ref), 99)
    for label, layers, prefix in (("reference", ref, "indirect"), ("uniform", uni, "indirect"),
                                  ("uniform_atrous", ua, "indirect"), ("adaptive_atrous", ada, "indirect")):
        to_png(indirect(layers, prefix), os.path.join(images, "adaptive_%s.png" % label), scale)
    counts = ada["sampleCount"]
    c = counts / max(1.0, float(np.percentile(counts, 99.5)))
    to_png(np.stack([c, c, c], axis=-1), os.path.join(images, "adaptive_sample_count.png"), 1.0)
    print("\nimages written to %s (adaptive_*.png; sample count scaled to its 99.5th percentile = %g)"
          % (images, np.percentile(counts, 99.5)))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    p.add_argument("--out", default=os.path.join(ROOT, "build", "bench-bauszat"))
    p.add_argument("--res", default="256x192")
    p.add_argument("--spp", type=int, default=4)
    p.add_argument("--ref-spp", type=int, default=1024)
    p.add_argument("--min-samples", type=int, default=1, help="the technique's min_samples (the paper: 2)")
    p.add_argument("--min-fraction", type=float, default=0.75, help="the technique's min_fraction (the paper: 0)")
    p.add_argument("--reuse-ref", action="store_true", help="keep a reference already rendered at this size and rate")
    p.add_argument("--seeds", type=int, default=3, help="seeds per filtered configuration (MSEs are their mean)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--scenes", default="cornell,glossy,bunny")
    p.add_argument("--tables", default="mse,overhead")
    p.add_argument("--set", action="append", default=[], help="extra filter parameter for both filtered modes")
    p.add_argument("--images", default="", help="write the pictures of the Cornell box (docs/lighting.md) here")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    print("load average at start: %.2f %.2f %.2f (%d cores)" % (os.getloadavg() + (os.cpu_count(),)))
    all_scenes = write_scenes(os.path.abspath(args.data), args.out)
    scenes = {k: all_scenes[k] for k in args.scenes.split(",")}
    tables = args.tables.split(",")
    if "mse" in tables:
        results = mse_table(scenes, args)
        if args.images and "cornell" in results:
            write_images(results, args.images)
    if "overhead" in tables:
        print()
        print(run([OVERHEAD, all_scenes["cornell"], "1024x768", "--threads", str(args.threads)]))
    print("load average at end: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
