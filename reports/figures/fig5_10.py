#!/usr/bin/python3
"""Thesis Fig. 5.10 / §5.5.1.2: the planner turns BigANT in place at 0.2 rad/s.

Input: DATA/ch5_planning/plans.csv (studies/ch5_planning/plans.toml, kind plan_run);
DATA/ch5_planning/replay_turn.csv when the replay study wrote it. Output: OUT/fig5_10.png,
OUT/values/fig5_10.json.

(a) Yaw against time, planned (greedy planner, both laws) and goal (the thesis: planned blue,
goal red; here the goal is dark gray, a reference), MuJoCo's replay in green when it exists.
(b) The body's path in the plane, which the thesis does not draw ("always less than 0.1 m radius
around the origin"), with that circle. (c) The shaft angles of the six legs (viscous-Coulomb
plan). Step 300 is t = 1.5 s (T_f = 2 substeps of 2.5 ms per planning step).
The criterion (ledger fig5.10-turn-in-place): the largest displacement of the body from the
origin is at most 0.1 m, as the thesis states.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import planning as pl  # noqa: E402

NAME = "fig5_10"
GOAL = "turn"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    table = pl.load_plans(args.data)
    plans = {law: pl.plan(table, GOAL, law) for law in ("viscous", "coulomb")
             if np.any((table.str("goal") == GOAL) & (table.str("law") == law))}
    if "viscous" not in plans:
        c.fail(f"{table.path}: no viscous-Coulomb plan for goal '{GOAL}'")
    r = pl.replay(args.data, GOAL)
    bound = float(c.thesis("fig5.10-turn-in-place"))
    values: dict = {"radius_bound_m": bound}
    for law, p in plans.items():
        for k, v in pl.summary(p).items():
            values[f"{law}_{k}"] = v
        s = values
        s[f"{law}_final_yaw_rel_goal"] = s[f"{law}_final_theta_rad"] / s[f"{law}_goal_theta_rad"]
    values.update(pl.replay_summary(r))
    v = values

    fig = plt.figure(figsize=(12, 9))
    gs = fig.add_gridspec(2, 2, hspace=0.35, wspace=0.25, left=0.07, right=0.98, top=0.92,
                          bottom=0.07)
    ax = fig.add_subplot(gs[0, 0])
    p = plans["viscous"]
    ax.plot(p["t"], p["goal_theta"], "--", color=c.REFERENCE, lw=1.5, label="goal yaw")
    for law, q in plans.items():
        ax.plot(q["t"], q["theta"], color=pl.LAW_COLOR[law], lw=1.5,
                label=f"planned yaw ({pl.LAW_NAME[law]})")
    if r is not None:
        ax.plot(r["t"], r["theta_mujoco"], color=c.MUJOCO, lw=1.3, label="MuJoCo replay")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("yaw θ [rad]")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title(f"(a) yaw: final {v['viscous_final_theta_rad']:.3f} rad of "
                 f"{v['viscous_goal_theta_rad']:.3f} (viscous-Coulomb)")

    ax = fig.add_subplot(gs[0, 1])
    circle = np.linspace(0, 2 * np.pi, 200)
    ax.plot(bound * np.cos(circle), bound * np.sin(circle), ":", color=c.REFERENCE, lw=1.2,
            label=f"{bound:g} m around the origin (the thesis' bound)")
    for law, q in plans.items():
        ax.plot(q["x"], q["y"], color=pl.LAW_COLOR[law], lw=1.5,
                label=f"planned ({pl.LAW_NAME[law]}): farthest "
                      f"{1e3 * v[f'{law}_max_radius_m']:.1f} mm")
    if r is not None:
        ax.plot(r["x_mujoco"], r["y_mujoco"], color=c.MUJOCO, lw=1.3, label="MuJoCo replay")
    ax.plot([0], [0], "+", color=c.REFERENCE, ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left", fontsize=9)
    ax.set_title("(b) body path (the thesis does not draw it)")
    pl.shaft_panel(fig.add_subplot(gs[1, :]), p,
                   "(c) shaft angles, viscous-Coulomb plan (left legs solid)")
    replay_note = "" if r is not None else " — no MuJoCo replay in the data"
    fig.suptitle(f"Fig. 5.10 analog: turning in place at 0.2 rad/s, {v['viscous_steps']} planning "
                 f"steps = {v['viscous_duration_s']:g} s (greedy planner){replay_note}")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
