#!/usr/bin/env python3
"""Prints the figures of the seed-scene runs (tests/validation/phase/seed_scenes.sh) as
Markdown tables for tests/validation/reports/seed_scenes.md: per scene the run's size and
wall time, mass conservation, the scalar's range against its bounds, and the solid over time;
for the 3D powder box and its 2D slice also how far the metal strays from the grains it
started in (the fraction of grain and melt particles more than 2 um outside every initial
grain: 0 while the melt keeps the grains' places, as it must with gravity moving a grain
0.15 um in 0.175 ms).

    scene_figures.py OUT_DIR"""
import os
import re
import sys

import h5py
import numpy as np

out = sys.argv[1]
SCENES = [  # folder, scalar, bounds of the scalar (initial and boundary values), times to list
    ("gastric_04", "concentration", (0.0, 1.0), [0, 0.2, 0.4, 0.6, 0.8, 1.0]),
    ("gastric_01", "concentration", (0.0, 1.0), [0, 0.2, 0.4, 0.6, 0.8, 1.0]),
    ("powder_2d_coarse", "temperature", (0.0, 100.0), [0, 0.1, 0.25, 0.3, 0.4, 0.5, 0.55, 0.6, 0.7, 0.75]),
    ("powder_3d_coarse", "temperature", (500.0, 1800.0), [0, 2.5e-5, 5e-5, 1e-4, 1.5e-4, 1.6e-4, 1.75e-4]),
    ("powder_slice_2d", "temperature", (500.0, 1800.0), [0, 2.5e-5, 5e-5, 7.5e-5, 1e-4, 1.5e-4, 1.6e-4, 1.75e-4]),
    ("powder_slice_2d_st", "temperature", (500.0, 1800.0), [0, 2.5e-5, 5e-5, 7.5e-5, 1e-4, 1.5e-4, 1.6e-4, 1.75e-4]),
    ("powder_3d_coarse_st", "temperature", (500.0, 1800.0), [0, 2.5e-5, 5e-5, 1e-4, 1.5e-4, 1.6e-4, 1.75e-4]),
    ("powder_2d", "temperature", (0.0, 100.0), [0, 0.1, 0.25, 0.3, 0.4, 0.5, 0.55, 0.6, 0.7, 0.75]),
    ("powder_3d", "temperature", (500.0, 1800.0), [0, 2.5e-5, 5e-5, 1e-4, 1.5e-4, 1.6e-4, 1.75e-4]),
]
STRAY = {"powder_3d_coarse", "powder_slice_2d", "powder_3d", "powder_slice_2d_st", "powder_3d_coarse_st"}  # scenes with the metal-outside-grains column
STRAY_MARGIN = 2e-6
MIXING = {"powder_2d_coarse", "powder_2d", "powder_3d_coarse", "powder_slice_2d", "powder_3d", "powder_slice_2d_st", "powder_3d_coarse_st"}  # melt-gas interface column


def grains_of(case_text):
    """(centre, radius) of each ball-shaped body of the case, 2D or 3D."""
    out = []
    for m in re.finditer(r"bodies \{.*?ball \{ center \{ (.*?) \} radius: (\S+) \}", case_text):
        c = [float(v) for v in re.findall(r"[xyz]: (\S+)", m.group(1))]
        out.append((np.array(c), float(m.group(2))))
    return out


def quintic(q):
    """The quintic spline up to its normalisation (which cancels in the shares below)."""
    return (np.where(q < 3, (3 - q) ** 5, 0) - 6 * np.where(q < 2, (2 - q) ** 5, 0)
            + 15 * np.where(q < 1, (1 - q) ** 5, 0))


def phase_mixing(snap, dx, h, dim):
    """(interface, stray) particles of a snapshot as solver/diagnostics/phase_mixing.h counts
    them: fluid particles with fluid of another material within 3 h, and those of them
    with more of it in their kernel support (V W, V = m / rho for fluid, dx^d for dummies) than
    half the support. Computed from the snapshot, so that runs of code older than that
    diagnostic get the figure too (the solver counts at the positions of its last neighbour
    search, one drift earlier: the two may differ by a particle)."""
    from scipy.spatial import cKDTree
    kind, mat, x = snap["kind"][:], snap["material"][:], snap["position"][:][:, :dim]
    fluid = kind == 0
    vol = np.where(fluid, snap["mass"][:] / np.where(fluid, snap["density"][:], 1.0), dx ** dim)
    tree = cKDTree(x)
    pairs = tree.sparse_distance_matrix(tree, 3 * h * (1 - 1e-12), output_type="ndarray")
    i, j, r = pairs["i"], pairs["j"], pairs["v"]
    keep = fluid[i]
    i, j, r = i[keep], j[keep], r[keep]
    self_term = (i == j)  # sparse_distance_matrix leaves out r = 0 pairs: added below
    vw = vol[j] * quintic(r / h) * ~self_term
    foreign = fluid[j] & (mat[j] != mat[i])
    n = len(kind)
    allw = np.bincount(i, vw, n) + vol * quintic(0.0)
    fw = np.bincount(i, vw * foreign, n)
    touched = np.bincount(i, foreign, n) > 0
    interface = fluid & touched
    return int(interface.sum()), int((interface & (fw > 0.5 * allw)).sum())


