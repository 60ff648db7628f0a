#!/usr/bin/python3
"""Draw a sweep's Pareto plot: sweep_plot.py SWEEP.json OUT.png

Two panels, log-log: the median render time and the samples (rays and
volume samples, a cost that does not depend on the machine) against the
sweep's error metric. One colour per technique, each point labelled with
its settings (only the front's once there are more than 16), the front (points no other point beats on both axes) drawn
as a line. `weft sweep` runs it after writing sweep.json; it needs
Debian's python3-matplotlib (run it with /usr/bin/python3).
"""

import json
import math
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HIGHER_IS_BETTER = {"psnr", "ssim"}
LABEL_ALL = 16  # runs up to which every point is labelled


def finite_positive(v):
    return v is not None and math.isfinite(v) and v > 0


def panel(ax, runs, metric, cost, front_key, xlabel):
    colours = {}
    for r in runs:
        t = r["technique"]
        colours.setdefault(t, "C%d" % len(colours))
    for t, colour in colours.items():
        pts = [(cost(r), r["error"][metric], r["label"], r["front"][front_key]) for r in runs if r["technique"] == t]
        pts = [p for p in pts if finite_positive(p[0]) and p[1] is not None and math.isfinite(p[1])]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=colour, label=t, s=22, zorder=3)
        # Labels for the front's points only once there are many (they would overlap); the table has them all.
        for x, y, label, on_front in pts:
            if on_front or len(runs) <= LABEL_ALL:
                ax.annotate(label, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points", color=colour)
    front = sorted((cost(r), r["error"][metric]) for r in runs if r["front"][front_key] and finite_positive(cost(r)))
    front = [p for p in front if p[1] is not None and math.isfinite(p[1])]
    if front:
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="0.3", linewidth=1, zorder=2, label="front")
    ax.set_xscale("log")
    if metric not in HIGHER_IS_BETTER and all(finite_positive(r["error"][metric]) for r in runs):
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(metric.upper() if metric != "relmse" else "relMSE")
    ax.grid(True, which="both", linewidth=0.3, alpha=0.5)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: sweep_plot.py SWEEP.json OUT.png\n")
        return 2
    with open(argv[1]) as f:
        sweep = json.load(f)
    # Settings the technique refused have no time or error.
    runs, metric = [r for r in sweep["runs"] if "refused" not in r], sweep["metric"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    panel(axes[0], runs, metric, lambda r: r["time_ms"]["median"] / 1000.0, "time", "median render time (s)")
    panel(axes[1], runs, metric, lambda r: float(r["samples"]), "samples", "samples (rays + volume samples)")
    axes[0].legend(fontsize=7)
    fig.suptitle("%s against %s" % (os.path.basename(sweep["scene"]), os.path.basename(sweep["reference"])), fontsize=10)
    fig.tight_layout()
    # Written beside the target and renamed: a failed plot leaves no partial file.
    fd, tmp = tempfile.mkstemp(suffix=".png", dir=os.path.dirname(os.path.abspath(argv[2])))
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120)
        os.replace(tmp, argv[2])
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
