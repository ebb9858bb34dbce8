#!/usr/bin/python3
"""Thesis Fig. 2.2: positions of m, M and the CoM vs time, instant-swap inchworm from rest.

Input: DATA/ch2_inchworm/fig2_2_trace.csv (F = 45 N, μ = 1, six cycles, 1 ms samples plus a row
at each event). Output: OUT/fig2_2.png, OUT/values/fig2_2.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig2_2"
COLUMNS = ["t", "x", "y", "com", "xdot", "ydot", "comdot", "side", "event"]


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    tr = c.read_table(args.data, "fig2_2_trace.csv", COLUMNS)
    side = c.read_sidecar(tr.path)
    if side is None or "params" not in side:
        c.fail(f"{tr.path.with_suffix('.json')}: sidecar with the trace's params missing")
    params = side["params"]
    t, x, y, com = tr["t"], tr["x"], tr["y"], tr["com"]
    xd, yd, cd = tr["xdot"], tr["ydot"], tr["comdot"]
    ev = tr.str("event")

    before = np.flatnonzero(ev == "collision_before")
    after = np.flatnonzero(ev == "collision_after")
    if before.size < 4 or before.size != after.size:
        c.fail(f"{tr.path}: expected matching collision_before/after rows for at least two "
               f"cycles, found {before.size}/{after.size}")

    # Swaps: the CoM jumps by (M − m)/(M + m)·d with d = x − y just before the collision.
    d_before = x[before] - y[before]
    jumps = com[after] - com[before]
    predicted = c.RHO * d_before
    jump_err = np.abs(jumps - predicted)
    # Stroke ends: extension strokes end at d = L_max, contraction strokes at d = −L_min.
    l_max = d_before[d_before > 0]
    l_min = -d_before[d_before < 0]

    # Cycles start at the start row and at each collision at L_min (the swap before an extension).
    t_ends = t[after]
    starts = [0] + [int(a) for a, d in zip(after, d_before) if d < 0]
    cycles = []
    for i0, i1 in zip(starts[:-1], starts[1:]):
        dur = t[i1] - t[i0]
        adv = com[i1] - com[i0]
        cycles.append({"t_start": t[i0], "duration": dur, "com_advance": adv, "mean_speed": adv / dur})
    durations = np.array([cy["duration"] for cy in cycles])
    advances = np.array([cy["com_advance"] for cy in cycles])
    speeds = np.array([cy["mean_speed"] for cy in cycles])
    strokes = np.diff(np.concatenate([[t[0]], t_ends]))

    # Accelerations between consecutive rows inside a stroke (no event in between).
    dt = np.diff(t)
    inside = dt > 1e-9
    inside &= ~np.isin(np.arange(len(t) - 1), before)  # skip the swap itself
    ax = np.diff(xd)[inside] / dt[inside]
    ay = np.diff(yd)[inside] / dt[inside]
    ac = np.diff(cd)[inside] / dt[inside]
    scale = max(np.max(np.abs(ax)), np.max(np.abs(ay)))
    tol = 1e-6 * scale
    # "opposite": never both clearly positive or both clearly negative (a stuck M has ÿ = 0)
    opposite = ~(((ax > tol) & (ay > tol)) | ((ax < -tol) & (ay < -tol)))
    max_com_acc_g = float(np.max(np.abs(ac)) / c.G)

    # The limit of the cycle averages by Aitken's extrapolation of the last three (they converge
    # geometrically, V_j − V_∞ ≈ C λ^j); the trace alone has only six cycles.
    final = speeds[-1]
    lam = limit = None
    if speeds.size >= 3:
        d1, d2 = speeds[-2] - speeds[-3], speeds[-1] - speeds[-2]
        if d1 != 0 and 0 < d2 / d1 < 1:
            lam = d2 / d1
            limit = final + d2 * lam / (1 - lam)
    ref = limit if limit is not None else final
    rel_dev = np.abs(speeds - ref) / abs(ref)

    # ---- figure: (a) the trace, (b) the thesis' upper-left inset as a panel of its own, large
    # enough to read: the last complete cycle from the collision at L_min. Line styles are the
    # caption's: m dashed, M solid, CoM dotted.
    F, mu = params["F"], params["mu"]
    fig, (ax0, ax1) = plt.subplots(2, 1, figsize=(7.2, 8.2), height_ratios=[1.25, 1])
    ax0.plot(t, x, "k--", lw=1.0, label="m (x)")
    ax0.plot(t, y, "k-", lw=1.0, label="M (y)")
    ax0.plot(t, com, "k:", lw=1.6, label="CoM (mx + My)/(m + M)")
    ax0.set_xlabel("t [s]")
    ax0.set_ylabel("position [m]")
    ax0.set_title(f"(a) from rest, F = {F:g} N, μ = {mu:g}: {len(cycles)} cycles")
    ax0.legend(loc="upper left")
    i0, i1 = starts[-2], starts[-1]
    sl = slice(i0, i1 + 1)
    ax0.axvspan(t[i0], t[i1], color="0.9", zorder=0)
    ax0.text(0.5 * (t[i0] + t[i1]), ax0.get_ylim()[0], "(b)", ha="center", va="bottom")
    ax1.plot(t[sl] - t[i0], x[sl] - com[i0], "k--", lw=1.2, label="m (x)")
    ax1.plot(t[sl] - t[i0], y[sl] - com[i0], "k-", lw=1.2, label="M (y)")
    ax1.plot(t[sl] - t[i0], com[sl] - com[i0], "k:", lw=1.8, label="CoM")
    ax1.set_title(f"(b) cycle {len(cycles)}, from the collision at y − x = L_min (shaded in a)")
    ax1.set_xlabel("t − t₀ [s]")
    ax1.set_ylabel("position − c(t₀) [m]")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)

    values = {
        "F": params["F"], "mu": params["mu"],
        "n_cycles": len(cycles),
        "cycle_durations": durations, "cycle_com_advances": advances, "cycle_mean_speeds": speeds,
        "stroke_durations": strokes,
        "cycle_period_last": durations[-1],
        "com_advance_last": advances[-1],
        "mean_speed_last": final,
        "per_cycle_contraction": lam,
        "speed_limit_extrapolated": limit,
        "closed_form_v_ss": c.closed_form(params["F"], params["mu"])["v_ss"],
        "limit_rel_diff_closed_form": abs(limit / c.closed_form(params["F"], params["mu"])["v_ss"]
                                          - 1) if limit else None,
        "rel_dev_from_limit_per_cycle": rel_dev,
        "rel_dev_cycle1": rel_dev[0],
        "rel_dev_cycle3": rel_dev[2] if len(rel_dev) > 2 else None,
        "rel_dev_last_cycle": rel_dev[-1],
        "swap_jumps": jumps,
        "swap_d": d_before,
        "jump_over_d_mean": float(np.mean(jumps / d_before)),
        "jump_over_d_expected": c.RHO,
        "jump_max_abs_error": float(np.max(jump_err)),
        "jump_max_rel_error": float(np.max(jump_err / np.abs(predicted))),
        "L_max_measured": float(np.mean(l_max)) if l_max.size else None,
        "L_min_measured": float(np.mean(l_min)) if l_min.size else None,
        "accel_opposite_fraction": float(np.mean(opposite)),
        "accel_intervals": int(opposite.size),
        "max_com_accel_g": max_com_acc_g,
        # Friction alone moves the CoM (the actuator force is internal), so |c̈| ≤ μg: the
        # bound's check, None when the trace breaks it (finite differences: 1e-6 relative).
        "com_accel_within_mu_g": max_com_acc_g if max_com_acc_g <= params["mu"] * (1 + 1e-6)
        else None,
        "com_accel_within_mu_g_reason": None if max_com_acc_g <= params["mu"] * (1 + 1e-6)
        else f"max |c̈| = {max_com_acc_g:.6g} g exceeds μg = {params['mu']:.6g} g",
        "rows": tr.n,
    }
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
