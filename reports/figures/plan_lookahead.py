#!/usr/bin/python3
"""Beyond the thesis (§5.7.3): the look-ahead planner against the greedy one, error against cost.

Input: DATA/ch5_planning/lookahead.csv (studies/ch5_planning/lookahead.toml, kind plan_summary:
one row per plan of each goal and each look-ahead H with beam K; H = 1 is the thesis' greedy
planner). Output: OUT/plan_lookahead.png, OUT/values/plan_lookahead.json.

Per goal, the mean distance to the target trajectory (a) and the final distance (b) against the
options the planner integrated per step, one marker per (H, K); (c) the wall time per planning
step against options per step (one core pair, the machine's two cores, threads = 2). §5.7.3: a
greedy choice "could only give us a local minimum"; a beam of K nodes over H levels of Δt looks
past one step. The own-check entry lookahead-lowers-error reads the values: the best look-ahead
plan's mean distance relative to the greedy plan's, per goal, and the cost factor it took.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import planning as pl  # noqa: E402

NAME = "plan_lookahead"
GOALS = {"straight": ("walk straight 0.2 m/s", "o"), "turn": ("turn 0.2 rad/s", "s"),
         "diagonal": ("diagonal (0.05, 0.02) m/s", "^")}
GOAL_COLOR = {"straight": "tab:cyan", "turn": "tab:olive", "diagonal": "tab:brown"}


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.Table(c.study_file(args.data, "lookahead.csv", pl.STUDY),
                ["goal", "lookahead", "beam", "steps", "mean_distance", "final_distance",
                 "final_y", "goal_y", "evaluated_per_step", "wall_per_step_s"])
    goal = t.str("goal")
    values: dict = {}
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.2))
    fig.subplots_adjust(left=0.06, right=0.99, top=0.84, bottom=0.13, wspace=0.28)
    best_rel = []
    greedy_equal = []
    for g, (label, marker) in GOALS.items():
        on = goal == g
        if not np.any(on):
            continue
        H, K = t["lookahead"][on].astype(int), t["beam"][on].astype(int)
        mean, final = t["mean_distance"][on], t["final_distance"][on]
        cost, wall = t["evaluated_per_step"][on], t["wall_per_step_s"][on]
        greedy = np.flatnonzero(H == 1)
        if greedy.size == 0:
            c.fail(f"{t.path}: no greedy plan (lookahead 1) for goal '{g}'")
        i0 = int(greedy[0])
        values[f"{g}_steps"] = int(t["steps"][on][i0])
        values[f"{g}_greedy_mean_distance_m"] = float(mean[i0])
        values[f"{g}_greedy_final_distance_m"] = float(final[i0])
        values[f"{g}_greedy_evaluated_per_step"] = float(cost[i0])
        for j in range(H.size):
            key = f"{g}_H{H[j]}_K{K[j]}"
            values[f"{key}_mean_distance_m"] = float(mean[j])
            values[f"{key}_final_distance_m"] = float(final[j])
            values[f"{key}_evaluated_per_step"] = float(cost[j])
            values[f"{key}_wall_per_step_s"] = float(wall[j])
            if H[j] > 1 and K[j] == 1:  # keeps only the greedy node: the greedy plan
                greedy_equal.append(bool(mean[j] == mean[i0] and final[j] == final[i0]))
        look = np.flatnonzero((H > 1) & (K > 1))  # K = 1 keeps the greedy node only
        if look.size == 0:
            c.fail(f"{t.path}: no look-ahead plan (lookahead > 1, beam > 1) for goal '{g}'")
        b = int(look[np.argmin(mean[look])])
        rel = float(mean[b] / mean[i0])
        values[f"{g}_best_H"] = int(H[b])
        values[f"{g}_best_K"] = int(K[b])
        values[f"{g}_best_mean_rel_greedy"] = rel
        values[f"{g}_best_final_rel_greedy"] = float(final[b] / final[i0])
        values[f"{g}_best_cost_factor"] = float(cost[b] / cost[i0])
        values[f"{g}_best_wall_factor"] = float(wall[b] / wall[i0])
        worst = int(look[np.argmax(mean[look])])
        values[f"{g}_worst_mean_rel_greedy"] = float(mean[worst] / mean[i0])
        if "final_y" in t.columns and t["goal_y"][on][i0] != 0:
            values[f"{g}_best_y_ratio"] = float(t["final_y"][on][b] / t["goal_y"][on][i0])
            values[f"{g}_greedy_y_ratio"] = float(t["final_y"][on][i0] / t["goal_y"][on][i0])
        best_rel.append(rel)
        for ax, y in ((axes[0], mean), (axes[1], final)):
            ax.plot(cost, 1e3 * y, marker, color=GOAL_COLOR[g], ms=7, ls="none", label=label)
            ax.plot(cost[i0], 1e3 * y[i0], marker, mfc="none", mec="black", ms=12, ls="none")
            for j in range(H.size):
                ax.annotate(f"{H[j]},{K[j]}", (cost[j], 1e3 * y[j]), textcoords="offset points",
                            xytext=(5, 3), fontsize=9, color=GOAL_COLOR[g])
        axes[2].plot(cost, 1e3 * wall, marker, color=GOAL_COLOR[g], ms=7, ls="none", label=label)
    if not best_rel:
        c.fail(f"{t.path}: no plans of the goals {', '.join(GOALS)}")
    values["best_mean_rel_greedy_min"] = float(min(best_rel))
    values["best_mean_rel_greedy_max"] = float(max(best_rel))
    values["lookahead_lowers_mean_error_all_goals"] = bool(max(best_rel) < 1.0)
    values["beam1_equals_greedy"] = bool(all(greedy_equal)) if greedy_equal else None
    for ax, what in ((axes[0], "(a) mean distance to the target"),
                     (axes[1], "(b) distance to the target at the end")):
        ax.set_xscale("log")
        ax.set_xlabel("options integrated per planning step")
        ax.set_ylabel("distance [mm] (SE(2), ρ = 0.3 m/rad)")
        ax.set_title(what)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(loc="upper right", fontsize=9)
    axes[2].set_xscale("log")
    axes[2].set_yscale("log")
    axes[2].set_xlabel("options integrated per planning step")
    axes[2].set_ylabel("wall time per planning step [ms]")
    axes[2].set_title("(c) cost (2 threads; machine shared, noisy)")
    axes[2].grid(alpha=0.3, which="both")
    axes[2].legend(loc="upper left", fontsize=9)
    steps = values.get("straight_steps", values.get("turn_steps", values.get("diagonal_steps")))
    fig.suptitle(f"Look-ahead H (levels of Δt) with beam K against the greedy planner (H = 1, "
                 f"circled), {steps} planning steps per plan; labels: H,K")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
