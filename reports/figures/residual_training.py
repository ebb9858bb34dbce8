#!/usr/bin/python3
"""§5.3.2: how many training trials B needs — validation error against the number of trials.

Input: DATA/ch5_residual/training.csv (residual_training, studies/ch5_residual: per frequency
and number k of training trials, random draws of k phase offsets from the 26-grid, the held-out
validation offsets never drawn). Output: OUT/residual_training.png,
OUT/values/residual_training.json.

Per component (panels), the validation RMSE of model + B against k: the median over the draws
(line) and the range between the quartiles (band), per frequency; the template model's own
validation RMSE dashed. The thesis chose four trials "because the validation error stopped
decreasing with increasing number of training trails"; here "stopped decreasing" is the smallest
k whose median is within 5 % of the least median over every k run (fixed before the data
existed), per component and for all three together (the largest of the three). When only the
largest k run is within 5 % the error is still decreasing there: the stop lies beyond the range
and is written as k_max + 1 (no square drawn).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import residual as rs  # noqa: E402

NAME = "residual_training"
WITHIN = 0.05  # "stopped decreasing": median within this fraction of the best median


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = rs.load(args.data, "training.csv", rs.TRAINING_COLUMNS)
    freqs = rs.frequencies(t, "frequency")
    if not freqs:
        c.fail(f"{t.path}: none of the frequencies {rs.FREQUENCIES} Hz")
    v: dict = {"frequencies": freqs, "within": WITHIN}
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.9))
    colors = dict(zip(freqs, c.CATEGORICAL))
    for f in freqs:
        tg = rs.tag(f)
        r = rs.rows(t, frequency=f)
        ks = np.unique(r["train_trials"].astype(int))
        v[f"{tg}_k_max"] = int(ks.max())
        v[f"{tg}_draws_min"] = int(min(np.sum(r["train_trials"] == k) for k in ks))
        stops = []
        for j, comp in enumerate(rs.COMPONENTS):
            med, lo, hi, model = [], [], [], []
            for k in ks:
                sel = r["train_trials"] == k
                e = r[f"validation_rmse_fit_{comp}"][sel]
                med.append(float(np.median(e)))
                lo.append(float(np.percentile(e, 25)))
                hi.append(float(np.percentile(e, 75)))
                model.append(float(np.median(r[f"validation_rmse_model_{comp}"][sel])))
            med = np.array(med)
            best = float(med.min())
            k_stop = int(ks[np.argmax(med <= (1.0 + WITHIN) * best)])
            # still decreasing at the largest k run: it stops beyond the range, counted k_max + 1
            if k_stop == ks.max() and ks.size > 1:
                k_stop = int(ks.max()) + 1
            stops.append(k_stop)
            v[f"{tg}_k_stop_{comp}"] = k_stop
            v[f"{tg}_best_median_{comp}"] = best
            v[f"{tg}_model_{comp}"] = model[0]
            for k, m in zip(ks, med):
                v[f"{tg}_median_k{k}_{comp}"] = float(m)
            if 4 in ks:
                v[f"{tg}_k4_over_best_{comp}"] = rs.ratio(float(med[list(ks).index(4)]), best)
            a = axes[j]
            a.fill_between(ks, lo, hi, color=colors[f], alpha=0.2, lw=0)
            a.plot(ks, med, "o-", color=colors[f], lw=1.6, ms=4, label=f"{f:g} Hz: model + B")
            a.plot(ks, model, "--", color=colors[f], lw=1.0, label=f"{f:g} Hz: model alone")
            if k_stop in ks:
                a.plot([k_stop], [med[list(ks).index(k_stop)]], "s", ms=10, mfc="none",
                       mec=colors[f], mew=1.8)
        v[f"{tg}_k_stop_all"] = max(stops)
    v["k_stop_all_max"] = max(v[f"{rs.tag(f)}_k_stop_all"] for f in freqs)
    v["k_stop_all_min"] = min(v[f"{rs.tag(f)}_k_stop_all"] for f in freqs)
    v["k_stop_y_max"] = max(v[f"{rs.tag(f)}_k_stop_y"] for f in freqs)
    for j, comp in enumerate(rs.COMPONENTS):
        a = axes[j]
        a.set_yscale("log")
        a.set_xlabel("training trials k")
        a.set_ylabel(f"validation RMSE [{rs.COMPONENT_UNIT[comp]}]")
        a.set_title(f"({'abc'[j]}) {rs.COMPONENT_NAME[comp]}")
        a.xaxis.set_major_locator(__import__("matplotlib").ticker.MaxNLocator(integer=True))
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(freqs) * 2 if len(freqs) <= 2
               else len(freqs), fontsize=9.5, frameon=False)
    fig.suptitle("Validation RMSE of model + B against the number of training trials: median over"
                 " the draws, quartiles shaded; squares: the smallest k within "
                 f"{WITHIN:.0%} of the best median (none: still decreasing)", x=0.01, ha="left", fontsize=11)
    fig.tight_layout(rect=(0, 0.13 if len(freqs) > 2 else 0.08, 1, 0.97))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
