#!/usr/bin/python3
"""The cost of accuracy of the §4.3 calibration: parameter errors against data and noise, the
standard errors' honesty over seeds, and the multistart of §4.4.2.

Input: DATA/ch4_calibration/accuracy.csv (calib_accuracy: errors against the synthetic truth over
noise_scale × poses × seed), seeds.csv (calib_parameters over seeds 1..20) and starts.csv
(calib_starts: 20 random starts per solver). Output: OUT/calib_accuracy.png,
OUT/values/calib_accuracy.json.

(a) the largest mounting-rotation error, (b) the largest displacement error against the number of
standing poses, a line per noise scale (median over seeds, dots: each seed), log axes; (c) the
hanging stage's largest weight and force-offset errors against the noise scale (all poses
pooled: the hanging stage does not use them); (d) the z-scores (estimate − truth)/SE of every
parameter over the 20 seeds against the standard normal; (e) the standing stage's time against
poses; (f) the multistart: each start's final cost over the least, per solver.
Noise scale 0 is not drawn on the log axes; its errors are the zero-noise recovery values.

Values: zero_noise_<metric>_max and zero_noise_recovered (every error below ZERO_TOL); per noise
scale the median errors at the most poses and the log-log slope of the median rotation and
displacement errors against poses; over the seeds the fraction within 3 SE, mean and SD of z;
the multistart's relative cost spread (max − min)/min per solver and over both, converged share,
median seconds.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import calibration as cal  # noqa: E402
import common as c  # noqa: E402

NAME = "calib_accuracy"
# Thresholds of the ledger, fixed before the study's data existed: what noiseless data must give
# (round-off and solver tolerances; the CoM through the smoother, whose prior biases it a little)
ZERO_TOL = {"weight_err_max": 1e-6, "offset_force_err_max": 1e-6, "offset_torque_err_max": 1e-7,
            "com_err_rms": 5e-4, "rotation_err_max_deg": 1e-4, "displacement_err_max_mm": 1e-3}
METRIC_LABEL = {"rotation_err_max_deg": "largest rotation error [°]",
                "displacement_err_max_mm": "largest displacement error [mm]"}
SOLVER_COLOR = {"alternating": "tab:cyan", "ceres_so3": "tab:brown"}


def tag(x: float) -> str:
    """A number as a value-key part: 0.25 -> '0p25'."""
    return f"{x:g}".replace(".", "p")


def log_axes(ax, noisy: list[float]) -> None:
    """Log axes, or a note where no noisy point exists to draw (noise scale 0 only)."""
    if noisy:
        ax.set_xscale("log")
        ax.set_yscale("log")
    else:
        ax.text(0.5, 0.5, "no point with noise > 0", ha="center", va="center",
                transform=ax.transAxes)


def pose_ticks(ax) -> None:
    """The pose counts of the study as the ticks of a log x axis."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter, NullLocator
    ax.xaxis.set_major_locator(FixedLocator(POSES_SHOWN))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_minor_formatter(NullFormatter())


