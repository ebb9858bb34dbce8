#!/usr/bin/python3
"""Thesis Figs. 3.7 and 3.10: residual distributions of BigANT's predictions (synthetic).

Input: DATA/ch3_robots/{tripod,metachronal}_{viscous,coulomb}.csv and, for MuJoCo,
DATA/ch3_peer/fig3_14.csv. Output: OUT/fig3_7.png (tripod, Fig. 3.7), OUT/fig3_10.png
(metachronal, Fig. 3.10), OUT/values/fig3_7_10.json.

The thesis plots each measured signal's spread about its mean (red) beside the residuals of the
predictions against the measurements (viscous-Coulomb orange, Coulomb blue, spring support
purple). We have no measurements; MuJoCo's BigANT driven by the same feet stands in for the robot
(labelled so, in its own colour; §3.5.4): its signal about its mean (filled) and each
prediction's residual against it at MuJoCo's sample times (outlines; velocities of both by the
same central differences of the poses sampled there; planar forces of feet MuJoCo and our run
both have down, the viscous ones σ-scaled per frame to MuJoCo's magnitudes as the thesis scales to
its F/T data; F_z/Mg of every foot). Dashed: viscous-Coulomb minus Coulomb, the two laws against
each other (the viscous forces σ-scaled to the Coulomb ones), whose size the panel gives in units
of the Coulomb signal's spread. Panels: body velocities (top), forces (bottom). Histograms are
fractions of each set's samples per bin. Without MuJoCo's data the Coulomb run plays the
reference (filled grey) against viscous − Coulomb, and the title says so.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_7_10"
# gait, the PNG it goes to (named after the thesis figure), its title
GAITS = (("tripod", "fig3_7", "Fig. 3.7, tripod"),
         ("metachronal", "fig3_10", "Fig. 3.10, metachronal"))
# the signals, one panel each: column, panel title, unit scale
VELOCITIES = (("vx", "heading velocity v_x [mm/s]", 1e3), ("vy", "side velocity v_y [mm/s]", 1e3),
              ("omega", "turning rate ω [deg/s]", 180 / np.pi))
FORCES = (("Fx", "F_x / Mg, feet down"), ("Fy", "F_y / Mg, feet down"),
          ("Fz", "F_z / Mg, every foot"))
LAW_COLOR = {"viscous": c.VISCOUS, "coulomb": c.COULOMB, "support": c.SUPPORT}
LAW_NAME = {"viscous": "viscous", "coulomb": "Coulomb", "support": "support"}


def laws(ref, diff, values, key):
    """Between the laws: the Coulomb signal's spread about its mean and viscous − Coulomb."""
    ref = ref - np.mean(ref)
    sd_ref = float(np.std(ref))
    values[f"{key}_sd_ref"] = sd_ref
    values[f"{key}_rms_diff"] = rb.rms(diff)
    values[f"{key}_ratio"] = rb.rms(diff) / sd_ref if sd_ref > 0 else None
    return ref, diff


def against(meas, preds, values, key):
    """The thesis' layout: the reference about its mean and each prediction's residual."""
    meas = meas - np.mean(meas)
    sd = float(np.std(meas))
    values[f"{key}_sd_mujoco"] = sd
    for law, d in preds:
        values[f"{key}_mujoco_ratio_{law}"] = rb.rms(d) / sd if sd > 0 else None
    return meas


def draw(ax, fill, fill_color, steps, lines):
    """One panel: a filled histogram (the spread to predict) and step outlines (residuals), as
    fractions of their samples per bin; `lines` are the panel's numbers, written top left."""
    lim = max([np.percentile(np.abs(fill), 99.5)]
              + [np.percentile(np.abs(d), 99.5) for _, d, _, _ in steps] + [1e-12])
    bins = np.linspace(-lim, lim, 41)
    ax.hist(fill, bins=bins, weights=np.full(fill.size, 1.0 / fill.size), color=fill_color,
            alpha=0.35)
    for _, d, color, ls in steps:
        ax.hist(d, bins=bins, weights=np.full(d.size, 1.0 / d.size), histtype="step",
                color=color, ls=ls, lw=1.8)
    top = ax.get_ylim()[1]
    ax.set_ylim(0, 1.3 * top)  # room for the numbers
    ax.text(0.02, 0.97, "\n".join(lines), transform=ax.transAxes, va="top", ha="left",
            bbox=dict(facecolor="white", alpha=0.8, lw=0, pad=1.5))


