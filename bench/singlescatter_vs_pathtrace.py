#!/usr/bin/env python3
"""volume.singlescatter against the volumetric path tracer restricted to
single scattering (mesh.pathtrace max_depth=1), on every combined scene.

Both are Monte Carlo estimates, so each is rendered twice with different
seeds: half the mean squared difference of a pair is the noise variance of
one render. What is left of the mean squared error once both noises are
taken off is the squared bias: the difference that more samples would not
remove. Values are compared as rendered (scene-linear, RGBA).

  /usr/bin/python3 bench/singlescatter_vs_pathtrace.py [--res 128x96] [--pt-spp 1024] [--ss-spp 32] [--scenes a,b]
"""
import argparse
import math
import os
import tempfile

import numpy as np
import OpenImageIO as oiio

from benchlib import ROOT, WEFT, run_timed

SCENES = ["smoke_over_ground", "two_volumes", "ct_stent", "smoke_in_cornell"]
# The singlescatter settings compared: its converged, unbiased form (ratio
# tracking) and its fast default estimator with fine steps. Jittered
# (stratified) pixel positions, as the path tracer's sampler takes them:
# with uniform ones the edges of a visible emitter (17 times brighter than
# anything else in the Cornell box) dominate the noise.
SETTINGS = {
    "ratio": ["physical=true", "estimator=ratio", "step=0.5", "cutoff=0", "pattern=jittered"],
    "cached": ["physical=true", "estimator=cached", "step=0.5", "shadowstep=0.5", "cache_voxel=1", "cutoff=0", "pattern=jittered"],
}


def pixels(path):
    buf = oiio.ImageBuf(path)
    return buf.get_pixels(oiio.FLOAT)[:, :, :4].astype(np.float64)


def render(scene, out, technique, res, spp, seed, sets):
    args = [WEFT, "render", os.path.join(ROOT, "scenes", "combined", scene + ".json"), "--technique", technique,
            "--res", res, "--spp", str(spp), "--seed", str(seed), "-o", out]
    for s in sets:
        args += ["--set", s]
    seconds, _ = run_timed(args)
    return seconds


def pair(scene, tmp, name, technique, res, spp, sets):
    """Two renders (seeds 1 and 2): their mean, one render's noise variance, seconds of one."""
    images, seconds = [], 0.0
    for seed in (1, 2):
        out = os.path.join(tmp, "%s_%s_%d.exr" % (scene, name, seed))
        seconds = render(scene, out, technique, res, spp, seed, sets)
        images.append(pixels(out))
    noise = 0.5 * float(np.mean((images[0] - images[1]) ** 2))
    return images, noise, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--res", default="128x96")
    ap.add_argument("--pt-spp", type=int, default=1024)
    ap.add_argument("--ss-spp", type=int, default=32)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--settings", default="ratio,cached")
    a = ap.parse_args()
    print("| scene | singlescatter settings | time (s) | RMSE vs path tracer | noise, path tracer | noise, singlescatter | bias (RMSE) | bias, emitter pixels left out |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes.split(","):
            ref, ref_noise, _ = pair(scene, tmp, "pt", "mesh.pathtrace", a.res, a.pt_spp, ["max_depth=1"])
            for name in a.settings.split(","):
                img, noise, seconds = pair(scene, tmp, name, "volume.singlescatter", a.res, a.ss_spp, SETTINGS[name])
                mse = float(np.mean((img[0] - ref[0]) ** 2))
                bias = math.sqrt(max(0.0, mse - noise - ref_noise))
                # Pixels that see an emitter (reference above 1) carry the
                # antialiasing error of its edge, 17x brighter than the rest.
                keep = np.max(ref[0][:, :, :3], axis=2) <= 1.0
                masked = lambda a, b: float(np.mean(((a - b)[keep]) ** 2))
                bias_dim = math.sqrt(max(0.0, masked(img[0], ref[0]) - 0.5 * masked(img[0], img[1]) - 0.5 * masked(ref[0], ref[1])))
                print("| %s | %s, %d spp | %.2f | %.4f | %.4f | %.4f | %.4f | %.4f (%d px) |" % (
                    scene, " ".join(SETTINGS[name]), a.ss_spp, seconds, math.sqrt(mse), math.sqrt(ref_noise),
                    math.sqrt(noise), bias, bias_dim, int((~keep).sum())), flush=True)


if __name__ == "__main__":
    main()
