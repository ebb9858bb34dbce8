#!/usr/bin/python3
"""Thesis Fig. 5.5 / §5.3.2: the Multipod's body velocity with and without the residual B.

Input: DATA/ch5_residual/transfer.csv (residual_transfer: a row per test snapshot) and
errors.csv (residual_errors: a row per point), studies/ch5_residual. Output: OUT/fig5_5.png,
OUT/values/fig5_5.json.

Rows 0.3, 0.6, 1.2, 2.4 Hz; columns forward velocity, side velocity, yaw rate. The test trial is
Δφ = π; B is fitted (pseudo-inverse, §5.3.1) on the trials Δφ = (0.65, 0.9, 1.1, 1.35)π at the
same frequency. MuJoCo's Multipod, whose legs differ in stiffness, friction and mounting in ways
the template does not know, stands in for the thesis' motion capture and is drawn in its red;
the template A(q)q̇ blue, (A(q) + B)q̇ orange; in the side-velocity column the means over the
test trial dashed (the drift). Two gait cycles are drawn: the second and third
recorded (the first, a transient, is dropped from every fit and error); the RMSEs are over all
test snapshots (recorded cycles 2-8).

Values (the ledger's entries 5.3-*, 5.3.2-*, 5.3.3-*): per frequency the test RMSE of each
component without and with B and its reduction in %; the mean velocities over the test snapshots
(the drift) and how much of the model's mean side-velocity error B removes; the training RMSE of
B on its own training trials and the ratio test/training (across gaits); rank and condition of
the training q̇ matrix.
"""
from __future__ import annotations

import sys
from pathlib import Path

import math

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import residual as rs  # noqa: E402

