#!/usr/bin/python3
"""Thesis Fig. 5.11 / §5.5.1.2: the planner moves BigANT diagonally, (0.05, 0.02) m/s, heading held.

Input: DATA/ch5_planning/plans.csv (studies/ch5_planning/plans.toml, kind plan_run);
DATA/ch5_planning/lookahead.csv (lookahead.toml, kind plan_summary: the same goal planned with
look-ahead, 100 steps); DATA/ch5_planning/replay_diagonal.csv when the replay study wrote it.
Output: OUT/fig5_11.png, OUT/values/fig5_11.json.

(a) The body's path in the plane, planned (greedy planner, both laws) and goal, yaw at steps 0,
100, 200, 300; MuJoCo's replay in green when it exists. (b) x and y against time. (c) The gait the
planner found: mean shaft speed of each leg over the plan, both laws (an alternating tripod would
give every leg the same mean speed). (d) The shaft angles of the six legs in the Coulomb plan, the one that moves sideways. Step 300 is t = 1.5 s (T_f = 2 substeps of 2.5 ms per planning step).
The criteria (ledger fig5.11-sideways): progress along both axes — the smaller of final x / goal x
and final y / goal y at least 0.5 — with the heading held; and (fig5.11-gait-not-designed) the
gait is not one a designer would write for BigANT: not a tripod (its steps move the legs as two
tripods in few of the steps) and not left-right symmetric.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import planning as pl  # noqa: E402

NAME = "fig5_11"
GOAL = "diagonal"
PROGRESS = 0.5        # least final/goal ratio along each axis
HEADING = 0.05        # rad, most mean heading error for "heading held"
TRIPOD_STEPS = 0.5    # most fraction of steps that move the legs as two tripods


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    table = pl.load_plans(args.data)
    plans = {law: pl.plan(table, GOAL, law) for law in ("viscous", "coulomb")
             if np.any((table.str("goal") == GOAL) & (table.str("law") == law))}
    if "viscous" not in plans:
        c.fail(f"{table.path}: no viscous-Coulomb plan for goal '{GOAL}'")
    r = pl.replay(args.data, GOAL)
    values: dict = {"progress_bound": PROGRESS, "heading_bound_rad": HEADING,
                    "tripod_bound": TRIPOD_STEPS}
    for law, p in plans.items():
        s = pl.summary(p)
        for k, v in s.items():
            values[f"{law}_{k}"] = v
        rx = s["final_x_m"] / s["goal_x_m"]
        ry = s["final_y_m"] / s["goal_y_m"]
        values[f"{law}_x_ratio"] = rx
        values[f"{law}_y_ratio"] = ry
        values[f"{law}_progress_ratio_min"] = min(rx, ry)
        values[f"{law}_tracks_goal"] = bool(min(rx, ry) >= PROGRESS
                                            and s["mean_yaw_error_rad"] <= HEADING)
        values[f"{law}_not_designed"] = bool(s["tripod_step_fraction"] <= TRIPOD_STEPS
                                             and s["mirror_step_fraction"] < 1.0)
    # The look-ahead planner on the same goal (100 steps): does a longer horizon move sideways?
    la_path = args.data / pl.STUDY / "lookahead.csv"
    if la_path.is_file():
        la = c.Table(la_path, ["goal", "lookahead", "beam", "final_y", "goal_y", "final_x",
                               "goal_x"])
        on = la.str("goal") == GOAL
        if np.any(on):
            ratio = la["final_y"][on] / la["goal_y"][on]
            values["lookahead_y_ratio_greedy"] = float(
                ratio[(la["lookahead"][on] == 1)][0]) if np.any(la["lookahead"][on] == 1) else None
            values["lookahead_y_ratio_best"] = float(np.max(ratio))
            best = int(np.argmax(ratio))
            values["lookahead_best_H"] = int(la["lookahead"][on][best])
            values["lookahead_best_K"] = int(la["beam"][on][best])
    values.update(pl.replay_summary(r))
    v = values

    fig = plt.figure(figsize=(12, 10))
    gs = fig.add_gridspec(3, 2, height_ratios=[1.1, 1, 1], hspace=0.45, wspace=0.25,
                          left=0.07, right=0.98, top=0.93, bottom=0.06)
    pl.trajectory_panel(fig.add_subplot(gs[0, :]), plans, r,
                        "(a) body path in the plane, yaw at steps 0/100/200/300", arrow=0.01)
    ax = fig.add_subplot(gs[1, 0])
    p = plans["viscous"]
    for axis, style in (("x", "-"), ("y", "-.")):
        ax.plot(p["t"], p[f"goal_{axis}"], style, color=c.REFERENCE, lw=1.3, label=f"goal {axis}")
        for law, q in plans.items():
            ax.plot(q["t"], q[axis], style, color=pl.LAW_COLOR[law], lw=1.5,
                    label=f"planned {axis} ({pl.LAW_NAME[law]})")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("position [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8, ncol=2)
    ax.set_title(f"(b) final y: {1e3 * v['viscous_final_y_m']:.1f} mm (viscous-Coulomb), "
                 f"{1e3 * v.get('coulomb_final_y_m', np.nan):.1f} mm (Coulomb) of "
                 f"{1e3 * v['viscous_goal_y_m']:.0f}", fontsize=10)
    ax = fig.add_subplot(gs[1, 1])
    xs = np.arange(len(pl.LEGS))
    width = 0.38
    for j, law in enumerate(plans):
        ax.bar(xs + (j - 0.5) * width, [v[f"{law}_mean_speed_{leg}"] for leg in pl.LEGS], width,
               color=pl.LAW_COLOR[law], label=pl.LAW_NAME[law])
    ax.axhline(0.0, color=c.REFERENCE, lw=0.8)
    ax.set_xticks(xs, pl.LEGS)
    ax.set_ylabel("mean shaft speed [turns/s]")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(loc="upper right", fontsize=9)
    ax.set_title(f"(c) the gait: tripod steps {100 * v['viscous_tripod_step_fraction']:.0f} % "
                 f"(viscous-Coulomb), {100 * v.get('coulomb_tripod_step_fraction', np.nan):.0f} %"
                 " (Coulomb)", fontsize=10)
    # The plan that moves sideways is the Coulomb one (the viscous-Coulomb law cannot, above).
    shown = "coulomb" if "coulomb" in plans else "viscous"
    pl.shaft_panel(fig.add_subplot(gs[2, :]), plans[shown],
                   f"(d) shaft angles, {pl.LAW_NAME[shown]} plan (left legs solid)")
    replay_note = "" if r is not None else " — no MuJoCo replay in the data"
    fig.suptitle(f"Fig. 5.11 analog: diagonal (0.05, 0.02) m/s with the heading held, "
                 f"{v['viscous_steps']} planning steps = {v['viscous_duration_s']:g} s"
                 f"{replay_note}")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
