#!/usr/bin/env python3
"""Force-elongation curve of the 2D necking bar (make_necking_bar.py): writes CSV_OUT with the
elongation (the grips' separation minus the initial one), the force the right grip holds per unit
thickness and per 1 mm of thickness, and the width at the centre (top and bottom observed
particles); prints the three stages and the peak force; plots PNG_OUT if matplotlib is there.

Stages: elastic until the equivalent plastic strain first appears (the force leaves the initial
slope: first sample whose secant modulus drops below 95 % of the initial one); uniform plastic
while the centre narrows as the homogeneous bar would (width / W0 within 0.5 % of 1 / lambda of
the grips); necking after that, the peak force at its start (Considere). The homogeneous
plane-strain force F = tau_xx(lambda) W0 / lambda with the rigid-plastic tau_xx = 2/sqrt(3)
k(alpha), alpha = 2/sqrt(3) ln(lambda) (elastic strains neglected) is printed alongside, and the
uniaxial-stress one (a plane-stress sheet or the 1D bar of the hardening law), F = k(ln lambda)
W0 t / lambda, whose Considere peak is what the thesis' "almost 8000 N" matches at t = 1 mm.

usage: analyze_necking_bar.py RESULT_H5 CSV_OUT [PNG_OUT]
"""
import math
import sys

import h5py

PL, PH = 53.334e-3, 12.826e-3
THICKNESS = 1e-3  # the convention of the thesis' "almost 8000 N": force per mm of thickness


def k(alpha):
    return 450e6 + (715e6 - 450e6) * (1 - math.exp(-16.93 * alpha)) + 129.24e6 * alpha


