#!/usr/bin/python3
"""Reproduces the comparison and the overhead tables of Bauszat et al. 2011
with lighting.adaptive_indirect.

MSE table  MSE of the incident indirect illumination (the indirect.RGB AOV)
           against a high-sample reference (mode=uniform, unfiltered, --ref-spp
           samples per pixel) for the three modes at the same total number of
           indirect samples (--spp per surface pixel): uniform unfiltered,
           uniform + A-Trous, adaptive + A-Trous. The A-Trous level count is
           the one that minimises the uniform + A-Trous MSE (levels 2..6), and
           the adaptive mode uses the same filter, as the paper does. The
           reference's own noise adds var/ref_spp to every MSE; it is estimated
           from the unfiltered uniform image (whose expected MSE is
           var/spp + var/ref_spp) and the "corrected" ratio takes it out.
Table 1/2  build/bin/weft_budget_overhead at 1024x768 (importance + counts
           per window size; sample generation and storage for 4/16/64 spp).

Scenes: the original Cornell box (data/ in the project), McGuire's glossy
Cornell box and the Stanford bunny on the short box of the original one
(both from the shared data folder, --data). The paper measured at 1024x768
with 1024-spp references; the defaults here (256x192, 1024-spp references)
run in a few minutes on two cores.

Usage: bench/bauszat_tables.py [--data DIR] [--out DIR] [--res WxH] [--spp N] [--ref-spp N]
                               [--min-samples N] [--threads N] [--scenes a,b] [--tables mse,overhead]
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


def mse_table(scenes, args):
    print("\nMSE of the incident indirect illumination (indirect.RGB) vs a %d-spp reference, %s, %d indirect samples per"
          " surface pixel (adaptive: the same total, at least %d per pixel), %d threads"
          % (args.ref_spp, args.res, args.spp, args.min_samples, args.threads))
    print("%-8s %7s %12s %12s %12s %12s %12s %8s %10s %9s" % ("scene", "levels", "uniform", "uni+atrous", "adapt+atrous",
                                                           "adapt (raw)", "ref. noise", "ratio", "corrected", "samples"))
    results = {}
    for name, scene in scenes.items():
        ref, _ = render(scene, os.path.join(args.out, name + "_ref.exr"), args.res, args.ref_spp, 1000, args.threads,
                        ["mode=uniform", "direct_samples=0"])
        ref_e = indirect(ref)
        best = None
        for levels in range(2, 7):
            img, st = render(scene, os.path.join(args.out, "%s_uniform_atrous_%d.exr" % (name, levels)), args.res,
                             args.spp, 1, args.threads, ["mode=uniform_atrous", "levels=%d" % levels] + args.set)
            e = mse(indirect(img), ref_e)
            if best is None or e < best[0]:
                best = (e, levels, img, st)
        e_ua, levels, ua, st_ua = best
        uni, st_u = render(scene, os.path.join(args.out, name + "_uniform.exr"), args.res, args.spp, 1, args.threads,
                           ["mode=uniform"])
        ada, st_a = render(scene, os.path.join(args.out, name + "_adaptive.exr"), args.res, args.spp, 1, args.threads,
                           ["mode=adaptive_atrous", "levels=%d" % levels, "min_samples=%d" % args.min_samples] + args.set)
        e_u, e_a, e_araw = mse(indirect(uni), ref_e), mse(indirect(ada), ref_e), mse(indirect(ada, "indirect_raw"), ref_e)
        samples = {k: s["counters"]["samples.indirect"] for k, s in (("u", st_u), ("ua", st_ua), ("a", st_a))}
        assert samples["u"] == samples["ua"] == samples["a"], samples
        noise = e_u / (1.0 + args.ref_spp / args.spp)  # var / ref_spp
        print("%-8s %7d %12.6f %12.6f %12.6f %12.6f %12.6f %7.1f%% %9.1f%% %9d"
              % (name, levels, e_u, e_ua, e_a, e_araw, noise, 100 * e_a / e_ua, 100 * (e_a - noise) / (e_ua - noise),
                 samples["a"]))
        results[name] = (ref, uni, ua, ada)
    print("ratio: adaptive + A-Trous MSE as a percentage of uniform + A-Trous (below 100%: adaptive is better);"
          " corrected: both with the reference noise taken out")
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
    p.add_argument("--min-samples", type=int, default=2)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--scenes", default="cornell,glossy,bunny")
    p.add_argument("--tables", default="mse,overhead")
    p.add_argument("--set", action="append", default=[], help="extra filter parameter for both filtered modes")
    p.add_argument("--images", default="", help="write the README pictures of the Cornell box here")
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
