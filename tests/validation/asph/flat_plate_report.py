#!/usr/bin/env python3
"""Report of run_flat_plate.sh: the 3D thin flat plate's centre deflection (X. Tang's thesis,
P-II, digest sec. 8.6, Table 2) against the thesis' z/H, with the load path, the inner steps and
the cost. Reads the series with h5dump (no h5py needed).

usage: flat_plate_report.py REPORT_MD COMMIT RANKS "NZ R LOAD_STEPS THRESHOLD P_OVER_E WALL H5"...
"""
import datetime
import math
import re
import subprocess
import sys

L, H = 0.508, 0.0254
E, NU = 53779.1e6, 0.3
# Thin-plate (Kirchhoff) centre deflection of a clamped square plate of side L under a uniform
# load q: 0.00126 q L^4 / D, D = E H^3 / (12 (1 - nu^2)) (Timoshenko & Woinowsky-Krieger 1959,
# Theory of plates and shells, Table 35, nu = 0.3). Shear deformation adds a few percent at
# L / H = 20.
KIRCHHOFF_W_OVER_P = 0.00126 * L**4 / (E * H**3 / (12 * (1 - NU**2)))
THESIS = {"SPH (N = 428 490)": 3.314, "ASPH r = 2 (114 490)": 3.338, "ASPH r = 4 (32 490)": 3.343,
          "ASPH r = 8 (10 240)": 3.320}


def zeta(t):
    """Gravity's ramp over damping_time = 1 (Adami 2012 eq. 13)."""
    return 0.5 * (math.sin((-0.5 + min(t, 1.0)) * math.pi) + 1.0)


def series(path, name):
    text = subprocess.run(["h5dump", "-y", "-w", "0", "-d", "/series/" + name, path],
                          check=True, capture_output=True, text=True).stdout
    dims = re.search(r"DATASPACE\s+SIMPLE\s+\{\s*\(([^)]*)\)", text).group(1)
    shape = [int(v) for v in dims.split(",")]
    body = text[text.index("DATA {") + len("DATA {"):]
    body = body[:body.rindex("}")]
    body = re.sub(r"\([0-9,]+\):", " ", body)
    values = [float(v) for v in re.findall(r"[-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?|nan|inf", body)]
    return shape, values


def particles(h5):
    text = subprocess.run(["h5dump", "-H", h5], check=True, capture_output=True,
                          text=True).stdout
    counts = re.findall(r'DATASET "id".*?DATASPACE\s+SIMPLE\s+\{\s*\(\s*(\d+)', text, re.S)
    return int(counts[0]) if counts else 0


def run(nz, r, steps, threshold, load, wall, h5):
    (rows, points, dim), d = series(h5, "elastic/plate/displacement")
    z = [sum(d[(k * points + p) * dim + 2] for p in range(points)) / points for k in range(rows)]
    _, t = series(h5, "diagnostics/time")
    _, inner = series(h5, "elastic/relaxation_steps")
    _, unrelaxed = series(h5, "elastic/unrelaxed_load_steps")
    return {"nz": int(nz), "r": float(r), "steps": int(steps), "threshold": float(threshold),
            "load": float(load),
            "wall": float(wall), "n": particles(h5), "t": t, "zh": [v / H for v in z],
            "inner": inner[-1], "unrelaxed": unrelaxed[-1]}


def main():
    report, commit, ranks = sys.argv[1], sys.argv[2], sys.argv[3]
    every = [run(*a.split()) for a in sys.argv[4:]]
    runs = [q for q in every if q["load"] >= 1e-3]
    linear = [q for q in every if q["load"] < 1e-3]
    ref = THESIS["ASPH r = 8 (10 240)"]
    lines = [
        "# 3D thin flat plate under a uniform load (X. Tang's thesis, P-II; digest sec. 8.6)",
        "",
        "Written by `tests/validation/asph/run_flat_plate.sh` (cases from `make_flat_plate.py`). "
        "A square neo-Hookean plate, L = W = 508 mm, H = 25.4 mm, E = 53779.1 MPa, nu = 0.3, "
        "rho = 1600 kg/m^3, clamped on all four edges by three layers of its own particles, under "
        "p = 0.01 E upwards (the 2D plate's load; the digest says the 3D load is the same \"by "
        "implication\"), carried as the body force p / (rho H) through the thickness and applied "
        "quasi-statically over the load steps (docs/quasi_static.md). z/H: the mid-plane's "
        "deflection at the centre (mean of the particles there) over H, at full load.",
        "",
        "| NZ | r | particles | load steps | threshold [J] | inner steps | unrelaxed | wall | z/H "
        f"| vs thesis ASPH r = 8 ({ref}) |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for q in runs:
        lines.append(
            f"| {q['nz']} | {q['r']:g} | {q['n']} | {q['steps']} | {q['threshold']:g} | "
            f"{q['inner']:.0f} | {q['unrelaxed']:.0f} | {q['wall']:.0f} s | {q['zh'][-1]:.4f} | "
            f"{100 * (q['zh'][-1] / ref - 1):+.2f}% |")
    lines += ["", "The thesis' Table 2 (z/H at steady state; N as printed there):",
              "", "| method | z/H |", "|---|---:|"]
    lines += [f"| {k} | {v} |" for k, v in THESIS.items()]
    if linear:
        lines += ["", "In the linear range (a load of 1e-6 E), the centre deflection w against thin-plate "
                  "theory, w_theory = 0.00126 q L^4 / D (Timoshenko & Woinowsky-Krieger, Table 35; "
                  "shear deformation would add a few percent at L / H = 20), and against the isotropic "
                  "run (r = 1) at the same NZ. With an even number of particles across the span the "
                  "centre is the mean of the four particles around it (w there is about 1% below the "
                  "centre's at 20 across, 5% at 10).", "",
                  "| NZ | r | particles across the span | particles | inner steps | wall | w / w_theory "
                  "| w / w of r = 1 |", "|---:|---:|---:|---:|---:|---:|---:|---:|"]
        iso = next((q for q in linear if q["r"] == 1), None)
        for q in linear:
            w = q["zh"][-1] * H
            theory = KIRCHHOFF_W_OVER_P * q["load"] * E
            across = round(L / (q["r"] * H / q["nz"]))
            rel = f"{w / (iso['zh'][-1] * H):.3f}" if iso and iso["nz"] == q["nz"] else ""
            lines.append(f"| {q['nz']} | {q['r']:g} | {across} | {q['n']} | {q['inner']:.0f} | "
                         f"{q['wall']:.0f} s | {w / theory:.3f} | {rel} |")
    first = runs[0]
    lines += ["", f"Load path of the first run (NZ = {first['nz']}, r = {first['r']:g}): z/H at "
              "load steps; the load is p zeta(t), gravity's ramp (Adami 2012 eq. 13) over t = 1.",
              "", "| t | load / p | z/H |", "|---:|---:|---:|"]
    every = max(1, len(first["t"]) // 10)
    for k in list(range(0, len(first["t"]), every)) + (
            [len(first["t"]) - 1] if (len(first["t"]) - 1) % every else []):
        t = first["t"][k]
        lines.append(f"| {t:.2f} | {zeta(t):.4f} | {first['zh'][k]:.4f} |")
    lines += ["", f"Code {commit}, {datetime.date.today()}, {ranks} rank(s) on this machine."]
    with open(report, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
