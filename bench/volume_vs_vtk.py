#!/usr/bin/python3
"""weft's volume techniques against VTK's CPU ray caster, side by side.

The aneurism (scenes/aneurism.json) through VTK 9's vtkFixedPointVolumeRayCastMapper
and weft, with weft's camera (Camera::framing), transfer function, resolution and
threads. Prints each setting's render time (median, no data loading: weft's stats
`render`, VTK's renWin.Render()) and RMSE/PSNR (`weft diff`, RGBA) against
volume.raymarch step=0.1 at --ref-spp samples per pixel (default 1, pixel centres
like every row; at weft's converged 256, aliasing would dominate every row).

Compared linear and premultiplied, as weft's EXR. VTK is read twice: its ray-cast
image (15-bit fixed point, before display) and the screen (8-bit over black, that
image resampled as a texture); VTK applies no display transform. Opacity: weft's
h voxels have 1 - exp(-extinction h); VTK gets 1 - exp(-extinction) per voxel.
Installs python3-vtk9 and xvfb with apt-get when VTK is missing, and re-runs under
xvfb-run when DISPLAY is unset (Debian's VTK needs X, offscreen too).

Usage: /usr/bin/python3 bench/volume_vs_vtk.py [--data DIR] [--out DIR] [--res WxH] [--threads N]
                                              [--repeat N] [--ref-spp N]
"""
import argparse
import gzip
import importlib.util
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError:
    sys.exit("bench: numpy or OpenImageIO missing (run with /usr/bin/python3)")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import ROOT, WEFT, diff_all, headline, prepare_aneurism, run  # noqa: E402

WEFT_SETTINGS = [  # (technique, --set values), at spp 1: every volume technique's default
    ("volume.raymarch", ["step=1"]), ("volume.raymarch", ["step=1", "skip_empty=true"]),
    ("volume.preint", []), ("volume.adaptive3d", ["oracle=gradient_alpha"]),
    ("volume.raymarch", ["step=0.8", "skip_empty=true"]),
    ("volume.raymarch", ["step=0.5", "skip_empty=true"]), ("volume.preint", ["spacing=0.5"]),
    ("volume.adaptive3d", ["oracle=gradient_alpha", "spacing=0.5"]),
]


def have_vtk():
    importlib.invalidate_caches()  # python3-vtk9 may have just been installed
    return importlib.util.find_spec("vtk") is not None


def ensure_vtk_and_display():
    if not (have_vtk() and (os.environ.get("DISPLAY") or shutil.which("xvfb-run"))):
        print("bench: installing VTK: apt-get install -y --no-install-recommends python3-vtk9 xvfb", flush=True)
        if subprocess.run(["apt-get", "install", "-y", "--no-install-recommends", "python3-vtk9", "xvfb"],
                          stdout=subprocess.DEVNULL).returncode != 0 or not have_vtk():
            sys.exit("bench: cannot install python3-vtk9 and xvfb with apt-get (as root on Debian 12), or import vtk")
    if not (os.environ.get("DISPLAY") or os.environ.get("WEFT_BENCH_XVFB")):
        os.environ["WEFT_BENCH_XVFB"] = "1"  # no second re-run if Xvfb sets no DISPLAY
        os.execvp("xvfb-run", ["xvfb-run", "-a", "-s", "-screen 0 1024x1024x24", sys.executable] + sys.argv)


def weft_camera(data, aspect):
    """Camera::framing of the non-zero (active) voxels padded by one, to their faces (voxel size 1, origin 0)."""
    nz = [np.flatnonzero(data.any(axis=axes)) for axes in ((0, 1), (0, 2), (1, 2))]  # x, y, z
    lo, hi = np.array([n[0] for n in nz]) - 1.5, np.array([n[-1] for n in nz]) + 1.5
    center, extent = (lo + hi) / 2, (hi - lo) / 2
    distance = extent[2] + 1.1 * max(extent[0] / aspect, extent[1]) / np.tan(np.radians(20.0))  # fov 40
    return center + [0, 0, distance], center


