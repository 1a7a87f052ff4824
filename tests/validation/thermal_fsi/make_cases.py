#!/usr/bin/env python3
"""Writes the four configurations of the reduced TFSI heated channel (X. Tang's thesis, paper
P-I; digest sec. 8.3, Table 3) as sph.v1.Case text files into the directory given:

  I    no vortex generator
  II   a fixed cylinder
  III  the cylinder with a rigid beam behind it
  IV   the cylinder with a flexible beam (total Lagrangian elastic body clamped in the cylinder)

Non-dimensional, after the Turek-Hron FSI2 set-up the thesis uses (digest 8.2): D = 1, mean
inflow velocity U = 1 (parabolic, peak 1.5, ramped over t_s = 2), rho_f = 1, Re = U D/nu = 100,
beam 3.5 D x 0.2 D, E = 1.4e3, nu_s = 0.4, rho_s/rho_f = 10; the diffusion constant
k/(rho c_p) = 0.001 (Pe = 1000). The channel walls are hot (T = 1), the inflow and the
initial fluid cold (T = 0); cylinder and beams exchange no heat (thesis: only fluid
temperatures evolve).

Reduced from the thesis: the channel is 12 D long instead of 31 D, 4.1 D wide (Turek-Hron,
so the cylinder at 2.0 D from the bottom is slightly off-centre and sheds) instead of 4.0 D,
the quintic spline with h = dx instead of Wendland C2 with h = 1.3 dx, and the run ends at
t = T_END (argument, default 20) instead of 100. The sound speed is the thesis' c = 20 U0 = 30:
with 15 the ramped inflow compressed the column by 5% and the fluid tore open when the ramp
ended (docs/thermal_fsi.md).

usage: make_cases.py OUT_DIR [DX] [T_END]
"""
import os
import sys

L, W, D = 12.0, 4.1, 1.0
XC, YC, R = 2.0, 2.0, 0.5
BEAM_T, BEAM_L = 0.2, 3.5


def box(ax, ay, bx, by):
    return f"box {{ lo {{ x: {ax:.10g} y: {ay:.10g} }} hi {{ x: {bx:.10g} y: {by:.10g} }} }}"


def case(config, dx, t_end):
    wall_t = 0.15 if dx <= 0.05 else 3 * dx
    buf = 4 * dx
    beam_lo, beam_hi = YC - BEAM_T / 2, YC + BEAM_T / 2
    # The beam reaches 3.5 D behind the cylinder's rear; the flexible one is clamped over its
    # first two particle columns, against the cylinder.
    beam = box(XC + R, beam_lo, XC + R + BEAM_L, beam_hi)
    ball = f"ball {{ center {{ x: {XC} y: {YC} }} radius: {R} }}"
    subtract = []
    solids = []
    if config >= 2:
        subtract.append(ball)
    if config >= 3:
        subtract.append(beam)
    if config == 2:
        solids.append(f'walls {{ name: "cylinder" shape {{ {ball} }} }}')
    elif config == 3:
        solids.append(
            f'walls {{ name: "cylinder" shape {{ union {{ shapes {{ {ball} }} shapes {{ {beam} }} }} }} }}')
    elif config == 4:
        solids.append(f'walls {{ name: "cylinder" shape {{ {ball} }} }}')
        clamp = box(XC, beam_lo - 0.1, XC + R + 2 * dx, beam_hi + 0.1)
        solids.append(
            'elastic_bodies { name: "beam" material: "beam" '
            f'shape {{ {beam} }} constraints {{ region {{ {clamp} }} }} '
            f'observation_points {{ x: {XC + R + BEAM_L - dx / 2} y: {YC} }} }}')
    channel = box(0, 0, L, W)
    if subtract:
        fluid_shape = "difference { base { " + channel + " } " + " ".join(
            "subtract { " + s + " }" for s in subtract) + " }"
    else:
        fluid_shape = channel
    name = ["", "I", "II", "III", "IV"][config]
    return f"""# Reduced TFSI heated channel, configuration {name} (tests/validation/thermal_fsi/make_cases.py)
name: "tfsi_channel_{name}"
description: "TFSI heated channel with vortex generators (thesis P-I), configuration {name}, reduced"
dimension: 2
dx: {dx}
domain {{ lo {{ x: {-buf} y: {-wall_t} }} hi {{ x: {L + buf} y: {W + wall_t} }} }}
materials {{
  name: "fluid"
  density: 1
  eos {{ kind: LINEAR sound_speed: 30 }}
  kinematic_viscosity: 0.01
  heat_capacity: 1
  thermal_conductivity: 0.001
}}
materials {{
  name: "beam"
  phase: SOLID
  density: 10
  youngs_modulus: 1.4e3
  poisson_ratio: 0.4
  heat_capacity: 1
  thermal_conductivity: 0
}}
fluids {{ name: "channel" material: "fluid" shape {{ {fluid_shape} }} initial_temperature: 0 }}
walls {{ name: "bottom" shape {{ {box(-buf, -wall_t, L + buf, 0)} }} temperature {{ value {{ constant: 1 }} }} }}
walls {{ name: "top" shape {{ {box(-buf, W, L + buf, W + wall_t)} }} temperature {{ value {{ constant: 1 }} }} }}
{chr(10).join(solids)}
open_boundaries {{
  name: "inlet" kind: INFLOW material: "fluid"
  region {{ {box(-buf, 0, 0, W)[6:-2]} }}
  direction {{ x: 1 }} profile: PARABOLIC mean_velocity: 1 ramp_time: 2 temperature: 0
}}
open_boundaries {{
  name: "outlet" kind: OUTFLOW material: "fluid"
  region {{ {box(L, 0, L + buf, W)[6:-2]} }}
  direction {{ x: 1 }} pressure: 0
}}
thermal {{ initial_temperature: 0 }}
fluid_model {{ density: SUMMATION transport_velocity: true }}
time {{ end_time: {t_end} }}
output {{ interval: 1 series_interval: 0.05 }}
"""


def main():
    out = sys.argv[1]
    dx = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
    t_end = float(sys.argv[3]) if len(sys.argv) > 3 else 20.0
    os.makedirs(out, exist_ok=True)
    for config in range(1, 5):
        name = ["", "I", "II", "III", "IV"][config]
        with open(os.path.join(out, f"tfsi_channel_{name}.textproto"), "w") as f:
            f.write(case(config, dx, t_end))


if __name__ == "__main__":
    main()