def against_mujoco(gait, v, k, mj, values) -> dict:
    """Residuals against MuJoCo standing in for the measured robot, per signal:
    {col: (MuJoCo about its mean, [(law, prediction − MuJoCo)])}; also MuJoCo's slip speeds and
    how far its trajectory ends from ours."""
    out = {}
    t = mj["t"]
    ours = {"viscous": rb.velocity_at(v, t), "coulomb": rb.velocity_at(k, t)}
    for col, _, scale in VELOCITIES:
        preds = [(law, scale * (o[col] - mj[col])) for law, o in ours.items()]
        out[col] = (against(scale * mj[col], preds, values, f"{gait}_{col}"), preds)
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
    # the viscous forces σ-scaled per frame to MuJoCo's magnitudes, as the thesis scales to its
    # F/T data (§3.5.1.4)
    s = rb.sigma(px["viscous"], py["viscous"], mf["Fx"], mf["Fy"])[:, None]
    scale = {"viscous": s, "coulomb": 1.0}
    for col, p, m in (("Fx", px, mf["Fx"]), ("Fy", py, mf["Fy"])):
        preds = [(law, ((scale[law] * p[law] - m) / mw)[down]) for law in p]
        out[col] = (against((m / mw)[down], preds, values, f"{gait}_{col}"), preds)
    # Fig. 3.7's purple: the spring support's F_z/Mg (the same for both laws) against MuJoCo's,
    # every foot and sample (a foot MuJoCo or we have up carries 0 there)
    fz = np.stack([rb.nearest(k, f"Fz_{leg}", t) for leg in legs], axis=1)
    preds = [("support", (fz / np.sum(fz, axis=1, keepdims=True) - mf["Fz"] / mw).ravel())]
    out["Fz"] = (against((mf["Fz"] / mw).ravel(), preds, values, f"{gait}_Fz"), preds)
    speed = np.hypot(mf["slip_x"], mf["slip_y"])[mf["contact"] > 0]
    values[f"{gait}_mujoco_slip_speed_median_mm_s"] = float(np.median(1e3 * speed))
    values[f"{gait}_mujoco_slip_speed_p95_mm_s"] = float(np.percentile(1e3 * speed, 95))
    path = float(np.sum(np.hypot(np.diff(mj["x"]), np.diff(mj["y"]))))
    for law, r in (("viscous", v), ("coulomb", k)):
        values[f"{gait}_mujoco_end_distance_rel_{law}"] = float(np.hypot(
            rb.nearest(r, "x", t)[-1] - mj["x"][-1], rb.nearest(r, "y", t)[-1] - mj["y"][-1])
            / max(path, 1e-300))
    return out


