#!/usr/bin/env python3
"""Run a parameter grid through weft and gather every run's stats into one CSV.

    sweep.py INPUT --vary step=0.25,0.5,1 --vary spp=1,4 --out DIR [--csv FILE] [-- RENDER OPTIONS]

Every combination of the --vary values is one render (DIR/run_NNN.exr with
DIR/run_NNN.json from --stats). Keys spp, seed, res and technique set those
render options; any other key is a technique parameter (--set key=value).
The CSV (default DIR/sweep.csv) has one row per run: run, exit status, the
varied values, then every field of the stats JSON flattened with dots
(technique, resolution, params.*, counters.*, timings_ms.*). It is written
to a temporary name and renamed, so a killed sweep leaves no partial CSV.
"""

import argparse
import csv
import itertools
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weftpipe  # noqa: E402
from weftpipe import PipelineError  # noqa: E402

OPTION_KEYS = {"spp": "--spp", "seed": "--seed", "res": "--res", "technique": "--technique"}


def parse_vary(items):
    axes = []
    for item in items:
        key, sep, values = item.partition("=")
        if not sep or not key or not values or "" in values.split(","):
            raise PipelineError("--vary '%s': expected key=v1,v2,..." % item)
        if key in (k for k, _ in axes):
            raise PipelineError("--vary %s given twice" % key)
        axes.append((key, values.split(",")))
    return axes


def run_args(combo):
    out = []
    for key, value in combo:
        out += [OPTION_KEYS[key], value] if key in OPTION_KEYS else ["--set", "%s=%s" % (key, value)]
    return out


def flatten(prefix, value, row):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(prefix + "." + k if prefix else k, v, row)
    elif isinstance(value, list):
        row[prefix] = "x".join(str(v) for v in value)
    else:
        row[prefix] = value


def write_csv(path, rows, first_columns):
    columns = list(first_columns)
    for row in rows:
        columns += [k for k in row if k not in columns]
    tmp = os.path.join(os.path.dirname(path) or ".", "." + os.path.basename(path) + ".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("input", help="scene .json, .vdb or builtin:NAME")
    p.add_argument("--vary", action="append", required=True, help="key=v1,v2,... (repeatable: the grid is their product)")
    p.add_argument("--out", required=True, help="folder for the runs' EXR and stats")
    p.add_argument("--csv", help="CSV to write (default OUT/sweep.csv)")
    p.add_argument("--weft", help="weft executable (default $WEFT, else weft on PATH)")
    mine, extra = weftpipe.split_at_dashes(sys.argv[1:])
    args = p.parse_args(mine)
    axes = parse_vary(args.vary)
    weft = weftpipe.weft_binary(args.weft)
    os.makedirs(args.out, exist_ok=True)
    rows, failed = [], 0
    combos = list(itertools.product(*[[(k, v) for v in values] for k, values in axes]))
    for n, combo in enumerate(combos, 1):
        name = os.path.join(args.out, "run_%03d" % n)
        cmd = [weft, "render", args.input] + extra + run_args(combo) + ["-o", name + ".exr", "--stats", name + ".json"]
        res = subprocess.run(cmd, capture_output=True, text=True)
        row = {"run": n, "status": res.returncode}
        row.update({k: v for k, v in combo})
        if res.returncode == 0:
            with open(name + ".json") as f:
                flatten("", json.load(f), row)
        else:
            failed += 1
            print("sweep: run %d (%s) failed: %s" % (n, " ".join(run_args(combo)), res.stderr.strip()), file=sys.stderr)
        rows.append(row)
    out_csv = args.csv or os.path.join(args.out, "sweep.csv")
    write_csv(out_csv, rows, ["run", "status"] + [k for k, _ in axes])
    print("sweep: %d runs, %d failed -> %s" % (len(rows), failed, out_csv))
    return 1 if failed else 0


if __name__ == "__main__":
    weftpipe.main_guard("sweep", main)
