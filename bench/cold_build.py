#!/usr/bin/env python3
"""How long a newcomer waits for the `weft` executable: a build of the
`weft` target and its modules (what scripts/demo.sh builds) from an empty
build folder, ccache off, on every core. Prints the wall time, the
compilers' CPU time, and the translation units that cost the most.

    /usr/bin/python3 bench/cold_build.py [--jobs N] [--top K] [--keep DIR]

Not part of `make bench` (it takes minutes): `make bench-build`.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def shown(src):
    """A source as the tree names it; a generated one by its file name."""
    rel = os.path.relpath(src, ROOT)
    return os.path.basename(src) if rel.startswith("..") else rel


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--top", type=int, default=12, help="how many of the costliest files to list")
    ap.add_argument("--keep", help="build here and keep it (default: a temporary folder, removed)")
    args = ap.parse_args()
    if shutil.which("cmake") is None:
        sys.exit("cold_build: cmake is not on PATH")
    build = args.keep or tempfile.mkdtemp(prefix="weft-cold-build.")
    if os.path.exists(os.path.join(build, "CMakeCache.txt")):
        sys.exit(f"cold_build: {build} already holds a build; name an empty folder")
    log = os.path.join(build, "compile-times.txt")
    os.makedirs(build, exist_ok=True)
    # /usr/bin/time as the compiler launcher: one line per compile, CPU and
    # wall seconds and the command (no ccache: every file is compiled).
    launcher = f"/usr/bin/time;-a;-o;{log};-f;%U %S %e %C"
    env = dict(os.environ, CCACHE_DISABLE="1")
    try:
        t0 = time.monotonic()
        subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                        f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}", f"-DCMAKE_C_COMPILER_LAUNCHER={launcher}"],
                       check=True, env=env, stdout=subprocess.DEVNULL)
        t1 = time.monotonic()
        subprocess.run(["cmake", "--build", build, "-j", str(args.jobs), "--target", "weft"],
                       check=True, env=env, stdout=subprocess.DEVNULL)
        t2 = time.monotonic()
        rows = []
        for line in open(log, encoding="utf-8", errors="replace"):
            parts = line.split(None, 3)
            if len(parts) < 4 or not re.match(r"^[\d.]+$", parts[0]):
                continue
            # Sources, and the precompiled header's own compile (cmake_pch.hxx.cxx).
            src = next((a for a in parts[3].split() if a.endswith((".cpp", ".c", ".cxx"))), None)
            rows.append((float(parts[0]) + float(parts[1]), float(parts[2]), shown(src) if src else "(link)"))
        cpu = sum(r[0] for r in rows)
        compiles = [r for r in rows if r[2] != "(link)"]
        print(f"cold build of weft, {args.jobs} jobs, ccache off")
        print(f"  configure {t1 - t0:7.1f} s")
        print(f"  build     {t2 - t1:7.1f} s wall, {cpu / 60:.1f} CPU-min in {len(compiles)} compiles and "
              f"{len(rows) - len(compiles)} links")
        print(f"  costliest files (CPU s):")
        for c, w, src in sorted(compiles, reverse=True)[:args.top]:
            print(f"    {c:7.1f}  {src}")
        by_folder = {}
        for c, _, src in compiles:
            top = "/".join(src.split("/")[:2])
            by_folder[top] = by_folder.get(top, 0.0) + c
        print("  by folder (CPU s): " + ", ".join(f"{k} {v:.0f}" for k, v in sorted(by_folder.items(), key=lambda kv: -kv[1])))
    finally:
        if not args.keep:
            shutil.rmtree(build, ignore_errors=True)


if __name__ == "__main__":
    main()
