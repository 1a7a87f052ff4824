#!/usr/bin/python3
"""Writes tests/validation/reports/magnus.md (+ PNG) from the runs of run_magnus.sh.

usage: magnus_report.py OUT_DIR REPORT_DIR

Each run folder OUT_DIR/g<gamma>_r<D/dx> holds a result.h5 whose /series/bodies/fluid_force is
the fluid's force on the cylinder. With rho = U = D = 1: c_d = 2 F_x, c_l = 2 F_y (Reder et al.
2021 normalise by rho U^2 R = rho U^2 D / 2, digest sec. 2.2). The statistics are taken after
t0 = 15 D/U (the start-up transient): the mean over the whole periods between the first and
the last upward crossing of the lift through its mean, and St = D / (U T) with T the mean
period between those crossings, found on the lift smoothed by a moving average over 1.5 D/U
applied twice (the series carries acoustic noise of the weakly compressible scheme, standard
deviation about 1 in c_l at D/dx = 10, at frequencies above 1 U/D). A run is counted as shedding when the
lift's standard deviation over the window exceeds 0.05 (Mittal & Kumar's shedding lift
amplitude at gamma <= 1 is about 0.7); without shedding the mean is over the last quarter.
Tolerances: digest sec. 4 item 10.
"""
import glob
import os
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

T0 = 15.0
SMOOTH = 1.5  # D/U, moving-average width (applied twice)
# Mittal & Kumar 2003 (Reder Table 3 [L]) and Reder et al. 2021 ([P]): St, c_l, c_d.
MK = {0: (0.1934, 0.0, 1.316), 1: (0.1921, 2.532, 1.088), 2: (None, 5.358, 0.298), 3: (None, 10.316, 0.043)}
REDER = {0: (0.1948, 0.0, 1.3298), 1: (0.1922, 2.5486, 1.2952), 2: (0.1758, 5.6254, 0.7009),
         3: (None, 10.07, 0.2285)}
# Digest sec. 4 item 10: (St rel, c_l rel, c_d check) per gamma.
TOL = {0: "St +-3%, c_d +-5%", 1: "St +-3%, c_l +-5%, c_d in [1.04, 1.36]", 2: "c_l +-7%",
       3: "c_l +-5%, no shedding"}


def analyse(path):
    f = h5py.File(os.path.join(path, "result.h5"), "r")
    b = f["/series/bodies"]
    t = b["time"][:]
    force = b["fluid_force"][:].reshape(len(t), -1)
    cd, cl = 2 * force[:, 0], 2 * force[:, 1]
    dt = np.median(np.diff(t))
    span = max(1, int(round(SMOOTH / dt)))
    kern = np.ones(span) / span
    smooth = np.convolve(np.convolve(cl, kern, mode="same"), kern, mode="same")
    late = t >= T0
    r = {"t": t, "cd": cd, "cl": cl, "smooth": smooth, "t_end": t[-1]}
    early = (t >= 5) & (t <= 10)
    r["cl_early"], r["cd_early"] = float(np.mean(cl[early])), float(np.mean(cd[early]))
    if np.count_nonzero(late) < 10:
        return r
    idx = np.nonzero(late)[0]
    # Drop the smoothing window's edge at the end of the record.
    idx = idx[idx < len(t) - 2 * span]
    s = smooth[idx] - smooth[idx].mean()
    up = idx[np.nonzero((s[:-1] < 0) & (s[1:] >= 0))[0]]
    std = float(np.std(smooth[idx]))
    r["amplitude"] = 0.5 * float(smooth[idx].max() - smooth[idx].min())
    r["shedding"] = std > 0.05 and len(up) >= 3
    if r["shedding"]:
        # Crossing times by linear interpolation between the samples.
        tc = []
        for k in up:
            a, c = smooth[k] - smooth[idx].mean(), smooth[k + 1] - smooth[idx].mean()
            tc.append(t[k] + dt * (-a) / (c - a) if c != a else t[k])
        tc = np.array(tc)
        r["periods"] = len(tc) - 1
        r["St"] = 1.0 / np.mean(np.diff(tc))
        win = (t >= tc[0]) & (t < tc[-1])
        r["window"] = (tc[0], tc[-1])
    else:
        win = t >= t[-1] - 0.25 * (t[-1] - T0)
        r["window"] = (t[win][0], t[-1])
    r["cl_mean"] = float(np.mean(cl[win]))
    r["cd_mean"] = float(np.mean(cd[win]))
    return r