def write_exr(path, rgba):
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(rgba.shape[1], rgba.shape[0], 4, oiio.FLOAT)  # channels R, G, B, A
    if not (out and out.open(path, spec) and out.write_image(np.ascontiguousarray(rgba, np.float32)) and out.close()):
        sys.exit("bench: cannot write %s: %s" % (path, oiio.geterror()))


def vtk_render(data, tf, eye, target, sample_distance, a, w, h):
    """(median seconds, ray-cast image EXR, screen EXR) of VTK's fixed-point mapper."""
    import ctypes
    import vtk
    from vtk.util import numpy_support
    img = vtk.vtkImageData()  # point data: voxel i at world i, as the VDB's voxel centres
    img.SetDimensions(data.shape[2], data.shape[1], data.shape[0])
    img.GetPointData().SetScalars(numpy_support.numpy_to_vtk(data.ravel(), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR))
    (lo, hi), pts = tf["range"], tf["points"]
    color, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
    for p in pts:  # weft's colour is linear in the value between points, as VTK's (in RGB space)
        color.AddRGBPoint(lo + p["s"] * (hi - lo), *p["color"])
    # Extinction is linear, opacity 1 - exp(-extinction) is not: one point per data value.
    for v in range(256):
        s = np.clip((v - lo) / (hi - lo), 0, 1)
        opacity.AddPoint(v, 1 - np.exp(-np.interp(s, [p["s"] for p in pts], [p["extinction"] for p in pts])))
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color), prop.SetScalarOpacity(opacity), prop.SetScalarOpacityUnitDistance(1.0)
    prop.ShadeOff(), prop.SetInterpolationTypeToLinear()
    vtk.vtkMultiThreader.SetGlobalMaximumNumberOfThreads(a.threads)
    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(img), mapper.SetNumberOfThreads(a.threads), mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(sample_distance), mapper.SetImageSampleDistance(1.0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper), volume.SetProperty(prop)
    ren, win = vtk.vtkRenderer(), vtk.vtkRenderWindow()
    ren.SetBackground(0, 0, 0), ren.AddVolume(volume)
    win.SetOffScreenRendering(1), win.SetSize(w, h), win.AddRenderer(ren)
    cam = ren.GetActiveCamera()
    cam.SetPosition(*eye), cam.SetFocalPoint(*target), cam.SetViewUp(0, 1, 0), cam.SetViewAngle(40.0)
    ren.ResetCameraClippingRange()
    win.Render()  # warm-up: buffers, tables, space-leaping volume
    times = []
    for _ in range(max(5, a.repeat)):
        mapper.Modified()  # nothing reused (each Render() casts every ray anyway, as timed)
        start = time.perf_counter()
        win.Render()
        times.append(time.perf_counter() - start)
    tag = os.path.join(a.out, "vtk_sample%g" % sample_distance)
    # The mapper's image before display: 4 x 15-bit premultiplied RGBA; the wrapper
    # hands its pointer out as text ('_<hex>_p_void').
    rc = mapper.GetRayCastImage()
    (mw, mh), (uw, uh), (ox, oy) = rc.GetImageMemorySize(), rc.GetImageInUseSize(), rc.GetImageOrigin()
    raw = (ctypes.c_ushort * (mw * mh * 4)).from_address(int(rc.GetImage().split("_")[1], 16))
    cast = np.zeros((h, w, 4), np.float32)
    cast[oy:oy + uh, ox:ox + uw] = np.frombuffer(raw, np.uint16).reshape(mh, mw, 4)[:uh, :uw] / 32767.0
    write_exr(tag + "_raycast.exr", cast[::-1])  # VTK's rows go bottom up
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win), grab.SetInputBufferTypeToRGBA(), grab.ReadFrontBufferOff(), grab.Update()
    screen = numpy_support.vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(h, w, 4)
    write_exr(tag + "_screen.exr", screen[::-1] / 255.0)
    return statistics.median(times), tag + "_raycast.exr", tag + "_screen.exr"


