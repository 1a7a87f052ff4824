#!/usr/bin/env python3
"""Writes cases/powder_grains_2d.textproto: Fuchs et al. 2021, "Powder grains exposed to a
highly dynamic gas flow" (2D, the paper's non-dimensional parameters).

    /usr/bin/python3 cases/tools/make_powder_grains.py [CASES_DIR]

writes the paper's resolution (dx = 0.1) and a coarse variant powder_grains_2d_coarse
(dx = 0.25, the coarsest dx on which the 3-wide openings, the 1-thick dividing wall and the
buffers are whole numbers of particles with full kernel support).

The paper's grains come from a DEM pre-processing step with a cohesive powder model; we do not
have those positions, so the grains' diameters are drawn with a fixed seed from [2.5, 4.4] and
their positions from a deterministic settling under gravity (settle_grains.py). The choices the
paper leaves open are marked [D] in the case's header."""
import argparse
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from settle_grains import settle  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("cases_dir", nargs="?", default="cases")
args = ap.parse_args()

W, H = 20.0, 12.0  # each chamber (paper)
DIV = 1.0          # thickness of the wall between the chambers [D]
OPEN = 3.0         # inlet and outlet width (paper)
BUF = 1.0          # buffer length: >= r_c = 3 dx and a whole number of dx for dx = 0.1-0.25 [D]
N_GRAINS = 10      # [D]
X1 = W + DIV       # left face of the right chamber
X2 = X1 + W        # right face of the right chamber

rng = random.Random(20210617)
diameters = [rng.uniform(2.5, 4.4) for _ in range(N_GRAINS)]
grains, _ = settle(diameters, [0.0, 0.0], [W, H], seed=42)


def box(x0, y0, x1, y1):
    return "box { lo { x: %g y: %g } hi { x: %g y: %g } }" % (x0, y0, x1, y1)


# The gas fills both chambers and the opening above the dividing wall; the buffers of the inlet
# and outlet sit in channels through the top wall.
fluid_shape = "difference { base { %s } subtract { %s } }" % (box(0, 0, X2, H), box(W, 0, X1, H / 2))
inner = ("union { shapes { %s } shapes { %s } shapes { %s } }"
         % (box(0, 0, X2, H), box(0, H, OPEN, H + BUF), box(X2 - OPEN, H, X2, H + BUF)))
# Walls: a shell (ceil(r_c/dx) layers) around chambers and channels, open beyond the buffers'
# outer faces, plus the solid dividing wall; split at half height for the temperatures.
shell = ("difference { base { shell { inner { %s } } } subtract { %s } subtract { %s } }"
         % (inner, box(-0.1, H + BUF, OPEN + 0.1, H + BUF + 2), box(X2 - OPEN - 0.1, H + BUF, X2 + 0.1, H + BUF + 2)))
lower = ("union { shapes { intersection { shapes { %s } shapes { %s } } } shapes { %s } }"
         % (shell, box(-2, -2, X2 + 2, H / 2), box(W, 0, X1, H / 2)))
upper = "intersection { shapes { %s } shapes { %s } }" % (shell, box(-2, H / 2, X2 + 2, H + BUF + 2))



