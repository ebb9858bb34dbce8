#!/usr/bin/python3
"""Thesis Figs. 3.7 and 3.10: residual distributions between the two friction laws (synthetic).

Input: DATA/ch3_robots/{tripod,metachronal}_{viscous,coulomb}.csv. Output: OUT/fig3_7_10.png,
OUT/values/fig3_7_10.json.

The thesis plots each measured signal's spread about its mean (red) beside the residuals of the
predictions against the measurements. Without the measurements the Coulomb run plays the
reference: grey is the Coulomb signal about its mean (how much there is to predict), orange the
viscous-Coulomb prediction minus the Coulomb one (body velocities; planar forces of feet in
contact, F/Mg, the viscous ones σ-scaled per frame as in §3.5.1.4). A narrow orange next to a wide
grey means the two laws agree. Rows: tripod (Fig. 3.7), metachronal (Fig. 3.10).

Two more rows take MuJoCo's BigANT driven by the same feet as the measured robot (labelled so;
DATA/ch3_peer/fig3_14.csv, §3.5.4), as the thesis' figures do with motion capture and F/T data:
red is MuJoCo's signal about its mean, orange and blue each law's prediction minus MuJoCo's, at
MuJoCo's sample times (velocities of both by the same central differences of the poses sampled
there; forces of feet MuJoCo and our run both have down, the viscous ones σ-scaled per frame to
MuJoCo's magnitudes as the thesis scales to its F/T data). Without MuJoCo's data those rows are
left out and the title says so.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_7_10"
MJ_LABEL = "MuJoCo" + rb.STANDIN  # the version comes with the data: rb.mujoco_label
GAITS = (("tripod", "tripod (Fig. 3.7)"), ("metachronal", "metachronal (Fig. 3.10)"))


def hist(ax, ref, diff, title, values, key):
    ref = ref - np.mean(ref)
    lim = max(np.percentile(np.abs(ref), 99.5), np.percentile(np.abs(diff), 99.5), 1e-12)
    bins = np.linspace(-lim, lim, 61)
    ax.hist(ref, bins=bins, color="0.6", alpha=0.7, density=True, label="Coulomb − its mean")
    ax.hist(diff, bins=bins, color=c.VISCOUS, alpha=0.7, density=True,
            label="viscous − Coulomb")
    ax.set_title(title, fontsize=8.5)
    ax.set_yticks([])
    sd_ref, sd_diff = float(np.std(ref)), float(np.std(diff))
    values[f"{key}_sd_ref"] = sd_ref
    values[f"{key}_rms_diff"] = rb.rms(diff)
    values[f"{key}_ratio"] = rb.rms(diff) / sd_ref if sd_ref > 0 else None
    ax.text(0.02, 0.97, f"rms diff / sd = {rb.rms(diff) / max(sd_ref, 1e-300):.2f}",
            transform=ax.transAxes, va="top", fontsize=7)


def hist_measured(ax, meas, preds, title, values, key):
    """The thesis' layout: the measured signal about its mean (red) and each prediction's
    residual against it (orange viscous-Coulomb, blue Coulomb)."""
    meas = meas - np.mean(meas)
    lim = max([np.percentile(np.abs(meas), 99.5)]
              + [np.percentile(np.abs(d), 99.5) for _, d in preds] + [1e-12])
    bins = np.linspace(-lim, lim, 41)
    ax.hist(meas, bins=bins, color=c.MUJOCO, alpha=0.6, density=True,
            label=f"{MJ_LABEL} − its mean")
    sd = float(np.std(meas))
    values[f"{key}_sd_mujoco"] = sd
    text = []
    for law, d in preds:
        color = {"viscous": c.VISCOUS, "coulomb": c.COULOMB, "support": c.SUPPORT}[law]
        ax.hist(d, bins=bins, color=color, alpha=0.5, density=True, histtype="stepfilled",
                label=f"{law} − MuJoCo")
        values[f"{key}_mujoco_ratio_{law}"] = rb.rms(d) / sd if sd > 0 else None
        text.append(f"{law[:4]} {rb.rms(d) / max(sd, 1e-300):.2f}")
    ax.set_title(title, fontsize=8.5)
    ax.set_yticks([])
    ax.text(0.02, 0.97, "rms resid / sd: " + ", ".join(text), transform=ax.transAxes, va="top",
            fontsize=6.5)


def against_mujoco(axes, gait, v, k, mj, values):
    """One row of residuals against MuJoCo as measured; also MuJoCo's slip speeds."""
    t = mj["t"]
    ours = {"viscous": rb.velocity_at(v, t), "coulomb": rb.velocity_at(k, t)}
    for j, (col, name, scale) in enumerate((("vx", "v_x [mm/s]", 1e3),
                                            ("vy", "v_y [mm/s]", 1e3),
                                            ("omega", "ω [deg/s]", 180 / np.pi))):
        hist_measured(axes[j], scale * mj[col],
                      [(law, scale * (o[col] - mj[col])) for law, o in ours.items()],
                      f"{gait} vs MuJoCo: {name}", values, f"{gait}_{col}")
    feet = mj["legs"]
    legs = k.legs
    mf = {w: np.stack([feet[leg][w] for leg in legs], axis=1) for w in rb.LEG_COLUMNS}
    mw = np.sum(mf["Fz"], axis=1)[:, None]
    down = mf["contact"] > 0
    for r in (v, k):
        down &= np.stack([rb.nearest(r, f"contact_{leg}", t) for leg in legs], axis=1) > 0
    px = {law: np.stack([rb.nearest(r, f"Fx_{leg}", t) for leg in legs], axis=1)
          for law, r in (("viscous", v), ("coulomb", k))}
    py = {law: np.stack([rb.nearest(r, f"Fy_{leg}", t) for leg in legs], axis=1)
          for law, r in (("viscous", v), ("coulomb", k))}
    s = rb.sigma(px["viscous"], py["viscous"], mf["Fx"], mf["Fy"])[:, None]
    scale = {"viscous": s, "coulomb": 1.0}
    for j, (name, p, m) in enumerate((("F_x/Mg", px, mf["Fx"]), ("F_y/Mg", py, mf["Fy"]))):
        hist_measured(axes[3 + j], (m / mw)[down],
                      [(law, ((scale[law] * p[law] - m) / mw)[down]) for law in p],
                      f"{gait} vs MuJoCo: {name}, feet down", values,
                      f"{gait}_F{'xy'[j]}")
    # Fig. 3.7's purple: the spring support's F_z/Mg (the same for both laws) against MuJoCo's,
    # every foot and sample (a foot MuJoCo or we have up carries 0 there)
    fz = np.stack([rb.nearest(k, f"Fz_{leg}", t) for leg in legs], axis=1)
    hist_measured(axes[5], (mf["Fz"] / mw).ravel(),
                  [("support", (fz / np.sum(fz, axis=1, keepdims=True) - mf["Fz"] / mw).ravel())],
                  f"{gait} vs MuJoCo: F_z/Mg, all feet", values, f"{gait}_Fz")
    speed = np.hypot(mf["slip_x"], mf["slip_y"])[mf["contact"] > 0]
    values[f"{gait}_mujoco_slip_speed_median_mm_s"] = float(np.median(1e3 * speed))
    values[f"{gait}_mujoco_slip_speed_p95_mm_s"] = float(np.percentile(1e3 * speed, 95))
    path = float(np.sum(np.hypot(np.diff(mj["x"]), np.diff(mj["y"]))))
    for law, r in (("viscous", v), ("coulomb", k)):
        values[f"{gait}_mujoco_end_distance_rel_{law}"] = float(np.hypot(
            rb.nearest(r, "x", t)[-1] - mj["x"][-1], rb.nearest(r, "y", t)[-1] - mj["y"][-1])
            / max(path, 1e-300))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    runs = {g: (rb.Run(args.data, f"{g}_viscous"), rb.Run(args.data, f"{g}_coulomb"))
            for g, _ in GAITS}
    mjs = {g: rb.mujoco_until(rb.mujoco_as_measured(args.data, g),
                              min(runs[g][0].time[-1], runs[g][1].time[-1])) for g, _ in GAITS}
    measured = all(rb.mujoco_feet(mjs[g], runs[g][1].legs) is not None for g, _ in GAITS)
    fig, axes = plt.subplots(4 if measured else 2, 6 if measured else 5,
                             figsize=(18 if measured else 15, 12.0 if measured else 6.2))
    if measured:  # F_z/Mg is compared with MuJoCo only (both laws share the spring support)
        axes[0, 5].axis("off")
        axes[1, 5].axis("off")
    values: dict = {"mujoco_as_measured": measured}
    for r, (gait, label) in enumerate(GAITS):
        v, k = runs[gait]
        for j, (col, name, scale) in enumerate((("vx", "v_x [mm/s]", 1e3),
                                                ("vy", "v_y [mm/s]", 1e3),
                                                ("omega", "ω [deg/s]", 180 / np.pi))):
            hist(axes[r, j], scale * k[col], scale * (v[col] - k[col]), f"{label}: {name}",
                 values, f"{gait}_{col}")
        vx, vy = rb.planar(v)
        kx, ky = rb.planar(k)
        s = rb.sigma(vx, vy, kx, ky)[:, None]
        w = rb.mg(k)[:, None]
        down = np.stack([k.leg("contact", leg) for leg in k.legs], axis=1) > 0
        down &= np.stack([v.leg("contact", leg) for leg in v.legs], axis=1) > 0
        # how much the feet slip (Coulomb run, feet down) and how far the laws' trajectories end
        # apart relative to the distance walked
        speed = np.stack([np.hypot(k.leg("slip_x", leg), k.leg("slip_y", leg))
                          for leg in k.legs], axis=1)[down]
        values[f"{gait}_slip_speed_median_mm_s"] = float(np.median(1e3 * speed))
        values[f"{gait}_slip_speed_p95_mm_s"] = float(np.percentile(1e3 * speed, 95))
        path = float(np.sum(np.hypot(np.diff(v["x"]), np.diff(v["y"]))))
        values[f"{gait}_end_distance_rel"] = float(
            np.hypot(v["x"][-1] - k["x"][-1], v["y"][-1] - k["y"][-1]) / max(path, 1e-300))
        for j, (name, pv, pk) in enumerate((("F_x/Mg", vx, kx), ("F_y/Mg", vy, ky))):
            hist(axes[r, 3 + j], (pk / w)[down], ((s * pv - pk) / w)[down],
                 f"{label}: {name}, feet down", values, f"{gait}_F{'xy'[j]}")
        if measured:
            against_mujoco(axes[2 + r], gait, v, k, mjs[gait], values)
    values["slip_p95_ratio_metachronal_tripod"] = (values["metachronal_slip_speed_p95_mm_s"] /
                                                   max(values["tripod_slip_speed_p95_mm_s"],
                                                       1e-300))
    if measured:
        values["mujoco_slip_p95_ratio_metachronal_tripod"] = (
            values["metachronal_mujoco_slip_speed_p95_mm_s"]
            / max(values["tripod_mujoco_slip_speed_p95_mm_s"], 1e-300))
        values["mujoco_slip_note"] = (
            f"{MJ_LABEL}: slip speed of feet down, median / 95 %: tripod "
            f"{values['tripod_mujoco_slip_speed_median_mm_s']:.2g} / "
            f"{values['tripod_mujoco_slip_speed_p95_mm_s']:.3g} mm/s, metachronal "
            f"{values['metachronal_mujoco_slip_speed_median_mm_s']:.3g} / "
            f"{values['metachronal_mujoco_slip_speed_p95_mm_s']:.3g} mm/s (95 % ratio "
            f"{values['mujoco_slip_p95_ratio_metachronal_tripod']:.3g}).")
        values["mujoco_end_note"] = (
            f"{MJ_LABEL}: its trajectory ends "
            f"{values['tripod_mujoco_end_distance_rel_viscous']:.3g} (viscous) / "
            f"{values['tripod_mujoco_end_distance_rel_coulomb']:.3g} (Coulomb) of its path from "
            f"ours on the tripod, {values['metachronal_mujoco_end_distance_rel_viscous']:.3g} / "
            f"{values['metachronal_mujoco_end_distance_rel_coulomb']:.3g} on the metachronal "
            "gait; heading-velocity rms residual against MuJoCo's, over its spread: tripod "
            f"{values['tripod_vx_mujoco_ratio_viscous']:.2f} (viscous) / "
            f"{values['tripod_vx_mujoco_ratio_coulomb']:.2f} (Coulomb), metachronal "
            f"{values['metachronal_vx_mujoco_ratio_viscous']:.2f} / "
            f"{values['metachronal_vx_mujoco_ratio_coulomb']:.2f}.")
        axes[2, 0].legend(fontsize=6, loc="upper right", bbox_to_anchor=(1.0, 0.9))
    else:
        values["mujoco_slip_note"] = values["mujoco_end_note"] = rb.MUJOCO_MISSING + "."
    axes[0, 0].legend(fontsize=6.5, loc="upper right")
    fig.suptitle("Residuals between the laws, synthetic (the thesis' residuals against motion "
                 "capture and F/T sensors need its data); " +
                 ("rows 3–4: against MuJoCo driven by the same feet (as measured, Fig. 3.14)"
                  if measured else rb.MUJOCO_MISSING), fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96 if measured else 0.95))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
