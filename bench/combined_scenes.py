#!/usr/bin/env python3
"""Volumes and meshes together: per combined scene (scenes/combined/) and
technique, the render time and the RMSE against a reference, as a Markdown
table (and pictures with --pictures DIR).

References: volume.singlescatter (physical=true: the path tracer's conventions) is measured
against the volumetric path tracer restricted to single scattering
(mesh.pathtrace max_depth=1, many samples); volume.raymarch, an
emission-absorption model with no counterpart in the path tracer, against
itself at a step ten times finer, and so are volume.preint and
volume.adaptive3d (the same emission-absorption model); mesh.pathtrace at its default depth against
itself at four times the samples.

  /usr/bin/python3 bench/combined_scenes.py [--res 128x96] [--ref-spp 256] [--pictures docs/images]
"""
import argparse
import os
import shutil
import subprocess
import tempfile

from benchlib import ROOT, WEFT, rmse, run_timed

SCENES = ["smoke_in_cornell", "smoke_over_ground", "ct_stent", "two_volumes"]


class Refused(Exception):
    """The technique does not render this scene (its one-line error)."""


def render_args(scene, out, technique, res, spp, sets):
    args = [WEFT, "render", os.path.join(ROOT, "scenes", "combined", scene + ".json"), "--technique", technique,
            "--res", res, "--spp", str(spp), "-o", out]
    for s in sets:
        args += ["--set", s]
    return args


def render(scene, out, technique, res, spp, sets, preview=None):
    """Seconds of one render; Refused when the technique does not render the scene."""
    args = render_args(scene, out, technique, res, spp, sets) + (["--preview", preview] if preview else [])
    probe = subprocess.run(render_args(scene, out, technique, "4x4", 1, sets), capture_output=True, text=True)
    if probe.returncode != 0:
        raise Refused(probe.stderr.strip().replace("weft: error: ", ""))
    seconds, _ = run_timed(args)
    return seconds


def picture(a, scene, name):
    return os.path.join(a.pictures, "combined_%s_%s.png" % (scene, name)) if a.pictures else None


def reference(scene, out, technique, a, spp, sets, preview=None):
    """The reference's path, or None when its technique refuses the scene."""
    try:
        render(scene, out, technique, a.res, spp, sets, preview)
        return out
    except Refused:
        return None


def rows_for(scene, tmp, a):
    ref_ss = reference(scene, os.path.join(tmp, scene + "_ref_single.exr"), "mesh.pathtrace", a, a.ref_spp, ["max_depth=1"])
    cases = [
        ("volume.singlescatter", ["physical=true", "estimator=ratio"], a.spp, ref_ss, "path tracer, single scattering", None),
        ("volume.singlescatter", ["physical=true"], a.spp, ref_ss, "path tracer, single scattering", picture(a, scene, "singlescatter")),
        ("mesh.pathtrace", ["max_depth=1"], a.spp, ref_ss, "path tracer, single scattering", None),
    ]
    ref_rm = reference(scene, os.path.join(tmp, scene + "_ref_raymarch.exr"), "volume.raymarch", a, 1, ["step=0.05"])
    cases.append(("volume.raymarch", ["step=0.5"], 1, ref_rm, "raymarch, step 0.05", picture(a, scene, "raymarch")))
    cases.append(("volume.raymarch", ["step=2"], 1, ref_rm, "raymarch, step 0.05", None))
    cases.append(("volume.preint", [], 1, ref_rm, "raymarch, step 0.05", None))
    cases.append(("volume.adaptive3d", [], 1, ref_rm, "raymarch, step 0.05", None))
    ref_pt = reference(scene, os.path.join(tmp, scene + "_ref_multi.exr"), "mesh.pathtrace", a, a.ref_spp, [],
                       picture(a, scene, "pathtrace"))
    cases.append(("mesh.pathtrace", [], a.ref_spp // 4, ref_pt, "path tracer, %d spp" % a.ref_spp, None))
    rows = []
    for i, (technique, sets, spp, ref, against, preview) in enumerate(cases):
        out = os.path.join(tmp, "%s_%d.exr" % (scene, i))
        settings = " ".join(sets) or "defaults"
        try:
            seconds = render(scene, out, technique, a.res, spp, sets, preview)
        except Refused as e:
            rows.append("| %s | %s | %s | %d | refused | | %s |" % (scene, technique, settings, spp, e))
            continue
        error = "%.2g" % rmse(out, ref) if ref else "no reference"
        rows.append("| %s | %s | %s | %d | %.2f | %s | %s |" % (scene, technique, settings, spp, seconds, error, against))
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--res", default="128x96")
    p.add_argument("--spp", type=int, default=16, help="samples per pixel of the measured renders")
    p.add_argument("--ref-spp", type=int, default=256, help="samples per pixel of the path-traced references")
    p.add_argument("--scenes", default=",".join(SCENES))
    p.add_argument("--pictures", help="write PNG previews of each scene's renders here")
    a = p.parse_args()
    tmp = tempfile.mkdtemp(prefix="weft-combined-")
    try:
        print("| scene | technique | settings | spp | time (s) | RMSE | against |")
        print("|---|---|---|---|---|---|---|")
        for scene in a.scenes.split(","):
            for row in rows_for(scene, tmp, a):
                print(row, flush=True)
    finally:
        shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
