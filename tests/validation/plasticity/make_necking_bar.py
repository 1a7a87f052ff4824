#!/usr/bin/env python3
"""Writes the 2D (plane-strain) tensile necking bar of X. Tang's thesis, P-III (digest sec. 8.11):
a 53.334 x 12.826 mm steel bar (Table 5.1) whose width is reduced linearly towards the centre, by
1.8 % there, stretched by 10 mm in total through 3 particle layers at each end that move apart
symmetrically.

The particles: a lattice of spacing dp = PH / NY mapped onto the tapered bar so that each still
covers dp^2. Column k sits where the half-width is s(x) PH / 2 (s = 1 - 0.018 (1 - |x| / (PL / 2)));
its rows are the lattice rows scaled by s(x), and the column spacing is dp / s(x), so particle
area, and with it the volume V0 = m / rho0 = dp^2 that total Lagrangian SPH gives each particle, is
right everywhere. (The plain lattice inside the tapered polygon would not show the taper at all at
these resolutions: 0.115 mm is a third of dp at NY = 40; and rows scaled at equal column spacing
would carry the full width's volume through the narrow section: the sums of total Lagrangian SPH
count V0 per particle, so the imperfection would cancel.)

Loading: each end moves at V/2 (V = 1 m/s by default, about what the literature uses; the thesis
loads at 0.05 mm/s with multi-time stepping, which the solver does not have), ramped over RAMP s,
for 10 mm of total stretch. Kelvin-Voigt damping elastic_damping ETA (Pa s), hourglass control HG.

With LOAD_STEPS > 0 the bar is loaded quasi-statically instead (time.quasi_static,
docs/quasi_static.md): LOAD_STEPS load steps, the thesis' damping RELAX_ETA (3e4 Pa s) and
kinetic energy threshold THRESHOLD (J/m; the thesis' 1e-3 E_e, E_e = F dx / 2 with F = 8000 N
per mm and dx = 10 mm, is 40 J/m); V = 1e-4 m/s is the thesis' loading (t = 100 s).
usage: make_necking_bar.py OUT.textproto [NY=20] [V=1.0] [ETA=3000] [HG=0.1] [STRETCH=0.010]
                           [LOAD_STEPS=0] [THRESHOLD=40] [RELAX_ETA=3e4]
"""
import math
import sys

PL, PH = 53.334e-3, 12.826e-3
REDUCTION = 0.018
# Table 5.1: mu = 80.1938 GPa, K = 164.21 GPa; E, nu from them (E = 9 K mu / (3 K + mu)).
MU, K = 80.1938e9, 164.21e9
E = 9 * K * MU / (3 * K + MU)
NU = (3 * K - 2 * MU) / (2 * (3 * K + MU))


def scale(x):
    return 1 - REDUCTION * (1 - min(abs(x), PL / 2) / (PL / 2))


def columns(dp):
    """Column centres x >= 0, spaced dp / s(x) (midpoint rule), up to the end of the bar."""
    xs = []
    x = 0.5 * dp / scale(0.0)
    while x < PL / 2:
        xs.append(x)
        step = dp / scale(x)
        step = dp / scale(x + 0.5 * step)
        x += step
    return xs