def verdict(g, r):
    """Digest sec. 4 item 10 for one run: 'met' or the quantities that miss."""
    st_ref, cl_ref, cd_ref = MK[g]
    miss = []
    if g in (0, 1) and (not r["shedding"] or abs(r["St"] / st_ref - 1) > 0.03):
        miss.append("St")
    if g == 0 and abs(r["cd_mean"] / cd_ref - 1) > 0.05:
        miss.append("c_d")
    if g >= 1 and abs(r["cl_mean"] / cl_ref - 1) > (0.07 if g == 2 else 0.05):
        miss.append("c_l")
    if g == 1 and not 1.04 <= r["cd_mean"] <= 1.36:
        miss.append("c_d")
    if g == 3 and r["shedding"]:
        miss.append("steady")
    return "met" if not miss else "missed: " + ", ".join(miss)


def couette(path):
    """Torque and profile of rotating_couette_2d: (torque over 6 <= t <= 8, analytic, mean
    and largest profile error over the fluid as fractions of the wall speed)."""
    f = h5py.File(os.path.join(path, "result.h5"), "r")
    b = f["/series/bodies"]
    t = b["time"][:]
    tq2 = b["fluid_torque"][:].reshape(len(t), -1)
    tq, ring = tq2[:, 0], tq2[:, 1]
    r1, r2, w, mu = 0.5, 1.0, -2.0, 0.05
    g = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
    x, v, kind = g["position"][:, :2], g["velocity"][:, :2], g["kind"][:]
    r = np.hypot(x[:, 0], x[:, 1])
    th = np.arctan2(x[:, 1], x[:, 0])
    ut = -v[:, 0] * np.sin(th) + v[:, 1] * np.cos(th)
    a, bb = -w * r1**2 / (r2**2 - r1**2), w * r1**2 * r2**2 / (r2**2 - r1**2)
    fl = kind == 0
    dev = np.abs(ut[fl] - (a * r[fl] + bb / r[fl])) / abs(w * r1)
    ref = 4 * np.pi * mu * abs(w) * r1**2 * r2**2 / (r2**2 - r1**2)
    # The braking torque: against the spin.
    late = t >= 6
    return (-float(np.mean(tq[late])) * np.sign(w), float(np.mean(ring[late])) * np.sign(w), ref,
            (float(np.mean(dev)), float(np.max(dev))))


def lowest_pressure(path, t0):
    """The lowest fluid pressure over the snapshots at t >= t0."""
    f = h5py.File(os.path.join(path, "result.h5"), "r")
    return min(float(g["pressure"][:][g["kind"][:] == 0].min()) for g in f["snapshots"].values()
               if g.attrs["time"] >= t0)


def near_wall(path, t0):
    """Over the snapshots at t >= t0, the fluid within one spacing of the cylinder on its fast
    (45 to 135 degrees) and slow (-135 to -45 degrees) sides: the fill (particles per dx^2 of
    area; a full lattice gives about 1), the mean clockwise velocity (the wall's is 1 at
    gamma = 1) and the mean pressure."""
    dx = float(re.search(r"^dx: ([0-9.]+)$", open(path + ".textproto").read(), re.M).group(1))
    f = h5py.File(os.path.join(path, "result.h5"), "r")
    sums = {"fast": [0, 0.0, 0.0, 0.0], "slow": [0, 0.0, 0.0, 0.0]}
    for g in f["snapshots"].values():
        if g.attrs["time"] < t0:
            continue
        fluid = g["kind"][:] == 0
        x, v, p = g["position"][:, :2][fluid], g["velocity"][:, :2][fluid], g["pressure"][:][fluid]
        r = np.hypot(x[:, 0], x[:, 1])
        th = np.arctan2(x[:, 1], x[:, 0])
        clockwise = v[:, 0] * np.sin(th) - v[:, 1] * np.cos(th)
        for side, lo in (("fast", np.pi / 4), ("slow", -3 * np.pi / 4)):
            sel = (r < 0.5 + dx) & (th > lo) & (th < lo + np.pi / 2)
            e = sums[side]
            e[0] += np.count_nonzero(sel)
            e[1] += ((0.5 + dx) ** 2 - 0.25) * (np.pi / 4) / dx**2
            e[2] += clockwise[sel].sum()
            e[3] += p[sel].sum()
    return {k: (e[0] / e[1], e[2] / max(e[0], 1), e[3] / max(e[0], 1)) for k, e in sums.items()}