def between_laws(gait, v, k, values) -> dict:
    """Viscous-Coulomb against Coulomb: {col: (Coulomb about its mean, viscous − Coulomb)}, for
    the body velocities and the planar forces of feet down; also the slip of the Coulomb run's
    feet and how far the two laws' trajectories end apart."""
    out = {}
    for col, _, scale in VELOCITIES:
        out[col] = laws(scale * k[col], scale * (v[col] - k[col]), values, f"{gait}_{col}")
    vx, vy = rb.planar(v)
    kx, ky = rb.planar(k)
    s = rb.sigma(vx, vy, kx, ky)[:, None]
    w = rb.mg(k)[:, None]
    down = np.stack([k.leg("contact", leg) for leg in k.legs], axis=1) > 0
    down &= np.stack([v.leg("contact", leg) for leg in v.legs], axis=1) > 0
    for col, pv, pk in (("Fx", vx, kx), ("Fy", vy, ky)):
        out[col] = laws((pk / w)[down], ((s * pv - pk) / w)[down], values, f"{gait}_{col}")
    # how much the feet slip (Coulomb run, feet down) and how far the laws' trajectories end
    # apart relative to the distance walked
    speed = np.stack([np.hypot(k.leg("slip_x", leg), k.leg("slip_y", leg))
                      for leg in k.legs], axis=1)[down]
    values[f"{gait}_slip_speed_median_mm_s"] = float(np.median(1e3 * speed))
    values[f"{gait}_slip_speed_p95_mm_s"] = float(np.percentile(1e3 * speed, 95))
    path = float(np.sum(np.hypot(np.diff(v["x"]), np.diff(v["y"]))))
    values[f"{gait}_end_distance_rel"] = float(
        np.hypot(v["x"][-1] - k["x"][-1], v["y"][-1] - k["y"][-1]) / max(path, 1e-300))
    return out


