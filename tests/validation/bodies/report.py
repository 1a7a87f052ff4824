#!/usr/bin/python3
"""Writes the rigid-body validation report (Markdown + PNG plots) from the runs of run.sh.

usage: report.py RUN_DIR REPORT_DIR
"""
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data")


def load_csv(name):
    rows = [l for l in open(os.path.join(DATA, name)) if not l.startswith("#")][1:]
    return np.array([[float(v) for v in l.split(",")] for l in rows if l.strip()])


def bodies(path):
    f = h5py.File(os.path.join(path, "result.h5"), "r")
    b = f["/series/bodies"]
    return f, {k: b[k][:] for k in b.keys()}


def wall_seconds(path):
    try:
        return float(open(os.path.join(path, "wall_seconds")).read())
    except OSError:
        return float("nan")


def meta(f, key):
    v = f["/meta"].attrs[key]
    return v.decode() if isinstance(v, bytes) else str(v)


def falling_disk(runs, out, lines):
    ref = load_csv("sedimentation_disk_glowinski2001_vy_history.csv")
    sel_ref = (ref[:, 0] >= 0.3) & (ref[:, 0] <= 0.65)
    v_ref = ref[sel_ref, 1].mean()
    lines += ["## Disk falling in a fluid column (Fuchs 2021; Glowinski et al. 2001)", "",
              "Settling speed = mean v_y over 0.3 s <= t <= 0.65 s; reference the Glowinski et al. (2001) FEM curve "
              f"(digitised, mean {-v_ref:.4f} m/s over the same window).", "",
              "| D/dx | particles | settling speed [m/s] | vs reference | max speed [m/s] | speed at t = 1 s | "
              "gap lowest disk particle - first wall layer | wall time |",
              "|---|---|---|---|---|---|---|---|"]
    plt.figure(figsize=(7, 4))
    plt.plot(ref[:, 0], ref[:, 1], "k.", label="Glowinski 2001 (FEM)")
    for name, path in runs:
        f, b = bodies(path)
        t, v = b["time"], b["velocity"][:, 0, :]
        sel = (t >= 0.3) & (t <= 0.65)
        vs = v[sel, 1].mean()
        g = f["/snapshots"][sorted(f["/snapshots"])[-1]]
        x, k = g["position"][:], g["kind"][:]
        dx = float(meta(f, "dx"))
        low = x[k == 2, 1].min()
        wall = x[(k == 1) & (x[:, 1] < 0) & (x[:, 0] > 0) & (x[:, 0] < 0.02), 1].max()
        ratio = 0.0025 / dx
        lines.append(f"| {ratio:.1f} | {len(k)} | {-vs:.4f} | {100 * (vs / v_ref - 1):+.1f}% | "
                     f"{np.abs(v[:, 1]).max():.4f} | {np.hypot(*v[-1]):.1e} m/s | {(low - wall) / dx:.2f} dx | "
                     f"{wall_seconds(path):.0f} s |")
        plt.plot(t, v[:, 1], label=f"sphd D/dx = {ratio:.1f}")
    plt.xlabel("t [s]")
    plt.ylabel("v_y [m/s]")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(out, "falling_disk.png"), dpi=90)
    lines += ["", "![falling disk](falling_disk.png)", ""]


