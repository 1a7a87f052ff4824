"""Writes docs/accuracy.md and docs/accuracy/<study>.png from the results of run.sh.

Reads, for every study listed on stdin ("name|case|sph-worker ladder flags" per line), the
study.csv and study.md that sph-worker wrote (study/study_report.cc): the numbers, fits and
target resolutions come from there, so the report says exactly what the studies measured.
Usage: printf '%s\\n' "${studies[@]}" | report.py --results DIR --docs DIR
"""
import argparse
import csv
import os
import platform
import shutil
import subprocess
import sys

# What each study shows, beyond its table (written after looking at the results of the ladders
# in run.sh; the numbers quoted are from the committed run).
COMMENTS = {
    "conduction": """
Second order, as Cleary-Monaghan conduction with the mirror Dirichlet wall should be: 3% at
two particles per diffusion length (dx = 0.1; the heat has spread 2 sqrt(a t) = 0.2) down to
0.05% at dx = 0.0125, a straight line over all seven levels. 1% needs dx = 0.057 (about four
particles per diffusion length). The cost grows fast with resolution because the conduction
time-step bound 0.1 h^2 / a, not the acoustic one, sets the step here (cost ~ dx^-4 in 2D),
so the error falls only as wall^-0.5 asymptotically (-0.7 measured: fixed costs per run flatter
the tiny coarse levels).
""",
    "poiseuille": """
The start-up profile at t = 10 converges at order 1.8 over seven levels: 3.7% of u_max with
four particles across the channel (dx = 0.25), 1.0% with eight, 0.086% with 32. 1% needs
about eight particles across (dx = 0.124), at 0.04 s of one core per unit of simulated time;
5% and 10% are met by the coarsest level, four particles across.
""",
    "couette": """
Order 1.85 over seven levels: 1.7% of the wall speed with four particles across (dx = 0.25),
0.72% with six, 0.038% with 32. Finer than this the error levels off: a previous ladder (ten
to 55 particles across, in a narrower box) gave 0.023% at dx = 0.025 and 0.0225% at 0.018,
where something other than resolution dominates (the weakly compressible model, Ma = 0.1, is
the likely one). 1% needs five particles across (dx = 0.2), 0.01 s of one core per unit of
simulated time; 5% and 10% are met by the coarsest level.
""",
    "taylor_green": """
The velocity field converges at first order: 21% of the amplitude at 20 particles per
wavelength, 5.6% at 80. The study measures the field because the decay rate (column
`quantity` of the CSV) is a signed quantity: it is 10.7% too fast at dx = 0.05, 0.04% off at dx = 0.018 and
0.8% too slow at dx = 0.0125, so its error passes through zero between levels and no power
law describes it (FreeSurface.TaylorGreenDecayRate still checks it at dx = 0.04). With the
amplitude right within about 1%, most of the field error at the finest level is in its shape
(particle-scale velocity fluctuations of the weakly compressible, transport-velocity scheme
are the likely source). 10% needs about 42 particles per wavelength; 5% about 85 (extrapolated); 1% would
need some 440 (dx = 0.0023, 190k particles, some 20 core-minutes per unit of simulated time),
which says the scheme at Ma = 0.1 is not the tool for a 1% velocity field.
""",
    "hydrostatic": """
Every level is within 1% of rho g (H + dx/2), but the error does not fall with resolution
(order -0.7), and this is not noise of the single snapshot the study measures. Sampled every
0.03 for 5 <= t <= 10 (by hand, not part of the study), the bottom pressure oscillates at the
quarter-wave acoustic period 4H/c (0.388 s measured, 0.379 predicted) with an amplitude of
0.42% at dx = 0.05, 0.79% at 0.025 and 0.75% at 0.0167, around a mean that is itself off by
0.05%, 0.48% and 0.38%. Keeping the Reynolds number fixed under refinement as Adami 2012 did
(alpha proportional to 1/dx, eq. 12) and switching on the transport-velocity formulation
change neither (0.48% and 0.50% at dx = 0.025). The time-averaged pressure of the first wall
layer is not uniform along the bottom: at dx = 0.025 it is 0.68% high in the middle and
-0.02% at the corners; the difference between the middle and the corners grows from 0 at
t = 3 to 1.0% at t = 6.6 and is back to 0.4% at t = 10, while the free surface stays flat to
0.4 mm (0.016 dx). The first fluid rows alternate (+0.47%, -0.77%, +0.13%, -0.50% of rho g H
at dx = 0.025). Run on to t = 40, the same happens at dx = 0.05 later (middle 1.0% above the
corners at t = 18, 0.14% at t = 40), while at dx = 0.025 the difference stays at 0.95% from
t = 24 to 40; the mean error over 30 <= t <= 40 is 0.26% at dx = 0.05 and 0.63% at 0.025.
At t = 40 the particles in the middle of the bottom are disordered (mean nearest-neighbour
distance 0.92 dx) and those near the side walls still close to the initial lattice (0.95 dx),
at the same mean density. So what does not converge is the wall pressure's dependence on the
local particle arrangement: the initial Cartesian lattice breaks up under the hydrostatic
load, from the middle outwards, at a time and to an extent that depend on the resolution.
What the particle arrangement and the oscillation leave aside is measured by the steady variant
([below](#hydrostatic_steady)), which damps the mode and keeps the lattice. All three
targets need only dx = 0.05, 18 particles over the depth.

Measured since (session of 2026-11-23, an experimental build with h / dx as a case setting,
kept as a patch, not on main; walls thickened with r_c, domain enlarged to hold them): the
same study with **h = 2 dx** gives 0.0084%, 0.023%, 0.0022%, 0.197% and 0.119% at dx = 0.05,
0.0333, 0.025, 0.02 and 0.0167 (h = dx, same domain: 0.45%, 0.090%, 0.25%, 0.83% at 0.05,
0.0333, 0.025, 0.0167). The acoustic oscillation of the centreline probe pressure over
5 <= t <= 10 (standard deviation / rho g H, mean over 0.2 < y < 0.7) falls from 0.17%, 0.35%,
0.44% (h = dx, dx = 0.05, 0.0333, 0.025; it grows as the artificial viscosity alpha h c / 8
falls with h) to 0.11%, 0.05%, 0.04% at h = 2 dx. So a larger h / dx lowers the error at the
coarse levels by up to two orders of magnitude, but the finer levels still show no order: a
larger smoothing length alone is not the cure either. The time-averaged centreline pressure
is 0.4% of rho g H below rho0 g (H - y) at every level and both ratios; that part is the
reference's (the surface of a compressed column sits about 0.5% of H below the mass-based H),
not the solver's.

Against the compressible column itself (dp/dy = -rho(p) g from the bottom pressure g M / W,
rho(p) from the Tait EOS; measured by hand on the same h = dx runs, not part of the study),
the time-averaged centreline pressure of the fluid (probes, 0.1 < y < 0.8) deviates by
0.078%, 0.047% and 0.047% of rho g H (rms; largest 0.15%, 0.12%, 0.10%) at dx = 0.05, 0.025
and 0.0167 (averaged over 5 <= t <= 40, or 20 at 0.0167), where the first wall layer under the
middle of the bottom is off by 0.26% and 0.63% (30 <= t <= 40, dx = 0.05 and 0.025). The
wall condition (Adami 2012 eq. 27) reproduces a linear fluid pressure exactly whatever the
particle arrangement, so the wall layer's excess comes from the first fluid rows, whose
particle pressures alternate about the smooth field (by up to 0.8% at dx = 0.025); the
smoothed pressure inside the fluid is about ten times more accurate than the wall layer's.
Neither shows an order: the acoustic oscillation (standard deviation over 10 <= t <= 40 of
the probes below y = 0.07: 0.22%, 0.44% and 0.71% of rho g H) grows under refinement, as the
artificial viscosity alpha h c / 8 falls with h.
""",
    "hydrostatic_steady": """
The same tank with the acoustic mode damped and a larger smoothing length: a physical
viscosity nu = 0.3 instead of alpha = 0.24 (the rest state does not depend on it) and
h = 2 dx (`smoothing_length_ratio: 2`; see the case file). The oscillation is gone (the probe
pressures' standard deviation over 9 <= t <= 10 is below 0.001% of rho g H), the Cartesian
lattice stays intact and the first wall layer is uniform along the bottom. The error falls
from 0.026% at dx = 0.05 to 0.0023% at dx = 0.0167 (fitted order 2.2; the first two levels are
equal, then it falls at order 1.6 and 4.9, so read the slope as "about second order"
rather than a clean power law). Why h = 2 dx, measured by hand on the same case:

- **At h = dx there is a floor.** The same ladder at h = dx gives 0.071%, 0.079%, 0.081% and
  0.084%: no dependence on dx left. On a square lattice with h = dx the quintic spline's
  discrete first moment sum_j V_j (y_j - y_i) dW/dy_i is -1.00080 instead of -1 (-0.99938 at
  h = 1.2 dx, -0.9999933 at h = 2 dx; summed directly), so the discrete gradient of a linear
  pressure is 0.08% too steep and in equilibrium the pressure rises 0.08% too slowly with
  depth. With c raised fourfold (which makes the compressible part below 16 times smaller) the
  error at h = dx is -0.065% and -0.067% at dx = 0.05 and 0.025, and -0.064% with the side
  walls replaced by a periodic boundary (so it is not the corners). At a fixed h / dx this part
  does not fall with dx; it falls with h / dx (SPH's discretisation error at fixed h / dx,
  Quinlan, Basa & Lastiwka 2006). At h = 2 dx and 4c the error falls from 0.049% to 0.0060%
  between dx = 0.05 and 0.025.
- **The Mach number adds an O(Ma^2) part at the wall.** The first fluid rows' pressures
  alternate about the smooth field, the second row below the first by 0.42%, 0.11% and 0.02%
  of rho g H at c, 2c and 4c (h = dx, at both dx): a quarter with each doubling of c. The
  dummy particles' volume m_w / rho_w (Adami 2012) shrinks with the wall pressure while the
  wall lattice does not compress; giving them the lattice volume dx^2 instead (as the
  continuity equation does) makes the error ten times larger (-0.81% at every dx), so the
  paper's choice stands. At c = 10 sqrt(g H) and h = dx this part adds about +0.14% at the wall
  layer, which with the -0.065% above gives the +0.07% to +0.08%; at 2c the error is -0.036%
  at both dx.

So for a hydrostatic pressure a user gains nothing from refining at h = dx below 0.1%; a
larger h / dx (here twice the support radius, four times the neighbours, with a step that grows
with h: the four levels cost 7 min against 10 min at h = dx before the Verlet lists, where the viscous step
0.125 h^2 / nu is four times smaller) or a larger c is what lowers it. All three targets are
met at the coarsest level either way.
""",
    "cooled_block": """
The multi-physics case: fluid flow around a rigid body, heat conduction in two materials and
across their interface, cold Dirichlet walls. The quantity is the heat the block has given off
by t = 2 (about 0.036, 22% of its initial heat), extrapolated from the two finest levels with
order 2 (estimated from the three finest it comes out near 4-5, beyond what the scheme can do,
so it is not used; see the case file). The error falls from 0.9% at dx = 0.05 (eight
particles across the block) to 0.03% at dx = 0.0167, faster than order 2 over this range.
Every level meets the targets; dx = 0.05 costs about a third of a second of one core per unit of
simulated time. At dx = 0.0167 the time step is set by conduction in the block (kappa = 0.1),
which doubles the steps.
""",
    "dam_break": """
Against the MPS surge front of Koshizuka & Oka 1996 the error falls at order 1.2, from 7% at
dx = a/20 to 2.1% at a/56. 10% is met at every level and 5% needs dx = 0.037 (a/27); 1% would
need dx = 0.0094 (a/106, extrapolated, about 25k particles and 3.5 core-minutes per unit of
simulated time). The reference is another simulation with its own error, and both particle
methods run ahead of the experiments (Adami 2012 Fig. 13a; FreeSurface.DamBreakFront* also
compares with them): a few percent below this, the error measures the difference between two
methods, not the distance to the physics.
""",
    "oscillating_plate": """
An elastic structure, and the study that ran through the service: `sph-server` on loopback
with a one-rank pool (`mpirun -np 1 sph-worker --server ADDR`), submitted with
`sphctl study cases/studies/oscillating_plate_2d.textproto --dx 0.004,0.002,0.001,0.0005
--watch` (11.6 min, the machine shared, hence CPU about half of wall) and fetched with
`sphctl fetch` (the tree was dirty with other work in progress on the elastic unit, off by
default; the H/dx = 10 level gives the committed test's number). The first period of the tip
of a cantilever plate (L = 0.2 m, H = 0.02 m, total Lagrangian SPH, Wendland C2 at
h = 1.3 dx) released in its first bending mode, against Euler-Bernoulli with the plane-strain
modulus (T = 0.254032 s): +19.95% at H/dx = 5, +6.07% at 10 (as
`ElasticSolid.CantileverPlateFirstPeriod` measures), +2.34% at 20, +1.18% at 40. The order
between successive levels falls, 1.72, 1.37, 0.98, because Euler-Bernoulli is the thin-plate
limit: shear and rotary inertia lengthen the period of a plate with H/L = 0.1, a floor under
this error that no resolution removes. How much (computed by
`tests/validation/studies/cantilever_periods.py`):

- the first-order Timoshenko correction
  omega_T / omega_EB = 1 - (k r)^2 (1 + E' / (kappa G)) / 2 with r^2 = H^2 / 12 and
  k L = 1.875 (the first-order expansion of the Timoshenko frequency of a simply supported
  beam's sine mode, here with the cantilever's k; Han, Benaroya & Wei 1999, J. Sound Vib.
  225(5) 935-988), E' = E / (1 - nu^2) = 2.375 MPa, G = E / (2 (1 + nu)) = 0.716 MPa and
  kappa = 5/6: (k r)^2 = 2.93e-3, E' / (kappa G) = 3.98, so the period is +0.73% longer;
- the clamped-free Timoshenko beam solved exactly (its amplitude equations integrated from
  the clamp, with the clamped-free conditions of Han et al.): +0.96% (kappa = 5/6), +0.94%
  (Cowper's kappa = 10 (1 + nu) / (12 + 11 nu));
- plane-strain elasticity of the same rectangle with the whole root face held, as the SPH
  clamp holds it (9-node finite elements, 50 x 5 to 400 x 40, converged to about 0.01%):
  +0.47%, T = 0.25523 s. At nu = 0 the finite elements and the Timoshenko beam agree
  (+0.654% and +0.655%), at nu = 0.2 they differ by 0.08% and at nu = 0.3975 by 0.5%: the
  difference is a Poisson effect the beam theories leave out (the held root face, which stops
  the plate's lateral contraction there, is the likely place).

So the error against Euler-Bernoulli cannot fall much below +0.5% (about +1% by Timoshenko's
beam). Against the continuum's 0.25523 s the periods are +19.4%, +5.57%, +1.86% and +0.71%
(order 1.80, 1.58, 1.39 between successive levels), and Richardson extrapolation from the
three finest levels (order 1.69 estimated) gives 0.25572 s, +0.66% above Euler-Bernoulli and
0.19% above the continuum. The fitted 1% target (dx = 0.00049, H/dx = 41, extrapolated) is
where the Euler-Bernoulli error meets its floor, not where the solver is within 1% of the
physics (H/dx = 40 is within 0.71% of it). 10% needs H/dx = 7.6 and 5% H/dx = 12.6, about 6
and 27 s of one core per simulated second.
""",
    "falling_disk": """
The settling speed against Glowinski et al. 2001: 7.6% at D/dx = 5, 2.8% at D/dx = 7.5, then
0.08% at D/dx = 10 and 1.2% at D/dx = 13.75. Past D/dx = 10 the error no longer falls: it has
reached the uncertainty of the reference (digitised from a figure, 1-3% scatter, and the
viscosity of the original setup is not settled; see the data file's header), and the speed
moves by about 1% between the finer levels. The fitted order (2.8) is pulled up by the level
that happens to sit on the data; read the table, not the slope: 5% needs D/dx = 5 to 7.5 and
1% D/dx = 9 or more, at about one core-minute per simulated second.
""",
}