def stray_fraction(snap, grains):
    kind, mat, x = snap["kind"][:], snap["material"][:], snap["position"][:]
    metal = (kind == 2) | ((kind == 0) & (mat == 1))  # rigid, or the melt (second material)
    xm = x[metal][:, : len(grains[0][0])]
    outside = np.ones(len(xm), bool)
    for c, r in grains:
        outside &= np.linalg.norm(xm - c, axis=1) > r + STRAY_MARGIN
    return outside.mean()


for name, scalar, (lo, hi), times in SCENES:
    path = os.path.join(out, name, "result.h5")
    if not os.path.exists(path):
        continue
    f = h5py.File(path, "r")
    meta = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f["meta"].attrs.items()}
    d = f["series/diagnostics"]
    t = d["time"][:]
    ph = f["series/phase"]
    b = f["series/bodies"]
    tb = b["time"][:]
    solid = np.nansum(b["mass"][:], axis=1)
    snaps = f["snapshots"]
    keys = sorted(snaps.keys())

    def total_mass(k):
        s = snaps[k]
        return s["mass"][:][s["kind"][:] != 1].sum()

    # Open boundaries change the total by the particles that crossed them.
    m0 = total_mass(keys[0])
    drift = max(abs(total_mass(k) / m0 - 1) for k in keys)
    try:
        wall = open(os.path.join(out, name, "wall_seconds")).read().strip()
    except OSError:
        wall = "?"
    smin, smax = d[scalar + "_min"][:], d[scalar + "_max"][:]
    print("### %s\n" % name)
    dx = re.search(r"^dx: (\S+)", meta["case_text"], re.M).group(1)  # /meta/dx is rounded to 1e-6
    print("dx %s, %s ranks, %d steps to t = %.4g, %d particles at the start, %s s wall; status %s.\n"
          % (dx, meta["ranks"], int(d["step"][-1]), t[-1], len(snaps[keys[0]]["kind"]), wall,
             meta["status"]))
    print("| figure | value |\n|---|---|")
    print("| %s range over the run | [%.4g, %.4g] (bounds [%g, %g]) |" % (scalar, smin.min(), smax.max(), lo, hi))
    print("| max density deviation (after t = %.3g) | %.3f |" % (t[len(t) // 50], d["max_density_deviation"][len(t) // 50:].max()))
    print("| total mass over snapshots, max relative change | %.1e%s |"
          % (drift, " (gas in and out through the open boundaries)" if "open_boundaries" in f["series"] else ""))
    print("| particles melted / solidified | %d / %d |" % (ph["melted"][-1], ph["solidified"][-1]))
    if "reversals" in ph:  # runs of code from 2463519 on
        print("| reversals (a particle's second or later transition) / fewest steps between two | %d / %d |"
              % (ph["reversals"][-1], ph["shortest_reversal_steps"][-1]))
    print("")
    stray = name in STRAY
    mixing = name in MIXING
    grains = grains_of(meta["case_text"]) if stray else []
    stimes = np.array([snaps[k].attrs["time"] for k in keys])
    print("| t | solid mass / initial | bodies | melted | solidified | %s min | %s max | max speed |%s%s"
          % (scalar, scalar, " metal > 2 um outside its grains |" if stray else "",
             " melt-gas interface: stray / interface particles |" if mixing else ""))
    print("|---|---|---|---|---|---|---|---|%s%s" % ("---|" if stray else "", "---|" if mixing else ""))
    for tt in [x for x in times if x <= t[-1]] + ([t[-1]] if times[-1] > t[-1] else []):
        k = int(np.argmin(abs(tb - tt)))
        kd = int(np.argmin(abs(t - tt)))
        extra = ""
        ks = int(np.argmin(abs(stimes - tt)))
        if stray:
            extra = " %.3f (t = %.4g) |" % (stray_fraction(snaps[keys[ks]], grains), stimes[ks])
        if mixing:
            itf, st = phase_mixing(snaps[keys[ks]], float(dx), float(meta["h"]), int(meta["dimension"]))
            extra += " %d / %d (t = %.4g) |" % (st, itf, stimes[ks])
        print("| %.4g | %.3f | %d | %d | %d | %.4g | %.4g | %.3g |%s"
              % (tb[k], solid[k] / solid[0], ph["active_bodies"][k], ph["melted"][k], ph["solidified"][k],
                 smin[kd], smax[kd], d["max_speed"][kd], extra))
    print("")