def migration(runs, out, lines):
    H = 0.01
    feng02 = load_csv("couette_migration_disk_feng2002_via_hashemi2012.csv")
    feng94 = load_csv("couette_migration_disk_feng1994.csv")
    lines += ["## Disk migrating to the centre line of a shear flow (Fuchs 2021 Case 1, Re = 0.625)", "",
              "Released at y = H/4; the centre line is y = H/2 = 5 mm. References: Feng, Hu & Joseph 1994 (time in "
              "units of H/U_w = 0.5 s) and Feng 2002 via Hashemi 2012 (released at 3H/4, mirrored here).", "",
              "The disk's spin is compared with the torque-free rate of a free cylinder in unbounded Stokes shear, "
              "omega = -gamma/2 = -1 rad/s (gamma = 2 U_w / H; Jeffery 1922), which inertia (Re = 0.625) and the "
              "walls (D/H = 0.25) lower slightly.", "",
              "| D/dx | final y [mm] | distance to centre line | final u_x [m/s] | final speed / wall speed | "
              "omega, last 10 s [rad/s] | vs -gamma/2 | wall time |",
              "|---|---|---|---|---|---|---|---|"]
    plt.figure(figsize=(7, 4))
    plt.plot(feng94[:, 0] * 0.5, feng94[:, 1] * H * 1e3, "k.", label="Feng, Hu & Joseph 1994")
    plt.plot(feng02[:, 0], (H - feng02[:, 1]) * 1e3, "kx", label="Feng 2002 (mirrored)")
    for name, path in runs:
        f, b = bodies(path)
        t, p, v = b["time"], b["position"][:, 0, :], b["velocity"][:, 0, :]
        w = np.asarray(b["angular_velocity"]).reshape(len(t), -1)[:, 0]
        w_end = float(np.mean(w[t >= t[-1] - 10]))
        dx = float(meta(f, "dx"))
        lines.append(f"| {0.0025 / dx:.2f} | {p[-1, 1] * 1e3:.3f} | {100 * abs(p[-1, 1] - H / 2) / H:.2f}% of H | "
                     f"{v[-1, 0]:+.1e} | {np.hypot(*v[-1]) / 0.01:.1e} | {w_end:.4f} | {100 * (w_end / -1.0 - 1):+.1f}% | "
                     f"{wall_seconds(path):.0f} s |")
        plt.plot(t, p[:, 1] * 1e3, label=f"sphd D/dx = {0.0025 / dx:.2f}")
    lines += ["",
              "Before 2026-11-28 a turning body lacked the torque of the symmetric part of the viscous stress "
              "(tests/validation/reports/magnus.md): the D/dx = 6.25 run turned the disk at -1.60 rad/s (+60%) and "
              "reached the centre line with the references (y = 3.33 mm at t = 10, 4.939 mm at t = 60). Turning at "
              "the right rate, the disk at D/dx = 6.25 migrates more slowly (3.10 mm at t = 10, against about 3.5 "
              "for Feng et al.), and at D/dx = 12.5 it follows the references (plot). So the over-spin had made up "
              "for the weak lateral force of the coarse run."]
    plt.axhline(5, color="gray", lw=0.5)
    plt.xlabel("t [s]")
    plt.ylabel("y of disk centre [mm]")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(out, "disk_migration.png"), dpi=90)
    lines += ["", "![disk migration](disk_migration.png)", ""]


def schiller_naumann(rho_p, rho_f, mu, D, g):
    u = (rho_p - rho_f) * g * D * D / (18 * mu)
    for _ in range(200):
        re = rho_f * u * D / mu
        u = (rho_p - rho_f) * g * D * D / (18 * mu * (1 + 0.15 * re ** 0.687))
    return u, rho_f * u * D / mu


def settling_sphere(runs, out, lines):
    rho_p, rho_f, mu, D, g = 1120.0, 970.0, 0.373, 0.015, 9.81
    u_sn, re_sn = schiller_naumann(rho_p, rho_f, mu, D, g)
    tc = load_csv("sphere_settling_tencate2002_Re1.5_velocity.csv")
    lines += ["## Sphere settling in a box (ten Cate et al. 2002, Re = 1.5)", "",
              f"Schiller-Naumann terminal speed in unbounded fluid: {u_sn:.4f} m/s (Re = {re_sn:.2f}); ten Cate's "
              f"measured speed in the 100 x 100 x 160 mm box: {-tc[:, 1].min():.4f} m/s (walls slow the sphere).", "",
              "Settling speed = mean -u_z over the last 40% of the run (t >= 1.2 s of 2 s: the speed is on its "
              "plateau, varying by 1%, and the sphere still 3.5 D above the bottom).", "",
              "| D/dx | particles | settling speed [m/s] | max [m/s] | Re | vs Schiller-Naumann | vs ten Cate | wall time |",
              "|---|---|---|---|---|---|---|---|"]
    plt.figure(figsize=(7, 4))
    plt.plot(tc[:, 0], tc[:, 1], "k.", label="ten Cate 2002 (PIV)")
    for name, path in runs:
        f, b = bodies(path)
        t, v = b["time"], b["velocity"][:, 0, :]
        dx = float(meta(f, "dx"))
        vmax = -v[:, 2].min()
        vs = -v[t >= 0.6 * t[-1], 2].mean()
        n = f["/snapshots"][sorted(f["/snapshots"])[0]]["kind"].shape[0]
        lines.append(f"| {D / dx:.0f} | {n} | {vs:.4f} | {vmax:.4f} | {rho_f * vs * D / mu:.2f} | "
                     f"{100 * (vs / u_sn - 1):+.1f}% | {100 * (vs / -tc[:, 1].min() - 1):+.1f}% | "
                     f"{wall_seconds(path):.0f} s |")
        plt.plot(t, v[:, 2], label=f"sphd D/dx = {D / dx:.0f}")
    plt.axhline(-u_sn, color="gray", ls="--", label="Schiller-Naumann (unbounded)")
    plt.xlabel("t [s]")
    plt.ylabel("u_z [m/s]")
    plt.legend()
    plt.tight_layout()
    plt.savefig(os.path.join(out, "settling_sphere.png"), dpi=90)
    lines += ["", "![settling sphere](settling_sphere.png)", ""]


