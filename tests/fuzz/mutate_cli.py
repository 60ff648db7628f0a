#!/usr/bin/env python3
"""Mutation campaign through the weft command: renders mutated copies of one
input file (bit flips, cuts, random blocks, extreme 32-bit values, anywhere
or within the first --head bytes) at 32x32 and reports every run that was
slow (> 2 s), crashed (exit other than 0 or 1), printed more than one line,
or printed a library's text. Flagged inputs are kept in --keep.

  python3 tests/fuzz/mutate_cli.py FILE [--runs 100] [--seed 1] [--head 2048] [--keep DIR] [--weft build/bin/weft]
"""
import argparse
import os
import random
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LIBRARY_WORDS = ("ioerror", "typeerror", "runtimeerror", "valueerror", "keyerror", "bad_alloc", "std::", "exception",
                 "iex", "json.exception")
EXTREMES = (b"\xff\xff\xff\x7f", b"\x00\x00\x00\x80", b"\xff\xff\xff\xff", b"\x00\x00\x00\x00")


def mutate(data, rng, region):
    b = bytearray(data)
    kind = rng.choice(["flip", "cut", "block", "extreme"])
    at = lambda: rng.randrange(min(region, len(b)))
    if kind == "flip":
        for _ in range(rng.randint(1, 8)):
            b[at()] ^= 1 << rng.randrange(8)
    elif kind == "cut":
        b = b[:rng.randrange(len(b))]
    elif kind == "block":
        p = at()
        b[p:p + 16] = bytes(rng.randrange(256) for _ in range(min(16, len(b) - p)))
    else:
        p = at()
        b[p:p + 4] = rng.choice(EXTREMES)
    return kind, bytes(b)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("input")
    ap.add_argument("--runs", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--head", type=int, default=0, help="mutate only the first N bytes (0: anywhere)")
    ap.add_argument("--keep", default="mutations")
    ap.add_argument("--weft", default=os.path.join(ROOT, "build", "bin", "weft"))
    a = ap.parse_args()
    data = open(a.input, "rb").read()
    rng = random.Random(a.seed)
    ext = os.path.splitext(a.input)[1]
    os.makedirs(a.keep, exist_ok=True)
    path, out = os.path.join(a.keep, "current" + ext), os.path.join(a.keep, "out.exr")
    flagged = 0
    for i in range(a.runs):
        kind, mutated = mutate(data, rng, a.head or len(data))
        with open(path, "wb") as f:
            f.write(mutated)
        start = time.time()
        try:
            r = subprocess.run([a.weft, "render", path, "--res", "32x32", "-o", out], capture_output=True, timeout=20)
            status, err = r.returncode, r.stderr.decode("utf-8", "replace").strip()
        except subprocess.TimeoutExpired:
            status, err = "timeout", ""
        seconds = time.time() - start
        flags = (["slow %.1f s" % seconds] if seconds > 2 else []) + (["exit %s" % status] if status not in (0, 1) else [])
        flags += ["%d lines" % (err.count("\n") + 1)] if "\n" in err else []
        flags += [w for w in LIBRARY_WORDS if w in err.lower()]
        if flags:
            flagged += 1
            with open(os.path.join(a.keep, "flagged_%d_%d%s" % (a.seed, i, ext)), "wb") as f:
                f.write(mutated)
            print("%d %s %s %s" % (i, kind, ", ".join(flags), err[:200]), flush=True)
    print("%d runs, %d flagged" % (a.runs, flagged))
    sys.exit(1 if flagged else 0)


if __name__ == "__main__":
    main()
