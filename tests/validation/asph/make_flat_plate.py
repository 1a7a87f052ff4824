#!/usr/bin/env python3
"""Writes the 3D thin flat plate of X. Tang's thesis, paper P-II (digest sec. 8.6) as a case.

A square neo-Hookean plate, L = W = 508 mm, H = 25.4 mm, E = 53779.1 MPa, nu = 0.3,
rho = 1600 kg/m^3, clamped on all four edges by three layers of its own particles, under a
uniform upward load p = 0.01 E. NZ particles through the thickness (dx = H / NZ) and R times
that along the plate (ASPH, docs/asph.md). The load is carried as a body force p / (rho H)
over the plate's thickness, ramped over the run and applied quasi-statically
(docs/quasi_static.md), so the run ends at the equilibrium the thesis calls steady state.
The centre deflection is the series elastic/plate/displacement: the mean z displacement of the
observation points (the mid-plane at the centre, or the two particles either side of it).

usage: make_flat_plate.py NZ R [LOAD_STEPS] [THRESHOLD_J] [P_OVER_E] [DAMPING_PA_S] > case
(P_OVER_E: the load over E, 0.01 by default; 1e-6 keeps the plate in its linear range, where
thin-plate theory gives the centre deflection. DAMPING_PA_S: eta of the relaxation, by default
the thesis' choice.)
"""
import sys

L, H = 0.508, 0.0254
E, NU, RHO = 53779.1e6, 0.3, 1600.0
CLAMP_LAYERS = 3


def main():
    nz, r = int(sys.argv[1]), float(sys.argv[2])
    load_steps = int(sys.argv[3]) if len(sys.argv) > 3 else 20
    threshold = float(sys.argv[4]) if len(sys.argv) > 4 else 0.1
    p = (float(sys.argv[5]) if len(sys.argv) > 5 else 0.01) * E
    dx = H / nz
    s = r * dx  # spacing along the plate
    n = L / s
    if abs(n - round(n)) > 1e-9:
        sys.exit(f"L / (R dx) = {n:g} is not a whole number of particles")
    c = CLAMP_LAYERS * s
    lo, hi = -c, L + c
    pad = 0.1
    # The lattice puts particles at lo + (k + 1/2) s: one lies at the centre when n is odd.
    centre = [L / 2] if round(n) % 2 == 1 else [L / 2 - s / 2, L / 2 + s / 2]
    zs = [H / 2] if nz % 2 == 1 else [H / 2 - dx / 2, H / 2 + dx / 2]
    g = p / (RHO * H)
    # The thesis' damping choice (docs/quasi_static.md): eta = beta / 4 sqrt(rho E) L, beta = H / L.
    eta = float(sys.argv[6]) if len(sys.argv) > 6 else (H / L) / 4 * (RHO * E) ** 0.5 * L
    out = [
        f"# Written by tests/validation/asph/make_flat_plate.py {' '.join(sys.argv[1:])}",
        "# 3D thin flat plate under a uniform load, all edges clamped (X. Tang's thesis, P-II;",
        "# digest sec. 8.6; tests/validation/reports/asph_flat_plate.md).",
        f'name: "flat_plate_asph_3d"',
        f'description: "3D square plate L = 508 mm, H = 25.4 mm, clamped edges, p = {p / E:g} E, '
        f'NZ = {nz}, ASPH r = {r:g}"',
        "dimension: 3",
        f"dx: {dx!r}",
        "kernel: WENDLAND_C2",
        "smoothing_length_ratio: 1.3",
        f"domain {{ lo {{ x: {lo - pad!r} y: {lo - pad!r} z: -0.05 }} "
        f"hi {{ x: {hi + pad!r} y: {hi + pad!r} z: 0.2 }} }}",
        "materials {",
        '  name: "plate"',
        "  phase: SOLID",
        f"  density: {RHO!r}",
        f"  youngs_modulus: {E!r}",
        f"  poisson_ratio: {NU!r}",
        "  elastic_law: NEO_HOOKEAN",
        "}",
        "elastic_bodies {",
        '  name: "plate"',
        '  material: "plate"',
        f"  shape {{ box {{ lo {{ x: {lo!r} y: {lo!r} z: 0 }} hi {{ x: {hi!r} y: {hi!r} z: {H!r} }} }} }}",
    ]
    big_lo, big_hi = lo - pad, hi + pad
    for box in [((big_lo, big_lo), (0.0, big_hi)), ((L, big_lo), (big_hi, big_hi)),
                ((big_lo, big_lo), (big_hi, 0.0)), ((big_lo, L), (big_hi, big_hi))]:
        (x0, y0), (x1, y1) = box
        out.append(f"  constraints {{ region {{ box {{ lo {{ x: {x0!r} y: {y0!r} z: -0.05 }} "
                   f"hi {{ x: {x1!r} y: {y1!r} z: 0.2 }} }} }} }}")
    for x in centre:
        for y in centre:
            for z in zs:
                out.append(f"  observation_points {{ x: {x!r} y: {y!r} z: {z!r} }}")
    out += [
        *([f"  anisotropy {{ ratio: {r:g} thickness_direction {{ z: 1 }} }}"] if r != 1 else []),
        "}",
        f"gravity {{ acceleration {{ z: {g!r} }} damping_time: 1 }}",
        "time {",
        "  end_time: 1",
        f"  quasi_static {{ load_step: {1.0 / load_steps!r} damping: {eta!r} "
        f"kinetic_energy_threshold: {threshold!r} }}",
        "}",
        f"output {{ interval: 0.5 series_interval: {1.0 / load_steps!r} }}",
    ]
    print("\n".join(out))


if __name__ == "__main__":
    main()
