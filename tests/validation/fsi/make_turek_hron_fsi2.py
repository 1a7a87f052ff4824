#!/usr/bin/env python3
"""Writes the Turek-Hron FSI2-type flexible beam behind a cylinder as X. Tang's thesis runs it
(paper P-I; digest ../shared/seeds/digests/tang_thesis_digest.md sec. 8.2) as a sph.v1.Case text.

Non-dimensional: D = 1, mean inflow U = 1 (parabolic, peak U0 = 1.5, ramped over t_s = 2),
rho_f = 1, Re = U D / nu = 100, beam 3.5 D x 0.2 D clamped in the cylinder's rear, linear elastic
(Saint Venant-Kirchhoff at these small strains) with E = 1.4e3, nu_s = 0.4, rho_s / rho_f = 10;
channel 11 D x 4.1 D (the thesis' shortened channel; Turek & Hron 2006 use 25 D), cylinder
centre 2 D from the inlet and 2 D from the bottom wall (slightly off-centre, which triggers the
oscillation), c = 20 U0 = 30, Wendland C2 with h = 1.3 dx, no-slip walls. The thesis' dp is
0.05 D. These are Turek & Hron's FSI2 numbers scaled by D = 0.1 m, U = 1 m/s, rho_f = 1000.

HOURGLASS sets the beam's Material.hourglass_control (default 0, off): at dx = D/30 the beam's
root went through the checkerboard mode without it (README.md).

usage: make_turek_hron_fsi2.py [DX] [T_END] [HOURGLASS] > case.textproto
"""
import sys

L, W, D = 11.0, 4.1, 1.0
XC, YC, R = 2.0, 2.0, 0.5
BEAM_T, BEAM_L = 0.2, 3.5


def box(ax, ay, bx, by):
    return f"box {{ lo {{ x: {ax:.10g} y: {ay:.10g} }} hi {{ x: {bx:.10g} y: {by:.10g} }} }}"


def case(dx, t_end, hourglass=0.0):
    h_ratio = 1.3
    rc = 2 * h_ratio * dx
    wall_t = rc
    buf = 4 * dx
    beam_lo, beam_hi = YC - BEAM_T / 2, YC + BEAM_T / 2
    beam = box(XC + R, beam_lo, XC + R + BEAM_L, beam_hi)
    ball = f"ball {{ center {{ x: {XC} y: {YC} }} radius: {R} }}"
    # Clamped over its first two particle columns, against the cylinder.
    clamp = box(XC, beam_lo - 0.1, XC + R + 2 * dx, beam_hi + 0.1)
    fluid = ("difference { base { " + box(0, 0, L, W) + " } subtract { " + ball +
             " } subtract { " + beam + " } }")
    tip = XC + R + BEAM_L - dx / 2
    return f"""# Turek-Hron FSI2-type flexible beam behind a cylinder, as in the thesis (paper P-I, digest 8.2).
# Written by tests/validation/fsi/make_turek_hron_fsi2.py {dx} {t_end}; report: tests/validation/fsi/README.md
name: "turek_hron_fsi2_2d"
description: "Flexible beam behind a cylinder (Turek-Hron FSI2, thesis P-I 8.2), D = 1, U = 1, Re = 100"
dimension: 2
dx: {dx:.10g}
kernel: WENDLAND_C2
smoothing_length_ratio: {h_ratio}
domain {{ lo {{ x: {-buf:.10g} y: {-wall_t:.10g} }} hi {{ x: {L + buf:.10g} y: {W + wall_t:.10g} }} }}
materials {{
  name: "fluid"
  density: 1
  eos {{ kind: LINEAR sound_speed: 30 }}
  kinematic_viscosity: 0.01
}}
materials {{
  name: "beam"
  phase: SOLID
  density: 10
  youngs_modulus: 1.4e3
  poisson_ratio: 0.4{f"{chr(10)}  hourglass_control: {hourglass:g}" if hourglass > 0 else ""}
}}
fluids {{ name: "channel" material: "fluid" shape {{ {fluid} }} }}
walls {{ name: "bottom" shape {{ {box(-buf, -wall_t, L + buf, 0)} }} }}
walls {{ name: "top" shape {{ {box(-buf, W, L + buf, W + wall_t)} }} }}
walls {{ name: "cylinder" shape {{ {ball} }} }}
elastic_bodies {{
  name: "beam" material: "beam"
  shape {{ {beam} }}
  constraints {{ region {{ {clamp} }} }}
  observation_points {{ x: {tip:.10g} y: {YC} }}
}}
open_boundaries {{
  name: "inlet" kind: INFLOW material: "fluid"
  region {{ lo {{ x: {-buf:.10g} y: 0 }} hi {{ x: 0 y: {W} }} }}
  direction {{ x: 1 }} profile: PARABOLIC mean_velocity: 1 ramp_time: 2
}}
open_boundaries {{
  name: "outlet" kind: OUTFLOW material: "fluid"
  region {{ lo {{ x: {L} y: 0 }} hi {{ x: {L + buf:.10g} y: {W} }} }}
  direction {{ x: 1 }} pressure: 0 backflow_stabilization: 1
}}
fluid_model {{ density: SUMMATION transport_velocity: true }}
time {{ end_time: {t_end:.10g} }}
output {{ interval: 1 series_interval: 0.02 }}
"""


def main():
    dx = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
    t_end = float(sys.argv[2]) if len(sys.argv) > 2 else 50.0
    hourglass = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
    sys.stdout.write(case(dx, t_end, hourglass))


if __name__ == "__main__":
    main()
