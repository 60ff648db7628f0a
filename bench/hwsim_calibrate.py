#!/usr/bin/python3
"""Calibrates a hwsim profile's cost model against measured times.

  /usr/bin/python3 bench/hwsim_calibrate.py --driver llvmpipe     # runs weft_gl_probe on Mesa llvmpipe
  /usr/bin/python3 bench/hwsim_calibrate.py --driver softpipe
  /usr/bin/python3 bench/hwsim_calibrate.py --measured h200.json --profile nvidia-h200 --base modern-desktop
  /usr/bin/python3 bench/hwsim_calibrate.py --measured a.json,b.json,c.json --profile mesa-softpipe

Times come from weft_gl_probe (each timed run of each replay, size and
variant: the process's CPU time for Mesa's software drivers, GL_TIME_ELAPSED
or wall time otherwise), a variant's time the fastest of its runs over every
probe file given (--statistic median for the median),
counts from `weft hwsim REPLAY --stats` at the same sizes and parameters. The
cost terms (ns per count of a few counters, hwsim/cost_model.hpp) are fitted
by non-negative least squares on relative errors, written into the profile's
"cost_model", and the speed-ups they predict are stored in
hwsim/profiles/calibration/<profile>.json, which the default tests recompute
from hwsim's counts (tests/hwsim/cost_model_test.cpp). Prints: variant, size,
measured ms, predicted ms, measured and predicted speed-up, error %.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.optimize import nnls

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROFILES = os.path.join(ROOT, "hwsim", "profiles")
TERMS = ["passes", "fragments.generated", "fragment_program.invocations", "fragment_program.cost", "texture.scattered_fetches"]
BASELINE = {"segovia.table1": "none", "keller.stipple": "supersampled"}
DRIVER_PROFILE = {"llvmpipe": "mesa-llvmpipe", "softpipe": "mesa-softpipe"}


def fail(why):
    print(f"hwsim_calibrate: {why}", file=sys.stderr)
    sys.exit(1)


def mesa_env(driver):
    env = dict(os.environ, GALLIUM_DRIVER=driver, LIBGL_ALWAYS_SOFTWARE="1", EGL_PLATFORM="surfaceless")
    vendor = "/usr/share/glvnd/egl_vendor.d/50_mesa.json"  # Mesa's EGL even where a GPU vendor's is installed
    if os.path.exists(vendor):
        env["__EGL_VENDOR_LIBRARY_FILENAMES"] = vendor
    return env


def run_probe(args):
    probe = args.probe
    if not os.access(probe, os.X_OK):
        fail(f"no weft_gl_probe at {probe} (cmake --build build --target weft_gl_probe, or --probe PATH)")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "probe.json")
        cmd = [probe, "--sizes", args.sizes, "--repeats", str(args.repeats), "--warmup", str(args.warmup), "--out", out]
        print("running:", " ".join(cmd), f"(GALLIUM_DRIVER={args.driver})", file=sys.stderr)
        r = subprocess.run(cmd, env=mesa_env(args.driver))
        if r.returncode != 0:
            fail(f"weft_gl_probe failed (exit {r.returncode})")
        with open(out) as f:
            measured = json.load(f)
        if args.save_measured:
            atomic_write(args.save_measured, json.dumps(measured, indent=1) + "\n")
        return measured


def read_measured(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"cannot read --measured {path}: {e}")


STATISTICS = {"min": min, "median": lambda v: float(np.median(v))}


def merged(runs, statistic):
    """Several probe processes as one: each variant's time the statistic
    (min or median) of its runs in every process, pooled. A shared machine's
    noise only ever adds time, and a software GL's time for one variant can
    sit 20-60% high for a whole process (in 2 of 3 processes at 1024 on
    softpipe, a different variant each time), so one process's median is not
    enough to calibrate on: the fastest run is the least disturbed one."""
    out = dict(runs[0], results=[])
    for m in runs[0]["results"]:
        key = (m["replay"], m["size"], m["variant"])
        same = [r for run in runs for r in run["results"] if (r["replay"], r["size"], r["variant"]) == key]
        if len(same) != len(runs):
            fail(f"{key[0]} {key[1]} {key[2]} is not in every --measured file")
        row = dict(m)
        for clock, runs_key in (("cpu_ms", "cpu_ms_runs"), ("gpu_ms", "gpu_ms_runs"), ("median_ms", "wall_ms")):
            pooled = [t for r in same for t in (r.get(runs_key) or [])]
            if pooled and all(t is not None for t in pooled):
                row[clock] = STATISTICS[statistic](pooled)
                row[runs_key] = pooled
        out["results"].append(row)
    return out


def hwsim_counts(weft, profile, replay, size, params):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        cmd = [weft, "hwsim", replay, "--profile", profile, "--set", f"width={size}", "--set", f"height={size}", "--stats", stats]
        for k, v in params.get(replay, {}).items():
            cmd += ["--set", f"{k}={v}"]
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL)
        if r.returncode != 0:
            fail(f"{' '.join(cmd)} failed (exit {r.returncode})")
        with open(stats) as f:
            return json.load(f)["variants"]


def clock_of(measured, choice):
    """cpu for a software GL (its work, robust on a shared machine); else the
    GPU's GL_TIME_ELAPSED where the probe had timer queries; else wall."""
    if choice != "auto":
        return choice
    renderer = measured.get("renderer", "")
    if "llvmpipe" in renderer or "softpipe" in renderer:
        return "cpu"
    return "gpu" if measured.get("timer_queries") else "wall"