def write(path, name, dx, note):
    with open(path, "w") as f:
        f.write("""# Powder grains in a highly dynamic gas flow (Fuchs et al. 2021, 2D, the paper's
# non-dimensional, non-physical parameters): metal grains resting in the left of two chambers
# melt where they touch the hot lower walls; from t = 0.25 a gas jet through an inlet at the
# top left sweeps them over the dividing wall into the right chamber and out towards an outlet
# at the top right; after t = 0.5 the lower walls are cold and the melt re-solidifies.
# Paper values: chambers 20 x 12 each, connected by an opening spanning the upper half; inlet
# and outlet 3 wide at the top left and top right; solid metal rho 1, c_p 1, kappa 10, T0 = 25,
# diameters 2.5-4.4, at rest; gas rho 0.1, nu 100, c_p 0.01, kappa 0.1, T0 = 50; liquid metal
# rho 1, nu 100, c_p 1, kappa 10; T_t = 50; walls: upper half T = 50 always, lower half
# T = 100 for t <= 0.5 and 0 after; parabolic gas inflow and outflow, mean velocity 420, for
# t > 0.25; |g| = 1e4 downwards on all phases; p0 = 16e6 for both fluids (linear EOS,
# p = p0 (rho/rho0 - 1): c = 12649 in the gas, 4000 in the melt), p_b = p0; k_c = 1e8,
# d_c = 1e2; dx = 0.1; t in [0, 0.75]. The paper's fixed dt = 0.625e-5 is 0.25 dx / 4000, the
# melt's acoustic bound; we keep the adaptive bound of eq. 41 with the gas's sound speed
# (dt = 1.9e-6 at dx = 0.1, about 400k steps), since a step past the gas's bound is unstable.
# Choices of ours [D]:
#  - grain positions: %d grains, diameters drawn (seeded) from [2.5, 4.4], positions from a
#    deterministic settling under gravity (cases/tools/settle_grains.py) in place of the
#    paper's cohesive DEM powder, so the grains start at rest on the floor and on each other;
#  - the dividing wall is %g thick (x in [%g, %g], y in [0, %g]), so the box is %g wide; the
#    chambers are 20 wide each;
#  - inlet and outlet are openings in the top wall (x in [0, %g] and [%g, %g]) with the gas
#    flowing in downwards and out upwards ("width 3"); their buffers are %g long channels
#    through the top wall; the outlet is a velocity outlet (the paper prescribes the outflow
#    too), both start at t = 0.25 and ramp in over 0.01 (a sudden start sends a pressure wave
#    rho c U = 5.3e5 through the gas); inflowing gas has T = 50;
#  - "upper/lower half of the walls": wall particles above/below y = 6; the dividing wall is
#    in the lower half; the lower walls jump from 100 to 0 at t = 0.5;
#  - a hysteresis band of 2 around T_t (melt above 51, freeze below 49): grains at the
#    gas's and upper walls' temperature 50 = T_t would otherwise flicker; no latent heat (the
#    paper gives none);
#  - room for 1000 bodies (phase_transitions.max_bodies): when the lower walls cool, the melt
#    on the floor freezes at many places at once, each a new body that keeps its slot (the
#    default 2 x 10 + 64 stopped the coarse run at t = 0.686 on the body-table guard);
#  - bodies merge on touching (phase_transitions.merge_bodies): a particle of the molten
#    surface that froze beyond join_radius of every solid one joins the body it drifts onto,
#    and refrozen pieces that meet become one body; the grains as placed, resting on each
#    other, keep colliding (only particles that solidified in the run merge bodies);
#  - gravity ramped in over 0.01 (Adami 2012 eq. 13), gas initially at zero gauge pressure.
# Generated by cases/tools/make_powder_grains.py (seeded).
""" % (N_GRAINS, DIV, W, X1, H / 2, X2, OPEN, X2 - OPEN, X2, BUF))
        f.write(note)
        f.write('name: "%s"\n' % name)
        f.write('description: "Powder grains melting at a hot wall, swept by a gas jet into a second '
                'chamber, re-solidifying after cooling"\n')
        f.write("dimension: 2\ndx: %g\n" % dx)
        f.write("domain { lo { x: -1.5 y: -1.5 } hi { x: %g y: %g } }\n" % (X2 + 1.5, H + BUF + 1.5))
        f.write("""materials {
  name: "gas"
  density: 0.1
  eos { kind: LINEAR reference_pressure: 16e6 }
  kinematic_viscosity: 100
  transport_background_pressure: 16e6
  heat_capacity: 0.01
  thermal_conductivity: 0.1
}
materials {
  name: "liquid_metal"
  density: 1
  eos { kind: LINEAR reference_pressure: 16e6 }
  kinematic_viscosity: 100
  transport_background_pressure: 16e6
  heat_capacity: 1
  thermal_conductivity: 10
}
materials { name: "solid_metal" phase: SOLID density: 1 heat_capacity: 1 thermal_conductivity: 10 }
""")
        f.write('fluids {\n  name: "gas"\n  material: "gas"\n  shape { %s }\n  initial_temperature: 50\n}\n'
                % fluid_shape)
        f.write('walls {\n  name: "lower"\n  shape { %s }\n' % lower)
        f.write("  temperature { value { piecewise_constant { times: [0, 0.5] values: [100, 0] } } }\n}\n")
        f.write('walls {\n  name: "upper"\n  shape { %s }\n' % upper)
        f.write("  temperature { value { constant: 50 } }\n}\n")
        for name, kind, x0, direction in (("inlet", "INFLOW", 0.0, "y: -1"),
                                          ("outlet", "OUTFLOW", X2 - OPEN, "y: 1")):
            f.write("""open_boundaries {
  name: "%s"
  kind: %s
  material: "gas"
  region { lo { x: %g y: %g } hi { x: %g y: %g } }
  direction { %s }
  profile: PARABOLIC
  mean_velocity: 420
  start_time: 0.25
  ramp_time: 0.01
%s}
""" % (name, kind, x0, H, x0 + OPEN, H + BUF, direction,
           "  temperature: 50\n" if kind == "INFLOW" else ""))
        for k, (c, r) in enumerate(grains):
            f.write('bodies { name: "grain_%02d" material: "solid_metal" initial_temperature: 25 '
                    "shape { ball { center { x: %.4f y: %.4f } radius: %.4f } } }\n" % (k, c[0], c[1], r))
        f.write("""contact { stiffness: 1e8 damping: 1e2 }
thermal { initial_temperature: 50 }
phase_transitions {
  solid_material: "solid_metal"
  fluid_material: "liquid_metal"
  driver: TEMPERATURE
  transition_value: 50
  hysteresis: 2
  reversible: true
  max_bodies: 1000
  merge_bodies: true
}
gravity { acceleration { y: -1e4 } damping_time: 0.01 }
fluid_model { density: SUMMATION transport_velocity: true }
time { end_time: 0.75 }
output { interval: 0.025 series_interval: 0.0025 }
""")

    print("wrote", path)


write(os.path.join(args.cases_dir, "powder_grains_2d.textproto"), "powder_grains_2d", 0.1, "")
write(os.path.join(args.cases_dir, "powder_grains_2d_coarse.textproto"), "powder_grains_2d_coarse", 0.25,
      "# Coarse variant: dx = 0.25 (the coarsest dx with whole particles across the openings, the\n"
      "# dividing wall and the buffers; about 9k particles), the same scene otherwise.\n")
print(len(grains), "grains, pile top at y = %.2f" % max(c[1] + r for c, r in grains))