def main():
    path, csv_out = sys.argv[1], sys.argv[2]
    png = sys.argv[3] if len(sys.argv) > 3 else None
    with h5py.File(path, "r") as f:
        t = f["/series/diagnostics/time"][()]
        d = f["/series/elastic/bar/displacement"][()].reshape(len(t), 4, 2)
        force = f["/series/elastic/bar/constraint_force"][()].reshape(len(t), 2, 2)
    # Observed: 0 top centre, 1 bottom centre, 2 left end, 3 right end (in the grips).
    elong = d[:, 3, 0] - d[:, 2, 0]
    F = force[:, 1, 0]  # right grip, x [N/m]
    width = PH + d[:, 0, 1] - d[:, 1, 1]  # outer rows' separation change added to PH
    rows = []
    for n in range(len(t)):
        lam = 1 + elong[n] / PL
        alpha = 2 / math.sqrt(3) * math.log(lam) if lam > 1 else 0.0
        f_h = 2 / math.sqrt(3) * k(alpha) * PH / lam if lam > 1.004 else float("nan")
        f_s = k(math.log(lam)) * PH / lam if lam > 1.003 else float("nan")
        rows.append((t[n], elong[n], F[n], F[n] * THICKNESS, width[n], f_h * THICKNESS,
                     f_s * THICKNESS))
    with open(csv_out, "w") as f:
        f.write("time_s,elongation_mm,force_per_thickness_N_per_m,force_N_per_mm_thickness,"
                "centre_width_mm,homogeneous_plane_strain_N_per_mm,homogeneous_uniaxial_stress_N_per_mm\n")
        for r in rows:
            f.write(f"{r[0]:.6e},{r[1] * 1e3:.6f},{r[2]:.6e},{r[3]:.3f},{r[4] * 1e3:.6f},"
                    f"{r[5]:.3f},{r[6]:.3f}\n")
    peak = max(range(len(rows)), key=lambda n: rows[n][3])
    k0 = next(n for n in range(len(rows)) if rows[n][1] > 0.02e-3)
    slope0 = rows[k0][3] / rows[k0][1]
    yield_n = next((n for n in range(k0, len(rows)) if rows[n][3] / rows[n][1] < 0.95 * slope0),
                   None)
    neck_n = None
    for n in range(len(rows)):
        lam = 1 + rows[n][1] / PL
        if rows[n][1] > 0.5e-3 and abs(rows[n][4] / PH * lam - 1) > 0.005:
            neck_n = n
            break
    print(f"{path}: {len(rows)} samples to elongation {rows[-1][1] * 1e3:.3f} mm")
    if yield_n is not None:
        print(f"  elastic until elongation {rows[yield_n][1] * 1e3:.3f} mm, "
              f"force {rows[yield_n][3]:.0f} N/mm")
    if neck_n is not None:
        print(f"  uniform plastic until elongation {rows[neck_n][1] * 1e3:.3f} mm (centre width "
              f"{rows[neck_n][4] * 1e3:.3f} mm departs from W0 / lambda by 0.5 %), "
              f"force {rows[neck_n][3]:.0f} N/mm")
    print(f"  peak force {rows[peak][3]:.0f} N per mm of thickness ({rows[peak][2]:.4g} N/m) at "
          f"elongation {rows[peak][1] * 1e3:.3f} mm; thesis: 'almost 8000 N'")
    print(f"  end: force {rows[-1][3]:.0f} N/mm ({100 * (rows[-1][3] / rows[peak][3] - 1):+.1f} % "
          f"of the peak), centre width {rows[-1][4] * 1e3:.3f} mm "
          f"({100 * (rows[-1][4] / PH - 1):+.1f} %)")
    hp = max((r[5] for r in rows if r[5] == r[5]), default=float("nan"))
    hs = max((r[6] for r in rows if r[6] == r[6]), default=float("nan"))
    print(f"  homogeneous rigid-plastic bar, plane strain: peak {hp:.0f} N/mm; uniaxial stress "
          f"(plane stress): peak {hs:.0f} N/mm")
    if png:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("  no matplotlib: no plot")
            return
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot([r[1] * 1e3 for r in rows], [r[3] for r in rows], label="SPH, right grip")
        ax.plot([r[1] * 1e3 for r in rows], [r[5] for r in rows], "--",
                label="homogeneous, plane strain (rigid-plastic)")
        ax.plot([r[1] * 1e3 for r in rows], [r[6] for r in rows], "-.",
                label="homogeneous, uniaxial stress (rigid-plastic)")
        ax.axhline(8000, color="grey", lw=0.8, ls=":", label="thesis: 'almost 8000 N'")
        ax.set_xlabel("elongation [mm]")
        ax.set_ylabel("force per mm of thickness [N]")
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(png, dpi=120)
        print(f"  wrote {png}")
        # The equivalent plastic strain in three snapshots: peak, late necking, end.
        with h5py.File(path, "r") as f:
            snaps = sorted(f["/snapshots"].keys())
            times = [f["/snapshots/" + k].attrs["time"] for k in snaps]
            picks = sorted({min(range(len(snaps)), key=lambda i: abs(times[i] - want))
                            for want in (rows[peak][0], 0.8 * rows[-1][0], rows[-1][0])})
            fig, axs = plt.subplots(len(picks), 1, figsize=(7, 2.4 * len(picks)))
            for ax, i in zip(axs, picks):
                g = f["/snapshots/" + snaps[i]]
                x = g["position"][()]
                a = g["equivalent_plastic_strain"][()]
                sc = ax.scatter(x[:, 0] * 1e3, x[:, 1] * 1e3, c=a, s=3, vmin=0,
                                vmax=min(a.max(), 1.0))
                ax.set_aspect("equal")
                ax.set_title(f"t = {times[i]:.4g} s: equivalent plastic strain (max {a.max():.3g})",
                             fontsize=9)
                fig.colorbar(sc, ax=ax)
            fig.tight_layout()
            alpha_png = png.replace(".png", "_alpha.png")
            fig.savefig(alpha_png, dpi=70)
            print(f"  wrote {alpha_png}")


if __name__ == "__main__":
    main()
