#!/usr/bin/python3
"""Thesis Fig. 5.2 / §5.2.1: BigANT's tripod up a 17° slope, and the slope at which it stalls.

Input: DATA/ch5_terrain/slope17_coulomb.csv, slope17_viscous.csv (the scene
studies/ch5_terrain/scenes/bigant_slope17.toml under both laws: `slipwalk run` columns plus the
world positions bx, by, bz of the body and px_L, py_L, pz_L of each toe before compression),
progress.csv (kind slope_progress: uphill progress per gait cycle against the slope) and
stall.csv (kind stall_slope: the bisection's probes, both laws).
Output: OUT/fig5_2.png, OUT/values/fig5_2.json.

Panels: (a) the Coulomb run seen from the side, in the vertical plane through the uphill
direction: the slope (gray), the body centre (black; the thesis draws it red, a colour the
report keeps for measured data), the toes of FL, ML, HL (blue, orange, purple; stance: stars,
swing: lines), as in the thesis; (b) the viscous-Coulomb run, which creeps downhill; (c) progress
per cycle against the slope for both laws with the stall slopes found by bisection and their
closed forms: Coulomb holds its stance feet up to tan σ = μ; the
viscous ansatz drifts at tan σ / μ (m/s) whatever the gait, so it stalls at tan σ = μ p₀ / T
(p₀ the flat progress per cycle, T the period).

What the thesis' figure shows (its caption: "a trajectory of simulated BigAnt robot moving up 17°
slope") is read as a climb at the walking stride: every gait cycle gains at least PROGRESS_MIN_REL of
the flat stride uphill along the plane, no slide back downhill by more than a tenth of the flat
stride, a body height above the plane without jumps of more than a centimetre from one frame to
the next, a world height that never falls more than a centimetre below the highest it reached
(a monotone climb), and a mean pitch that follows the slope within PITCH_TOL_DEG.
"""
from __future__ import annotations

import sys
from pathlib import Path

import json

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402
import terrain_peer as tp  # noqa: E402

NAME = "fig5_2"
STUDY = "ch5_terrain"
LEGS = {"FL": "tab:blue", "ML": "tab:orange", "HL": "tab:purple"}
BODY = "black"
LAW_COLOR = {"viscous": c.VISCOUS, "coulomb": c.COULOMB}
LAW_NAME = {"viscous": "viscous-Coulomb", "coulomb": "Coulomb"}
BACKSLIDE_LIMIT = 0.1   # of the flat progress per cycle
JUMP_LIMIT = 0.01       # m, of the body's height above the plane, per frame
PROGRESS_MIN_REL = 0.8  # of the flat stride, the least uphill progress in any gait cycle
FALLBACK_LIMIT = 0.01   # m, the most the body's world height may fall below its highest
PITCH_TOL_DEG = 2.0     # deg, the body's mean pitch against the slope's angle


def load_run(data, name):
    path = c.study_file(data, f"{name}.csv", STUDY)
    cols = ["t", "x", "y", "theta", "beta", "z", "bx", "by", "bz"]
    for leg in LEGS:
        cols += [f"px_{leg}", f"pz_{leg}", f"contact_{leg}"]
    t = c.Table(path, cols)
    if t.n < 2:
        c.fail(f"{path}: fewer than two rows")
    side = path.with_suffix(".json")
    meta = json.loads(side.read_text()) if side.is_file() else {}
    return t, meta


def climb(t, meta, stride: float) -> dict:
    """What the criterion measures on one run: uphill progress along the plane in each whole
    gait cycle, the largest slide back downhill behind the farthest point reached, and the
    largest frame-to-frame change of the body's height above the plane (column z)."""
    scene = meta.get("scene", {})
    period = 1.0 / float(scene.get("gait", {}).get("frequency", 0.1))
    psi = np.radians(float(scene.get("terrain", {}).get("heading_deg", 0.0)))
    s = t["x"] * np.cos(psi) + t["y"] * np.sin(psi)  # uphill, in the plane's coordinates
    n = int(np.floor(t["t"][-1] / period + 1e-9))
    prog = np.diff(np.interp(np.arange(n + 1) * period, t["t"], s))
    back = float(np.max(np.maximum.accumulate(s) - s))
    jump = float(np.max(np.abs(np.diff(t["z"]))))
    fallback = float(np.max(np.maximum.accumulate(t["bz"]) - t["bz"]))
    # The body frame is parallel to the plane: its pitch about the horizontal is σ less the
    # support's δβ (column beta, nose-down positive, eq. 3.6), seen along the uphill direction.
    sigma = np.radians(float(scene.get("terrain", {}).get("angle_deg", 17.0)))
    pitch_deg = float(np.degrees(sigma - np.mean(t["beta"])))
    v = {"cycle_progress_min_m": float(np.min(prog)),
         "cycle_progress_min_rel_flat": float(np.min(prog) / stride), "max_backslide_m": back,
         "max_backslide_rel_stride": back / stride, "max_height_jump_m": jump,
         "max_height_fallback_m": fallback, "mean_pitch_deg": pitch_deg,
         "mean_pitch_minus_slope_deg": pitch_deg - float(np.degrees(sigma))}
    v["climbs_like_thesis"] = bool(np.min(prog) >= PROGRESS_MIN_REL * stride
                                   and back <= BACKSLIDE_LIMIT * stride and jump <= JUMP_LIMIT
                                   and fallback <= FALLBACK_LIMIT
                                   and abs(v["mean_pitch_minus_slope_deg"]) <= PITCH_TOL_DEG)
    return v


