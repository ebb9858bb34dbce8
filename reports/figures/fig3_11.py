#!/usr/bin/python3
"""Thesis Fig. 3.11: Multipods with 6 and 12 legs, 0.3 Hz, phase offset 1.35π (synthetic).

Input: DATA/ch3_robots/multipod6.csv, multipod12.csv (viscous-Coulomb, Mg = N, K = 1, μ = 1,
§3.5.2.1). Output: OUT/fig3_11.png, OUT/values/fig3_11.json.

Per robot (rows): heading and side velocity (same units and scale, as in the thesis), turning
rate, and the trajectory. The thesis' motion tracking (red) needs its Multipod dataset.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_11"
ROBOTS = (("multipod6", "6 legs"), ("multipod12", "12 legs"))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    fig, axes = plt.subplots(2, 4, figsize=(14, 7.0))
    values: dict = {}
    runs = [rb.Run(args.data, name) for name, _ in ROBOTS]
    vlim = max(np.max(np.abs(np.r_[r["vx"], r["vy"]])) for r in runs) * 1.05
    for i, ((name, label), r) in enumerate(zip(ROBOTS, runs)):
        t = r.time
        for j, (col, title) in enumerate((("vx", "heading velocity [m/s]"),
                                          ("vy", "side velocity [m/s]"))):
            a = axes[i, j]
            a.plot(t, r[col], color=c.ESTIMATE, lw=0.9)
            a.set_ylim(-vlim, vlim)
            a.set_title(f"{label}: {title}")
        a = axes[i, 2]
        a.plot(t, np.degrees(r["omega"]), color=c.ESTIMATE, lw=0.9)
        a.set_title(f"{label}: turning rate [deg/s]")
        a = axes[i, 3]
        a.plot(r["x"], r["y"], color=c.ESTIMATE, lw=1.2)
        a.plot(r["x"][[0, -1]], r["y"][[0, -1]], "+", color="k", ms=8)
        a.set_aspect("equal", adjustable="datalim")
        a.set_title(f"{label}: trajectory [m]")
        axes[i, 0].set_xlabel("t [s]")
        axes[i, 1].set_xlabel("t [s]")
        axes[i, 2].set_xlabel("t [s]")
        dist = float(np.hypot(r["x"][-1], r["y"][-1]))
        values[f"{name}_mean_vx"] = float(np.mean(r["vx"]))
        values[f"{name}_rms_vy"] = rb.rms(r["vy"] - np.mean(r["vy"]))
        values[f"{name}_displacement_m"] = dist
        values[f"{name}_heading_change_deg"] = float(np.degrees(r["theta"][-1] - r["theta"][0]))
        values[f"{name}_duration_s"] = float(t[-1])
        values[f"{name}_legs"] = len(r.legs)
    fig.suptitle("Multipod, undulation gait at 0.3 Hz, Δφ = 1.35π, viscous-Coulomb, the model's "
                 "estimate in the thesis' blue\n(synthetic: the thesis' motion tracking, red, "
                 "needs its data)")
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