def collect(measured, weft, profile, clock):
    """Rows of (replay, size, variant, measured ms, spread %, counts)."""
    rows, counts = [], {}
    for m in measured["results"]:
        key = (m["replay"], m["size"])
        if key not in counts:
            counts[key] = hwsim_counts(weft, profile, m["replay"], m["size"], measured.get("params", {}))
        if m["variant"] not in counts[key]:
            fail(f"hwsim's {m['replay']} has no variant '{m['variant']}'")
        ms, runs = {"cpu": (m.get("cpu_ms"), m.get("cpu_ms_runs")), "gpu": (m.get("gpu_ms"), m.get("gpu_ms_runs")),
                    "wall": (m["median_ms"], m["wall_ms"])}[clock]
        if ms is None or ms <= 0:
            fail(f"the measured file has no {clock} time for {m['replay']} {m['size']} {m['variant']} (--clock wall)")
        spread = 100.0 * (max(runs) - min(runs)) / ms if runs else 0.0
        rows.append(dict(replay=m["replay"], size=m["size"], variant=m["variant"], measured_ms=ms,
                         spread_pct=spread, counts=counts[key][m["variant"]]))
    return rows


def fit(rows, fit_replays):
    used = [r for r in rows if r["replay"] in fit_replays]
    if len(used) < len(TERMS):
        fail(f"{len(used)} measurements cannot fit {len(TERMS)} terms")
    a = np.array([[r["counts"].get(t, 0) / r["measured_ms"] for t in TERMS] for r in used], dtype=float)
    scale = a.max(axis=0)
    scale[scale == 0] = 1
    x, _ = nnls(a / scale, np.ones(len(used)))  # relative error of each time
    return {t: float(v) * 1e6 for t, v in zip(TERMS, x / scale)}  # ns per count


def predict(ns_per, counts):
    return sum(ns_per[t] * counts.get(t, 0) for t in ns_per) * 1e-6


def speedups(rows, ns_per):
    base = {}
    for r in rows:
        r["predicted_ms"] = predict(ns_per, r["counts"])
        if r["variant"] == BASELINE.get(r["replay"]):
            base[(r["replay"], r["size"])] = r
    for r in rows:
        b = base.get((r["replay"], r["size"]))
        r["measured_speedup"] = b["measured_ms"] / r["measured_ms"] if b else float("nan")
        r["predicted_speedup"] = b["predicted_ms"] / r["predicted_ms"] if b and r["predicted_ms"] > 0 else float("nan")
        r["error_pct"] = 100.0 * (r["predicted_speedup"] / r["measured_speedup"] - 1)


def print_table(rows, renderer, clock, statistic):
    print(f"renderer: {renderer}; measured: {statistic} {clock} time of the runs; spread: (max - min) / measured")
    print(f"{'replay':16s} {'size':>5s} {'variant':14s} {'measured ms':>12s} {'predicted ms':>12s} "
          f"{'meas. x':>8s} {'pred. x':>8s} {'error %':>8s} {'spread %':>8s}")
    for r in rows:
        print(f"{r['replay']:16s} {r['size']:5d} {r['variant']:14s} {r['measured_ms']:12.3f} {r['predicted_ms']:12.3f} "
              f"{r['measured_speedup']:8.3f} {r['predicted_speedup']:8.3f} {r['error_pct']:+8.1f} {r['spread_pct']:8.1f}")
    seg = [abs(r["error_pct"]) for r in rows if r["replay"] == "segovia.table1"]
    if seg:
        print(f"segovia.table1: largest speed-up error {max(seg):.1f}% (target 15%)")


def profile_path(profile, base):
    """The profile's file; a new one copies --base's behaviour keys."""
    path = os.path.join(PROFILES, profile + ".json")
    if os.path.exists(path):
        return path
    if not base:
        fail(f"no profile file {path} (to make one, name --base PROFILE whose behaviour keys it copies)")
    with open(profile_path(base, None)) as f:
        prof = json.load(f)
    prof["name"], prof["description"] = profile, f"{profile}: the behaviour of {base} with its own measured cost model"
    atomic_write(path, json.dumps(prof, indent=2) + "\n")
    return path


