#!/usr/bin/env python3
"""Finish a partial farm run: find the frames that are missing or corrupt and render only those.

    resume.py --frames 1001-1100 -o out/shot.#.exr [--tiles N] [--local] [--dry-run] [submit options] -- INPUT [RENDER OPTIONS]

A frame is complete when its EXR reads back in full and carries the
weft:complete attribute (`weft check`); a file killed mid-write never reaches
its final name (weft writes to a temporary name, then renames), so a killed
task shows up as missing. The frames to redo are printed, one per line, then
submitted to Slurm as an array of just those frames (same options as
submit_slurm.py), or rendered here one after the other with --local.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import submit_slurm  # noqa: E402
import weftpipe  # noqa: E402


def frames_to_redo(weft, output, frames):
    """[(frame, state)] of the frames whose output is not complete, in frame order."""
    paths = {f: weftpipe.expand(output, f) for f in frames}
    status = weftpipe.frame_status(weft, list(paths.values()))
    return [(f, status[paths[f]]) for f in frames if status[paths[f]] != "ok"]


def stray_temporaries(output):
    """Temporary files that killed writes left beside the outputs (.NAME.weft-tmp-PID.exr)."""
    folder = os.path.dirname(output) or "."
    if not os.path.isdir(folder):
        return []
    return sorted(n for n in os.listdir(folder) if n.startswith(".") and ".weft-tmp-" in n)


def local_commands(args, weft, render_args, frames):
    cmds = []
    for f in frames:
        if args.tiles == 1:
            cmds.append(("%s_%d" % (args.name, f), weftpipe.render_command(weft, render_args, f, args.output)))
            continue
        for i in range(1, args.tiles + 1):
            tile = weftpipe.tile_name(args.output, i, args.tiles)
            cmds.append(("%s.t%dof%d_%d" % (args.name, i, args.tiles, f),
                         weftpipe.render_command(weft, render_args, f, tile, (i, args.tiles))))
        cmds.append(("%s.merge_%d" % (args.name, f), weftpipe.merge_command(weft, args.output, f, args.tiles)))
    return cmds


def run_here(args, weft, frames):
    render_args = submit_slurm.render_args_of(args)
    cmds = local_commands(args, weft, render_args, frames)
    if args.dry_run:
        for _, cmd in cmds:
            print(weftpipe.quote(cmd))
        return 0
    if args.tiles > 1:
        os.makedirs(os.path.dirname(weftpipe.tile_name(args.output, 1, 1)), exist_ok=True)
    failed = weftpipe.run_local(cmds, args.logs)
    if failed:
        print("resume: %d of %d tasks failed (logs in %s)" % (failed, len(cmds), args.logs), file=sys.stderr)
    return 1 if failed else 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("--frames", required=True, help="the run's whole frame range")
    p.add_argument("--local", action="store_true", help="render the frames here instead of submitting them")
    submit_slurm.add_submit_options(p)
    mine, render = weftpipe.split_at_dashes(sys.argv[1:])
    args = p.parse_args(mine)
    args.render_args = render
    frames = weftpipe.parse_frames(args.frames)
    weft = weftpipe.weft_binary(args.weft)
    redo = frames_to_redo(weft, args.output, frames)
    for f, state in redo:
        print("frame %d: %s" % (f, state))
    print("resume: %d of %d frames to render" % (len(redo), len(frames)))
    stray = stray_temporaries(args.output)
    if stray:
        print("resume: %d temporary files from interrupted writes in %s (e.g. %s); delete them when no task runs"
              % (len(stray), os.path.dirname(args.output) or ".", stray[0]))
    if not redo:
        return 0
    todo = [f for f, _ in redo]
    if args.local:
        return run_here(args, weft, todo)
    ids = submit_slurm.submit(args, todo)
    if not args.dry_run:
        print("\n".join(ids))
    return 0


if __name__ == "__main__":
    weftpipe.main_guard("resume", main)
