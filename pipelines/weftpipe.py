"""Shared pieces of the weft pipeline scripts (standard library only).

Frame ranges and frame-numbered names follow `weft render` exactly
(core/base/options/frames.hpp): "1001-1100x2", "1,3,5-9", "-5--1"; in names the first run
of '#' and '@' is the frame number, 4 digits per '#' and 1 per '@'
("#" -> 0042, "@@@" -> 042), "%04d" works too.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys

_ITEM = re.compile(r"^(-?\d+)(?:-(-?\d+)(?:x(\d+))?)?$")
_WILDCARD = re.compile(r"[#@]+|%0?(\d*)d")


class PipelineError(Exception):
    """A one-line error the scripts print as 'NAME: error: ...' with exit status 1."""


def parse_frames(text):
    """Frames of a range text, in order; duplicates and bad syntax are errors."""
    frames = []
    for item in text.split(","):
        m = _ITEM.match(item)
        if not m or (m.group(3) is not None and int(m.group(3)) < 1):
            raise PipelineError("bad frame range '%s': expected e.g. 1001-1100x2, 1,3,5-9 or -5--1" % text)
        first = int(m.group(1))
        last = int(m.group(2)) if m.group(2) is not None else first
        step = int(m.group(3) or 1)
        frames += list(range(first, last + 1, step)) if last >= first else list(range(first, last - 1, -step))
    if len(set(frames)) != len(frames):
        raise PipelineError("bad frame range '%s': a frame is listed twice" % text)
    return frames


def has_wildcard(name):
    return _WILDCARD.search(name) is not None


def expand(name, frame):
    """The name with its first frame wildcard replaced, as weft does."""
    m = _WILDCARD.search(name)
    if not m:
        return name
    token = m.group(0)
    if token[0] == "%":
        width = int(m.group(1) or 0)
    else:
        width = sum(4 if c == "#" else 1 for c in token)
    return name[: m.start()] + "%0*d" % (width, frame) + name[m.end():]


def slurm_array_spec(frames):
    """Slurm --array text for the frames: runs of a constant step as A-B:S, joined by commas."""
    frames = sorted(frames)
    parts, i = [], 0
    while i < len(frames):
        j = i
        step = frames[i + 1] - frames[i] if i + 1 < len(frames) else 1
        while j + 1 < len(frames) and frames[j + 1] - frames[j] == step:
            j += 1
        if j == i or (j == i + 1 and step != 1):  # a lone frame, or a pair better joined to what follows
            parts.append(str(frames[i]))
            i += 1
            continue
        parts.append("%d-%d" % (frames[i], frames[j]) + (":%d" % step if step != 1 else ""))
        i = j + 1
    return ",".join(parts)


def split_at_dashes(argv):
    """(script arguments, render arguments): what follows the first '--' goes to weft render."""
    if "--" in argv:
        k = argv.index("--")
        return argv[:k], argv[k + 1:]
    return argv, []


def weft_binary(explicit=None):
    """The weft executable: --weft, $WEFT, or weft on PATH."""
    path = explicit or os.environ.get("WEFT") or shutil.which("weft")
    if not path:
        raise PipelineError("weft not found: pass --weft PATH, set WEFT, or put weft on PATH")
    return os.path.abspath(path) if os.path.sep in path else path


def tile_name(output, index, count):
    """Where tile index/count of a frame-numbered output goes: out/shot.#.exr -> out/tiles/shot.#.t2of4.exr."""
    folder, base = os.path.split(output)
    stem = base[:-4] if base.lower().endswith(".exr") else base
    return os.path.join(folder, "tiles", "%s.t%dof%d.exr" % (stem, index, count))


def render_command(weft, render_args, frame, output, tile=None):
    """The weft command line of one task."""
    cmd = [weft, "render"] + list(render_args) + ["--frames", str(frame), "-o", output]
    if tile:
        cmd += ["--tile", "%d/%d" % tile]
    return cmd


def merge_command(weft, output, frame, count):
    tiles = [tile_name(output, i, count) for i in range(1, count + 1)]
    return [weft, "merge"] + tiles + ["--frame", str(frame), "-o", output]


def quote(cmd):
    return " ".join(shlex.quote(c) for c in cmd)


def weft_module(weft):
    """The weft Python module built beside the weft executable (build/bin), or None.

    None when this interpreter cannot load it (another Python version, a weft
    installed without its module): the scripts then ask the command.
    """
    found = shutil.which(weft) if os.path.sep not in weft else weft
    if not found:
        return None
    folder = os.path.dirname(os.path.realpath(found))
    if folder not in sys.path:
        sys.path.insert(0, folder)
    try:
        import weft as module
    except ImportError:
        return None
    return module if hasattr(module, "check") else None


def frame_status(weft, paths):
    """{path: 'ok' | 'missing' | 'corrupt: why'} for rendered frames.

    A frame is complete when its EXR reads in full and carries
    weft:complete = 1, which weft writes into every finished render and merge.
    Asked of the weft module (weft.check) where it loads, else of `weft check`.
    """
    module = weft_module(weft)
    if module is not None:
        return module.check(list(paths))
    return _frame_status_from_command(weft, paths)


def _frame_status_from_command(weft, paths):
    status = {}
    for i in range(0, len(paths), 200):
        chunk = paths[i:i + 200]
        res = subprocess.run([weft, "check"] + chunk, capture_output=True, text=True)
        if res.returncode not in (0, 2):
            raise PipelineError("weft check failed: " + (res.stderr.strip().splitlines() or ["?"])[-1])
        for line in res.stdout.splitlines():
            state, _, path = line.partition("\t")
            status[path] = state
    missing = [p for p in paths if p not in status]
    if missing:
        raise PipelineError("weft check said nothing about '%s'" % missing[0])
    return status


def run_local(commands, log_dir=None):
    """Runs task command lines one after the other; returns how many failed."""
    failed = 0
    for name, cmd in commands:
        out = None
        if log_dir:
            os.makedirs(log_dir, exist_ok=True)
            out = open(os.path.join(log_dir, name + ".log"), "w")
        try:
            res = subprocess.run(cmd, stdout=out or None, stderr=subprocess.STDOUT if out else None)
        finally:
            if out:
                out.close()
        failed += res.returncode != 0
    return failed


def main_guard(name, fn):
    """Runs fn() and turns PipelineError into one line and exit status 1."""
    try:
        sys.exit(fn())
    except PipelineError as e:
        print("%s: error: %s" % (name, e), file=sys.stderr)
        sys.exit(1)
