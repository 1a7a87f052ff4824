# Plots a convergence study: error against dx and error against wall time, log-log, with the
# least-squares power laws and their slopes (the observed order). Reads study.csv as written
# by study/study_report.cc; sph-worker runs it (embedded, with /usr/bin/python3) after a
# study, and it runs standalone too:  python3 study/plot_study.py study.csv study.png
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_study(path):
    meta, rows = {}, []
    with open(path) as f:
        lines = []
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].partition(":")
                meta[key.strip()] = value.strip()
            else:
                lines.append(line)
    for row in csv.DictReader(lines):
        rows.append(row)
    return meta, rows


def fit(x, y):
    lx, ly = np.log(x), np.log(y)
    slope, intercept = np.polyfit(lx, ly, 1)
    return slope, intercept


def panel(ax, x, y, xlabel, slope_name):
    ax.loglog(x, y, "o", color="C0", label="levels")
    if len(x) >= 2:
        slope, intercept = fit(x, y)
        xs = np.geomspace(min(x), max(x), 50)
        ax.loglog(xs, np.exp(intercept) * xs**slope, "-", color="C1",
                  label="%s = %.2f" % (slope_name, slope))
    for level, xi, yi in zip(range(1, len(x) + 1), x, y):
        ax.annotate(str(level), (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=8)
    # The target errors of docs/accuracy.md, where they fall near the measured range.
    for target in (0.01, 0.05, 0.10):
        if min(y) / 3 <= target <= max(y) * 3:
            ax.axhline(target, color="0.6", linestyle="--", linewidth=0.8)
            ax.annotate("%g%%" % (100 * target), (1, target), xycoords=("axes fraction", "data"),
                        xytext=(-28, 2), textcoords="offset points", fontsize=7, color="0.4")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_study.py study.csv study.png")
    meta, rows = read_study(sys.argv[1])
    good = [r for r in rows if r["status"] == "completed" and r["error"] not in ("nan", "")
            and float(r["error"]) > 0]
    dx = np.array([float(r["dx"]) for r in good])
    err = np.array([float(r["error"]) for r in good])
    wall = np.array([float(r["wall_seconds"]) for r in good])
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    if len(good):
        panel(a, dx, err, "dx", "order")
        panel(b, wall, err, "wall time [s] (%s rank(s))" % good[-1]["ranks"], "slope")
        a.invert_xaxis()
    else:
        a.text(0.5, 0.5, "no level has an error", ha="center", transform=a.transAxes)
    fig.suptitle("%s: %s" % (meta.get("case", "study"), meta.get("error", "")), fontsize=8,
                 wrap=True)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    fig.savefig(sys.argv[2], dpi=110)


main()
