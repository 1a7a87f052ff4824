#!/usr/bin/python3
"""Checks on result.h5 files for the service tests (h5py from Debian's python3-h5py).

  h5check.py snapshots FILE N_PARTICLES T0 T1 ...   the snapshots hold N particles at these times
  h5check.py same FILE_A FILE_B                     same snapshot times, identical snapshots (by id)
  h5check.py finite FILE                            at least one snapshot, every value finite
"""
import sys

import h5py
import numpy as np


def snapshots(path):
    with h5py.File(path, "r") as f:
        return [(float(g.attrs["time"]), {k: g[k][()] for k in g.keys()})
                for _, g in sorted(f["snapshots"].items())]


def check_snapshots(path, n, times):
    snaps = snapshots(path)
    got = [t for t, _ in snaps]
    if len(got) != len(times) or any(abs(a - b) > 1e-9 for a, b in zip(got, times)):
        sys.exit(f"{path}: snapshot times {got}, expected {times}")
    for t, data in snaps:
        if data["position"].shape != (n, 3):
            sys.exit(f"{path}: t={t}: position has shape {data['position'].shape}, expected ({n}, 3)")
        if len(np.unique(data["id"])) != n:
            sys.exit(f"{path}: t={t}: particle ids are not {n} distinct values")
    print(f"{path}: {len(snaps)} snapshots of {n} particles at {got}")


def check_same(path_a, path_b):
    snaps_a, snaps_b = snapshots(path_a), snapshots(path_b)
    times_a, times_b = [t for t, _ in snaps_a], [t for t, _ in snaps_b]
    if times_a != times_b:
        sys.exit(f"snapshot times differ:\n  {path_a}: {times_a}\n  {path_b}: {times_b}")
    for (t, a), (_, b) in zip(snaps_a, snaps_b):
        order_a, order_b = np.argsort(a["id"]), np.argsort(b["id"])
        for key in ("position", "velocity", "density", "pressure"):
            x, y = a[key][order_a], b[key][order_b]
            if not np.array_equal(x, y):
                sys.exit(f"{key} differs at t={t}: max |a-b| = {np.max(np.abs(x - y))}")
    print(f"{len(times_a)} snapshots identical (t = {times_a[0]} ... {times_a[-1]})")


def check_finite(path):
    snaps = snapshots(path)
    if not snaps:
        sys.exit(f"{path}: no snapshots")
    for t, data in snaps:
        for key in ("position", "velocity", "density", "pressure"):
            if not np.all(np.isfinite(data[key])):
                sys.exit(f"{path}: t={t}: {key} is not finite")
    print(f"{path}: {len(snaps)} snapshots, all finite (last t = {snaps[-1][0]})")


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "snapshots":
        check_snapshots(sys.argv[2], int(sys.argv[3]), [float(t) for t in sys.argv[4:]])
    elif len(sys.argv) == 4 and sys.argv[1] == "same":
        check_same(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "finite":
        check_finite(sys.argv[2])
    else:
        sys.exit(__doc__)