NAME = "fig5_5"
SHOWN_CYCLES = 2
# Thresholds of the ledger, fixed before the study's data existed:
GREAT = 50.0  # %: "greatly improved" = B cuts the side-velocity test RMSE by at least this
SAME = 1.5  # "almost the same" = test and training RMSE within this factor of each other
FAILED = 0.5  # "failed to model the side velocity": the model explains less than this share
LEGS = 8  # the §5.3 Multipod; the q̇ matrix has 2K = 16 columns


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    transfer = rs.load(args.data, "transfer.csv", rs.TRANSFER_COLUMNS)
    errors = rs.load(args.data, "errors.csv", rs.ERRORS_COLUMNS)
    freqs = rs.frequencies(transfer, "test_frequency")
    if not freqs:
        c.fail(f"{transfer.path}: none of the frequencies {rs.FREQUENCIES} Hz")
    v: dict = {"frequencies": freqs, "frequency_count": len(freqs),
               "great_reduction_pct": GREAT, "same_ratio_bound": SAME,
               "failed_explained_bound": FAILED, "qdot_columns": 2 * LEGS,
               "shown_cycles": SHOWN_CYCLES}

    fig, axes = plt.subplots(len(freqs), 3, figsize=(14, 2.35 * len(freqs) + 1.2),
                             squeeze=False, sharex="row")
    for i, f in enumerate(freqs):
        r = rs.test_trial(transfer, f, f)
        tg = rs.tag(f)
        # the numbers of this frequency (all test snapshots)
        for k in rs.COMPONENTS:
            true = r[f"v_true_{k}"]
            e_model = rs.rmse(r[f"v_model_{k}"] - true)
            e_fit = rs.rmse(r[f"v_fit_{k}"] - true)
            v[f"{tg}_test_rmse_model_{k}"] = e_model
            v[f"{tg}_test_rmse_fit_{k}"] = e_fit
            v[f"{tg}_reduction_{k}_pct"] = 100.0 * (1.0 - rs.ratio(e_fit, e_model))
            for w in ("true", "model", "fit"):
                v[f"{tg}_mean_{w}_{k}"] = float(np.mean(r[f"v_{w}_{k}"]))
        # how much of the model's side drift B removes, over the test trial's whole cycles (B q̇
        # averages to zero over whole cycles of a periodic gait, so ≈ 0 is expected) and over all
        # its snapshots, whose last cycle is cut short
        v[f"{tg}_drift_removed_y_all"], v[f"{tg}_mean_bqdot_y_all"] = drift_removed(r)
        cycles = r["t"] * f
        whole_cycles = math.floor(cycles[-1] - cycles[0] + 1e-9)
        whole = cycles < cycles[0] + whole_cycles
        v[f"{tg}_drift_removed_y"], v[f"{tg}_mean_bqdot_y"] = drift_removed(r.subset(whole))
        v[f"{tg}_test_snapshots"] = r.n
        v[f"{tg}_test_cycles"] = float((r["t"][-1] - r["t"][0]) * f)
        v[f"{tg}_drift_whole_cycles"] = int(whole_cycles)
        ms_true = float(np.mean(r["v_true_y"] ** 2))
        v[f"{tg}_model_explains_y"] = 1.0 - v[f"{tg}_test_rmse_model_y"] ** 2 / ms_true
        v[f"{tg}_fit_explains_y"] = 1.0 - v[f"{tg}_test_rmse_fit_y"] ** 2 / ms_true
        # across gaits and the fit itself, from errors.csv (B on its own training snapshots)
        e = rs.error_point(errors, f, f)
        v[f"{tg}_rank"] = int(e["rank"])
        v[f"{tg}_condition"] = e["condition"]
        v[f"{tg}_train_snapshots"] = int(e["snapshots"])
        for k in rs.COMPONENTS:
            v[f"{tg}_train_rmse_fit_{k}"] = e[f"train_rmse_fit_{k}"]
            ratio = rs.ratio(v[f"{tg}_test_rmse_fit_{k}"], e[f"train_rmse_fit_{k}"])
            v[f"{tg}_test_over_train_{k}"] = ratio
            # the same ratio for the template alone: how much the gaits differ before any B
            v[f"{tg}_template_test_over_train_{k}"] = rs.ratio(e[f"test_rmse_model_{k}"],
                                                                e[f"train_rmse_model_{k}"])
            # the same RMSE from the two files: errors.csv's row and transfer.csv's snapshots
            v[f"{tg}_errors_vs_transfer_rel_{k}"] = rs.rel_diff(e[f"test_rmse_fit_{k}"],
                                                                v[f"{tg}_test_rmse_fit_{k}"])

        # the floor any constant B reaches on the test gait: B fitted on that trial itself
        # (errors.csv's in-sample block); a reduction below GREAT there means no B, however
        # trained, greatly improves this gait
        ins = rs.rows(errors, train_frequency=f, train_dphi_pi=(rs.TEST_DPHI,), test_frequency=f,
                      test_dphi_pi=rs.TEST_DPHI, estimator="pinv", asymmetry=1.0)
        for k in rs.COMPONENTS:
            v[f"{tg}_insample_reduction_{k}_pct"] = (
                100.0 * (1.0 - rs.ratio(float(ins[f"test_rmse_fit_{k}"][0]),
                                        float(ins[f"test_rmse_model_{k}"][0])))
                if ins.n else None)

        # the training trials evaluated as test trials (transfer.csv) pool to the training RMSE
        # of errors.csv when both kinds drop the same cycle: a check of the two kinds
        pooled = {k: [] for k in rs.COMPONENTS}
        for d in rs.TRAIN_DPHI:
            tr = rs.rows(transfer, train_frequency=f, test_frequency=f, test_dphi_pi=d,
                         estimator="pinv", asymmetry=1.0)
            for k in rs.COMPONENTS:
                pooled[k].append(tr[f"v_fit_{k}"] - tr[f"v_true_{k}"])
        if all(a.size for a in pooled["x"]):
            v[f"{tg}_train_pooled_rel"] = max(
                rs.rel_diff(rs.rmse(np.concatenate(pooled[k])), e[f"train_rmse_fit_{k}"])
                for k in rs.COMPONENTS)
        else:
            v[f"{tg}_train_pooled_rel"] = None
            v[f"{tg}_train_pooled_rel_reason"] = (f"transfer.csv lacks a training trial at "
                                                  f"{f:g} Hz as a test trial")

        # the traces: the second and third recorded cycles, against t·f
        cyc = r["t"] * f
        start = np.floor(cyc[0] + 1e-9)
        win = (cyc >= start) & (cyc <= start + SHOWN_CYCLES)
        for j, k in enumerate(rs.COMPONENTS):
            a = axes[i, j]
            a.plot(cyc[win], r[f"v_true_{k}"][win], color=rs.TRUE, lw=2.0,
                   label="MuJoCo Multipod ('measured')")
            a.plot(cyc[win], r[f"v_model_{k}"][win], color=rs.MODEL, lw=1.3,
                   label="model A(q)q̇")
            a.plot(cyc[win], r[f"v_fit_{k}"][win], color=rs.FIT, lw=1.3,
                   label="model + B, (A(q)+B)q̇")
            if k == "y":  # the drift: means over all test snapshots, dashed
                for w, color in (("true", rs.TRUE), ("model", rs.MODEL), ("fit", rs.FIT)):
                    a.axhline(v[f"{tg}_mean_{w}_y"], color=color, lw=1.0, ls="--")
            a.set_title(f"{f:g} Hz, {rs.COMPONENT_NAME[k]}: RMSE "
                        f"{c.fmt(v[f'{tg}_test_rmse_model_{k}'], 2)} → "
                        f"{c.fmt(v[f'{tg}_test_rmse_fit_{k}'], 2)} {rs.COMPONENT_UNIT[k]}")
            a.set_ylabel(f"{rs.COMPONENT_NAME[k]} [{rs.COMPONENT_UNIT[k]}]")
            if i == len(freqs) - 1:
                a.set_xlabel("t · f [gait cycles since recording began]")
        v[f"{tg}_shown_from_cycle"] = float(start)

    for k in rs.COMPONENTS:
        v[f"reduction_{k}_min_pct"] = min(v[f"{rs.tag(f)}_reduction_{k}_pct"] for f in freqs)
    v["side_greatly_improved"] = bool(v["reduction_y_min_pct"] >= GREAT)
    insample = {f: v[f"{rs.tag(f)}_insample_reduction_y_pct"] for f in freqs}
    if all(x is not None for x in insample.values()):
        v["insample_reduction_y_min_pct"] = min(insample.values())
        v["insample_below_great_frequencies"] = ", ".join(
            f"{f:g}" for f, x in insample.items() if x < GREAT) or "none"
    else:
        v["insample_reduction_y_min_pct"] = None
        v["insample_below_great_frequencies"] = None
    across_gaits(v, freqs)
    v["model_explains_y_max"] = max(v[f"{rs.tag(f)}_model_explains_y"] for f in freqs)
    v["fit_explains_y_min"] = min(v[f"{rs.tag(f)}_fit_explains_y"] for f in freqs)
    v["rank_min"] = min(v[f"{rs.tag(f)}_rank"] for f in freqs)
    v["condition_max"] = max(v[f"{rs.tag(f)}_condition"] for f in freqs)
    for suffix in ("", "_all"):
        drift = [v[f"{rs.tag(f)}_drift_removed_y{suffix}"] for f in freqs]
        v[f"drift_removed_y{suffix}_max"] = max(d for d in drift if d is not None) if any(
            d is not None for d in drift) else None
    pooled = [v[f"{rs.tag(f)}_train_pooled_rel"] for f in freqs]
    v["train_pooled_rel_max"] = (max(pooled) if all(p is not None for p in pooled) else None)
    if v["train_pooled_rel_max"] is None:
        v["train_pooled_rel_max_reason"] = "some training trials are not in transfer.csv"
    v["errors_vs_transfer_rel_max"] = max(v[f"{rs.tag(f)}_errors_vs_transfer_rel_{k}"]
                                          for f in freqs for k in rs.COMPONENTS)

    from matplotlib.lines import Line2D
    handles, labels = axes[0, 0].get_legend_handles_labels()
    handles.append(Line2D([], [], color=c.NEUTRAL, lw=1.0, ls="--"))
    labels.append("side velocity: means over the test trial")
    fig.legend(handles, labels, loc="upper right", ncol=2, fontsize=10, frameon=False,
               bbox_to_anchor=(0.99, 1.0))
    fig.suptitle("Fig. 5.5 analog: test trial Δφ = π, B from Δφ = (0.65, 0.9, 1.1, 1.35)π at "
                 "the same frequency;\nrecorded cycles "
                 f"{int(v[f'{rs.tag(freqs[0])}_shown_from_cycle']) + 1}–"
                 f"{int(v[f'{rs.tag(freqs[0])}_shown_from_cycle']) + SHOWN_CYCLES} shown, "
                 "RMSE over all test snapshots (without → with B)", x=0.01, ha="left",
                 fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.985))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)



