#!/usr/bin/env python3
"""Report of the porous beam run (run_porous_beam.sh): the centre's deflection (bottom and top
rows, series elastic/beam/displacement) and the species mass at each load step, the inner steps
they took, against the thesis' step counts (P-III Table 5.5: 125 outer and 3.25e5 inner steps
against 1.58e7 straightforward ones). Reads the series with h5dump (no h5py needed).

usage: analyze_porous_beam.py RESULT_H5 CSV_OUT MD_OUT WALL_SECONDS RANKS
"""
import re
import subprocess
import sys


def series(path, name):
    text = subprocess.run(["h5dump", "-y", "-w", "0", "-d", "/series/" + name, path],
                          check=True, capture_output=True, text=True).stdout
    body = text[text.index("DATA {") + len("DATA {"):]
    body = body[:body.rindex("}")]
    body = re.sub(r"\([0-9,]+\):", " ", body)
    return [float(v) for v in re.findall(r"[-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?|nan|inf", body)]


def main():
    path, csv_out, md_out = sys.argv[1], sys.argv[2], sys.argv[3]
    wall, ranks = float(sys.argv[4]), int(sys.argv[5])
    t = series(path, "diagnostics/time")
    d = series(path, "elastic/beam/displacement")  # per row: bottom x, y, top x, y
    inner = series(path, "elastic/relaxation_steps")
    unrelaxed = series(path, "elastic/unrelaxed_load_steps")
    mass = series(path, "diagnostics/species_mass")
    cmax = series(path, "diagnostics/concentration_max")
    n = len(t)
    rows = []
    for k in range(n):
        rows.append((t[k], d[4 * k + 1], d[4 * k + 3], inner[k], unrelaxed[k], mass[k], cmax[k]))
    with open(csv_out, "w") as f:
        f.write("time_s,centre_bottom_uy_m,centre_top_uy_m,inner_steps_so_far,"
                "unrelaxed_load_steps,species_mass,concentration_max\n")
        for r in rows:
            f.write(f"{r[0]:.4f},{r[1]:.6e},{r[2]:.6e},{r[3]:.0f},{r[4]:.0f},{r[5]:.6e},"
                    f"{r[6]:.6f}\n")
    peak = max(range(n), key=lambda k: abs(rows[k][1]))
    load_steps = round(t[-1] / (t[1] - t[0])) if n > 1 else 0
    h = 1.3 * 3.125e-5
    plain = t[-1] / (0.6 * h / (8.242e6 / (3 * (1 - 2 * 0.2631)) / 2000) ** 0.5)
    lines = [
        "# Porous beam bent by a diffusing droplet (thesis P-III sec. 5.5.3, digest sec. 8.13)",
        "",
        "Written by tests/validation/porous/run_porous_beam.sh from cases/porous_beam_2d.textproto "
        f"({ranks} rank(s), {wall:.0f} s wall time on this machine). Deflection: the beam's centre "
        "particle on its bottom row (y displacement; negative is downwards).",
        "",
        "| t [s] | centre deflection, bottom [um] | top [um] | inner steps so far | max saturation |",
        "|---|---|---|---|---|",
    ]
    for k in range(n):
        if k % 10 == 0 or k == peak or k == n - 1:
            r = rows[k]
            lines.append(f"| {r[0]:.1f} | {r[1] * 1e6:.3f} | {r[2] * 1e6:.3f} | {r[3]:.0f} | "
                         f"{r[6]:.4f} |")
    lines += [
        "",
        f"- Largest deflection {rows[peak][1] * 1e6:.3f} um at t = {rows[peak][0]:.1f} s; at the "
        f"end {rows[-1][1] * 1e6:.3f} um.",
        f"- {load_steps} load steps, {inner[-1]:.0f} inner steps ({inner[-1] / max(load_steps, 1):.0f} "
        f"a load step), {unrelaxed[-1]:.0f} load steps unrelaxed; plain steps at the solid's bound at "
        f"rest (0.6 h / c_s) would take {plain:.3g}.",
        "- Thesis (P-III Table 5.5, NY = 8, its own units): 125 outer and 3.25e5 inner steps "
        "against 1.58e7 straightforward ones.",
        f"- Species mass: {mass[0]:.4e} at the start, {max(mass):.4e} at most, {mass[-1]:.4e} at "
        "the end (the hold puts water in for the first 10 s; none leaves afterwards).",
    ]
    with open(md_out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
