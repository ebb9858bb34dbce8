#!/usr/bin/python3
"""Thesis Fig. 4.6 / §4.4.2: the total wrench residual on the standing robot, before and after.

Input: DATA/ch4_calibration/pose_residuals.csv (calib_pose_residuals: per standing pose and
method the residual of the total wrench at the robot's CoM, W frame, N and N·m). Output:
OUT/fig4_6.png, OUT/values/fig4_6.json.

(a) forces, (b) torques: violins per component of naive taring (light blue), the calibration
without the transformation error (the com_only model, orange), the full calibration (green), as
the thesis draws them, and beyond the thesis the full model fitted to eq. 4.8 as printed (the
legs' gravity moments about C subtracted too, purple). (c) The RMSE of each, log scale.

Values: per method and component RMSE, mean, SD, range; the force (torque) RMSE pooled over the
three components; the reductions naive → full, 1 − RMSE_full / RMSE_naive, pooled and per
component (the caption's 63 %, 66 %, …); the naive horizontal force against the robot's weight
(§4.5's 25 % of mg); the torque bias (norm of the mean torque residual) of each method.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import calibration as cal  # noqa: E402
import calibration_search as cs  # noqa: E402
import common as c  # noqa: E402

NAME = "fig4_6"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = cal.load(args.data, "pose_residuals.csv", cal.POSE_COLUMNS)
    methods = [m for m in cal.POSE_METHODS if np.any(t.str("method") == m)]
    for need in ("naive", "full"):
        if need not in methods:
            c.fail(f"{t.path}: no rows of method '{need}'")
    weight = cal.robot_weight()
    v: dict = {"methods": methods, "robot_weight_N": weight}
    res = {}
    for m in methods:
        r = cal.rows(t, method=m)
        v[f"{m}_poses"] = r.n
        for k in cal.COMPONENTS:
            x = r[k].astype(float)
            res[m, k] = x
            v[f"{m}_{k}_rmse"] = cal.rmse(x)
            v[f"{m}_{k}_mean"] = float(np.mean(x))
            v[f"{m}_{k}_sd"] = float(np.std(x))
            v[f"{m}_{k}_min"] = float(np.min(x))
            v[f"{m}_{k}_max"] = float(np.max(x))
        for kind, comps in (("force", cal.FORCES), ("torque", cal.TORQUES)):
            v[f"{m}_{kind}_rmse"] = cal.rmse(np.concatenate([res[m, k] for k in comps]))
        v[f"{m}_torque_bias_Nm"] = float(np.linalg.norm([v[f"{m}_{k}_mean"]
                                                         for k in cal.TORQUES]))
        v[f"{m}_horizontal_force_rms_N"] = cal.rmse(np.hypot(res[m, "fx"], res[m, "fy"]))
    for kind, comps in (("force", cal.FORCES), ("torque", cal.TORQUES)):
        for part in ("",) + comps:
            key = f"{kind}" if part == "" else part
            before = v[f"naive_{key}_rmse"]
            after = v[f"full_{key}_rmse"]
            v[f"reduction_{key}"] = cal.rel_reduction(before, after)
        v[f"naive_over_full_{kind}_rmse"] = (v[f"naive_{kind}_rmse"] / v[f"full_{kind}_rmse"]
                                             if v[f"full_{kind}_rmse"] > 0 else None)
        if v[f"naive_over_full_{kind}_rmse"] is None:
            v[f"naive_over_full_{kind}_rmse_reason"] = "the full calibration leaves no residual"
    v["naive_force_sd_N"] = float(np.std(np.concatenate([res["naive", k] for k in cal.FORCES])))
    v["naive_horizontal_over_weight"] = v["naive_horizontal_force_rms_N"] / weight
    if "literal" in methods:
        v["literal_over_full_torque_rmse"] = (v["literal_torque_rmse"] / v["full_torque_rmse"]
                                              if v["full_torque_rmse"] > 0 else None)
        if v["literal_over_full_torque_rmse"] is None:
            v["literal_over_full_torque_rmse_reason"] = "the full calibration leaves no residual"

    search(args.data, v)

    # ---- figure
    fig, axes = plt.subplots(1, 3, figsize=(14, 5.6), gridspec_kw={"width_ratios": [1, 1, 1.1]})
    n = len(methods)
    width = 0.8 / n
    for a, comps in zip(axes[:2], (cal.FORCES, cal.TORQUES)):
        for i, m in enumerate(methods):
            pos = np.arange(3) + (i - (n - 1) / 2) * width
            cal.violins(a, [res[m, k] for k in comps], pos, cal.METHOD_COLOR[m], None,
                        width=width * 0.95, alpha=0.7)
        a.axhline(0.0, color=c.REFERENCE, lw=0.8)
        a.set_xticks(np.arange(3), [cal.COMPONENT_LABEL[k] for k in comps])
        a.grid(axis="x", visible=False)
    axes[0].set_ylabel("total force residual [N]")
    axes[1].set_ylabel("total torque residual [N·m]")
    axes[0].set_title(f"(a) forces: RMSE {c.fmt(v['naive_force_rmse'], 2)} naive → "
                      f"{c.fmt(v['full_force_rmse'], 2)} N full")
    axes[1].set_title(f"(b) torques: RMSE {c.fmt(v['naive_torque_rmse'], 2)} → "
                      f"{c.fmt(v['full_torque_rmse'], 2)} N·m")
    a = axes[2]
    x = np.arange(len(cal.COMPONENTS), dtype=float)
    for i, m in enumerate(methods):
        vals = [max(v[f"{m}_{k}_rmse"], 1e-300) for k in cal.COMPONENTS]
        a.bar(x + (i - (n - 1) / 2) * width, vals, width, color=cal.METHOD_COLOR[m],
              label=cal.METHOD_LABEL[m])
    a.set_yscale("log")
    a.set_xticks(x, [f"{cal.COMPONENT_LABEL[k]}\n[{cal.COMPONENT_UNIT[k]}]"
                     for k in cal.COMPONENTS])
    a.set_title("(c) RMSE per component (log scale)")
    a.grid(axis="x", visible=False)
    fig.legend(handles=a.get_legend_handles_labels()[0], loc="upper center", ncol=n,
               frameon=False, bbox_to_anchor=(0.5, 0.94))
    fig.suptitle(f"Fig. 4.6 analog: total wrench residual at the CoM over "
                 f"{v['full_poses']} synthetic standing poses (W frame); force RMSE reduced "
                 f"{100 * v['reduction_force']:.0f} %, torque {100 * v['reduction_torque']:.0f} %",
                 x=0.01, ha="left", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.88))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


# The search's numbers that the ledger quotes at the default rotations, one per noise scale.
BY_ROTATION = ("naive_horizontal_over_weight", "naive_over_full_force", "literal_over_full_torque")


def search(data: Path, v: dict) -> None:
    """The chapter 4 forensics (calibration_search.py) over cv_search.csv and pose_search.csv:
    ch4_joint_noise_scale is the check behind the seven entries' explanation, None when no one
    setting holds them all."""
    # Every value the ledger quotes, present even when the search finds nothing or cannot run.
    for key in ("noise_scale", "mounting_rotation", "cv_factor", "cv_relative", "force_reduction",
                "torque_reduction", "shared_over_full", "com_over_translations",
                "naive_over_full_force", "literal_over_full_torque",
                "naive_horizontal_over_weight"):
        v[f"ch4_joint_{key}"] = None
    v["ch4_search_n"] = 0
    for key in BY_ROTATION:
        v[f"ch4_{key}_at_default_rotation"] = None
    for key in ("slope", "intercept", "r2", "rotation_for_thesis"):
        v[f"ch4_horizontal_{key}"] = None
    files = [data / "ch4_calibration" / f for f in ("cv_search.csv", "pose_search.csv")]
    if not all(f.is_file() for f in files):
        v["ch4_joint_noise_scale_reason"] = "cv_search.csv or pose_search.csv missing"
        return
    knobs = list(cs.KNOBS)
    cv = cal.load(data, "cv_search.csv", cal.MODEL_COLUMNS + knobs)
    poses = cal.load(data, "pose_search.csv", cal.POSE_COLUMNS + knobs)
    settings, hit = cs.search(cv, poses, {e: c.target(e) for e in cs.ENTRIES})
    v["ch4_search_settings"] = settings
    v["ch4_search_n"] = len(settings)
    v["ch4_search_rotations"] = sorted({s["mounting_rotation"] for s in settings})
    v["ch4_search_noise_scales"] = sorted({s["noise_scale"] for s in settings}, reverse=True)
    default = [s for s in settings if s["mounting_rotation"] == min(v["ch4_search_rotations"])]
    for key in BY_ROTATION:
        v[f"ch4_{key}_at_default_rotation"] = [s[key] for s in default]
    horizontal_law(settings, v)
    if hit is None:
        v["ch4_joint_noise_scale_reason"] = (f"none of the {len(settings)} settings holds "
                                             f"{', '.join(cs.ENTRIES)} together")
        return
    for key in ("noise_scale", "mounting_rotation", "cv_factor", "cv_relative",
                "naive_over_full_force", "literal_over_full_torque",
                "naive_horizontal_over_weight"):
        v[f"ch4_joint_{key}"] = hit[key]
    v["ch4_joint_force_reduction"] = hit["force"]
    v["ch4_joint_torque_reduction"] = hit["torque"]
    v["ch4_joint_shared_over_full"] = hit["cv_relative"][1]
    v["ch4_joint_com_over_translations"] = hit["cv_relative"][3] / hit["cv_relative"][2]


def horizontal_law(settings: list[dict], v: dict) -> None:
    """How naive taring's horizontal force grows with the mounting rotations: a line through
    the settings of the least noise (the rotations tilt the legs' loads into x and y), and the
    rotation σ at which it would reach the thesis' 25 % of the weight."""
    least = min(s["noise_scale"] for s in settings)
    rows = [s for s in settings if s["noise_scale"] == least]
    fit = c.linfit([s["mounting_rotation"] for s in rows],
                   [s["naive_horizontal_over_weight"] for s in rows])
    if fit["k"] is None or fit["k"] <= 0:
        v["ch4_horizontal_slope_reason"] = ("fewer than three mounting rotations searched, or no "
                                            "growth with them")
        return
    v["ch4_horizontal_slope"] = fit["k"]
    v["ch4_horizontal_intercept"] = fit["b"]
    v["ch4_horizontal_r2"] = fit["r2"]
    v["ch4_horizontal_rotation_for_thesis"] = ((float(c.thesis("4.5-naive-horizontal")) - fit["b"])
                                               / fit["k"])


if __name__ == "__main__":
    main()