def drift_removed(r) -> tuple[float | None, float]:
    """1 − |mean fit − mean true| / |mean model − mean true| of the side velocity over the rows
    (None when the model has no mean error), and the mean of B q̇ = v_fit − v_model."""
    gap_model = float(np.mean(r["v_model_y"] - r["v_true_y"]))
    gap_fit = float(np.mean(r["v_fit_y"] - r["v_true_y"]))
    removed = 1.0 - abs(gap_fit) / abs(gap_model) if gap_model else None
    return removed, float(np.mean(r["v_fit_y"] - r["v_model_y"]))


def spread(x: float) -> float:
    """A ratio's distance from 1 as a factor: max(x, 1/x)."""
    return max(x, 1.0 / x) if x > 0 else math.inf


def across_gaits(v: dict, freqs: list[float]) -> None:
    """The worst test ÷ training factor with B, the same for the template alone (the gaits'
    own difference, before B), and how far B moves it; template_differs_worst, the check behind
    entry 5.3.3-across-gaits' explanation, is the template's factor where it alone exceeds the
    bound, None where it does not."""
    pairs = [(v[f"{rs.tag(f)}_test_over_train_{k}"], v[f"{rs.tag(f)}_template_test_over_train_{k}"])
             for f in freqs for k in rs.COMPONENTS]
    v["test_over_train_worst"] = max(spread(fit) for fit, _ in pairs)
    v["template_test_over_train_worst"] = max(spread(model) for _, model in pairs)
    v["template_test_over_train_min"] = min(model for _, model in pairs)
    v["b_moves_test_over_train_max"] = max(spread(fit / model) if model > 0 else math.inf
                                           for fit, model in pairs)
    worst = v["template_test_over_train_worst"]
    v["template_differs_worst"] = worst if worst > SAME else None


if __name__ == "__main__":
    main()
