#!/usr/bin/python3
"""§5.5, beyond the thesis: the three goals' plans replayed open-loop on MuJoCo's BigANT.

Input: DATA/ch5_planning/replay.csv (kind plan_replay: per goal -- straight, turn, diagonal --,
plan length `steps` and MuJoCo variant `label`, one row per planning step time with the plan's
pose x, y, theta and MuJoCo's x_mujoco, y_mujoco, theta_mujoco, and the run's gaps on every row)
and, optional, DATA/ch5_planning/replay_coulomb.csv (the same kind: the turn planned with
Coulomb friction, label "coulomb", set beside replay.csv's stiff turn of its own length).
Output: OUT/plan_replay.png, OUT/values/plan_replay.json.

Panels: (top) per goal the body paths in the plane, the plan (black) against MuJoCo with §3.5.4's
actuators (base, green), with stiff x/y actuators (dashed) and those replayed 4× slower
(dotted); (bottom) per goal the progress
along the goal against time (straight, diagonal: the displacement along the goal's direction;
turn: the yaw), and a last panel with the relative gap of every MuJoCo variant against the
bound of the ledger's own check. Each variant's longest plan in the data is drawn (1200 steps,
6 s; the Coulomb plan 300 steps unless `--full`; the quick run has shorter ones). Without MuJoCo in the build only the plans are drawn and the panels
say so.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "plan_replay"
STUDY = "ch5_planning"
GOALS = ("straight", "turn", "diagonal")
GOAL_TITLE = {"straight": "walk straight, 0.2 m/s", "turn": "turn in place, 0.2 rad/s",
              "diagonal": "diagonal (0.05, 0.02) m/s"}
GOAL_DIR = {"straight": (1.0, 0.0), "diagonal": (0.05, 0.02)}  # body twist (v_x, v_y)
LABELS = ("base", "stiff", "slow", "contact", "coulomb")
LABEL_TEXT = {"base": "§3.5.4 actuators (kp_xy 100 N/m)",
              "stiff": "stiff x/y slides (2675 N/m) + lead",
              "slow": "stiff, plan replayed 4× slower",
              "contact": "stiff, contact solref 2 ms",
              "coulomb": "stiff, plan made with Coulomb friction"}
SHORT = {"base": "base", "stiff": "stiff", "slow": "stiff,\n4× slower",
         "contact": "stiff,\ncontact 2 ms", "coulomb": "stiff,\nCoulomb plan"}
# The ledger's own check (data/thesis/claims.toml, "5.5-plan-survives-mujoco"): fixed before the
# replay was run. The relative gap is MuJoCo's final distance from the plan's final pose over the
# plan's path length (straight, diagonal), and the yaw gap over the plan's yaw change (turn).
BOUND = 0.25


def rel_gap(row: dict, goal: str) -> float:
    return row["yaw_rel"] if goal == "turn" else row["gap_rel"]


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    path = c.study_file(args.data, "replay.csv", STUDY)
    cols = ["id", "goal", "label", "steps", "slowdown", "t", "x", "y", "theta", "x_mujoco",
            "y_mujoco", "theta_mujoco", "plan_path", "plan_yaw", "gap_final", "gap_rms",
            "yaw_gap_final", "yaw_gap_rms", "gap_rel", "yaw_rel", "progress", "rmse_x", "rmse_y",
            "mean_contacts", "message"]
    t = c.Table(path, cols)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    coulomb_path = args.data / STUDY / "replay_coulomb.csv"
    tc = c.Table(coulomb_path, cols) if coulomb_path.is_file() else None
    steps = int(np.nanmax(t["steps"]))
    have_mujoco = bool(np.isfinite(t["x_mujoco"]).any())

    def longest(table, label: str) -> int | None:
        if table is None or table.n == 0:
            return None
        m = table.str("label") == label
        return int(np.nanmax(table["steps"][m])) if m.any() else None

    def run(goal: str, label: str, length: int | None = None) -> dict | None:
        table = tc if label == "coulomb" else t
        length = length if length is not None else longest(table, label)
        if length is None:
            return None
        m = ((table.str("goal") == goal) & (table.str("label") == label)
             & (table["steps"] == length))
        if not m.any():
            return None
        s = table.subset(m)
        order = np.argsort(s["t"])
        out = {k: s[k][order] for k in ("t", "x", "y", "theta", "x_mujoco", "y_mujoco",
                                         "theta_mujoco")}
        for k in ("plan_path", "plan_yaw", "gap_final", "gap_rms", "yaw_gap_final",
                  "yaw_gap_rms", "gap_rel", "yaw_rel", "progress", "rmse_x", "rmse_y",
                  "mean_contacts", "slowdown"):
            out[k] = float(s[k][0])
        out["message"] = str(s.str("message")[0])
        return out

    values: dict = {"steps": steps, "bound": BOUND, "mujoco": have_mujoco}
    fig = plt.figure(figsize=(14, 9.5))
    gs = fig.add_gridspec(2, 4, width_ratios=[1, 1, 1, 0.8], hspace=0.32, wspace=0.32,
                          left=0.05, right=0.98, top=0.9, bottom=0.08)
    for j, goal in enumerate(GOALS):
        base, stiff, slow = run(goal, "base"), run(goal, "stiff"), run(goal, "slow")
        if base is None:
            c.fail(f"{path}: no base run of goal {goal} with {steps} steps")
        ax = fig.add_subplot(gs[0, j])
        ax.plot(base["x"], base["y"], color=c.REFERENCE, lw=2, label="plan (quasi-static model)")
        ax.plot(base["x"][-1], base["y"][-1], "o", color=c.REFERENCE, ms=5)
        for r, style, lab in ((base, "-", "base"), (stiff, "--", "stiff"), (slow, ":", "slow")):
            if r is None or not np.isfinite(r["x_mujoco"]).any():
                continue
            ax.plot(r["x_mujoco"], r["y_mujoco"], style, color=c.MUJOCO, lw=1.5,
                    label=f"MuJoCo, {LABEL_TEXT[lab]}")
            ax.plot(r["x_mujoco"][-1], r["y_mujoco"][-1], "o", color=c.MUJOCO, ms=5)
        if not have_mujoco:
            ax.text(0.5, 0.5, "built without MuJoCo:\nplan only", transform=ax.transAxes,
                    ha="center", va="center", color=c.NEUTRAL)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title(f"({'abc'[j]}) {GOAL_TITLE[goal]}: body path")
        if j == 0:
            ax.legend(loc="upper left", fontsize=9)

        # Progress along the goal against time.
        ax2 = fig.add_subplot(gs[1, j])
        if goal == "turn":
            ax2.plot(base["t"], base["theta"], color=c.REFERENCE, lw=2, label="plan")
            for r, style in ((base, "-"), (stiff, "--")):
                if r is not None and np.isfinite(r["theta_mujoco"]).any():
                    ax2.plot(r["t"], r["theta_mujoco"], style, color=c.MUJOCO, lw=1.5)
            ax2.plot(base["t"], 0.2 * base["t"], ":", color=c.NEUTRAL, lw=1, label="goal 0.2 t")
            ax2.set_ylabel("yaw θ [rad]")
        else:
            u = np.array(GOAL_DIR[goal]) / np.hypot(*GOAL_DIR[goal])
            speed = 0.2 if goal == "straight" else float(np.hypot(0.05, 0.02))
            ax2.plot(base["t"], u[0] * base["x"] + u[1] * base["y"], color=c.REFERENCE, lw=2,
                     label="plan")
            for r, style in ((base, "-"), (stiff, "--")):
                if r is not None and np.isfinite(r["x_mujoco"]).any():
                    ax2.plot(r["t"], u[0] * r["x_mujoco"] + u[1] * r["y_mujoco"], style,
                             color=c.MUJOCO, lw=1.5)
            ax2.plot(base["t"], speed * base["t"], ":", color=c.NEUTRAL, lw=1,
                     label=f"goal {speed:.3g} t")
            ax2.set_ylabel("progress along the goal [m]")
        ax2.set_xlabel("t [s]")
        ax2.set_title(f"({'def'[j]}) {goal}: progress against time")
        ax2.legend(loc="upper left", fontsize=9)

        for label in LABELS:
            r = run(goal, label)
            if r is None:
                continue
            for k in ("plan_path", "plan_yaw", "gap_final", "gap_rms", "yaw_gap_final",
                      "yaw_gap_rms", "progress", "rmse_x", "mean_contacts"):
                values[f"{label}_{goal}_{k}"] = r[k]
            values[f"{label}_{goal}_rel_gap"] = rel_gap(r, goal)
        values[f"plan_{goal}_duration_s"] = float(base["t"][-1] - base["t"][0])

    # The Coulomb plan beside the same robot's turn of the same length planned with the viscous
    # ansatz: the friction law's share of the turn's yaw deficit, like for like.
    if "coulomb_turn_rel_gap" not in values:
        values["coulomb_turn_rel_gap"] = None
        values["coulomb_turn_rel_gap_reason"] = "no Coulomb plan of the turn in the data"
    coulomb_steps = longest(tc, "coulomb")
    values["coulomb_steps"] = coulomb_steps
    reference = run("turn", "stiff", coulomb_steps) if coulomb_steps is not None else None
    values["coulomb_reference_turn_rel_gap"] = (rel_gap(reference, "turn")
                                                if reference is not None else None)
    if coulomb_steps is None:
        values["coulomb_steps_reason"] = f"{c.shown_path(coulomb_path)} is missing"
    if values["coulomb_reference_turn_rel_gap"] is None:
        values["coulomb_reference_turn_rel_gap_reason"] = (
            "no Coulomb plan, or no stiff turn of its length in replay.csv")

    # The relative gap of every MuJoCo variant, per goal, against the bound.
    ax3 = fig.add_subplot(gs[:, 3])
    present = [lab for lab in LABELS if any(run(g, lab) is not None for g in GOALS)]
    width = 0.8 / max(len(GOALS), 1)
    for k, goal in enumerate(GOALS):
        ys = [values.get(f"{lab}_{goal}_rel_gap", np.nan) for lab in present]
        ax3.barh(np.arange(len(present)) + (k - 1) * width, ys, height=width,
                 color=c.CATEGORICAL[k], label=goal + (" (yaw)" if goal == "turn" else ""))
    ax3.axvline(BOUND, color=c.REFERENCE, ls="--", lw=1, label=f"bound {BOUND:g}")
    ax3.set_yticks(np.arange(len(present)))
    ax3.set_yticklabels([SHORT[lab] + (f"\n({coulomb_steps} steps)" if lab == "coulomb" and
                                        coulomb_steps != steps else "") for lab in present])
    ax3.invert_yaxis()
    ax3.set_xlabel("final gap / the plan's travel")
    ax3.set_title("(g) relative gap of each variant")
    ax3.legend(loc="lower right", fontsize=9)
    if not have_mujoco:
        ax3.text(0.5, 0.5, "built without MuJoCo", transform=ax3.transAxes, ha="center",
                 color=c.NEUTRAL)

    # The ledger's numbers: each variant's relative gap, worst of the three goals.
    for label in LABELS:
        gaps = [values.get(f"{label}_{g}_rel_gap") for g in GOALS]
        ok = all(v is not None and np.isfinite(v) for v in gaps)
        values[f"{label}_rel_gap_max"] = max(gaps) if ok else None
    values["survives"] = (values["base_rel_gap_max"] is not None
                          and values["base_rel_gap_max"] <= BOUND)
    fig.suptitle(f"Plans of §5.5's three goals ({steps} steps, "
                 f"{values['plan_straight_duration_s']:.2g} s) replayed open-loop on MuJoCo's "
                 "BigANT (synthetic: MuJoCo stands in for the robot)")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
