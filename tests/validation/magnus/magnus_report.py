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
        runs.append((res, g, wall, analyse(d)))
    lines = [
        "# Magnus effect: a rotating cylinder in a stream at Re = 200 (Reder et al. 2021 sec. 3.2)",
        "",
        "Written by `tests/validation/magnus/run_magnus.sh` (`magnus_report.py`) from runs of",
        "`cases/magnus_cylinder_2d.textproto`: a cylinder of diameter D held in place and turned",
        "clockwise at gamma = omega D / (2 U) in a uniform stream at Re = U D / nu = 200, in a",
        "channel 14 D long (inlet 4 D upstream, pressure outlet 10 D downstream) and 8 D wide",
        "between free-slip walls (blockage 12.5%). Reder et al. give no domain or resolution;",
        "these are ours, chosen for a 2-core machine. Sound speed 10, 10, 15, 20 U for gamma =",
        "0, 1, 2, 3; gamma = 0 is spun at omega = 1 for 2 <= t <= 3 to break the symmetry.",
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
            lines.append("| %d | %.0f | %.3f | %s | %.3f | %.0f s |" % (
                res, r["t_end"], r["cl_early"], rel(r["cl_early"], 2.532), r["cd_early"], wall))
    lines += [
        "",
        "What this says. The Strouhal number at gamma = 1 is the one figure near its reference.",
        "The Magnus lift is 40-60% short at every resolution run here, and grows only slowly",
        "with D/dx (table above): the lift comes from the circulation the spinning wall drags",
        "into the flow through its boundary layer, about D / sqrt(Re) = 0.07 D thick at Re 200,",
        "which is one or two particle spacings at D/dx = 10 to 20 and well inside the kernel's",
        "support (3 dx); the dummy-particle no-slip condition (Adami 2012 eq. 23) then lets the",
        "fluid next to the wall slip (at gamma = 1, D/dx = 10, t = 40, the fluid within one",
        "spacing below the cylinder moves at +0.03 U where the wall moves at -1 U). The same",
        "weak boundary layer shows at gamma = 0 as a low Strouhal number and a weak, irregular",
        "shedding, as at a lower effective Reynolds number; the drag is high there by about what",
        "the 12.5% blockage of the channel adds. At gamma = 2 and 3 the coarse wall also cannot",
        "hold the closed streamline region that suppresses shedding (M&K: gamma_c = 1.91), so",
        "the wake still sheds and the drag stays high. The references are body-fitted FEM",
        "(Mittal & Kumar) and a phase-field method on a fine grid (Reder); meeting the digest's",
        "tolerances needs resolutions this 2-core machine does not afford (D/dx of 40 or more",
        "and t U / D of about 150: the digest's estimate, 1.2e11 particle steps per rate).",
        "Without the transport velocity (continuity density) the lift is lower still (0.39 at",
        "D/dx = 5 against 1.01 with it, 5 <= t <= 10).",
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
        ls = "-" if res == max(x[0] for x in runs) else ":"
        span = max(1, int(round(SMOOTH / np.median(np.diff(r["t"])))))
        kern = np.ones(span) / span
        cd_s = np.convolve(np.convolve(r["cd"], kern, mode="same"), kern, mode="same")
        ax[0].plot(r["t"], r["smooth"], ls, lw=0.9, label="gamma %d, D/dx %d" % (g, res))
        ax[1].plot(r["t"], cd_s, ls, lw=0.9)
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