POSES_SHOWN: list[float] = []


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    acc = cal.load(args.data, "accuracy.csv", cal.ACCURACY_COLUMNS)
    seeds = cal.load(args.data, "seeds.csv", cal.PARAMETER_COLUMNS + ["seed"])
    starts = cal.load(args.data, "starts.csv", cal.START_COLUMNS)
    v: dict = {f"zero_tol_{m}": tol for m, tol in ZERO_TOL.items()}
    v["z_bound"] = cal.Z_BOUND

    noise = acc["noise_scale"].astype(float)
    poses_all = sorted(set(acc["poses"].astype(float)))
    noises = sorted(set(noise))
    v["noise_scales"] = noises
    v["poses"] = poses_all
    POSES_SHOWN[:] = poses_all

    # ---- zero-noise recovery
    zero = acc.subset(noise == 0.0)
    if zero.n:
        ok = True
        for m, tol in ZERO_TOL.items():
            v[f"zero_noise_{m}"] = float(np.max(zero[m]))
            ok &= bool(v[f"zero_noise_{m}"] <= tol)
        v["zero_noise_recovered"] = ok
    else:
        v["zero_noise_recovered"] = None
        v["zero_noise_recovered_reason"] = f"{acc.path}: no row with noise_scale 0"

    # ---- per noise scale: medians over seeds against poses, slopes
    noisy = [s for s in noises if s > 0]
    med: dict = {}
    for s in noisy:
        for m in METRIC_LABEL:
            ys = []
            for p in poses_all:
                r = cal.rows(acc, noise_scale=s, poses=p)
                ys.append(float(np.median(r[m])) if r.n else math.nan)
            med[s, m] = np.array(ys)
            v[f"noise{tag(s)}_{m}_at_most_poses"] = ys[-1]
            lp, ly = np.log(poses_all), np.log(med[s, m])
            okp = np.isfinite(ly)
            v[f"noise{tag(s)}_{m}_slope"] = (float(np.polyfit(lp[okp], ly[okp], 1)[0])
                                             if okp.sum() >= 2 else None)
            if v[f"noise{tag(s)}_{m}_slope"] is None:
                v[f"noise{tag(s)}_{m}_slope_reason"] = "fewer than two pose counts"
        for m in ("weight_err_max", "offset_force_err_max", "offset_torque_err_max",
                  "com_err_rms"):
            v[f"noise{tag(s)}_{m}_median"] = float(np.median(cal.rows(acc, noise_scale=s)[m]))
    z_rows = acc.subset(noise > 0)
    if z_rows.n:
        v["within_3se_mean"] = float(np.nanmean(z_rows["within_3se"]))
        v["z_rms_mean"] = float(np.nanmean(z_rows["z_rms"]))

    # ---- seeds: z over 20 calibrations
    z = seeds["z"].astype(float)
    zf = z[np.isfinite(z)]
    v["seeds_count"] = len(set(seeds["seed"].astype(float)))
    v["seeds_parameters"] = int(zf.size)
    v["seeds_within_3se_fraction"] = float(np.mean(np.abs(zf) <= cal.Z_BOUND)) if zf.size else None
    v["seeds_z_mean"] = float(np.mean(zf)) if zf.size else None
    v["seeds_z_sd"] = float(np.std(zf)) if zf.size else None
    v["seeds_z_abs_max"] = float(np.max(np.abs(zf))) if zf.size else None
    for key in ("seeds_within_3se_fraction", "seeds_z_mean", "seeds_z_sd", "seeds_z_abs_max"):
        if v[key] is None:
            v[key + "_reason"] = "no finite z (standard errors of zero)"

    # ---- multistart
    solvers = sorted(set(starts.str("solver")))
    spreads = []
    for sv in solvers:
        r = cal.rows(starts, solver=sv)
        conv = cal.flag(r["converged"])
        cost = r["cost"][conv]
        v[f"starts_{sv}_count"] = r.n
        v[f"starts_{sv}_iterations_max"] = int(np.max(r["iterations"]))
        v[f"starts_{sv}_converged_fraction"] = float(np.mean(conv))
        v[f"starts_{sv}_seconds_median"] = float(np.median(r["seconds"]))
        v[f"starts_{sv}_rotation_error_deg_max"] = float(np.max(r["rotation_error_deg"][conv])) \
            if conv.any() else None
        if cost.size and np.min(cost) > 0:
            v[f"starts_{sv}_cost_spread"] = float((np.max(cost) - np.min(cost)) / np.min(cost))
            spreads.append(v[f"starts_{sv}_cost_spread"])
        else:
            v[f"starts_{sv}_cost_spread"] = None
            v[f"starts_{sv}_cost_spread_reason"] = "no converged start, or a cost of 0"
        if v[f"starts_{sv}_rotation_error_deg_max"] is None:
            v[f"starts_{sv}_rotation_error_deg_max_reason"] = "no converged start"
    v["solvers"] = solvers
    v["starts_cost_spread"] = max(spreads) if spreads else None
    if v["starts_cost_spread"] is None:
        v["starts_cost_spread_reason"] = "no solver with converged starts of positive cost"

    # ---- figure
    fig, axes = plt.subplots(2, 3, figsize=(14, 9))
    colors = dict(zip(noisy, plt.cm.viridis(np.linspace(0.0, 0.85, max(len(noisy), 1)))))
    for a, m in zip(axes[0][:2], METRIC_LABEL):
        for s in noisy:
            r = cal.rows(acc, noise_scale=s)
            a.plot(r["poses"], r[m], ".", color=colors[s], alpha=0.5, ms=4)
            a.plot(poses_all, med[s, m], "-o", color=colors[s], ms=4, label=f"noise × {s:g}")
        log_axes(a, noisy)
        a.set_xlabel("standing poses P")
        a.set_ylabel(METRIC_LABEL[m])
        pose_ticks(a)
    axes[0][0].set_title("(a) mounting rotation R̃_k")
    axes[0][1].set_title("(b) displacement u_k")
    if noisy:
        axes[0][0].legend(fontsize=9.5)
    a = axes[0][2]
    for m, label, mk in (("weight_err_max", "weight m g [N]", "o"),
                         ("offset_force_err_max", "force offsets [N]", "s")):
        ys = [float(np.median(cal.rows(acc, noise_scale=s)[m])) for s in noisy]
        a.plot(noisy, ys, "-" + mk, color=c.NEUTRAL if mk == "o" else "0.2", label=label)
    log_axes(a, noisy)
    if len(noisy) > 1:
        c.log_ticks(a.xaxis, min(noisy), max(noisy))
    a.set_xlabel("noise scale")
    a.set_ylabel("largest error over legs (median)")
    a.set_title("(c) hanging stage: weights and offsets")
    if noisy:
        a.legend(fontsize=9.5)
    a = axes[1][0]
    if zf.size:
        a.hist(zf, bins=np.linspace(-5, 5, 41), density=True, color=c.NEUTRAL, alpha=0.7,
               label=f"{v['seeds_parameters']} estimates, {v['seeds_count']} seeds")
        g = np.linspace(-5, 5, 200)
        a.plot(g, np.exp(-g * g / 2) / math.sqrt(2 * math.pi), color=c.REFERENCE,
               label="standard normal")
        a.set_title(f"(d) z: {100 * v['seeds_within_3se_fraction']:.1f} % within 3 SE, "
                    f"SD {v['seeds_z_sd']:.2f}")
    a.set_xlabel("z = (estimate − truth) / SE")
    a.set_ylabel("density")
    a.legend(fontsize=9.5)
    a = axes[1][1]
    for s in noisy:
        r = cal.rows(acc, noise_scale=s)
        a.plot(r["poses"], r["seconds_standing"], ".", color=colors[s], ms=4)
    log_axes(a, noisy)
    a.set_xlabel("standing poses P")
    a.set_ylabel("standing stage [s]")
    a.set_title("(e) time of the standing stage")
    pose_ticks(a)
    a = axes[1][2]
    for i, sv in enumerate(solvers):
        r = cal.rows(starts, solver=sv)
        lo = float(np.min(r["cost"]))
        rel = 100 * (r["cost"] / lo - 1.0) if lo > 0 else r["cost"] * 0
        conv = cal.flag(r["converged"])
        col = SOLVER_COLOR.get(sv, c.CATEGORICAL[i % len(c.CATEGORICAL)])
        spread = v[f"starts_{sv}_cost_spread"]
        a.plot(r["start"][conv], rel[conv], "o", color=col, ms=5,
               label=f"{sv}: spread {'—' if spread is None else f'{100 * spread:.2g} %'}")
        if (~conv).any():
            a.plot(r["start"][~conv], rel[~conv], "x", color=col, ms=6)
    from matplotlib.ticker import MaxNLocator
    a.xaxis.set_major_locator(MaxNLocator(integer=True))
    a.set_xlabel("start (x: not converged)")
    a.set_ylabel("cost / least cost − 1 [%]")
    a.set_title("(f) multistart (§4.4.2)")
    a.legend(fontsize=9.5)
    fig.suptitle("Cost of accuracy of the calibration on synthetic data: errors against poses and "
                 "noise, standard errors over seeds, multistart", x=0.01, ha="left", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
