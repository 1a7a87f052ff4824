#!/usr/bin/env python3
"""Renders frames of a phase-change result (e.g. the gastric bolus scene) and a page of
invariants: python3 render.py RESULT.h5 OUT_DIR [NAME]. Bolus (rigid) particles black, chyme
(melted) red, gastric juice coloured by speed, walls light grey."""
import sys, os
import h5py, numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

path, out = sys.argv[1], sys.argv[2]
name = sys.argv[3] if len(sys.argv) > 3 else "gastric"
f = h5py.File(path, "r")
S = f["snapshots"]
keys = sorted(S.keys())
pick = [keys[i] for i in np.linspace(0, len(keys) - 1, 6).round().astype(int)]
fig, axes = plt.subplots(3, 2, figsize=(12, 8.4))
mats = f["meta"].attrs.get("materials", None)
for ax, k in zip(axes.ravel(), pick):
    s = S[k]
    x = s["position"][:]
    kind = s["kind"][:]
    mat = s["material"][:]
    v = np.linalg.norm(s["velocity"][:], axis=1)
    wall, rigid, fluid = kind == 1, kind == 2, kind == 0
    chyme = fluid & (mat == 1)
    juice = fluid & (mat == 0)
    ms = 2.0
    ax.scatter(x[wall, 0], x[wall, 1], s=ms, c="0.85", lw=0)
    sc = ax.scatter(x[juice, 0], x[juice, 1], s=ms, c=v[juice], cmap="viridis", vmin=0, vmax=100, lw=0)
    ax.scatter(x[chyme, 0], x[chyme, 1], s=3 * ms, c="red", lw=0)
    ax.scatter(x[rigid, 0], x[rigid, 1], s=3 * ms, c="k", lw=0)
    ax.set_title("t = %.3f: %d bolus particles, %d chyme" % (s.attrs["time"], rigid.sum(), chyme.sum()))
    ax.set_aspect("equal")
    ax.set_xticks([]); ax.set_yticks([])
fig.colorbar(sc, ax=axes.ravel().tolist(), shrink=0.6, label="speed of the gastric juice")
os.makedirs(out, exist_ok=True)
fig.savefig(os.path.join(out, name + "_frames.png"), dpi=90)

ph = f["series/phase"]
t = f["series/bodies/time"][:]
m = f["series/bodies/mass"][:]
fig, ax = plt.subplots(1, 2, figsize=(11, 3.5))
ax[0].plot(t, np.nansum(m, axis=1) / np.nansum(m[0]), label="bolus mass / initial")
ax[0].plot(t, ph["active_bodies"][:] / ph["active_bodies"][0], label="boluses / initial")
ax[0].set_xlabel("t"); ax[0].legend()
d = f["series/diagnostics"]
ax[1].plot(d["time"][:], d["concentration_min"][:], label="C min")
ax[1].plot(d["time"][:], d["concentration_max"][:], label="C max")
ax[1].set_xlabel("t"); ax[1].legend()
fig.tight_layout()
fig.savefig(os.path.join(out, name + "_invariants.png"), dpi=90)
print("wrote", os.path.join(out, name + "_frames.png"), os.path.join(out, name + "_invariants.png"))
