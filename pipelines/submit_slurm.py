#!/usr/bin/env python3
"""Submit a weft frame range to Slurm as a job array, one task per frame.

    submit_slurm.py --frames 1001-1100x2 -o out/shot.#.exr [--tiles N] [options] -- INPUT [RENDER OPTIONS]

(A range starting with a minus sign is written --frames=-5--1.)

Array indices are the frame numbers when every frame is a valid index (>= 0
and below the cluster's MaxArraySize, 1001 by default in Slurm; set
MaxArraySize=100000 in slurm.conf for frames like 1001); otherwise (negative
frames, or frames past MaxArraySize) index i is frame FIRST + i, FIRST the
lowest frame, and the scripts add FIRST back. Each task runs
`weft render INPUT ... --frames FRAME -o OUTPUT` and logs to
LOGS/NAME_%A_%a.log (%A: array job id, %a: the array index). With --tiles N, each tile
is its own array (out/tiles/shot.#.tIofN.exr) and a merge array, one task per
frame, starts a frame's merge as soon as that frame's tiles are done
(--dependency=aftercorr on every tile array).

--dry-run prints the sbatch script(s) instead of submitting them. The job ids
are printed one per line, tile arrays first, the merge array last.
"""

import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weftpipe  # noqa: E402
from weftpipe import PipelineError  # noqa: E402


def add_submit_options(p):
    p.add_argument("-o", "--output", required=True, help="frame-numbered output EXR, e.g. out/shot.#.exr")
    p.add_argument("--tiles", type=int, default=1, help="split each frame into N row bands, merged after")
    p.add_argument("--name", default="weft", help="job name (default weft)")
    p.add_argument("--logs", default="logs", help="folder of the per-task logs (default logs)")
    p.add_argument("--weft", help="weft executable (default $WEFT, else weft on PATH)")
    p.add_argument("--partition", help="Slurm partition")
    p.add_argument("--cpus-per-task", type=int, default=1, help="cores per task; weft uses as many threads")
    p.add_argument("--time", help="time limit per task, e.g. 00:30:00")
    p.add_argument("--max-running", type=int, help="at most this many tasks at once (array %%N)")
    p.add_argument("--max-array-size", type=int, default=100000, help="the cluster's MaxArraySize (default 100000)")
    p.add_argument("--dry-run", action="store_true", help="print the sbatch script(s), submit nothing")


def render_args_of(args):
    rest = args.render_args
    if not rest:
        raise PipelineError("nothing to render: give -- INPUT [weft render options]")
    for flag in ("-o", "--output", "--frames", "--tile"):
        if flag in rest:
            raise PipelineError("%s belongs to the submit script, not to the render options" % flag)
    return rest


def index_base(frames, max_array_size):
    """The frame array index 0 stands for: 0 when frames are indices themselves, else the lowest frame."""
    if all(0 <= f < max_array_size for f in frames):
        return 0
    base = min(frames)
    if max(frames) - base >= max_array_size:
        raise PipelineError("frames %d to %d span more than MaxArraySize %d array indices; submit them in parts"
                            % (base, max(frames), max_array_size))
    return base


def header(args, name, array, log_dir, dependency=None):
    array += ("%%%d" % args.max_running) if args.max_running else ""
    lines = ["#!/bin/bash",
             "#SBATCH --job-name=%s" % name,
             "#SBATCH --array=%s" % array,
             "#SBATCH --output=%s" % os.path.join(log_dir, name + "_%A_%a.log"),
             "#SBATCH --cpus-per-task=%d" % args.cpus_per_task]
    if args.partition:
        lines.append("#SBATCH --partition=%s" % args.partition)
    if args.time:
        lines.append("#SBATCH --time=%s" % args.time)
    if dependency:
        lines.append("#SBATCH --dependency=%s" % dependency)
    frame = "$((SLURM_ARRAY_TASK_ID + %d))" % args.index_base if args.index_base else "$SLURM_ARRAY_TASK_ID"
    return lines + ["set -euo pipefail", "frame=" + frame]