def series_mean(path, t0, t1):
    b = h5py.File(os.path.join(path, "result.h5"), "r")["/series/bodies"]
    t = b["time"][:]
    force = b["fluid_force"][:].reshape(len(t), -1)
    m = (t >= t0) & (t <= t1)
    return 2 * force[m].mean(axis=0)


def rel(v, ref):
    return "%+.1f%%" % (100 * (v / ref - 1)) if ref else "-"


def main():
    out, report = sys.argv[1], sys.argv[2]
    runs = []
    for d in sorted(glob.glob(os.path.join(out, "g*_r*"))):
        m = re.match(r"g(\d+)_r(\d+)(_t\d+)?$", os.path.basename(d))
        # A run still going (no wall_seconds yet) is left out.
        if not m or not os.path.isfile(os.path.join(d, "wall_seconds")):
            continue
        g, res = int(m.group(1)), int(m.group(2))
        try:
            wall = float(open(os.path.join(d, "wall_seconds")).read())
        except OSError:
            wall = float("nan")
        r = analyse(d)
        # Wall and buffer thickness: the domain's lower x face lies that far below -4.
        try:
            text = open(d + ".textproto").read()
            r["walls"] = -4 - float(re.search(r"domain \{ lo \{ x: (-?[0-9.]+)", text).group(1))
        except (OSError, AttributeError):
            r["walls"] = float("nan")
        try:
            r["unstable"] = open(os.path.join(d, "unstable")).read().split(":")[0].strip()
        except OSError:
            r["unstable"] = ""
        runs.append((res, g, wall, r))
    lines = [
        "# Magnus effect: a rotating cylinder in a stream at Re = 200 (Reder et al. 2021 sec. 3.2)",
        "",
        "Written by `tests/validation/magnus/run_magnus.sh` (`magnus_report.py`) from runs of",
        "`cases/magnus_cylinder_2d.textproto`: a cylinder of diameter D held in place and turned",
        "clockwise at gamma = omega D / (2 U) in a uniform stream at Re = U D / nu = 200, in a",
        "channel 14 D long (inlet 4 D upstream, pressure outlet 10 D downstream) and 8 D wide",
        "between free-slip walls (blockage 12.5%). Reder et al. give no domain or resolution;",
        "these are ours, chosen for a 2-core machine. Sound speed 10, 10, 15, 20 U for gamma =",
        "0, 1, 2, 3, and the fluid's pressure level (EOS background pressure chi, Adami 2012",
        "eq. 3, also the outlet's pressure) 0.1 rho c^2: 10, 10, 22.5, 40 rho U^2 (until",
        "2026-11-29 it was 0; see below). gamma = 0 is spun at omega = 1 for 2 <= t <= 3 to break",
        "the symmetry.",
        "c_d = F_x / (rho U^2 D / 2), c_l = F_y / (rho U^2 D / 2) from the fluid force on the body",
        "(`/series/bodies/fluid_force`, every 0.05 D/U). Statistics after t = %.0f D/U over whole" % T0,
        "shedding periods (St from the mean period of the lift smoothed over 1.5 D/U, twice); a run",
        "without shedding (lift standard deviation under 0.05) is averaged over its last quarter.",
        "References: Mittal & Kumar 2003 (M&K) and Reder et al. Table 3; tolerances of the",
        "digest's section 4 item 10. Wall times on one core of the shared 2-core machine.",
        "",
        "| D/dx | gamma | t_end | St | vs M&K | mean c_l | vs M&K | mean c_d | vs M&K | lift amplitude (smoothed) | shedding | periods | tolerance | verdict | wall |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for res, g, wall, r in runs:
        if "cl_mean" not in r:
            continue
        st_ref, cl_ref, cd_ref = MK[g]
        st = "%.4f" % r["St"] if "St" in r else "-"
        lines.append(
            "| %d | %d | %.0f | %s | %s | %.3f | %s | %.3f | %s | %.3f | %s | %s | %s | %s | %.0f s |"
            % (res, g, r["t_end"], st, rel(r["St"], st_ref) if "St" in r and st_ref else "-",
               r["cl_mean"], rel(r["cl_mean"], cl_ref) if cl_ref else "(0)", r["cd_mean"],
               rel(r["cd_mean"], cd_ref), r["amplitude"], "yes" if r["shedding"] else "no",
               r.get("periods", "-"), TOL[g], verdict(g, r), wall))
    odd = [" D/dx = %d, gamma = %d" % (res, g) for res, g, wall, r in runs
           if "cl_mean" in r and res >= 8 and abs(r["walls"] - 0.4) > 1e-9]
    if odd:
        lines += ["", "Walls and buffers 0.3 thick (3 dx) instead of the case's 0.4 in:" +
                  ";".join(odd) + " (run before the case file was changed so that D/dx = 15",
                  "and 20 fit its lattice; the flow region and everything else are the same)."]
    lines += [
        "",
        "References (Table 3): gamma = 0: St 0.1934, c_d 1.316 (Reder 0.1948, 1.3298); gamma = 1:",
        "St 0.1921, c_l 2.532, c_d 1.088 (Reder 0.1922, 2.5486, 1.2952); gamma = 2: c_l 5.358,",
        "c_d 0.298 (Reder St 0.1758, 5.6254, 0.7009); gamma = 3: c_l 10.316, c_d 0.043, steady",
        "(Reder 10.07, 0.2285).",
        "",
        "Resolution: gamma = 1, means over 5 <= t <= 10 D/U (the start of shedding; every run",
        "reaches it, the short ones end at t = 10). D/dx = 5 has walls and buffers 0.6 thick",
        "(3 dx); it is the run of the CI test `Magnus.RotatingCylinderLiftsTowardsItsFasterSide`.",
        "",
        "| D/dx | t_end | mean c_l, 5 <= t <= 10 | vs M&K 2.532 | mean c_d | wall |",
        "|---|---|---|---|---|---|",
    ]
    for res, g, wall, r in sorted(runs, key=lambda x: (x[0], x[3]["t_end"])):
        if g == 1:
            end = "%.2f (%s)" % (r["t_end"], r["unstable"]) if r["unstable"] else "%.0f" % r["t_end"]
            lines.append("| %d | %s | %.3f | %s | %.3f | %.0f s |" % (
                res, end, r["cl_early"], rel(r["cl_early"], 2.532), r["cd_early"], wall))
    levels = []
    for path in glob.glob(os.path.join(out, "level_g1_p*")):
        m = re.match(r"level_g1_p([0-9.]+)$", os.path.basename(path))
        if not m or not os.path.isfile(os.path.join(path, "wall_seconds")):
            continue
        cl = series_mean(path, 5, 10)[1]
        g0 = os.path.join(out, "level_g0_p" + m.group(1))
        done = os.path.isfile(os.path.join(g0, "wall_seconds"))
        cd = series_mean(g0, 10, 20)[0] if done else float("nan")
        levels.append((float(m.group(1)), cl, lowest_pressure(path, 5), cd))
    if levels:
        lines += [
            "",
            "Pressure level (`run_magnus.sh`, D/dx = 5 as in the CI test): the EOS background",
            "pressure chi, which is also the outlet's pressure, in units of rho U^2. The lift at",
            "gamma = 1 over 5 <= t <= 10 with the lowest fluid pressure (snapshots every D/U from",
            "t = 5), and the drag at gamma = 0 over 10 <= t <= 20.",
            "",
            "| chi | mean c_l | vs M&K 2.532 | lowest fluid pressure | mean c_d (gamma = 0) | vs M&K 1.316 |",
            "|---|---|---|---|---|---|",
        ]
        for chi, cl, p_min, cd in sorted(levels):
            lines.append("| %g | %.3f | %s | %.2f | %.3f | %s |" % (
                chi, cl, rel(cl, 2.532), p_min, cd, rel(cd, 1.316)))
    walls = []
    for chi in ("0", "10"):
        path = os.path.join(out, "wall_g1_p" + chi)
        if os.path.isfile(os.path.join(path, "wall_seconds")):
            walls.append((chi, series_mean(path, 5, 15)[1], near_wall(path, 5)))
    if walls:
        lines += [
            "",
            "The fluid within one spacing of the turning wall (`run_magnus.sh`, D/dx = 10,",
            "gamma = 1, snapshots every D/U over 5 <= t <= 15; the wall turns clockwise at speed 1;",
            "fast side 45 to 135 degrees, slow side -135 to -45 degrees; fill: particles per dx^2,",
            "about 1 for a full lattice):",
            "",
            "| chi | mean c_l | fast side: fill, clockwise velocity, pressure - chi | slow side: fill, clockwise velocity, pressure - chi |",
            "|---|---|---|---|",
        ]
        for chi, cl, w in walls:
            lines.append("| %s | %.3f | %.2f, %.2f, %.2f | %.2f, %.2f, %.2f |" % (
                chi, cl, w["fast"][0], w["fast"][1], w["fast"][2] - float(chi), w["slow"][0],
                w["slow"][1], w["slow"][2] - float(chi)))
    lines += [
        "",
        "What this says. The pressure level decides the lift. Until 2026-11-29 the case ran at a",
        "zero level (outlet pressure 0, no background pressure) and the lift came out 41-59% short",
        "at gamma = 1, 2, 3 (D/dx = 10: 1.044, 3.186, 5.359) without growing with resolution",
        "(gamma = 1, D/dx = 5 to 20: 1.01 to 1.36). The suction on the fast side and the pressure",
        "noise of the weakly compressible fluid then swing the pressure negative (to -5.7 rho U^2 at",
        "D/dx = 5, the pressure-level table), where SPH's pressure force draws particle pairs",
        "together (the tensile instability). Next to the turning wall the fluid thins out and",
        "follows the wall less (the near-wall table: within one spacing of the slow side it turns",
        "at 0.02 of the wall's speed against 0.40 at chi = 10, and the fast side's first spacing",
        "holds 78% of a lattice's particles against 97%), so the wall puts less circulation into",
        "the flow. With the level at 0.1 rho c^2 the fluid stays in compression, and at D/dx = 10",
        "the lift is +1.0%, +5.7% and -7.7% of Mittal & Kumar's at gamma = 1, 2, 3: the digest's",
        "tolerance is met at gamma = 1 and 2 and missed by 2.7 points at gamma = 3 (Reder's own",
        "10.07 lies 2.4% below M&K's). At D/dx = 5 (the CI test) the lift needs a level of about",
        "4 rho U^2 and above that is 15-26% short with no trend, a spread a change of the time",
        "steps alone produces (at chi = 10: 2.030 with a snapshot every D/U, whose times the steps",
        "land on, 2.307 in the resolution table and the CI test, without them).",
        "",
        "The price is the drag. The level's part of the pressure force, chi sum_j (V_i^2 + V_j^2)",
        "grad W_ij, vanishes only where the particles lie evenly; elsewhere it pushes them towards",
        "that, and in the momentum equation it pushes the physical velocity, a spurious force on",
        "the flow (why Adami, Hu & Adams 2013 moved the background pressure into the transport",
        "velocity, which this case uses too, with p_b = rho c^2). The drag at gamma = 0 rises with",
        "the level (D/dx = 5: +19.5% of M&K at chi = 0, about +39% at 10, +65% at 30) and at",
        "D/dx = 10 is +34.9% at chi = 10 against +12.9% at chi = 0; it comes down with resolution",
        "(D/dx = 15: +17.4%; at gamma = 1, 1.288, inside the digest's [1.04, 1.36]). It is the flow",
        "that changes, not the sum over the cylinder's surface: leaving the level's part out of the",
        "force the cylinder receives (tried at D/dx = 5, chi = 10) moved the mean drag by 0.04 of",
        "the 0.3 rise. A larger transport-velocity background pressure at a zero level instead",
        "(p_b = 5 rho c^2, as Reder et al. use in two of their examples) raised the lift at",
        "D/dx = 5 only from 0.68 to 1.33, and p_b = 20 rho c^2 failed on the solid-fraction guard.",
        "",
        "The shedding at gamma = 0 and 1 is weak (smoothed lift amplitude 0.1-0.3 against about",
        "0.7 in M&K) and irregular at these resolutions, so the Strouhal numbers miss (two or three",
        "periods after t = 15, or none the crossing count accepts). At gamma = 3 the lift drifts",
        "slowly (amplitude 1.3 smoothed) without periodic shedding, as it should. So at",
        "D/dx = 10-15 the lift meets or nearly meets the digest's tolerances and the drag and",
        "Strouhal numbers do not; the digest estimates D/dx = 40 for Reder's runs, beyond this",
        "2-core machine (D/dx = 15 to t = 40 takes 15 minutes a run, D/dx = 40 about 20 times as",
        "long).",
        "",
        "Torque check (`rotating_couette_2d.textproto`, R1 = 0.5 turning at omega = -2 inside a",
        "fixed ring (a FIXED body) at R2 = 1, nu = 0.05, steady by t = 5; `run_magnus.sh` runs it):",
        "",
    ]
    rows = []
    for r1dx in (10, 20):
        cpath = os.path.join(out, "couette_r%d" % r1dx)
        if os.path.isfile(os.path.join(cpath, "result.h5")):
            tq, ring, ref, err = couette(cpath)
            rows.append("| %d | %.4f (%+.1f%%) | %.4f (%+.1f%%) | %.4f | %.1f%% (%.1f%%) of omega R1 |"
                        % (r1dx, tq, 100 * (tq / ref - 1), ring, 100 * (ring / ref - 1), ref,
                           100 * err[0], 100 * err[1]))
    if rows:
        lines += [
            "| R1/dx | torque on the turning cylinder, against the spin (6 <= t <= 8) | on the fixed ring, with the spin | analytic 4 pi mu omega R1^2 R2^2 / (R2^2 - R1^2) | error of u_theta over the fluid: mean (largest) |",
            "|---|---|---|---|---|",
        ] + rows
    rigid = os.path.join(out, "couette_rigid", "result.h5")
    if os.path.isfile(rigid):
        b = h5py.File(rigid, "r")["/series/bodies"]
        t = b["time"][:]
        tq = b["fluid_torque"][:].reshape(len(t), -1)[t >= 1].mean(axis=0)
        lines += [
            "",
            "In rigid rotation (the ring turned with the cylinder at omega = -2, the fluid started",
            "turning with them, 1 <= t <= 3, R1/dx = 10) every torque should vanish; the cylinder",
            "takes %.4f and the ring %.4f (before the fix -0.1614 and 0.7040; positive is" % (tq[0], tq[1]),
            "counter-clockwise, against the spin). The cause of the Couette deficit was the viscous",
            "term: Morris' form (Adami 2012 eq. 8) discretises mu lap(u), which equals the divergence",
            "of the viscous stress mu (grad u + grad u^T) only because div u = 0, so a wall pair",
            "carries the flux mu (grad u) n, not the traction. On a no-slip rigid wall the missing",
            "part mu (grad u^T) n is the body's own -mu omega x n. Summed over a wetted body it adds",
            "no force and a torque -2 mu V omega: 0.157 for this cylinder, which is the 0.153 it",
            "lacked (in rigid rotation: the cylinder's 0.161, and 2 pi mu omega R2^2 = 0.63 of the",
            "ring's 0.70 over the ring's wetted side). The coupling now gives the body that part's",
            "torque (solver/physics/fluid_forces.h, compute_solid_coupling; its net force, zero over",
            "a closed surface, is left out so that the momentum of fluid and bodies stays exact, and",
            "the torque, a damping of the body's spin, is taken implicitly); the fluid keeps",
            "mu lap(u).",
            "What is left in rigid rotation, and the 4% by which a free cylinder overshoots (below),",
            "is the slip of eq. 23 at a turning wall. The fluid's mean velocity v~ belongs to the",
            "fluid's mean position, about two spacings out, not to the dummy. Both halve from",
            "R1/dx = 10 to 20 (rigid rotation -0.0097 / 0.0264, the free cylinder +2.3%). Mirroring",
            "v~ about the body's rigid velocity at that position (v_w' = 2 v_w - v~ + omega x",
            "(r~ - x_w)) removes both (rigid rotation -0.0003 / 0.0014, the free cylinder within",
            "0.2%). It was not kept: it raises the ring's Couette torque to +8.6% (+4.0% at R1/dx =",
            "20), lowers the Magnus lift at D/dx = 5 from 1.01 to 0.37, and at D/dx = 10 it pushed a",
            "fluid particle into the cylinder by t = 4.6.",
        ]
    pinned = os.path.join(out, "couette_pinned", "result.h5")
    if os.path.isfile(pinned):
        b = h5py.File(pinned, "r")["/series/bodies"]
        t = b["time"][:]
        w = b["angular_velocity"][:].reshape(len(t), -1)[t >= 11].mean(axis=0)
        lines += [
            "",
            "A free body spun by its fluid (the ring turned at omega = -2, the cylinder PINNED and",
            "free to turn, the fluid at rest at t = 0, R1/dx = 10): all three end turning together,",
            "and over 11 <= t <= 12 the cylinder turns at %.4f (%+.1f%% of the ring's rate; before" % (w[0], 100 * (w[0] / w[1] - 1)),
            "the fix -3.21, +61%). The CI test `TurningBody.APinnedCylinderEndsTurningWithItsRing`",
            "runs this to t = 8, and `TurningBody.CircularCouetteTorqueOnTheTurningCylinderAndTheFixedRing`",
            "the Couette flow at R1/dx = 10.",
        ]
    spheres = os.path.join(out, "spheres_3d", "result.h5")
    if os.path.isfile(spheres):
        b = h5py.File(spheres, "r")["/series/bodies"]
        t = b["time"][:]
        tq = b["fluid_torque"][:].reshape(len(t), 2, 3)[t >= 4].mean(axis=0)[:, 2]
        ref = 8 * np.pi * 0.05 * 2 * 0.5**3 / (1 - 0.5**3)
        lines += [
            "",
            "In 3D (`rotating_spheres_3d.textproto`: a sphere of radius 0.5 turned at omega = -2",
            "about z inside a fixed spherical shell of radius 1, nu = 0.05, a/dx = 5, 4 <= t <= 5)",
            "the sphere takes %.4f (%s) and the shell %.4f (%s) of the Stokes torque" % (tq[0], rel(tq[0], ref), -tq[1], rel(-tq[1], ref)),
            "8 pi mu omega a^3 b^3 / (b^3 - a^3) = %.4f; before the fix the sphere took 0.2709 (-24.6%%)." % ref,
        ]
    lines += [
        "",
        "![lift and drag](magnus.png)",
        "",
    ]
    os.makedirs(report, exist_ok=True)
    open(os.path.join(report, "magnus.md"), "w").write("\n".join(lines))
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for res, g, wall, r in runs:
        if r["t_end"] < T0:
            continue
        ls = "-" if res == 10 else "--"
        span = max(1, int(round(SMOOTH / np.median(np.diff(r["t"])))))
        kern = np.ones(span) / span
        cd_s = np.convolve(np.convolve(r["cd"], kern, mode="same"), kern, mode="same")
        # Leave out the ends, where the moving averages run past the record.
        keep = slice(2 * span, len(r["t"]) - 2 * span)
        ax[0].plot(r["t"][keep], r["smooth"][keep], ls, lw=0.9, label="gamma %d, D/dx %d" % (g, res))
        ax[1].plot(r["t"][keep], cd_s[keep], ls, lw=0.9)
    for g, (_, cl, cd) in MK.items():
        ax[0].axhline(cl, color="gray", lw=0.5, ls="--")
        ax[1].axhline(cd, color="gray", lw=0.5, ls="--")
    ax[0].set_ylabel("c_l (smoothed)")
    ax[1].set_ylabel("c_d (smoothed)")
    ax[1].set_xlabel("t U / D")
    ax[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Rotating cylinder, Re 200 (dashed: Mittal & Kumar 2003 means)")
    fig.tight_layout()
    fig.savefig(os.path.join(report, "magnus.png"), dpi=90)
    print("\n".join(lines))


main()
