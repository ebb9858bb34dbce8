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
"""
from __future__ import annotations

import numpy as np

import common as c
import robots as rb

NAME = "fig3_7_10"
GAITS = (("tripod", "tripod (Fig. 3.7)"), ("metachronal", "metachronal (Fig. 3.10)"))


def hist(ax, ref, diff, title, values, key):
    ref = ref - np.mean(ref)
    lim = max(np.percentile(np.abs(ref), 99.5), np.percentile(np.abs(diff), 99.5), 1e-12)
    bins = np.linspace(-lim, lim, 61)
    ax.hist(ref, bins=bins, color="0.6", alpha=0.7, density=True, label="Coulomb − its mean")
    ax.hist(diff, bins=bins, color=rb.VISCOUS, alpha=0.7, density=True,
            label="viscous − Coulomb")
    ax.set_title(title, fontsize=8.5)
    ax.set_yticks([])
    sd_ref, sd_diff = float(np.std(ref)), float(np.std(diff))
    values[f"{key}_sd_ref"] = sd_ref
    values[f"{key}_rms_diff"] = rb.rms(diff)
    values[f"{key}_ratio"] = rb.rms(diff) / sd_ref if sd_ref > 0 else None
    ax.text(0.02, 0.97, f"rms diff / sd = {rb.rms(diff) / max(sd_ref, 1e-300):.2f}",
            transform=ax.transAxes, va="top", fontsize=7)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    fig, axes = plt.subplots(2, 5, figsize=(15, 6.2))
    values: dict = {}
    for r, (gait, label) in enumerate(GAITS):
        v = rb.Run(args.data, f"{gait}_viscous")
        k = rb.Run(args.data, f"{gait}_coulomb")
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
    values["slip_p95_ratio_metachronal_tripod"] = (values["metachronal_slip_speed_p95_mm_s"] /
                                                   max(values["tripod_slip_speed_p95_mm_s"],
                                                       1e-300))
    axes[0, 0].legend(fontsize=6.5, loc="upper right")
    fig.suptitle("Residuals between the laws, synthetic (the thesis' residuals against motion "
                 "capture and F/T sensors need its data)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
