#!/usr/bin/python3
"""Thesis Fig. 2.4: velocities of m, M and the CoM within one velocity cycle of regime II.

Input: DATA/ch2_inchworm/fig2_4_trace.csv and its sidecar (F = 45 N, μ = 1, the Fig. 2.2 system,
40 cycles from rest by exact event-driven integration, so the last strokes are the limit cycle).
Output: OUT/fig2_4.png, OUT/values/fig2_4.json.

The thesis' schematic (§2.4) follows one stroke from the plastic collision at d = L_min, where
ẋ0 = ẏ0 = ċ0, through t1 (M's velocity reaches 0) to t1 + t2 (d = L_max), where a second plastic
collision resets the velocities. Here the same stroke is read from the trace: the times and
velocities at its events, and the accelerations of each stage as least-squares slopes of the
sampled velocities; they are compared with the thesis' expressions (eqs. 2.7, 2.8, the t1 and ċ1
of §2.4, eq. 2.4 at the collision, eq. 2.9 for t2, eq. 2.11 for v_ss). The closed form of
common.py serves only as a cross-check of the fixed point.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig2_4"
COLUMNS = ["t", "x", "y", "com", "xdot", "ydot", "comdot", "side", "event"]
PARAMS = ["F", "mu", "mu_s", "m", "M", "g", "L_min", "L_max"]


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def num(x: float, digits: int) -> str:
    """x to `digits` decimals with a typographic minus."""
    return f"{x:.{digits}f}".replace("-", "−")


def slope(t: np.ndarray, v: np.ndarray) -> tuple[float, float]:
    """Least-squares slope of v(t) and the largest residual from that line (the velocities of a
    stage are linear in t if its acceleration is constant)."""
    k, b = np.polyfit(t, v, 1)
    return float(k), float(np.max(np.abs(v - (k * t + b))))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    tr = c.read_table(args.data, "fig2_4_trace.csv", COLUMNS)
    side_json = c.read_sidecar(tr.path)
    if side_json is None or "params" not in side_json:
        c.fail(f"{tr.path.with_suffix('.json')}: sidecar with the trace's params missing")
    p = side_json["params"]
    missing = [k for k in PARAMS if p.get(k) is None]
    if missing or p.get("model", "instant") != "instant":
        c.fail(f"{tr.path.with_suffix('.json')}: need an instant-swap trace with "
               f"{', '.join(PARAMS)} (missing: {', '.join(missing) or 'none'})")
    F, mu, mu_s, m, M, g = (float(p[k]) for k in ("F", "mu", "mu_s", "m", "M", "g"))
    dL = float(p["L_max"]) - float(p["L_min"])
    rho = (M - m) / (M + m)
    if F <= mu_s * M * g:
        c.fail(f"{tr.path}: F = {F:g} N ≤ μ_s M g = {mu_s * M * g:.4g} N is regime I; "
               "Fig. 2.4 is a cycle of regime II")

    t, com = tr["t"], tr["com"]
    xd, yd, cd = tr["xdot"], tr["ydot"], tr["comdot"]
    ev, side = tr.str("event"), tr["side"]
    after = np.flatnonzero(ev == "collision_after")
    before = np.flatnonzero(ev == "collision_before")
    # Strokes start after a collision; side > 0 there means an extension from d = L_min (the
    # thesis' start). The last complete extension stroke is the cycle shown.
    ext = [i for i in after if side[i] > 0 and np.any(after > i)]
    if len(ext) < 2:
        c.fail(f"{tr.path}: fewer than two complete extension strokes")
    i0 = int(ext[-1])
    ie = int(before[before > i0][0])      # the second collision, just before
    ia = int(after[after > i0][0])        # and just after
    stops = [i for i in range(i0, ie) if ev[i] == "M_stops"]
    if len(stops) != 1:
        c.fail(f"{tr.path}: expected one M_stops event in the stroke at t = {t[i0]:.6g} s, "
               f"found {len(stops)}")
    i1 = stops[0]

    # ---- the stroke's events (the thesis' symbols)
    c0, x0, y0 = cd[i0], xd[i0], yd[i0]
    T1 = t[i1] - t[i0]
    T2 = t[ie] - t[i1]
    T = T1 + T2
    c1, x_t1, y_t1 = cd[i1], xd[i1], yd[i1]
    x_end, y_end, c_end = xd[ie], yd[ie], cd[ie]
    x_next, y_next, c_next = xd[ia], yd[ia], cd[ia]

    # ---- stage accelerations: slopes of the sampled velocities (rows strictly inside a stage
    # plus its end events; event rows at the same time as a sample add nothing)
    s1 = slice(i0, i1 + 1)
    s2 = slice(i1, ie + 1)
    xdd1, rx1 = slope(t[s1], xd[s1])
    xdd2, rx2 = slope(t[s2], xd[s2])
    ydd1, ry1 = slope(t[s1], yd[s1])
    ydd2, ry2 = slope(t[s2], yd[s2])
    cdd1, rc1 = slope(t[s1], cd[s1])
    cdd2, rc2 = slope(t[s2], cd[s2])
    v_scale = max(np.max(np.abs(xd[i0:ie + 1])), np.max(np.abs(yd[i0:ie + 1])))
    linear_residual = max(rx1, rx2, ry1, ry2, rc1, rc2) / v_scale

    # ---- the thesis' expressions, evaluated with the run's parameters and our ċ0
    xdd_th = (F - mu * m * g) / m                      # eq. 2.7
    ydd1_th = (-F - mu * M * g) / M                    # eq. 2.8, ẏ > 0
    ydd2_th = min(-F + mu * M * g, 0.0) / M            # eq. 2.8, ẏ ≤ 0
    cdd1_th = -mu * g                                  # §2.4: c̈1 = −μg
    cdd2_th = mu * g * rho                             # eq. 2.10: (M − m)/(M + m) μg over t2
    t1_th = c0 / (F / M + mu * g)                      # §2.4: t1 = ċ0/(F/M + μg)
    c1_th = c0 * F / (F + mu * M * g)                  # §2.4: ċ1 = ċ0 F/(F + μMg)
    acc = {"xdd_stage1": (xdd1, xdd_th), "xdd_stage2": (xdd2, xdd_th),
           "ydd1": (ydd1, ydd1_th), "ydd2": (ydd2, ydd2_th)}
    acc_rel = {k: rel(a, b) for k, (a, b) in acc.items()}

    # eq. 2.9, t2 from the stroke length with our t1 and ẋ_t1: as derived (½ on the t2² term)
    # and as printed (without it; ledger entry 2.4-eq2.9-printed)
    rhs = dL - 0.5 * (xdd_th - ydd1_th) * T1**2

    def t2_of(a: float) -> float:
        return (-x_t1 + math.sqrt(x_t1**2 + 4 * a * rhs)) / (2 * a)

    t2_eq29 = t2_of(0.5 * (xdd_th - ydd2_th))
    t2_eq29_printed = t2_of(xdd_th - ydd2_th)

    # eq. 2.4 at the second collision: both velocities become the momentum average, which on the
    # limit cycle is the ċ0 the stroke started with
    v_plus = (m * x_end + M * y_end) / (m + M)
    reset = max(abs(x_next - v_plus), abs(y_next - v_plus), abs(v_plus - c0)) / c0

    # ẏ > 0 until t1, then < 0 (M decelerates to zero, then slides backward: §2.4); the trace
    # writes a plain row at each event's time as well, so the stages are told apart by time
    ts, ys = t[i0:ie + 1], yd[i0:ie + 1]
    m_reverses = bool(np.all(ys[ts < t[i1]] > 0) and np.all(ys[ts > t[i1]] < 0))

    # the limit cycle: ċ0 of this stroke against the previous extension stroke's
    c0_prev = cd[int(ext[-2])]
    # v_ss over the full cycle (this extension stroke and the contraction after it)
    nxt = [i for i in after if side[i] > 0 and i > i0]
    v_cycle = (com[nxt[0]] - com[i0]) / (t[nxt[0]] - t[i0]) if nxt else None
    v_eq211 = (2 * F + mu * M * g) / (2 * (F + mu * M * g)) * c0 + rho * dL / (2 * T)

    # cross-check only: the closed form's fixed point (common.py, the thesis' §2.3 constants)
    same_constants = all(math.isclose(a, b) for a, b in
                         ((m, c.m), (M, c.M), (g, c.G), (dL, c.DL))) and mu_s == mu
    cf = c.closed_form(F, mu) if same_constants else None

    values = {
        "F": F, "mu": mu, "regime": 2, "F_over_muMg": F / (mu * M * g),
        "t_start": t[i0], "stroke_index": len(ext), "cycles_from_rest": side_json.get("cycles"),
        "c0": c0, "x0": x0, "y0": y0,
        "start_velocity_max_rel_spread": max(abs(x0 - c0), abs(y0 - c0)) / c0,
        "t1": T1, "t2": T2, "period": T,
        "t1_thesis": t1_th, "t1_rel_diff": rel(T1, t1_th),
        "c1": c1, "c1_thesis": c1_th, "c1_rel_diff": rel(c1, c1_th),
        "c1_over_c0": c1 / c0,
        "x_t1": x_t1, "y_t1": y_t1,
        "x_end": x_end, "y_end": y_end, "c_end": c_end,
        "x_next": x_next, "y_next": y_next, "c_next": c_next,
        "xdd_stage1": xdd1, "xdd_stage2": xdd2, "xdd_thesis": xdd_th,
        "ydd1": ydd1, "ydd1_thesis": ydd1_th, "ydd2": ydd2, "ydd2_thesis": ydd2_th,
        "accel_rel_diffs": acc_rel,
        "accel_max_rel_diff": max(acc_rel.values()),
        "cdd1": cdd1, "cdd1_thesis": cdd1_th, "cdd1_rel_diff": rel(cdd1, cdd1_th),
        "cdd2": cdd2, "cdd2_thesis": cdd2_th, "cdd2_rel_diff": rel(cdd2, cdd2_th),
        "velocities_linear_max_rel_residual": linear_residual,
        "M_reverses_once": m_reverses,
        "t2_eq2_9": t2_eq29, "t2_eq2_9_rel_diff": rel(T2, t2_eq29),
        "t2_eq2_9_printed": t2_eq29_printed,
        "t2_eq2_9_printed_rel_diff": rel(T2, t2_eq29_printed),
        "collision_v_plus": v_plus,
        "reset_max_rel_diff": reset,
        "c0_change_from_previous_stroke_rel": rel(c0, c0_prev),
        "v_ss_cycle": v_cycle,
        "v_ss_eq2_11": v_eq211,
        "v_ss_eq2_11_rel_diff": rel(v_eq211, v_cycle) if v_cycle else None,
        "closed_form_c0": cf["c0"] if cf else None,
        "closed_form_period": cf["period"] if cf else None,
        "closed_form_v_ss": cf["v_ss"] if cf else None,
        "c0_vs_closed_form_rel": rel(c0, cf["c0"]) if cf else None,
        "period_vs_closed_form_rel": rel(T, cf["period"]) if cf else None,
    }

    # ---- figure: (a) the cycle as in the thesis' schematic — m dashed, M solid, CoM dotted
    # (caption of Fig. 2.4), the two arrows of the second collision; (b) the CoM enlarged
    tt = t[i0:ie + 1] - t[i0]
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7.2, 8.6), height_ratios=[1.45, 1])
    ax.plot(tt, xd[i0:ie + 1], "k--", lw=1.3, label="m: ẋ")
    ax.plot(tt, yd[i0:ie + 1], "k-", lw=1.3, label="M: ẏ")
    ax.plot(tt, cd[i0:ie + 1], "k:", lw=1.8, label="CoM: ċ")
    ax.axhline(0, color="0.5", lw=0.7)
    for tv in (T1, T):
        ax.axvline(tv, color="0.6", lw=0.8, ls="--")
    arrow = dict(arrowstyle="-|>", color="k", lw=1.2, shrinkA=0, shrinkB=0, mutation_scale=14)
    ax.annotate("", xy=(T, c_next), xytext=(T, x_end), arrowprops=arrow)
    ax.annotate("", xy=(T, c_next), xytext=(T, y_end), arrowprops=arrow)
    ax.plot([T], [c_next], "o", ms=5, mfc="white", mec="k", zorder=4)
    ax.plot([0], [c0], "o", ms=5, mfc="white", mec="k", zorder=4)
    lead = dict(arrowstyle="-", color="0.4", lw=0.8)
    ax.annotate(f"ẋ0 = ẏ0 = ċ0 = {num(c0, 3)} m/s", xy=(0, c0), xytext=(0.02 * T, 3.0),
                arrowprops=lead)
    ax.annotate(f"second plastic collision\n(eq. 2.4): ẋ, ẏ → {num(c_next, 3)} m/s",
                xy=(T, c_next), xytext=(0.93 * T, 2.3), ha="right", arrowprops=lead)
    ax.text(0.55 * T, xd[i0] + xdd2 * 0.55 * T + 0.25, f"ẍ = {num(xdd2, 1)} m/s²",
            ha="right", va="bottom")
    ax.annotate(f"ÿ₁ = {num(ydd1, 1)} m/s²", xy=(0.5 * T1, y0 + 0.5 * ydd1 * T1),
                xytext=(0.005 * T, -0.55), va="top", arrowprops=lead)
    ax.text(T1 + 0.6 * T2, ydd2 * 0.6 * T2 - 0.25, f"ÿ₂ = {num(ydd2, 1)} m/s²", ha="right",
            va="top")
    ax.set_xticks([0, T1, 0.05, 0.1, T] if T > 0.11 else [0, T1, T])
    ax.set_xticklabels(["0", "t₁", "0.05", "0.1", "t₁ + t₂"] if T > 0.11 else
                       ["0", "t₁", "t₁ + t₂"])
    ax.set_xlim(-0.04 * T, 1.06 * T)
    ax.set_xlabel("t − t₀ [s]  (t₀: the collision at d = L_min)")
    ax.set_ylabel("velocity [m/s]")
    ax.set_title(f"(a) one velocity cycle of regime II, the limit cycle at F = {F:g} N, "
                 f"μ = {mu:g}", fontsize=10.5)
    ax.legend(loc="upper left")

    bx.plot(tt, cd[i0:ie + 1], "k:", lw=2.0)
    bx.plot([0, T1, T], [c0, c1, c_end], "o", ms=5, mfc="white", mec="k")
    bx.axvline(T1, color="0.6", lw=0.8, ls="--")
    bx.annotate(f"ċ0 = {num(c0, 3)}", xy=(0, c0), xytext=(6, -4), textcoords="offset points",
                va="top")
    bx.annotate(f"ċ1 = {num(c1, 3)} = {num(c1 / c0, 3)} ċ0", xy=(T1, c1), xytext=(8, -2),
                textcoords="offset points", va="top")
    bx.text(0.8 * T1, c0 + 0.6 * cdd1 * T1, f"c̈₁ = {num(cdd1, 2)} m/s² (= −μg)", ha="left",
            va="bottom")
    bx.text(T, c1 + 0.1 * (c0 - c1), f"c̈₂ = {num(cdd2, 3)} m/s²\n(= μg(M − m)/(M + m))",
            ha="right", va="top")
    bx.set_xticks(ax.get_xticks())
    bx.set_xticklabels([tl.get_text() for tl in ax.get_xticklabels()])
    bx.set_xlim(ax.get_xlim())
    lo, hi = min(c1, c0), max(c1, c0)
    bx.set_ylim(lo - 0.35 * (hi - lo), hi + 0.15 * (hi - lo))
    bx.set_xlabel("t − t₀ [s]")
    bx.set_ylabel("CoM velocity ċ [m/s]")
    bx.set_title(f"(b) the CoM: t₁ = {T1 * 1e3:.1f} ms, t₂ = {T2 * 1e3:.1f} ms, "
                 f"v_ss = {v_cycle:.3f} m/s", fontsize=10.5)
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