def main():
    out = sys.argv[1]
    ny = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    v = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    eta = float(sys.argv[4]) if len(sys.argv) > 4 else 3000.0
    hg = float(sys.argv[5]) if len(sys.argv) > 5 else 0.1
    stretch = float(sys.argv[6]) if len(sys.argv) > 6 else 0.010
    load_steps = int(sys.argv[7]) if len(sys.argv) > 7 else 0
    threshold = float(sys.argv[8]) if len(sys.argv) > 8 else 40.0
    relax_eta = float(sys.argv[9]) if len(sys.argv) > 9 else 3e4
    dp = PH / ny
    xs = columns(dp)
    pts = []
    for xc in xs:
        for x in (-xc, xc):
            s = scale(x)
            for j in range(ny):
                pts.append((x, (j + 0.5 - ny / 2) * dp * s))
    pts.sort()
    end = stretch / v  # each end at v / 2
    ramp = min(2e-4, 0.1 * end)
    end += 0.5 * ramp  # the ramp's lost half
    grip = xs[-3] - 0.5 * dp  # the outer three columns
    quasi_static = ""
    if load_steps > 0:
        quasi_static = (f"\n  quasi_static {{ load_step: {end / load_steps:.17g} damping: {relax_eta:g} "
                        f"kinetic_energy_threshold: {threshold:g} }}\n")
    half = xs[-1] + dp
    with open(out, "w") as f:
        f.write(f"""# Written by tests/validation/plasticity/make_necking_bar.py {' '.join(sys.argv[2:])}
# 2D plane-strain tensile necking bar (thesis P-III, digest sec. 8.11): steel of Table 5.1
# (mu = 80.1938 GPa, K = 164.21 GPa, sigma_0 = 450 MPa, sigma_inf = 715 MPa, delta = 16.93,
# H = 129.24 MPa), 53.334 x 12.826 mm with a 1.8 % linear width reduction at the centre, NY = {ny}
# particles across (dp = {dp * 1e3:.5f} mm, {len(pts)} particles), stretched {stretch * 1e3:g} mm
# at {v:g} m/s in total. The force per unit thickness that the grips hold is the series
# elastic/bar/constraint_force (N/m; times 1 mm of thickness it is in N, the thesis' unit).
# tests/validation/plasticity/README.md has the results.
name: "necking_bar_2d"
description: "2D plane-strain necking of a J2-plastic steel bar (thesis P-III)"
dimension: 2
dx: {dp:.17g}
kernel: WENDLAND_C2
smoothing_length_ratio: 1.3
domain {{ lo {{ x: {-half - 0.01:.6g} y: -0.01 }} hi {{ x: {half + 0.01:.6g} y: 0.01 }} }}
materials {{
  name: "steel"
  phase: SOLID
  density: 7850
  youngs_modulus: {E:.17g}
  poisson_ratio: {NU:.17g}
  elastic_law: NEO_HOOKEAN
  elastic_damping: {eta:g}
  hourglass_control: {hg:g}
  plasticity {{
    yield_stress: 4.5e8
    saturation_stress: 7.15e8
    saturation_exponent: 16.93
    linear_hardening: 1.2924e8
  }}
}}
elastic_bodies {{
  name: "bar"
  material: "steel"
  shape {{ points {{
""")
        for x, y in pts:
            f.write(f"    points {{ x: {x:.9g} y: {y:.9g} }}\n")
        f.write(f"""  }} }}
  constraints {{
    region {{ box {{ lo {{ x: {-half:.6g} y: -0.01 }} hi {{ x: {-grip:.9g} y: 0.01 }} }} }}
    motion {{ velocity_x {{ piecewise_linear {{ times: [0, {ramp:g}, 1] values: [0, {-v / 2:g}, {-v / 2:g}] }} }} }}
  }}
  constraints {{
    region {{ box {{ lo {{ x: {grip:.9g} y: -0.01 }} hi {{ x: {half:.6g} y: 0.01 }} }} }}
    motion {{ velocity_x {{ piecewise_linear {{ times: [0, {ramp:g}, 1] values: [0, {v / 2:g}, {v / 2:g}] }} }} }}
  }}
  observation_points {{ x: 0 y: {PH / 2:.6g} }}
  observation_points {{ x: 0 y: {-PH / 2:.6g} }}
  observation_points {{ x: {-PL / 2:.6g} y: 0 }}
  observation_points {{ x: {PL / 2:.6g} y: 0 }}
}}
time {{ end_time: {end:.9g}{quasi_static} }}
output {{ interval: {end / 10:.6g} series_interval: {end / 400:.6g} }}
""")
    print(f"{out}: {len(pts)} particles, dp {dp * 1e3:.5f} mm, {len(xs) * 2} columns, "
          f"end time {end:.4g} s")


if __name__ == "__main__":
    main()