def write_profile(path, calibration, ns_per):
    with open(path) as f:
        prof = json.load(f)
    prof["cost_model"] = {"calibration": calibration, "ns_per": {t: float(f"{v:.6g}") for t, v in ns_per.items()}}
    lines = []
    for k, v in prof.items():
        if k == "cost_model":
            terms = ",\n".join(f"      {json.dumps(t)}: {json.dumps(x)}" for t, x in v["ns_per"].items())
            lines.append(f'  "cost_model": {{\n    "calibration": {json.dumps(v["calibration"])},\n    "ns_per": {{\n{terms}\n    }}\n  }}')
        else:
            lines.append(f"  {json.dumps(k)}: {json.dumps(v)}")
    atomic_write(path, "{\n" + ",\n".join(lines) + "\n}\n")
    return prof["cost_model"]["ns_per"]


def atomic_write(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_record(profile, measured, rows, command, clock):
    os.makedirs(os.path.join(PROFILES, "calibration"), exist_ok=True)
    keep = ["replay", "size", "variant", "measured_ms", "spread_pct", "predicted_ms", "measured_speedup", "predicted_speedup"]
    record = {"profile": profile, "renderer": measured.get("renderer", ""), "command": command, "clock": clock,
              "params": measured.get("params", {}),
              "rows": [{k: (round(r[k], 6) if isinstance(r[k], float) else r[k]) for k in keep} for r in rows]}
    atomic_write(os.path.join(PROFILES, "calibration", profile + ".json"), json.dumps(record, indent=1) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--driver", choices=sorted(DRIVER_PROFILE), help="measure with this Mesa driver now")
    ap.add_argument("--measured", help="weft_gl_probe --out files measured elsewhere, comma list: their runs pooled (needs --profile)")
    ap.add_argument("--profile", help="profile to calibrate (default: the driver's)")
    ap.add_argument("--base", help="for a --profile without a file: the profile whose behaviour keys it copies")
    ap.add_argument("--sizes", default="512,1024")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--warmup", type=int, default=1)
    ap.add_argument("--fit", default="segovia.table1", help="replays whose times the terms are fitted to (comma list)")
    ap.add_argument("--probe", default=os.path.join(ROOT, "build", "bin", "weft_gl_probe"))
    ap.add_argument("--weft", default=os.path.join(ROOT, "build", "bin", "weft"))
    ap.add_argument("--clock", choices=["auto", "cpu", "gpu", "wall"], default="auto",
                    help="measured time: process CPU, GL_TIME_ELAPSED or wall (auto: cpu for llvmpipe/softpipe, else gpu if timed)")
    ap.add_argument("--save-measured", help="with --driver: also keep the probe's output here (for --measured later)")
    ap.add_argument("--statistic", choices=sorted(STATISTICS), default="min",
                    help="a variant's time over every run of every process (default min: noise only adds time)")
    ap.add_argument("--dry-run", action="store_true", help="print the table, write nothing")
    args = ap.parse_args()
    if bool(args.driver) == bool(args.measured):
        fail("give exactly one of --driver or --measured")
    profile = args.profile or (DRIVER_PROFILE[args.driver] if args.driver else None)
    if not profile:
        fail("--measured needs --profile NAME")
    path = profile_path(profile, args.base)
    if args.measured:
        measured = merged([read_measured(path) for path in args.measured.split(",")], args.statistic)
    else:
        measured = merged([run_probe(args)], args.statistic)
    clock = clock_of(measured, args.clock)
    rows = collect(measured, args.weft, path, clock)  # the file: a new profile is not built in yet
    ns_per = fit(rows, set(args.fit.split(",")))
    ns_per = {t: float(f"{v:.6g}") for t, v in ns_per.items()}
    speedups(rows, ns_per)
    print_table(rows, measured.get("renderer", "?"), clock, args.statistic)
    print("ns per count: " + ", ".join(f"{t} {v:.4g}" for t, v in ns_per.items()))
    if args.dry_run:
        return
    source = f"--driver {args.driver}" if args.driver else "--measured " + ",".join(os.path.basename(p) for p in args.measured.split(","))
    command = f"bench/hwsim_calibrate.py {source} --profile {profile} --statistic {args.statistic}"
    when = datetime.date.today().isoformat()
    write_profile(path, f"calibrated {when} ({args.statistic} {clock} time) on {measured.get('renderer', '?')} by {command}", ns_per)
    write_record(profile, measured, rows, command, clock)
    print(f"wrote {os.path.relpath(path, ROOT)} and hwsim/profiles/calibration/{profile}.json")


if __name__ == "__main__":
    main()
