#!/usr/bin/python3
"""Thesis Fig. 5.8 / §5.5: BigANT's toe path over one turn of the motor shaft.

Input: DATA/ch5_planning/foot_path.csv (studies/ch5_planning/foot_path.toml, kind foot_path:
the front-left toe in the body frame at 200 shaft angles φ ∈ [0, 1), lib/robots/bigant.hpp's
four-bar leg). Output: OUT/fig5_8.png, OUT/values/fig5_8.json.

The toe's closed path in the leg's xz-plane with the thesis' points φ = 0, 0.2, 0.4, 0.6, 0.8
(stars; red in the thesis, a colour the report keeps for measured data), the stance window
|φ| ≤ 0.175 (the flat bottom the planner's geometric contact rule counts as "in contact") and
the direction of travel. The thesis gives no link lengths: the leg is our crank-rocker chosen to
trace a BigANT-like path (robots/bigant.hpp), so the figure compares shapes, not millimetres.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig5_8"
STUDY = "ch5_planning"
POINTS = (0.0, 0.2, 0.4, 0.6, 0.8)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.Table(c.study_file(args.data, "foot_path.csv", STUDY),
                ["leg", "phi", "x", "z", "marked", "in_window"])
    if t.n < 5:
        c.fail(f"{t.path}: too few samples ({t.n})")
    phi, x, z = t["phi"], t["x"], t["z"]
    window = t["in_window"] > 0.5
    marked = t["marked"] > 0.5
    leg = str(t.str("leg")[0])
    x0 = float(np.interp(0.0, phi, x))  # the stance centre: the path relative to it
    xs, zs = 1e3 * (x - x0), 1e3 * z

    values: dict = {"leg": leg, "samples": int(t.n)}
    values["stroke_mm"] = float(np.ptp(xs[window]))
    values["stance_height_variation_mm"] = float(np.ptp(zs[window]))
    values["lift_mm"] = float(np.max(zs) - np.min(zs[window]))
    values["width_mm"] = float(np.ptp(xs))
    values["stance_fraction"] = float(np.mean(window))
    # Which way the toe moves in stance: backward (−x) pushes the body forward.
    mid = np.flatnonzero(window & (phi < 0.1))
    values["stance_toe_moves_backward"] = bool(np.all(t["dx_dphi"][mid] < 0)) \
        if "dx_dphi" in t.columns and mid.size else None
    for p in POINTS:
        i = int(np.argmin(np.abs(phi - p)))
        values[f"phi_{p:g}_x_mm"] = float(xs[i])
        values[f"phi_{p:g}_z_mm"] = float(zs[i])

    fig, ax = plt.subplots(figsize=(8, 5.5))
    fig.subplots_adjust(left=0.1, right=0.97, top=0.9, bottom=0.12)
    ax.plot(np.append(xs, xs[0]), np.append(zs, zs[0]), color="black", lw=1.5, label="toe path")
    ax.plot(np.where(window, xs, np.nan), np.where(window, zs, np.nan), color=c.SUPPORT, lw=4,
            alpha=0.35, label="stance window |φ| ≤ 0.175")
    ax.plot(xs[marked], zs[marked], "*", color="black", ms=13, label="φ = 0, 0.2, 0.4, 0.6, 0.8")
    for i in np.flatnonzero(marked):
        ax.annotate(f"φ = {phi[i]:.1f}", (xs[i], zs[i]), textcoords="offset points",
                    xytext=(8, 6), fontsize=10)
    # Direction of travel: an arrow from φ = 0 towards φ = 0.05.
    j = int(np.argmin(np.abs(phi - 0.05)))
    ax.annotate("", xy=(xs[j], zs[j]), xytext=(xs[0], zs[0]),
                arrowprops=dict(arrowstyle="-|>", color="black", lw=1.2))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x from the stance centre [mm] (forward →)")
    ax.set_ylabel("z, body frame [mm]")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=9)
    ax.set_title(f"Fig. 5.8 analog: BigANT's toe over one shaft turn ({leg} leg; our four-bar)")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
