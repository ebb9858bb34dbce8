#!/usr/bin/python3
"""Thesis Fig. 5.9 / §5.5.1.2: the planner walks BigANT straight at 0.2 m/s along x.

Input: DATA/ch5_planning/plans.csv (studies/ch5_planning/plans.toml, kind plan_run: one row per
planning step of each plan, and the state after the last step); DATA/ch5_planning/
replay_straight.csv when the replay study wrote it (MuJoCo's body driven by the plan's shaft
angles). Output: OUT/fig5_9.png, OUT/values/fig5_9.json.

(a) The body's path in the plane, planned (greedy planner, both laws) and goal, with the yaw
at steps 0, 100, 200, 300 (the thesis draws planned blue and goal red; here the goal is dark
gray, a reference, and the laws keep the report's colours); MuJoCo's replay in green when it
exists. (b) x against time, planned and goal. (c) The shaft angles of the six legs (viscous-
Coulomb plan), unwrapped. A planning step executes T_f = 2 substeps of Δt/T_s = 2.5 ms, so step
300 is t = 1.5 s (the thesis labels its steps "Δt = 0.05").
The criterion (ledger fig5.9-straight): the mean distance to the goal trajectory is at most 5 %
of the distance the goal travels.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import planning as pl  # noqa: E402

NAME = "fig5_9"
GOAL = "straight"
BOUND = 0.05  # of the goal's travel: the ledger's bound on the mean tracking distance


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    table = pl.load_plans(args.data)
    plans = {law: pl.plan(table, GOAL, law) for law in ("viscous", "coulomb")
             if np.any((table.str("goal") == GOAL) & (table.str("law") == law))}
    if "viscous" not in plans:
        c.fail(f"{table.path}: no viscous-Coulomb plan for goal '{GOAL}'")
    r = pl.replay(args.data, GOAL)
    values: dict = {"bound_rel_travel": BOUND}
    for law, p in plans.items():
        for k, v in pl.summary(p).items():
            values[f"{law}_{k}"] = v
    values.update(pl.replay_summary(r))
    v = values
    v["tracks_goal"] = bool(v["viscous_mean_distance_rel_travel"] <= BOUND)
    v["viscous_final_x_rel_goal"] = v["viscous_final_x_m"] / v["viscous_goal_x_m"]

    fig = plt.figure(figsize=(12, 9))
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1], hspace=0.35, wspace=0.22,
                          left=0.07, right=0.98, top=0.92, bottom=0.07)
    pl.trajectory_panel(fig.add_subplot(gs[0, :]), plans, r,
                        "(a) body path in the plane, yaw at steps 0/100/200/300", arrow=0.02)
    ax = fig.add_subplot(gs[1, 0])
    p = plans["viscous"]
    ax.plot(p["t"], p["goal_x"], "--", color=c.REFERENCE, lw=1.5, label="goal x")
    for law, q in plans.items():
        ax.plot(q["t"], q["x"], color=pl.LAW_COLOR[law], lw=1.5,
                label=f"planned x ({pl.LAW_NAME[law]})")
    if r is not None:
        ax.plot(r["t"], r["x_mujoco"], color=c.MUJOCO, lw=1.3, label="MuJoCo replay")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("x [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title(f"(b) mean distance to the goal {1e3 * v['viscous_mean_distance_m']:.1f} mm "
                 f"({100 * v['viscous_mean_distance_rel_travel']:.1f} % of its travel)")
    pl.shaft_panel(fig.add_subplot(gs[1, 1]), p,
                   "(c) shaft angles, viscous-Coulomb plan (left legs solid)")
    replay_note = "" if r is not None else " — no MuJoCo replay in the data"
    fig.suptitle(f"Fig. 5.9 analog: walking straight at 0.2 m/s, {v['viscous_steps']} planning "
                 f"steps = {v['viscous_duration_s']:g} s (greedy planner){replay_note}")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
