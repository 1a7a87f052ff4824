#!/usr/bin/env python3
"""Report of the reduced TFSI heated channel (run.sh): per configuration the wall-averaged
Nusselt number and the mixing index (thesis P-I eqs. 41 and 42; digest sec. 8.3), and whether
the thesis' ordering IV > II > III > I of heat-transfer enhancement holds.

  Nu(x) = -dT/dn W / (T_w - T_m(x))   at each wall, T_m the mean fluid temperature of the
          section (x-bins of width 0.5 D), dT/dn from T_w at the wall surface and the mean of
          the first two fluid rows (at dx/2 and 3 dx/2): (-8 T_w + 9 T_1 - T_2) / (3 dx);
  D     = sqrt(mean over the channel's fluid particles of ((T - T_avg) / T_avg)^2).

Nu is averaged over both walls, the channel's length and the snapshots of the second half of
the run. Reads result.h5 with h5dump (no Python HDF5 module needed).

usage: analyze.py OUT_DIR [T_FROM]   (OUT_DIR/I/result.h5 ... OUT_DIR/IV/result.h5; Nu averaged
       over the snapshots with t >= T_FROM, default the second half of each run)
"""
import math
import os
import re
import subprocess
import sys

L, W, T_WALL = 12.0, 4.1, 1.0
CONFIGS = ["I", "II", "III", "IV"]
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def dataset(path, name):
    out = subprocess.run(["h5dump", "-d", name, "-y", "-w", "0", path], capture_output=True,
                         text=True, check=True).stdout
    body = out.split("DATA {", 1)[1].rsplit("}", 2)[0]
    return [float(v) for v in NUMBER.findall(body)]


def groups(path):
    out = subprocess.run(["h5ls", path + "/snapshots"], capture_output=True, text=True,
                         check=True).stdout
    return sorted(line.split()[0] for line in out.splitlines() if line.strip())


def attribute(path, name):
    out = subprocess.run(["h5dump", "-a", name, path], capture_output=True, text=True,
                         check=True).stdout
    return float(NUMBER.findall(out.split("(0):", 1)[1])[0])


def snapshot(path, g):
    pos = dataset(path, f"/snapshots/{g}/position")
    kind = dataset(path, f"/snapshots/{g}/kind")
    T = dataset(path, f"/snapshots/{g}/temperature")
    t = attribute(path, f"/snapshots/{g}/time")
    fluid = [(pos[3 * i], pos[3 * i + 1], T[i]) for i in range(len(kind))
             if kind[i] == 0 and 0 <= pos[3 * i] <= L]
    return t, fluid


def mixing_index(fluid):
    avg = sum(p[2] for p in fluid) / len(fluid)
    if avg <= 0:
        return float("nan")
    return math.sqrt(sum(((p[2] - avg) / avg) ** 2 for p in fluid) / len(fluid))


def nusselt(fluid, dx, bin_width=0.5):
    nb = int(round(L / bin_width))
    sums = [[0.0] * 6 for _ in range(nb)]  # T sum, count; rows 1, 2 at the bottom and top
    rows = [[0.0] * 8 for _ in range(nb)]
    for x, y, T in fluid:
        b = min(int(x / bin_width), nb - 1)
        sums[b][0] += T
        sums[b][1] += 1
        for k, (lo, hi) in enumerate([(0, dx), (dx, 2 * dx), (W - dx, W), (W - 2 * dx, W - dx)]):
            if lo <= y < hi:
                rows[b][2 * k] += T
                rows[b][2 * k + 1] += 1
    local = []
    for b in range(nb):
        if sums[b][1] == 0 or min(rows[b][1::2]) == 0:
            continue
        Tm = sums[b][0] / sums[b][1]
        r = [rows[b][2 * k] / rows[b][2 * k + 1] for k in range(4)]
        for T1, T2 in ((r[0], r[1]), (r[2], r[3])):
            dTdn = (-8 * T_WALL + 9 * T1 - T2) / (3 * dx)
            local.append(-dTdn * W / (T_WALL - Tm))
    return sum(local) / len(local)


def main():
    out = sys.argv[1]
    t_from = float(sys.argv[2]) if len(sys.argv) > 2 else None
    rows = []
    for c in CONFIGS:
        path = os.path.join(out, c, "result.h5")
        if not os.path.exists(path):
            rows.append((c, None))
            continue
        series = [snapshot(path, g) for g in groups(path)]
        # dx from the first fluid row's lattice: the smallest y of a fluid particle is dx/2.
        dx = 2 * min(p[1] for p in series[0][1])
        t_end = series[-1][0]
        D = [(t, mixing_index(f)) for t, f in series if t > 0]
        late = [(t, f) for t, f in series if t >= (t_end / 2 if t_from is None else t_from)]
        if not late or not D:
            rows.append((c, None))  # stopped before the window
            continue
        Nu = sum(nusselt(f, dx) for _, f in late) / len(late)
        rows.append((c, dict(t_end=t_end, Nu=Nu, D=D, dx=dx)))
    print("# Reduced TFSI heated channel (tests/validation/thermal_fsi)\n")
    window = "second half" if t_from is None else f"t >= {t_from:g}"
    print(f"| configuration | t_end | mean Nu ({window}) | D at t = 5, 10, end | minimum D (t) |")
    print("|---|---|---|---|---|")
    for c, r in rows:
        if r is None:
            print(f"| {c} | not run | | | |")
            continue
        Dd = dict(r["D"])
        pick = [Dd.get(t, float("nan")) for t in (5.0, 10.0)] + [r["D"][-1][1]]
        dmin = min(r["D"], key=lambda p: p[1])
        print(f"| {c} | {r['t_end']:.3g} | {r['Nu']:.3f} | " +
              ", ".join(f"{v:.4f}" for v in pick) + f" | {dmin[1]:.4f} ({dmin[0]:.3g}) |")
    done = {c: r for c, r in rows if r is not None}
    if len(done) == 4:
        order = sorted(done, key=lambda c: -done[c]["Nu"])
        print(f"\nOrdering by Nu: {' > '.join(order)} (thesis: IV > II > III > I): " +
              ("holds" if order == ["IV", "II", "III", "I"] else "does not hold"))
        orderD = sorted(done, key=lambda c: done[c]["D"][-1][1])
        print(f"Final mixing index, lowest first: {' < '.join(orderD)} (thesis: IV lowest)")


if __name__ == "__main__":
    main()