TITLES = {
    "conduction": "1D conduction (erf profile)",
    "poiseuille": "Poiseuille flow (start-up, analytic)",
    "couette": "Couette flow (start-up, analytic)",
    "taylor_green": "Taylor-Green vortex (velocity field, analytic)",
    "hydrostatic": "Hydrostatic tank (bottom pressure, analytic)",
    "hydrostatic_steady": "Hydrostatic tank, acoustic mode damped, h = 2 dx (bottom pressure, analytic)",
    "cooled_block": "Multi-physics: hot block in a channel flow (Richardson)",
    "dam_break": "Dam break surge front (reference data: MPS)",
    "falling_disk": "Falling disk settling speed (reference data: Glowinski 2001)",
    "oscillating_plate": "Cantilever plate first period (elastic solid, Euler-Bernoulli)",
}


def read_csv(path):
    meta, targets, lines = {}, [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].partition(":")
                key, value = key.strip(), value.strip()
                if key.startswith("target "):
                    targets.append((float(key.split()[1]), value))
                else:
                    meta[key] = value
            else:
                lines.append(line)
    return meta, targets, list(csv.DictReader(lines))


def seconds(s):
    if s < 120:
        return "%.3g s" % s
    if s < 7200:
        return "%.3g min" % (s / 60)
    if s < 172800:
        return "%.3g h" % (s / 3600)
    return "%.3g d" % (s / 86400)