def gait_figure(plt, out, gait, png, title, laws_res, mj_res, mj_label, values):
    """One PNG per gait, as the thesis' Figs. 3.7 and 3.10: body velocities (top) and forces
    (bottom); with MuJoCo, its spread about its mean filled and each prediction's residual
    against it outlined, plus viscous − Coulomb dashed; without, the Coulomb run plays the
    reference."""
    fig, axes = plt.subplots(2, 3, figsize=(13.5, 8.8))
    panels = [(col, name, "mm/s" if col != "omega" else "deg/s") for col, name, _ in VELOCITIES]
    panels += [(col, name, "Mg") for col, name in FORCES]
    for ax, (col, name, unit) in zip(axes.ravel(), panels):
        ax.set_title(name)
        ax.set_xlabel(f"deviation [{unit}]")
        if mj_res is not None:
            fill, preds = mj_res[col]
            steps = [(law, d, LAW_COLOR[law], "-") for law, d in preds]
            lines = ["rms / sd(MuJoCo): " + ", ".join(
                f"{LAW_NAME[law]} {values[f'{gait}_{col}_mujoco_ratio_{law}']:.2f}"
                for law, _ in preds)]
            if col in laws_res:
                steps.append(("laws", laws_res[col][1], c.NEUTRAL, "--"))
                lines.append(f"viscous − Coulomb: {values[f'{gait}_{col}_ratio']:.2f} × "
                             "sd(Coulomb)")
            draw(ax, fill, c.MUJOCO, steps, lines)
        elif col in laws_res:
            ref, diff = laws_res[col]
            draw(ax, ref, c.NEUTRAL, [("laws", diff, c.VISCOUS, "-")],
                 [f"rms(viscous − Coulomb) / sd = {values[f'{gait}_{col}_ratio']:.2f}"])
        else:
            ax.text(0.5, 0.5, "both laws share the spring\nsupport's F_z: nothing to\ncompare "
                    "without MuJoCo", transform=ax.transAxes, ha="center", va="center",
                    color="0.3")
            ax.axis("off")
    for ax in axes[:, 0]:
        ax.set_ylabel("fraction of samples per bin")
    if mj_res is not None:
        handles = [Patch(color=c.MUJOCO, alpha=0.35, label=f"{mj_label} − its mean"),
                   Line2D([], [], color=c.VISCOUS, lw=1.8, label="viscous-Coulomb − MuJoCo"),
                   Line2D([], [], color=c.COULOMB, lw=1.8, label="Coulomb − MuJoCo"),
                   Line2D([], [], color=c.SUPPORT, lw=1.8, label="spring support − MuJoCo (F_z)"),
                   Line2D([], [], color=c.NEUTRAL, lw=1.8, ls="--",
                          label="viscous-Coulomb − Coulomb")]
    else:
        handles = [Patch(color=c.NEUTRAL, alpha=0.35, label="Coulomb run − its mean"),
                   Line2D([], [], color=c.VISCOUS, lw=1.8, label="viscous-Coulomb − Coulomb")]
    fig.legend(handles=handles, loc="upper center", ncol=3 if mj_res is not None else 2,
               bbox_to_anchor=(0.5, 0.95), frameon=False)
    fig.suptitle(f"{title}: residual distributions (synthetic; the thesis' are against motion "
                 "capture and F/T data)" + ("" if mj_res is not None else
                                            "\n" + rb.MUJOCO_MISSING_TITLE), y=0.995)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    c.save_figure(fig, out, png)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    runs = {g: (rb.Run(args.data, f"{g}_viscous"), rb.Run(args.data, f"{g}_coulomb"))
            for g, _, _ in GAITS}
    mjs = {g: rb.mujoco_until(rb.mujoco_as_measured(args.data, g),
                              min(runs[g][0].time[-1], runs[g][1].time[-1])) for g, _, _ in GAITS}
    measured = all(rb.mujoco_feet(mjs[g], runs[g][1].legs) is not None for g, _, _ in GAITS)
    mj_label = mjs["tripod"]["label"] + rb.STANDIN if measured else None
    values: dict = {"mujoco_as_measured": measured}
    for gait, png, title in GAITS:
        v, k = runs[gait]
        laws_res = between_laws(gait, v, k, values)
        mj_res = against_mujoco(gait, v, k, mjs[gait], values) if measured else None
        gait_figure(plt, args.out, gait, png, title, laws_res, mj_res, mj_label, values)
    values["slip_p95_ratio_metachronal_tripod"] = (values["metachronal_slip_speed_p95_mm_s"] /
                                                   max(values["tripod_slip_speed_p95_mm_s"],
                                                       1e-300))
    if measured:
        values["mujoco_slip_p95_ratio_metachronal_tripod"] = (
            values["metachronal_mujoco_slip_speed_p95_mm_s"]
            / max(values["tripod_mujoco_slip_speed_p95_mm_s"], 1e-300))
        values["mujoco_slip_note"] = (
            f"{mj_label}: slip speed of feet down, median / 95 %: tripod "
            f"{values['tripod_mujoco_slip_speed_median_mm_s']:.2g} / "
            f"{values['tripod_mujoco_slip_speed_p95_mm_s']:.3g} mm/s, metachronal "
            f"{values['metachronal_mujoco_slip_speed_median_mm_s']:.3g} / "
            f"{values['metachronal_mujoco_slip_speed_p95_mm_s']:.3g} mm/s (95 % ratio "
            f"{values['mujoco_slip_p95_ratio_metachronal_tripod']:.3g}).")
        values["mujoco_end_note"] = (
            f"{mj_label}: its trajectory ends "
            f"{values['tripod_mujoco_end_distance_rel_viscous']:.3g} (viscous) / "
            f"{values['tripod_mujoco_end_distance_rel_coulomb']:.3g} (Coulomb) of its path from "
            f"ours on the tripod, {values['metachronal_mujoco_end_distance_rel_viscous']:.3g} / "
            f"{values['metachronal_mujoco_end_distance_rel_coulomb']:.3g} on the metachronal "
            "gait; heading-velocity rms residual against MuJoCo's, over its spread: tripod "
            f"{values['tripod_vx_mujoco_ratio_viscous']:.2f} (viscous) / "
            f"{values['tripod_vx_mujoco_ratio_coulomb']:.2f} (Coulomb), metachronal "
            f"{values['metachronal_vx_mujoco_ratio_viscous']:.2f} / "
            f"{values['metachronal_vx_mujoco_ratio_coulomb']:.2f}.")
    else:
        values["mujoco_slip_note"] = values["mujoco_end_note"] = rb.MUJOCO_MISSING + "."
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
