#!/usr/bin/python3
"""Thesis Fig. 4.5 / §4.4.1: hanging residuals with and without the hanging-orientation error ŝ.

Input: DATA/ch4_calibration/hanging_residuals.csv (calib_hanging_residuals: reading −
predict_hanging per leg, orientation, component, model, sample). Output: OUT/fig4_5.png,
OUT/values/fig4_5.json.

As the thesis: forces in the first row, torques in the second, a column per axis, in each panel a
split violin per transducer: the exact model (misalignment estimated, orange, right half) and
no_misalignment (ŝ = 0, blue, left half), all four hanging orientations pooled.

Values: per model the largest standard deviation of a transducer's force (N) and torque (N·m)
residuals; the thesis' "multimodal without ŝ", measured as the separation of the orientations:
for a transducer and component, (largest − smallest orientation mean) / the pooled SD within the
orientations (two normal modes a distance d apart are bimodal from d > 2 SD); its largest value
per model.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import calibration as cal  # noqa: E402
import common as c  # noqa: E402

NAME = "fig4_5"
# Threshold of the ledger, fixed before the study's data existed: orientation means further apart
# than this many within-orientation SDs make the pooled distribution bimodal (two equal normals
# are bimodal beyond 2 SD).
MODES_APART = 2.0


def separation(r: c.Table) -> float:
    """(max − min) of the orientation means over the pooled within-orientation SD."""
    means, dev = [], []
    for o in sorted(set(r.str("orientation"))):
        x = r.subset(r.str("orientation") == o)["residual"]
        means.append(float(np.mean(x)))
        dev.append(x - np.mean(x))
    sd = float(np.std(np.concatenate(dev)))
    spread = max(means) - min(means)
    return spread / sd if sd > 0 else (0.0 if spread == 0 else np.inf)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = cal.load(args.data, "hanging_residuals.csv", cal.HANGING_COLUMNS)
    legs = cal.legs_in(t)
    v: dict = {"modes_apart_bound": MODES_APART, "legs": legs,
               "orientations": sorted(set(t.str("orientation")))}
    fig, axes = plt.subplots(2, 3, figsize=(14, 8.2), squeeze=False)
    pos = np.arange(len(legs), dtype=float)
    for model in cal.HANGING_MODELS:
        for kind, comps in (("force", cal.FORCES), ("torque", cal.TORQUES)):
            sds, seps = [], []
            for comp in comps:
                for leg in legs:
                    r = cal.rows(t, leg=leg, component=comp, model=model)
                    if r.n == 0:
                        c.fail(f"{t.path}: no rows for leg {leg}, {comp}, model {model}")
                    sd = float(np.std(r["residual"]))
                    sep = separation(r)
                    v[f"{leg}_{comp}_{model}_sd"] = sd
                    v[f"{leg}_{comp}_{model}_separation"] = sep
                    sds.append(sd)
                    seps.append(sep)
            v[f"{model}_{kind}_sd_max"] = float(max(sds))
            v[f"{model}_{kind}_separation_max"] = float(max(seps))
    for kind in ("force", "torque"):
        exact = v[f"exact_{kind}_sd_max"]
        key = f"no_mis_over_exact_{kind}_sd_max"
        v[key] = v[f"no_misalignment_{kind}_sd_max"] / exact if exact > 0 else None
        if v[key] is None:
            v[key + "_reason"] = "the exact model leaves no residual (noiseless data)"
    v["exact_unimodal"] = bool(max(v["exact_force_separation_max"],
                                   v["exact_torque_separation_max"]) <= MODES_APART)
    v["no_misalignment_multimodal"] = bool(v["no_misalignment_force_separation_max"]
                                           > MODES_APART)

    for j, comp in enumerate(cal.COMPONENTS):
        ax = axes[j // 3][j % 3]
        for model, side in (("no_misalignment", "left"), ("exact", "right")):
            data = [cal.rows(t, leg=leg, component=comp, model=model)["residual"] for leg in legs]
            cal.violins(ax, data, pos, cal.HANGING_COLOR[model], side, width=0.8)
        ax.axhline(0.0, color=c.REFERENCE, lw=0.8)
        ax.set_xticks(pos, legs)
        ax.grid(axis="x", visible=False)
        sd_ex = max(v[f"{leg}_{comp}_exact_sd"] for leg in legs)
        sd_no = max(v[f"{leg}_{comp}_no_misalignment_sd"] for leg in legs)
        ax.set_title(f"{cal.COMPONENT_LABEL[comp]}: largest SD {c.fmt(sd_ex, 2)} with ŝ, "
                     f"{c.fmt(sd_no, 2)} without [{cal.COMPONENT_UNIT[comp]}]")
        if j % 3 == 0:
            ax.set_ylabel(f"{'force' if j < 3 else 'torque'} residual "
                          f"[{cal.COMPONENT_UNIT[comp]}]")
    from matplotlib.patches import Patch
    fig.legend(handles=[Patch(color=cal.HANGING_COLOR["no_misalignment"], alpha=0.6,
                              label="without ŝ (no_misalignment, left half)"),
                        Patch(color=cal.HANGING_COLOR["exact"], alpha=0.6,
                              label="with ŝ (exact model, right half)")],
               loc="upper center", ncol=2, frameon=False, bbox_to_anchor=(0.5, 0.955))
    fig.suptitle("Fig. 4.5 analog: hanging residuals (reading − model) per transducer, all four "
                 "orientations pooled, synthetic data", x=0.01, ha="left", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
