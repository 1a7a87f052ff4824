#!/usr/bin/env python3
"""Tip oscillation of the Turek-Hron FSI2-type beam (make_turek_hron_fsi2.py): frequency and
amplitude of the tip's y displacement over the periodic window [T_FROM, end], against Turek &
Hron 2006 (0.19, 0.83; ../shared/reference/fsi_turek_hron_FSI2_FSI3_benchmark_values.csv:
uy_A 0.0806 m at 2.0 Hz, i.e. 0.806 D at 0.20 U/D) and the thesis (0.178, 0.92; digest 8.2).

  frequency: 1 / mean period, a period running from one crossing of y = mean(y) to the next
             but one (upward and downward crossings both start one; linearly interpolated);
  amplitude: (max y - min y) / 2 over each such period, averaged;
  mean:      mean y over the whole periods; the x frequency too (the figure-eight, 2:1).

Non-dimensional (D = 1, U = 1). Reads result.h5 with h5dump (no Python HDF5 module needed).

usage: analyze_turek_hron_fsi2.py RESULT_H5 [T_FROM]   (default T_FROM = 40)
"""
import re
import subprocess
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
REFERENCES = [("Turek & Hron 2006", 0.19, 0.83), ("Bhardwaj & Mittal 2012", 0.19, 0.92),
              ("Zhang et al. 2021 (SPH)", 0.189, 0.86), ("thesis, P-I (SPH)", 0.178, 0.92)]


def dataset(path, name):
    out = subprocess.run(["h5dump", "-d", name, "-y", "-w", "0", path], capture_output=True,
                         text=True, check=True).stdout
    body = out.split("DATA {", 1)[1].rsplit("}", 2)[0]
    return [float(v) for v in NUMBER.findall(body)]


def crossings(t, u):
    mean = sum(u) / len(u)
    c = []
    for k in range(1, len(u)):
        a, b = u[k - 1] - mean, u[k] - mean
        if (a < 0 <= b) or (b < 0 <= a):
            c.append(t[k - 1] + (t[k] - t[k - 1]) * (-a) / (b - a))
    return c


def main():
    path = sys.argv[1]
    t_from = float(sys.argv[2]) if len(sys.argv) > 2 else 40.0
    t = dataset(path, "/series/diagnostics/time")
    d = dataset(path, "/series/elastic/beam/displacement")
    n = min(len(t), len(d) // 2)
    t, x, y = t[:n], d[0:2 * n:2], d[1:2 * n:2]
    keep = [k for k in range(n) if t[k] >= t_from]
    if len(keep) < 3:
        sys.exit(f"the run ended at t = {t[-1]:.4g}, before t = {t_from}")
    tw, xw, yw = [t[k] for k in keep], [x[k] for k in keep], [y[k] for k in keep]
    cy = crossings(tw, yw)
    if len(cy) < 3:
        sys.exit(f"less than one period after t = {t_from} (run to t = {t[-1]:.3g})")
    spans = list(zip(cy, cy[2:]))
    periods = [b - a for a, b in spans]
    f = 1 / (sum(periods) / len(periods))
    amps, means = [], []
    for a, b in spans:
        seg = [yw[k] for k in range(len(tw)) if a <= tw[k] < b]
        amps.append((max(seg) - min(seg)) / 2)
        means.append(sum(seg) / len(seg))
    amp = sum(amps) / len(amps)
    cx = crossings(tw, xw)
    fx = (len(cx) - 1) / (2 * (cx[-1] - cx[0])) if len(cx) > 1 else float("nan")
    print(f"window t = {t_from:g} .. {t[-1]:.4g}: {len(cy) - 1} half periods of y")
    print(f"  frequency {f:.4f} U/D (periods {min(periods):.3f} .. {max(periods):.3f}), "
          f"x frequency {fx:.4f} (ratio {fx / f:.2f})")
    print(f"  amplitude {amp:.4f} D (per period {min(amps):.4f} .. {max(amps):.4f}), "
          f"mean y {sum(means) / len(means):+.4f} D")
    for name, fr, ar in REFERENCES:
        print(f"  vs {name:26s} frequency {fr:.3f} ({100 * (f / fr - 1):+5.1f}%), "
              f"amplitude {ar:.2f} ({100 * (amp / ar - 1):+5.1f}%)")


if __name__ == "__main__":
    main()