def render_script(args, weft, render_args, array, tile=None):
    name = args.name + (".t%dof%d" % tile if tile else "")
    output = weftpipe.tile_name(args.output, *tile) if tile else args.output
    line = 'exec %s --frames "$frame" -o %s' % (weftpipe.quote([weft, "render"] + render_args), weftpipe.quote([output]))
    if tile:
        line += " --tile %d/%d" % tile
    line += ' --threads "${SLURM_CPUS_PER_TASK:-1}"'
    return name, "\n".join(header(args, name, array, args.logs) + [line]) + "\n"


def merge_script(args, weft, array, tile_jobs):
    """One merge task per frame, started when that frame's task of every tile array is done."""
    name = args.name + ".merge"
    tiles = [weftpipe.tile_name(args.output, i, args.tiles) for i in range(1, args.tiles + 1)]
    lines = header(args, name, array, args.logs, "aftercorr:" + ":".join(tile_jobs))
    lines.insert(-2, "#SBATCH --kill-on-invalid-dep=yes")  # a failed tile cancels its merge instead of leaving it pending
    lines.append('exec %s --frame "$frame" -o %s' % (weftpipe.quote([weft, "merge"] + tiles), weftpipe.quote([args.output])))
    return name, "\n".join(lines) + "\n"


def sbatch(text, script_path):
    with open(script_path, "w") as f:
        f.write(text)
    res = subprocess.run(["sbatch", "--parsable", script_path], capture_output=True, text=True)
    if res.returncode != 0:
        raise PipelineError("sbatch %s failed: %s" % (script_path, (res.stderr.strip() or res.stdout.strip())))
    return res.stdout.strip().split(";")[0]


def submit(args, frames):
    """Submits (or prints) the arrays for the frames; returns the job ids (or names in a dry run)."""
    render_args = render_args_of(args)
    args.index_base = index_base(frames, args.max_array_size)
    if not weftpipe.has_wildcard(args.output):
        raise PipelineError("output '%s' has no frame number (# = 4 digits, @ = 1 digit)" % args.output)
    if args.tiles < 1:
        raise PipelineError("--tiles must be >= 1")
    weft = weftpipe.weft_binary(args.weft) if not args.dry_run else (args.weft or os.environ.get("WEFT") or "weft")
    weft = os.path.abspath(weft) if os.path.sep in weft else weft
    array = weftpipe.slurm_array_spec([f - args.index_base for f in frames])
    tiles = [None] if args.tiles == 1 else [(i, args.tiles) for i in range(1, args.tiles + 1)]
    scripts = [render_script(args, weft, render_args, array, t) for t in tiles]
    if args.dry_run:
        return dry_run(args, weft, array, scripts)
    for folder in {args.logs, os.path.dirname(args.output) or "."} | ({os.path.dirname(weftpipe.tile_name(args.output, 1, 1))} if args.tiles > 1 else set()):
        os.makedirs(folder, exist_ok=True)
    os.makedirs(os.path.join(args.logs, "scripts"), exist_ok=True)
    ids = [sbatch(text, os.path.join(args.logs, "scripts", name + ".sh")) for name, text in scripts]
    if args.tiles > 1:
        name, text = merge_script(args, weft, array, ids)
        ids.append(sbatch(text, os.path.join(args.logs, "scripts", name + ".sh")))
    return ids


def dry_run(args, weft, array, scripts):
    if args.tiles > 1:
        scripts.append(merge_script(args, weft, array, ["<job id of %s>" % n for n, _ in scripts]))
    for name, text in scripts:
        print("# ---- sbatch script %s ----" % name)
        print(text, end="")
    return [name for name, _ in scripts]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1], formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n", 3)[3])
    p.add_argument("--frames", required=True, help="frame range, e.g. 1001-1100x2 or 1,3,5-9")
    add_submit_options(p)
    mine, render = weftpipe.split_at_dashes(sys.argv[1:])
    args = p.parse_args(mine)
    args.render_args = render
    ids = submit(args, weftpipe.parse_frames(args.frames))
    if not args.dry_run:
        print("\n".join(ids))
    return 0


if __name__ == "__main__":
    weftpipe.main_guard("submit_slurm", main)