def spheres_box(runs, out, lines):
    lines += ["## 27 spheres settling in a cube (reduced strong-scaling case of Fuchs 2021)", ""]
    for name, path in runs:
        f, b = bodies(path)
        t, n, ke = b["time"], b["contacts"], b["kinetic_energy"].sum(axis=1)
        first = t[np.argmax(n.sum(axis=1) > 0)] if (n.sum(axis=1) > 0).any() else float("nan")
        vmax = np.abs(b["velocity"][-1]).max()
        lines += [f"First contact at t = {first:.2f} (the paper: first wall contact at about 2.5 for its taller cube); "
                  f"kinetic energy of the bodies peaks at {ke.max():.3g} and ends at {ke[-1]:.3g}; largest body speed "
                  f"at t = {t[-1]:.1f}: {vmax:.3g}; wall time {wall_seconds(path):.0f} s.", ""]
        # What the bodies and contact cost next to the fluid: the run's own per-unit timers.
        steps = float(f["/series/diagnostics/step"][-1])
        units = dict(kv.split("=") for kv in meta(f, "unit_seconds").split(","))
        total = sum(float(v) for v in units.values())
        kind = f["/snapshots"][sorted(f["/snapshots"])[0]]["kind"][:]
        lines += [f"Cost per step by unit over the whole run ({int(steps)} steps, {len(kind)} particles of which "
                  f"{int((kind == 2).sum())} rigid, {meta(f, 'ranks')} rank; `/meta/unit_seconds`), rigid-body and "
                  "contact units next to the fluid's:", "",
                  "| unit | ms per step | share |", "|---|---:|---:|"]
        for u, sec in sorted(units.items(), key=lambda kv: -float(kv[1])):
            if float(sec) / total >= 0.001:
                lines.append(f"| {u} | {1e3 * float(sec) / steps:.2f} | {100 * float(sec) / total:.1f}% |")
        lines.append("")
        plt.figure(figsize=(7, 4))
        plt.semilogy(t, ke + 1e-12, label="kinetic energy of the bodies")
        plt.semilogy(t, n.sum(axis=1) + 1e-12, label="contacting particle pairs")
        plt.xlabel("t")
        plt.legend()
        plt.tight_layout()
        plt.savefig(os.path.join(out, "spheres_box.png"), dpi=90)
        lines += ["![spheres box](spheres_box.png)", ""]


def main():
    runs_dir, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    found = sorted(d for d in os.listdir(runs_dir) if os.path.isfile(os.path.join(runs_dir, d, "result.h5")))
    group = lambda prefix: [(d, os.path.join(runs_dir, d)) for d in found if d.startswith(prefix)]
    lines = ["# Rigid-body validation report", "",
             "Written by `tests/validation/bodies/run.sh` (runs) and `report.py` (this page). Numbers are measured, "
             "not copied; wall times are on the machine that ran the script.", ""]
    if group("falling_disk"):
        falling_disk(group("falling_disk"), out, lines)
    if group("migration"):
        migration(group("migration"), out, lines)
    if group("settling_sphere"):
        settling_sphere(group("settling_sphere"), out, lines)
    if group("spheres_box"):
        spheres_box(group("spheres_box"), out, lines)
    open(os.path.join(out, "bodies.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
