#!/usr/bin/env python3
"""Renders frames of a phase-change result and a page of its invariants (2D scenes):

    python3 render.py RESULT.h5 OUT_DIR [NAME] [--scalar temperature|concentration]
        [--speed-max V] [--labels SOLID,MELT,FLUID] [--frames N] [--plane xy|xz]
        [--frames-only]

Rigid (solid) particles black, melted particles (the second material) red, the first fluid
coloured by speed, walls light grey. A 3D result is drawn as a projection on --plane
(default xy, seen from above) of the solid and melted particles only. Writes NAME_frames.png and NAME_invariants.png (solid
mass and number of bodies over time; the scalar's range against its bounds) unless
--frames-only (a second projection of the same run has the same invariants)."""
import argparse
import os

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("result")
ap.add_argument("out")
ap.add_argument("name", nargs="?", default="gastric")
ap.add_argument("--scalar", default="concentration")
ap.add_argument("--speed-max", type=float, default=100)
ap.add_argument("--labels", default="bolus,chyme,gastric juice")
ap.add_argument("--frames", type=int, default=6)
ap.add_argument("--plane", default="xy")
ap.add_argument("--frames-only", action="store_true")
a = ap.parse_args()
solid_label, melt_label, fluid_label = a.labels.split(",")

f = h5py.File(a.result, "r")
S = f["snapshots"]
keys = sorted(S.keys())
pick = [keys[i] for i in np.linspace(0, len(keys) - 1, a.frames).round().astype(int)]
rows = (a.frames + 1) // 2
axis = {"x": 0, "y": 1, "z": 2}
ia, ib = axis[a.plane[0]], axis[a.plane[1]]
x0 = S[keys[0]]["position"][:]
dim = f["meta"].attrs["dimension"]
three_d = int(dim.decode() if isinstance(dim, bytes) else dim) == 3  # positions have 3 columns in 2D too
aspect = np.ptp(x0[:, ib]) / max(np.ptp(x0[:, ia]), 1e-300)
fig, axes = plt.subplots(rows, 2, figsize=(12, 0.3 + rows * (5.2 * aspect + 0.35)), squeeze=False)
for ax in np.ravel(axes)[len(pick):]:  # an odd number of frames leaves one panel empty
    ax.set_visible(False)
for ax, k in zip(np.ravel(axes), pick):
    s = S[k]
    x = s["position"][:][:, [ia, ib]]
    kind = s["kind"][:]
    mat = s["material"][:]
    v = np.linalg.norm(s["velocity"][:], axis=1)
    wall, rigid, fluid = kind == 1, kind == 2, kind == 0
    melt = fluid & (mat == 1)
    carrier = fluid & (mat == 0)
    ms = 2.0
    if three_d:  # a projection: the carrier fluid and walls would hide the bodies
        wall[:] = False
        carrier[:] = False
        box = x0[:, [ia, ib]]
        ax.set_xlim(box[:, 0].min(), box[:, 0].max())
        ax.set_ylim(box[:, 1].min(), box[:, 1].max())
    ax.scatter(x[wall, 0], x[wall, 1], s=ms, c="0.85", lw=0)
    sc = ax.scatter(x[carrier, 0], x[carrier, 1], s=ms, c=v[carrier], cmap="viridis", vmin=0,
                    vmax=a.speed_max, lw=0)
    ax.scatter(x[melt, 0], x[melt, 1], s=3 * ms, c="red", lw=0)
    ax.scatter(x[rigid, 0], x[rigid, 1], s=3 * ms, c="k", lw=0)
    ax.set_title("t = %.4g: %d %s particles, %d %s" % (s.attrs["time"], rigid.sum(), solid_label,
                                                       melt.sum(), melt_label), fontsize=9)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
if not three_d:  # the projection leaves the carrier fluid out
    fig.colorbar(sc, ax=np.ravel(axes).tolist(), shrink=0.6, label="speed of the " + fluid_label)
os.makedirs(a.out, exist_ok=True)
fig.savefig(os.path.join(a.out, a.name + "_frames.png"), dpi=90)
print("wrote", os.path.join(a.out, a.name + "_frames.png"))
if a.frames_only:
    raise SystemExit(0)

ph = f["series/phase"]
t = f["series/bodies/time"][:]
m = f["series/bodies/mass"][:]
fig, ax = plt.subplots(1, 2, figsize=(11, 3.5))
ax[0].plot(t, np.nansum(m, axis=1) / np.nansum(m[0]), label="%s mass / initial" % solid_label)
ax[0].plot(t, ph["active_bodies"][:] / ph["active_bodies"][0], label="bodies / initial")
ax[0].set_xlabel("t")
ax[0].legend()
d = f["series/diagnostics"]
ax[1].plot(d["time"][:], d[a.scalar + "_min"][:], label=a.scalar + " min")
ax[1].plot(d["time"][:], d[a.scalar + "_max"][:], label=a.scalar + " max")
ax[1].set_xlabel("t")
ax[1].legend()
fig.tight_layout()
fig.savefig(os.path.join(a.out, a.name + "_invariants.png"), dpi=90)
print("wrote", os.path.join(a.out, a.name + "_invariants.png"))
