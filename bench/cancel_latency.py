#!/usr/bin/env python3
"""How soon `weft render` stops after SIGINT or SIGTERM: every technique
renders a frame that takes seconds, the signal comes at a few points of its
run, and the time from the signal to the process's exit is measured. A
cancelled render writes nothing; the process must end by the signal. Target:
every stop within 0.5 s (the worst over techniques and points is the
headline).

  /usr/bin/python3 bench/cancel_latency.py
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

from benchlib import WEFT, headline

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (technique, input, extra arguments): each renders for several seconds on 2 threads.
CASES = [
    ("volume.raymarch", "builtin:cloud", ["--res", "1024x1024", "--spp", "64"]),
    ("volume.preint", "builtin:cloud", ["--res", "1024x1024", "--spp", "64"]),
    ("volume.adaptive3d", "builtin:cloud", ["--res", "1024x1024", "--spp", "16"]),
    ("volume.singlescatter", "builtin:cloud", ["--res", "1024x1024", "--spp", "16"]),
    ("mesh.pathtrace", os.path.join(ROOT, "scenes", "cornell.json"), ["--res", "1024x1024", "--spp", "64"]),
    ("lighting.vpl_deferred", os.path.join(ROOT, "scenes", "cornell.json"), ["--res", "1024x1024", "--set", "vpls=20000"]),
    ("lighting.adaptive_indirect", os.path.join(ROOT, "scenes", "cornell.json"), ["--res", "1024x1024", "--spp", "64"]),
    ("analytic.2d", "builtin:zoneplate", ["--res", "2048x2048", "--spp", "256"]),
]
DELAYS_S = [0.5, 1.5]


def stop_after(args, delay, sig, out):
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    if proc.poll() is not None:
        return None, "finished before the signal"
    sent = time.perf_counter()
    proc.send_signal(sig)
    _, err = proc.communicate()
    latency = time.perf_counter() - sent
    if proc.returncode != -sig:
        sys.exit("bench: %s ended with %d, not by the signal: %s" % (" ".join(args), proc.returncode, err.strip()))
    if os.path.exists(out):
        sys.exit("bench: %s wrote %s although cancelled" % (" ".join(args), out))
    return latency, "stopped in the render" if "wrote nothing" in err else "ended at once"


def main():
    worst = 0.0
    print("| technique | signal | after (s) | stop latency (ms) | how |")
    print("|---|---|---:|---:|---|")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "frame.exr")
        for technique, scene, extra in CASES:
            args = [WEFT, "render", scene, "--technique", technique, "--threads", "2", "-o", out] + extra
            for delay, sig in zip(DELAYS_S, (signal.SIGINT, signal.SIGTERM)):
                latency, how = stop_after(args, delay, sig, out)
                if latency is None:
                    print("| %s | %s | %.1f | - | %s |" % (technique, sig.name, delay, how))
                    continue
                worst = max(worst, latency)
                print("| %s | %s | %.1f | %.0f | %s |" % (technique, sig.name, delay, 1000 * latency, how))
                sys.stdout.flush()
    headline("worst stop after SIGINT/SIGTERM during a render", "%.0f ms" % (1000 * worst), "<= 500 ms", worst <= 0.5)


if __name__ == "__main__":
    main()