def weft_render(scene, name, technique, sets, a, spp=1, repeat=None):
    """(median render seconds, EXR) over `repeat` runs of weft render."""
    exr, stats = os.path.join(a.out, name + ".exr"), os.path.join(a.out, name + ".json")
    args = [WEFT, "render", scene, "--technique", technique, "--res", a.res, "--threads", str(a.threads),
            "--spp", str(spp), "-o", exr, "--stats", stats] + [x for s in sets for x in ("--set", s)]
    times = []
    for _ in range(repeat or a.repeat):
        run(args)
        with open(stats) as f:
            times.append(json.load(f)["timings_ms"]["render"] / 1000)
    return statistics.median(times), exr


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-vtk"))
    ap.add_argument("--res", default="512x512")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3, help="weft renders per setting (VTK: at least 5); the median counts")
    ap.add_argument("--ref-spp", type=int, default=1, help="samples per pixel of the step=0.1 reference")
    a = ap.parse_args()
    raw = os.path.join(a.data, "aneurism.raw.gz")
    if not os.path.exists(raw):
        sys.exit("bench: aneurism.raw.gz not found in %s (use --data DIR)" % a.data)
    ensure_vtk_and_display()
    os.makedirs(a.out, exist_ok=True)
    prepare_aneurism(a.data, a.out)
    scene = os.path.join(a.out, "aneurism.json")
    shutil.copyfile(os.path.join(ROOT, "scenes", "aneurism.json"), scene)  # beside the VDB it names
    with open(scene) as f:
        tf = json.load(f)["volumes"][0]["transfer_function"]
    t_ref, ref = weft_render(scene, "reference", "volume.raymarch", ["step=0.1"], a, spp=a.ref_spp, repeat=1)
    rows = []  # (renderer, setting, seconds, exr)
    for technique, sets in WEFT_SETTINGS:
        t, exr = weft_render(scene, "_".join([technique] + sets).replace("=", ""), technique, sets, a)
        rows.append(("weft", " ".join([technique] + sets), t, exr))
    with gzip.open(raw) as f:  # x fastest, as weft convert reads it
        data = np.frombuffer(f.read(), np.uint8).reshape(256, 256, 256)
    w, h = map(int, a.res.split("x"))
    eye, target = weft_camera(data, w / h)
    for d in (1.0, 0.5):  # voxels; the headline uses 1
        t, cast, screen = vtk_render(data, tf, eye, target, d, a, w, h)
        rows += [("VTK", "sample %g, ray-cast image" % d, t, cast), ("VTK", "sample %g, screen 8-bit" % d, t, screen)]

    print("\naneurism %s, %d threads; reference: volume.raymarch step=0.1 spp %d (%.1f s); camera eye %s target %s fov 40"
          % (a.res, a.threads, a.ref_spp, t_ref, np.round(eye, 3).tolist(), np.round(target, 3).tolist()))
    print("\n| renderer | setting | time (s) | RMSE vs weft reference | PSNR (dB) |\n|---|---|---:|---:|---:|")
    rows = [r + (diff_all(r[3], ref),) for r in rows]  # + (RMSE, relMSE, PSNR, SSIM, max abs)
    for who, setting, t, _, e in rows:
        print("| %s | %s | %.3f | %.5f | %.2f |" % (who, setting, t, e[0], e[2]))
    vtk_cast = rows[len(WEFT_SETTINGS)]
    same = diff_all(vtk_cast[3], rows[0][3])
    print("\nVTK sample 1 (ray-cast image) vs weft volume.raymarch step=1: RMSE %.5f, PSNR %.2f dB" % (same[0], same[2]))

    passing = [r for r in rows if r[0] == "weft" and r[4][0] <= 1 / 255]
    what = "weft's fastest volume technique at RMSE <= 1/255 vs VTK vtkFixedPointVolumeRayCastMapper, aneurism %s" % a.res
    best = min(passing, key=lambda r: r[2]) if passing else None
    ratio = vtk_cast[2] / best[2] if best else 0.0
    measured = ("weft %s %.3f s vs VTK %.3f s: %.2fx" % (best[1], best[2], vtk_cast[2], ratio) if best
                else "no weft setting reached RMSE <= 1/255 (VTK %.3f s)" % vtk_cast[2])
    headline(what, measured, ">= 2x faster than VTK", ratio >= 2)


if __name__ == "__main__":
    main()
