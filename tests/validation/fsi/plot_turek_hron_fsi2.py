#!/usr/bin/env python3
"""Plots the tip displacement of the Turek-Hron FSI2-type beam from the CSV files
run_turek_hron_fsi2.sh writes (t, x_tip, y_tip; D = 1): y(t) with the reference amplitudes,
and the tip's path (the figure-eight) over t >= 40. Needs matplotlib (Debian: python3-matplotlib,
/usr/bin/python3).

usage: plot_turek_hron_fsi2.py OUT_PNG LABEL=CSV ...
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    out = sys.argv[1]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [2.2, 1]})
    for spec in sys.argv[2:]:
        label, path = spec.rsplit("=", 1)
        rows = list(csv.DictReader(open(path)))
        t = [float(r["t"]) for r in rows]
        x = [float(r["x_tip"]) for r in rows]
        y = [float(r["y_tip"]) for r in rows]
        ax.plot(t, y, lw=0.8, label=label)
        late = [k for k in range(len(t)) if t[k] >= 40]
        ax2.plot([x[k] for k in late], [y[k] for k in late], lw=0.8, label=label)
    for amp, name, style in [(0.83, "Turek & Hron 0.83", "--"), (0.92, "thesis 0.92", ":")]:
        ax.axhline(amp, color="k", ls=style, lw=0.7, label=name)
        ax.axhline(-amp, color="k", ls=style, lw=0.7)
    ax.set_xlabel("t U / D")
    ax.set_ylabel("tip y displacement / D")
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("Turek-Hron FSI2-type beam, tip")
    ax2.set_xlabel("tip x / D")
    ax2.set_ylabel("tip y / D")
    ax2.set_title("tip path, t >= 40")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
