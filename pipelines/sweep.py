#!/usr/bin/env python3
"""The farm form of `weft sweep`: one task per run, merged into the same tables and plot.

    sweep.py --local -o DIR -- SWEEP ARGS
    sweep.py [--logs LOGS] [--partition P] [--time T] [--cpus-per-task N] [--max-running M] [--dry-run] -o DIR -- SWEEP ARGS

SWEEP ARGS are what `weft sweep` takes besides -o: the scene, --technique
and --vary groups, --reference REF.exr|auto, --repeat, --metric, --res ...
(docs/trade.md). `weft sweep ... --list` gives the number of runs N (every
run is checked there, so a bad --vary fails before anything is submitted);
then three jobs: `--prepare` renders the automatic references once, an
array of N tasks runs `--run K` each (DIR/runs/run-K.json), and `--merge`
writes DIR/sweep.csv, sweep.json, sweep.md and sweep.png from them, the
same tables a one-process `weft sweep` writes. On Slurm they are chained
with --dependency=afterok; --local runs them here one after the other.
"""

import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weftpipe  # noqa: E402
from weftpipe import PipelineError  # noqa: E402


def weft_sweep(weft, sweep_args, out, *extra):
    return [weft, "sweep"] + list(sweep_args) + ["-o", out] + list(extra)


def run_count(weft, sweep_args, out):
    res = subprocess.run(weft_sweep(weft, sweep_args, out, "--list"), capture_output=True, text=True)
    if res.returncode != 0:
        raise PipelineError((res.stderr.strip() or res.stdout.strip()).replace("weft: error: ", ""))
    first = res.stdout.split("\n", 1)[0]
    if not first.endswith(" runs"):
        raise PipelineError("weft sweep --list printed '%s'" % first)
    return int(first.split()[0])


def tasks(weft, sweep_args, out, count):
    """(name, command) of every task, in the order they must run."""
    yield "prepare", weft_sweep(weft, sweep_args, out, "--prepare")
    for k in range(1, count + 1):
        yield "run%d" % k, weft_sweep(weft, sweep_args, out, "--run", str(k))
    yield "merge", [weft, "sweep", "--merge", "-o", out] + (["--no-plot"] if "--no-plot" in sweep_args else [])


def job_script(args, name, body, array=None, dependency=None):
    lines = ["#!/bin/bash", "#SBATCH --job-name=%s" % name, "#SBATCH --cpus-per-task=%d" % args.cpus_per_task,
             "#SBATCH --output=%s" % os.path.join(args.logs, name + ("_%A_%a.log" if array else "_%j.log"))]
    if array:
        lines.append("#SBATCH --array=%s" % (array + ("%%%d" % args.max_running if args.max_running else "")))
    for flag, value in (("partition", args.partition), ("time", args.time)):
        if value:
            lines.append("#SBATCH --%s=%s" % (flag, value))
    if dependency:
        lines += ["#SBATCH --dependency=%s" % dependency, "#SBATCH --kill-on-invalid-dep=yes"]
    return "\n".join(lines + ["set -euo pipefail", body]) + "\n"


def submit(args, weft, sweep_args, count):
    threads = ' --threads "${SLURM_CPUS_PER_TASK:-1}"'
    prepare = "exec " + weftpipe.quote(weft_sweep(weft, sweep_args, args.out, "--prepare")) + threads
    run = "exec " + weftpipe.quote(weft_sweep(weft, sweep_args, args.out)) + ' --run "$SLURM_ARRAY_TASK_ID"' + threads
    merge = "exec " + weftpipe.quote([weft, "sweep", "--merge", "-o", args.out] + (["--no-plot"] if "--no-plot" in sweep_args else []))
    if args.dry_run:
        for name, text in (("prepare", job_script(args, args.name + ".prepare", prepare)),
                           ("runs", job_script(args, args.name + ".runs", run, "1-%d" % count, "afterok:PREPARE")),
                           ("merge", job_script(args, args.name + ".merge", merge, None, "afterok:RUNS"))):
            print("# %s\n%s" % (name, text))
        return 0
    os.makedirs(os.path.join(args.logs, "scripts"), exist_ok=True)

    def sbatch(name, text):
        path = os.path.join(args.logs, "scripts", name + ".sh")
        with open(path, "w") as f:
            f.write(text)
        res = subprocess.run(["sbatch", "--parsable", path], capture_output=True, text=True)
        if res.returncode != 0:
            raise PipelineError("sbatch %s failed: %s" % (path, res.stderr.strip() or res.stdout.strip()))
        return res.stdout.strip().split(";")[0]

    first = sbatch(args.name + ".prepare", job_script(args, args.name + ".prepare", prepare))
    runs = sbatch(args.name + ".runs", job_script(args, args.name + ".runs", run, "1-%d" % count, "afterok:" + first))
    last = sbatch(args.name + ".merge", job_script(args, args.name + ".merge", merge, None, "afterok:" + runs))
    print("\n".join((first, runs, last)))
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("-o", "--out", required=True, help="the sweep's folder")
    p.add_argument("--local", action="store_true", help="run the tasks here, one after the other")
    p.add_argument("--name", default="weft-sweep", help="job name (default weft-sweep)")
    p.add_argument("--logs", default="logs", help="folder of the task logs (default logs)")
    p.add_argument("--partition", help="Slurm partition")
    p.add_argument("--time", help="time limit per task, e.g. 00:30:00")
    p.add_argument("--cpus-per-task", type=int, default=1, help="cores per task; weft uses as many threads")
    p.add_argument("--max-running", type=int, help="at most this many run tasks at once (array %%N)")
    p.add_argument("--dry-run", action="store_true", help="print the sbatch scripts, submit nothing")
    p.add_argument("--weft", help="weft executable (default $WEFT, else weft on PATH)")
    mine, sweep_args = weftpipe.split_at_dashes(sys.argv[1:])
    args = p.parse_args(mine)
    if not sweep_args:
        raise PipelineError("nothing to sweep: give -- SCENE --technique ... --vary ... --reference ...")
    if "-o" in sweep_args or "--out" in sweep_args:
        raise PipelineError("-o belongs to sweep.py, before the --")
    weft = weftpipe.weft_binary(args.weft)
    weft = os.path.abspath(weft) if os.path.sep in weft else weft
    count = run_count(weft, sweep_args, args.out)
    if not args.local:
        return submit(args, weft, sweep_args, count)
    failed = weftpipe.run_local(list(tasks(weft, sweep_args, args.out, count)), os.path.join(args.out, "logs"))
    if failed:
        raise PipelineError("%d of %d tasks failed (logs in %s)" % (failed, count + 2, os.path.join(args.out, "logs")))
    print("sweep: %d runs -> %s" % (count, os.path.join(args.out, "sweep.csv")))
    return 0


if __name__ == "__main__":
    weftpipe.main_guard("sweep", main)
