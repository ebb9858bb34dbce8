"""Shared helpers of the planning figures (thesis §5.4-5.5, studies/ch5_planning).

The plans are DATA/ch5_planning/plans.csv (kind plan_run, sweeps/points/planning.cpp): one row per
planning step per plan — the step's start state, the target there and the choice made (the plan
CSV's columns, lib/planning/plan_csv.hpp) — and a last row, step = steps, with the state after
the last step (option -1, speeds NaN). A plan is the rows of one (goal, law, lookahead, beam).
A MuJoCo replay of a plan, when the replay sweep ran (DATA/ch5_planning/replay.csv, kind
plan_replay), is its rows of the goal with label "base" and the fewest steps (300 in the full
study: the same greedy plan as plans.csv's, which the planner makes identically on any thread
count): columns t, x, y, theta (the plan), x_mujoco, y_mujoco, theta_mujoco.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

import common as c

STUDY = "ch5_planning"
LEGS = ("HL", "ML", "FL", "HR", "MR", "FR")  # the thesis' order (§5.5)
TRIPOD_A = ("HL", "FL", "MR")  # at φ = 0.5 in the start pose (tripod_start)
TRIPOD_B = ("ML", "HR", "FR")
LEFT = ("HL", "ML", "FL")
RIGHT = ("HR", "MR", "FR")
LAW_NAME = {"viscous": "viscous-Coulomb", "coulomb": "Coulomb"}
LAW_COLOR = {"viscous": c.VISCOUS, "coulomb": c.COULOMB}
LEG_COLOR = dict(zip(LEGS, ("tab:cyan", "tab:olive", "tab:brown", "tab:pink", "0.3", "tab:purple")))
LEG_STYLE = {leg: ("-" if leg in LEFT else "--") for leg in LEGS}
ARROW_STEPS = (0, 100, 200, 300)  # the thesis' yaw arrows (Figs. 5.9, 5.11)

PLAN_COLUMNS = ["goal", "law", "lookahead", "beam", "step", "t", "x", "y", "theta", "goal_x",
                "goal_y", "goal_theta", "distance", "evaluated", "step_wall_s"] + \
    [f"{p}_{leg}" for p in ("speed", "phi") for leg in LEGS]


def load_plans(data: Path) -> c.Table:
    return c.Table(c.study_file(data, "plans.csv", STUDY), PLAN_COLUMNS)


def plan(table: c.Table, goal: str, law: str = "viscous") -> c.Table:
    """The greedy plan of a goal under a law, rows in step order."""
    mask = ((table.str("goal") == goal) & (table.str("law") == law) & (table["lookahead"] == 1))
    p = table.subset(mask)
    if p.n < 2:
        c.fail(f"{table.path}: no plan for goal '{goal}' under law '{law}'")
    order = np.argsort(p["step"], kind="stable")
    return _sorted(p, order)


def _sorted(t: c.Table, order: np.ndarray) -> c.Table:
    s = c.Table.__new__(c.Table)
    s.path = t.path
    s.columns = {k: v[order] for k, v in t.columns.items()}
    s.n = t.n
    return s


def summary(p: c.Table) -> dict:
    """What a plan did: tracking error, where the body went, how the legs moved, what it cost.
    The step starts are rows 0 … n-1 (the planner's mean distance is over them); the last row
    is the state after the last step."""
    steps = int(p["step"][-1])
    starts = slice(0, p.n - 1)
    yaw = np.abs(p["theta"] - p["goal_theta"])  # both unwrapped from 0
    gx, gy, gth = p["goal_x"][-1], p["goal_y"][-1], p["goal_theta"][-1]
    travel = float(np.hypot(gx - p["goal_x"][0], gy - p["goal_y"][0]))
    path = float(np.sum(np.hypot(np.diff(p["x"]), np.diff(p["y"]))))
    speeds = {leg: p[f"speed_{leg}"][starts] for leg in LEGS}
    mean_speed = {leg: float(np.mean(v)) for leg, v in speeds.items()}

    def same(legs):
        return np.all([speeds[leg] == speeds[legs[0]] for leg in legs[1:]], axis=0)

    tripod = same(TRIPOD_A) & same(TRIPOD_B)
    mirror = np.all([speeds[left] == speeds[right] for left, right in zip(LEFT, RIGHT)], axis=0)
    left = float(np.mean([mean_speed[leg] for leg in LEFT]))
    right = float(np.mean([mean_speed[leg] for leg in RIGHT]))
    wall = p["step_wall_s"][starts]
    forward, lateral = body_displacements(p)
    out = {
        "steps": steps,
        "duration_s": float(p["t"][-1]),
        "mean_distance_m": float(np.mean(p["distance"][starts])),
        "final_distance_m": float(p["distance"][-1]),
        "max_distance_m": float(np.max(p["distance"])),
        "mean_yaw_error_rad": float(np.mean(yaw[starts])),
        "final_yaw_error_rad": float(yaw[-1]),
        "max_yaw_error_rad": float(np.max(yaw)),
        "max_radius_m": float(np.max(np.hypot(p["x"], p["y"]))),
        "final_x_m": float(p["x"][-1]),
        "final_y_m": float(p["y"][-1]),
        "final_theta_rad": float(p["theta"][-1]),
        "goal_x_m": float(gx),
        "goal_y_m": float(gy),
        "goal_theta_rad": float(gth),
        "goal_travel_m": travel,
        "body_path_m": path,
        "tripod_step_fraction": float(np.mean(tripod)),
        "mirror_step_fraction": float(np.mean(mirror)),
        "left_mean_speed": left,
        "right_mean_speed": right,
        "left_minus_right_speed": left - right,
        "lateral_fraction": float(np.sum(np.abs(lateral)) / np.sum(np.abs(forward))),
        "evaluated_per_step": float(np.mean(p["evaluated"][starts])),
        "wall_per_step_s": float(np.mean(wall)) if np.all(np.isfinite(wall)) else None,
        "wall_s": float(np.sum(wall)) if np.all(np.isfinite(wall)) else None,
    }
    out["mean_distance_rel_travel"] = (out["mean_distance_m"] / travel) if travel > 0 else None
    for leg, v in mean_speed.items():
        out[f"mean_speed_{leg}"] = v
    return out


def body_displacements(p: c.Table) -> tuple[np.ndarray, np.ndarray]:
    """Per planning step, the body's forward and lateral displacement in its own frame: the
    SE(2) log of the step's relative motion (the constant body twist that moves the body from
    one step start to the next, times the step's duration)."""
    dx, dy, dth = np.diff(p["x"]), np.diff(p["y"]), np.diff(p["theta"])
    cos, sin = np.cos(p["theta"][:-1]), np.sin(p["theta"][:-1])
    xb, yb = cos * dx + sin * dy, -sin * dx + cos * dy  # in the frame at the step's start
    h = 0.5 * dth
    sinc = np.where(np.abs(h) > 1e-12, np.sin(h) / np.where(h == 0, 1.0, h), 1.0)
    forward = (np.cos(h) * xb + np.sin(h) * yb) / sinc
    lateral = (-np.sin(h) * xb + np.cos(h) * yb) / sinc
    return forward, lateral


def replay(data: Path, goal: str) -> c.Table | None:
    """MuJoCo's replay of the goal's plan (see above); None when there is none or no MuJoCo."""
    path = data / STUDY / "replay.csv"
    if not path.is_file():
        return None
    t = c.Table(path, ["goal", "label", "steps", "t", "x", "y", "theta", "x_mujoco", "y_mujoco",
                       "theta_mujoco"])
    mine = (t.str("goal") == goal) & (t.str("label") == "base")
    if not mine.any():
        return None
    r = t.subset(mine & (t["steps"] == np.min(t["steps"][mine])))  # one point: rows in time order
    return r if r.n > 0 and np.isfinite(r["x_mujoco"]).any() else None


def replay_summary(r: c.Table | None) -> dict:
    if r is None:
        return {"mujoco_replay": False}
    gap = np.hypot(r["x_mujoco"] - r["x"], r["y_mujoco"] - r["y"])
    return {"mujoco_replay": True,
            "mujoco_final_x_m": float(r["x_mujoco"][-1]),
            "mujoco_final_y_m": float(r["y_mujoco"][-1]),
            "mujoco_final_theta_rad": float(r["theta_mujoco"][-1]),
            "mujoco_max_gap_m": float(np.max(gap)),
            "mujoco_final_gap_m": float(gap[-1]),
            "mujoco_max_yaw_gap_rad": float(np.max(np.abs(r["theta_mujoco"] - r["theta"])))}


def yaw_arrows(ax, x, y, theta, steps, color, length, label=None, numbers=False):
    """Heading arrows at the thesis' steps 0/100/200/300 (those the plan reaches)."""
    first = True
    for k in ARROW_STEPS:
        hit = np.flatnonzero(steps == k)
        if hit.size == 0:
            continue
        i = hit[0]
        ax.annotate("", xy=(x[i] + length * np.cos(theta[i]), y[i] + length * np.sin(theta[i])),
                    xytext=(x[i], y[i]),
                    arrowprops=dict(arrowstyle="-|>", color=color, lw=1.4))
        ax.plot([x[i]], [y[i]], "o", color=color, ms=4, label=label if first else None)
        if numbers:
            ax.annotate(f"step {k}", (x[i], y[i]), textcoords="offset points", xytext=(4, -14),
                        color=color, fontsize=9)
        first = False


def trajectory_panel(ax, plans: dict, r: c.Table | None, title: str, arrow: float):
    """The body's path in the plane: goal (reference, dashed), plans per law, MuJoCo's replay."""
    p0 = next(iter(plans.values()))
    ax.plot(p0["goal_x"], p0["goal_y"], "--", color=c.REFERENCE, lw=1.5, label="goal Ω^target(t)")
    yaw_arrows(ax, p0["goal_x"], p0["goal_y"], p0["goal_theta"], p0["step"], c.REFERENCE, arrow,
               numbers=True)
    for law, p in plans.items():
        ax.plot(p["x"], p["y"], color=LAW_COLOR[law], lw=1.6, label=f"planned ({LAW_NAME[law]})")
        yaw_arrows(ax, p["x"], p["y"], p["theta"], p["step"], LAW_COLOR[law], arrow,
                   label=f"yaw at steps {', '.join(map(str, ARROW_STEPS))}" if law == "viscous"
                   else None)
    if r is not None:
        ax.plot(r["x_mujoco"], r["y_mujoco"], color=c.MUJOCO, lw=1.4,
                label="MuJoCo replay of the viscous plan")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(loc="lower right", fontsize=9)


def shaft_panel(ax, p: c.Table, title: str):
    """Shaft angles per leg against time, unwrapped (turns: one gait cycle per unit)."""
    for leg in LEGS:
        phi = np.unwrap(p[f"phi_{leg}"] * 2 * np.pi) / (2 * np.pi)
        ax.plot(p["t"], phi, LEG_STYLE[leg], color=LEG_COLOR[leg], lw=1.3, label=leg)
    ax.set_xlabel("time [s] (one planning step executes 5 ms)")
    ax.set_ylabel("shaft angle φ, unwrapped [turns]")
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(loc="upper left", ncol=2, fontsize=9)