def count(n):
    if n >= 1e9:
        return "%.2fG" % (n / 1e9)
    if n >= 1e6:
        return "%.2fM" % (n / 1e6)
    if n >= 1e4:
        return "%.1fk" % (n / 1e3)
    return "%.0f" % n


def target_cell(value):
    """'dx 0.05 particles 200 core_seconds_per_simulated_second 3.1 extrapolated' -> text."""
    if value.startswith("not reachable"):
        return "not reachable"
    words = value.split()
    fields = dict(zip(words[0:6:2], words[1:6:2]))
    how = words[6] if len(words) > 6 else ""
    return "dx %.3g, %s particles, %s%s" % (
        float(fields["dx"]), count(float(fields["particles"])),
        seconds(float(fields["core_seconds_per_simulated_second"])),
        {"extrapolated_finer": " (extrapolated)",
         "every_level": " (every level)"}.get(how, ""))


def machine():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, %d cores" % (cpu, os.cpu_count() or 0)


def git_describe(root):
    try:
        return subprocess.run(["git", "describe", "--always", "--dirty"], cwd=root,
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def committed_parts(path):
    """The summary rows and sections of an existing report, by study name, so that a study
    without results here (run.sh --only ran others) keeps what the report already says."""
    rows, sections = {}, {}
    if not os.path.exists(path):
        return rows, sections
    text = open(path).read()
    for line in text.splitlines():
        if line.startswith("| [") and "](#" in line:
            rows[line.split("](#", 1)[1].split(")", 1)[0]] = line
    end = text.find("## How studies work")
    body = text[:end] if end >= 0 else text
    marks = body.split('<a id="')[1:]
    for part in marks:
        name = part.split('"', 1)[0]
        sections[name] = '<a id="' + part.rstrip() + "\n\n"
    return rows, sections


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--results", required=True)
    ap.add_argument("--docs", required=True)
    args = ap.parse_args()
    studies = [line.strip().split("|") for line in sys.stdin if line.strip()]
    # Before anything is written: a rewritten report would make the tree look dirty.
    root = os.path.dirname(os.path.abspath(args.docs))
    version = git_describe(root)
    figures = os.path.join(args.docs, "accuracy")
    os.makedirs(figures, exist_ok=True)

    summary, sections = [], []
    kept_rows, kept_sections = committed_parts(os.path.join(args.docs, "accuracy.md"))
    for name, case, flags in studies:
        d = os.path.join(args.results, name)
        title = TITLES.get(name, name)
        command = "sph-worker --case %s --out out/%s %s" % (case, name, flags)
        if not os.path.exists(os.path.join(d, "study.csv")):
            if name in kept_rows and name in kept_sections:
                summary.append(kept_rows[name])
                sections.append(kept_sections[name])
                continue
            summary.append("| [%s](#%s) | not run | | | | |" % (title, name))
            sections.append("<a id=\"%s\"></a>\n## %s\n\nNot run yet: `%s`.\n" % (name, title, command))
            continue
        meta, targets, rows = read_csv(os.path.join(d, "study.csv"))
        order = meta.get("observed_order_dx")
        order_text = "%.2f" % float(order) if order else "n/a"
        t = {e: target_cell(v) for e, v in targets}
        summary.append("| [%s](#%s) | %s | %s | %s | %s | %s |" % (
            title, name, len(rows), order_text, t.get(0.01, "-"), t.get(0.05, "-"),
            t.get(0.1, "-")))
        with open(os.path.join(d, "study.md")) as f:
            md = f.read()
        # The raw table next to the plot, for anyone who wants the numbers.
        shutil.copyfile(os.path.join(d, "study.csv"), os.path.join(figures, name + ".csv"))
        png = os.path.join(d, "study.png")
        if os.path.exists(png):
            shutil.copyfile(png, os.path.join(figures, name + ".png"))
            md = md.replace("](study.png)", "](accuracy/%s.png)" % name)
        md = md.replace("## Convergence study: ", "### Study table: ", 1)
        # The levels ran once; a regenerated report reuses them, which is no news here.
        md = md.replace(" (reused)", "")
        text = "<a id=\"%s\"></a>\n## %s\n\n" % (name, title)
        text += "One command (from the repository root, after building): `%s` " % command
        text += "(or through the service: `sphctl study %s %s`). Numbers: " % (
            case, flags.replace("--study-", "--"))
        text += "[accuracy/%s.csv](accuracy/%s.csv)." % (name, name)
        # run.sh records the code version a study ran with: studies are re-run one at a time.
        vfile = os.path.join(d, "code_version")
        ran_with = open(vfile).read().strip() if os.path.exists(vfile) else version
        text += " Ran with code version %s.\n\n" % ran_with
        if name in COMMENTS:
            text += COMMENTS[name].strip() + "\n\n"
        sections.append(text + md)

    with open(os.path.join(args.docs, "accuracy.md"), "w") as out:
        out.write(HEADER.format(machine=machine(), version=version))
        out.write("| study | levels | observed order | 1% error | 5% error | 10% error |\n")
        out.write("|---|---:|---:|---|---|---|\n")
        out.write("\n".join(summary) + "\n\n")
        out.write(READING)
        out.write("\n".join(sections))
        out.write(QUASI_STATIC)
        out.write(DESIGN)


HEADER = """# Accuracy and what it costs: convergence studies

Generated by `tests/validation/studies/run.sh` (which runs the studies and then
`tests/validation/studies/report.py`); do not edit by hand. Report written at code version
{version} (each study states the version it ran with); machine:
{machine}, shared with other work while the studies ran (see *Timing* below). Every study ran
on one rank.

A **convergence study** runs one case at a ladder of resolutions and measures each run against
the case's reference (`reference {{ }}` in the case file: an analytic solution, reference
data, or Richardson extrapolation from the finest runs). It is a job kind of its own:

```sh
sph-worker --case CASE --out DIR --study-refine N [--study-ratio R]     # locally, or under mpirun
sph-worker --case CASE --out DIR --study-dx A,B,C
sphctl study CASE --refine N [--ratio R] [--watch]                      # through the service
sphctl study CASE --dx A,B,C [--watch]
```

Each produces `study.csv` and `study.md` (one row per level: dx, particles, steps,
particle-steps, wall time, CPU time, cost per unit of simulated time, peak memory, ranks,
error), `study.png` (error against dx and against wall time, log-log, with the fitted slopes)
and `level_<k>/result.h5` per level. The design is described in *How studies work* at the end.

## Summary

What resolution a 2D case needs for a relative error of 1%, 5% and 10%, and what that costs
per unit of simulated time on one core (processor time per simulated second at that
resolution, from power laws fitted to the measured levels). "(every level)": every level of
the ladder is already within the target, and the numbers are the coarsest level's own (a
coarser resolution may do too; a power law carried towards a handful of particles across the
geometry would not say so reliably). "(extrapolated)": the target is below the finest level's
error, and dx comes from carrying the fitted order beyond the ladder (less certain the further
it goes). Unmarked: interpolated between levels.

"""

READING = """### How to read the numbers

- **Error** is relative and non-dimensional, defined per study (each section states it). For
  the analytic references it goes to zero with resolution until something resolution does not
  remove dominates (the weakly compressible model, an undamped oscillation: Couette,
  hydrostatic tank; a beam theory's thin-plate limit: cantilever plate); for reference data
  (dam break, falling disk) it cannot fall below the uncertainty of the data and the
  difference between the models, and stops falling there.
- **Observed order** is the least-squares slope of log(error) against log(dx) over all levels
  that completed; the slope against wall time says how fast accuracy improves with money
  (about -order/3 in 2D with an acoustic time step: particles ~ dx^-2, steps ~ dx^-1; -order/4
  where conduction sets the step). Particle counts include wall particles.
- **Resolution for a target error** is dx from the fitted power law; particles from a power
  law fitted to the particle counts, cost from a power law fitted to the processor time per
  unit of simulated time. Interpolated targets lie within the measured errors; extrapolated
  ones are less certain, and much less so far from the ladder.
- **Timing**: the machine was shared with other jobs, so wall times include waiting for a
  core; the cost columns use processor time (user + system, summed over ranks), which does not.
  On an idle core the two agree for one rank.

"""

# Not a study: one comparison, measured once (docs/quasi_static.md has how to rerun it).
QUASI_STATIC = """
## Quasi-static loading against plain steps (multi-time stepping, docs/quasi_static.md)

The plane-strain steel bar of `tests/support/plastic_bar.h` (460 particles, thesis Table 5.1)
stretched 3.1 mm at 1.6 mm/s a grip, the same problem solved twice on one core of the 2-core
machine (2026-11-29; the plain run shared the machine with other runs for most of its time):

| method | steps | wall time | grips' force |
|---|---|---|---|
| plain steps (eq. 33, 1.7e-7 s) | 5 746 412 | 2461 s | reference |
| quasi-static: 100 load steps, threshold 1e-5 J/m | 100 outer, 27 594 inner | 7.4 s | within 0.125% of the plain steps' at every sample past lambda = 1.003 (0.07-0.11% low) |

208 times fewer inner steps than plain steps, 330 times less wall time.
"""

DESIGN = """
## How studies work

**References live with the case.** `reference { }` in the case file (`proto/sph/v1/case.proto`,
message `Reference`) is a oneof of typed references with their parameters:

| kind | what the error is | evaluator |
|---|---|---|
| `channel_flow` | start-up Poiseuille and/or Couette flow (series solution), mean \\|u_x - u_exact\\| over the fluid at the end, relative to u_max | `analysis/channel_flow.cc` |
| `hydrostatic` | pressure of the first wall layer under the bottom against rho g (H + dx/2), H from the fluid mass | `analysis/hydrostatic.cc` |
| `taylor_green` | fitted decay rate of max\\|u\\| against -2 nu k^2 | `analysis/taylor_green.cc` |
| `conduction` | max \\|T - T_erf\\| / \\|T_b - T_0\\| (semi-infinite medium, held surface) | `analysis/conduction.cc` |
| `series_data` | a result series against a data file (inlined into the case when it is loaded, like point files): mean pointwise relative deviation, or relative difference of window means | `analysis/series_data.cc` |
| `richardson` | \\|q - q*\\| / \\|q*\\|, q a series value at a time, q* extrapolated from the finest levels with a given or estimated order | `analysis/richardson.cc` |
| `series_period` | \\|T / T_exact - 1\\|, T the period of an oscillating series (a cycle, or the mean of several) from its crossings of a mean value, linearly interpolated between samples | `analysis/series_period.cc` |

`reference.lattice_period` snaps every level's dx to period/n, so that boxes on multiples of
the period (walls, periodic lengths) hold whole numbers of particles at every level: otherwise
a gap at a wall or a periodic seam adds an error that does not converge. A case with a
reference runs as an ordinary job; the reference is only read by the evaluators. The
evaluators are one library (`analysis/`, serial HDF5, no MPI/gRPC/SQLite) used both by the
study runner and by the validation tests (`tests/validation/*`), so a test and a study measure
the same thing.

**The runner** (`study/run_study.cc`) runs the case with dx replaced (everything else
unchanged) at each level in `OUT/level_<k>/`, coarsest first, measures error, wall time,
processor time, particle-steps (steps x particles), peak memory (VmHWM, reset per level through
`/proc/self/clear_refs`, maximum over ranks) and the rank count, then writes `study.csv`,
`study.md` and `study.png` (matplotlib, started with `posix_spawn` because pool processes run
gRPC threads and must not fork). The observed order is the least-squares slope of log error
against log dx; the slope against log wall time says what accuracy costs. A level that is over
leaves `level_<k>/level.txt`; a study run again into the same directory (or a later attempt of
a study job, which gets the earlier attempts' directories in its claim) reuses those levels,
and a level interrupted with a checkpoint continues from it (its wall time so far is kept in a
file next to the checkpoint). A level that a stability guard stops is recorded as `unstable`
and the study goes on; the study fails only when fewer than two levels give an error.

**Through the service**, `SubmitRequest.study` (`proto/sph/v1/study.proto`, `StudySpec`:
`refine` with an optional `ratio`, or a `dx` list) is validated at the door (a case without a
reference is `INVALID_ARGUMENT` naming `reference`; ladder problems name `study.refine`,
`study.ratio`, `study.dx[k]`; every level must pass case validation, the finest the particle
limit), stored with the job (schema migration 2 adds `jobs.study`), handed to the pool in the
claim, and shown by `sphctl status`. Progress covers the whole ladder (`ProgressInfo.study`:
level, levels, dx, fraction of the estimated particle-steps done, ETA). The result manifest
holds `study.csv`, `study.md`, `study.png` and `level_<k>/result.h5`, `result.xmf`;
`sphctl fetch` downloads them.

**Tests**: `ReferenceEvaluators.*`, `SeriesPeriod.*`, `StudyLadder.*`, `StudyReport.*` (unit),
`ConvergenceStudy.ConductionSlabIsSecondOrderOnACoarseLadder` (validation: a three-level study
that must show order 2 +- 0.5, then reuse every level when run again), `ServiceStudy.*`
(service: `sphctl study --watch` on a two-rank pool with fetch and one row per level,
validation at the door, a cancelled study keeping the report of its finished levels, a killed
pool's study resuming on another pool with its finished levels reused and the interrupted level
resumed from its checkpoint), `StoreTest.MigratesAVersion1DatabaseAndKeepsStudiesWithTheirJobs`
(the schema migration).
"""

if __name__ == "__main__":
    main()