def side_view(ax, t, meta, title):
    terrain = meta.get("scene", {}).get("terrain", {})
    sigma = np.radians(float(terrain.get("angle_deg", 17.0)))
    lo = min(np.min(t["bx"]), min(np.min(t[f"px_{leg}"]) for leg in LEGS)) - 0.1
    hi = max(np.max(t["bx"]), max(np.max(t[f"px_{leg}"]) for leg in LEGS)) + 0.1
    xs = np.array([lo, hi])
    ax.fill_between(xs, xs * np.tan(sigma), lo * np.tan(sigma) - 0.15, color="0.85",
                    label=f"slope {np.degrees(sigma):.0f}°")
    ax.plot(t["bx"], t["bz"], color=BODY, lw=1.5, label="body centre")
    for leg, col in LEGS.items():
        px, pz, on = t[f"px_{leg}"], t[f"pz_{leg}"], t[f"contact_{leg}"] > 0.5
        swing = np.where(on, np.nan, pz)
        ax.plot(px, swing, color=col, lw=0.8)
        idx = np.flatnonzero(on)[::25]
        ax.plot(px[idx], pz[idx], "*", color=col, ms=5, label=f"{leg} toe (stance *, swing —)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("horizontal distance uphill [m]")
    ax.set_ylabel("height [m]")
    ax.set_title(title)
    ax.legend(loc="upper left")


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    coul, coul_meta = load_run(args.data, "slope17_coulomb")
    visc, visc_meta = load_run(args.data, "slope17_viscous")
    prog = c.Table(c.study_file(args.data, "progress.csv", STUDY),
                   ["law", "angle_deg", "progress_per_cycle", "sliding_frames"])
    stall = c.Table(c.study_file(args.data, "stall.csv", STUDY),
                    ["law", "angle_deg", "progress_per_cycle", "sliding_frames", "stall_deg"])
    period = 1.0 / float(coul_meta.get("scene", {}).get("gait", {}).get("frequency", 0.1))
    mu = 1.0  # BigANT's μ (robots/bigant.hpp), the same in every run here

    sigma_deg = float(coul_meta.get("scene", {}).get("terrain", {}).get("angle_deg", 17.0))
    cycles = int(np.floor(coul["t"][-1] / period + 1e-9))

    fig = plt.figure(figsize=(13, 9))
    gs = fig.add_gridspec(2, 2, height_ratios=[1.1, 1], hspace=0.3, wspace=0.2,
                          left=0.06, right=0.98, top=0.92, bottom=0.07)
    peer = tp.load(args.data)  # MuJoCo's BigANT on the same slope (referee.toml), if run
    ax_a, ax_b = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1])
    side_view(ax_a, coul, coul_meta,
              f"(a) Coulomb friction: up {sigma_deg:g}°, {cycles} cycles at {1 / period:g} Hz")
    tp.overlay(ax_a, peer, "bigant_slope17")
    side_view(ax_b, visc, visc_meta,
              "(b) viscous-Coulomb ansatz: slides downhill at tan σ/μ m/s")
    tp.overlay(ax_b, peer, "bigant_slope17")

    ax = fig.add_subplot(gs[1, :])
    law = prog.str("law")
    values: dict = {}
    for name in ("coulomb", "viscous"):
        on = law == name
        a, p = prog["angle_deg"][on], prog["progress_per_cycle"][on]
        order = np.argsort(a)
        a, p = a[order], p[order]
        slid = prog["sliding_frames"][on][order] > 0
        ax.plot(a[~slid], p[~slid], "o-", color=LAW_COLOR[name], ms=3,
                label=f"{LAW_NAME[name]}: progress per cycle")
        if slid.any():
            ax.plot(a[slid], np.zeros(slid.sum()), "x", color=LAW_COLOR[name], ms=7,
                    label=f"{LAW_NAME[name]}: slides (no quasi-static balance)")
        s_on = stall.str("law") == name
        if s_on.any():
            s_deg = float(stall["stall_deg"][s_on][0])
            values[f"stall_{name}_deg"] = s_deg
            ax.axvline(s_deg, color=LAW_COLOR[name], ls="--", lw=1,
                       label=f"{LAW_NAME[name]}: stall {s_deg:.3f}° (bisection)")
        flat = p[a == 0]
        if flat.size:
            values[f"flat_progress_{name}_m"] = float(flat[0])
        if name == "viscous" and flat.size:
            # The ansatz's drift tan σ/μ (m/s) over a period, against the flat progress p₀.
            sig = np.linspace(0.0, a.max(), 50)
            ax.plot(sig, flat[0] - period * np.tan(np.radians(sig)) / mu, ":", color="black",
                    lw=1.5, label="viscous-Coulomb closed form p₀ − T tan σ/μ")
        at17 = p[np.isclose(a, 17.0)]
        if at17.size:
            values[f"progress17_{name}_m"] = float(at17[0])
    ax.axhline(0.0, color="0.4", lw=0.8)
    ax.set_xlabel("slope σ [deg]")
    ax.set_ylabel("uphill progress per gait cycle [m]")
    ax.set_ylim(-0.5, 0.35)
    ax.set_title("(c) progress per cycle against the slope, stall slopes by bisection")
    # Lower centre: below the Coulomb curve, right of the viscous one, left of the stall line.
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 0.02))

    # Closed forms: Coulomb holds up to tan σ = μ; the viscous drift tan σ/μ (m/s) over a period T
    # cancels the flat progress p₀ at tan σ = μ p₀ / T.
    values["holding_angle_deg"] = float(np.degrees(np.arctan(mu)))
    p0 = values.get("flat_progress_viscous_m")
    if p0 is not None:
        values["viscous_stall_closed_form_deg"] = float(np.degrees(np.arctan(mu * p0 / period)))
    if "stall_coulomb_deg" in values:
        values["coulomb_stall_minus_holding_deg"] = (values["stall_coulomb_deg"]
                                                     - values["holding_angle_deg"])
    if "stall_viscous_deg" in values and "viscous_stall_closed_form_deg" in values:
        values["viscous_stall_minus_closed_form_deg"] = (values["stall_viscous_deg"]
                                                         - values["viscous_stall_closed_form_deg"])
    for name, (run, meta) in {"coulomb": (coul, coul_meta), "viscous": (visc, visc_meta)}.items():
        stride = values.get(f"flat_progress_{name}_m")
        if not stride:
            c.fail(f"{args.data / STUDY / 'progress.csv'}: no flat (0°) progress for {name}")
        for key, v in climb(run, meta, stride).items():
            values[f"{name}_{key}"] = v
    values["backslide_limit_rel_stride"] = BACKSLIDE_LIMIT
    values["jump_limit_m"] = JUMP_LIMIT
    values["progress_min_rel_flat"] = PROGRESS_MIN_REL
    values["fallback_limit_m"] = FALLBACK_LIMIT
    values["pitch_tol_deg"] = PITCH_TOL_DEG
    values["coulomb_uphill_m"] = float(coul["x"][-1] - coul["x"][0])
    values["viscous_uphill_m"] = float(visc["x"][-1] - visc["x"][0])
    values["coulomb_height_gain_m"] = float(coul["bz"][-1] - coul["bz"][0])
    if values.get("flat_progress_coulomb_m") and "progress17_coulomb_m" in values:
        values["coulomb_progress17_rel_flat"] = (values["progress17_coulomb_m"]
                                                 / values["flat_progress_coulomb_m"])
    values["viscous_drift_17_mps"] = float(np.tan(np.radians(17.0)) / mu)
    values["walking_speed_flat_mps"] = (float(p0 / period) if p0 is not None else None)
    summary_c = coul_meta.get("summary", {})
    values["coulomb_not_converged_frames"] = int(summary_c.get("not_converged_frames", 0))
    values["coulomb_max_balance_residual"] = float(summary_c.get("max_friction_residual", 0.0))
    values.update(tp.values(peer, "bigant_slope17"))
    fig.suptitle("Fig. 5.2 analog: BigANT's alternating tripod on a slope (synthetic; μ = 1)")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
