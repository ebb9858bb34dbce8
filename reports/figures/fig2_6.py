#!/usr/bin/python3
"""Thesis Fig. 2.6: positions of the two end masses and Δm over four cycles, instant swap vs dm.

Input: DATA/ch2_dm_swap/fig2_6_F{12,20}_{instant,a1,a5,a10}.csv (μ = 1, from rest at
x − y = L_min, four cycles, exact event-driven integration). Output: OUT/fig2_6.png,
OUT/values/fig2_6.json.

The trace's labels follow the load: y is the end mass carrying Δm, x the other, and the two
swap at every arrival of Δm (at every collision for the instant model). Here each end mass is
followed through the relabelling, so it is one continuous curve: dashed while it is m (x),
solid while it carries or is losing Δm (y, "M"); Δm (z) dotted.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig2_6"
STUDY = "ch2_dm_swap"
FORCES = (12, 20)
CONDITIONS = ("instant", "a1", "a5", "a10")
LABEL = {"instant": "instant swap", "a1": "α = 1", "a5": "α = 5", "a10": "α = 10"}
COLUMNS = ["t", "x", "y", "z", "com", "phase", "slide_y", "side", "event"]


def read_trace(data, F: int, cond: str) -> c.Table:
    path = c.study_file(data, f"fig2_6_F{F}_{cond}.csv", STUDY)
    t = c.Table(path, COLUMNS)
    if t.n < 10:
        c.fail(f"{path}: only {t.n} rows")
    return t


def track_ends(tr: c.Table) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Positions of the two end masses A (x at the start) and B, followed through the swaps of
    the labels, and whether A is y (the load's end) at each row. At every *_after row the labels
    may have swapped: keep each end where it was a row before (positions are continuous)."""
    x, y = tr["x"], tr["y"]
    ev = tr.str("event")
    a_is_y = np.zeros(tr.n, bool)
    flipped = False
    for i in range(1, tr.n):
        if ev[i].endswith("_after"):
            prev_a = y[i - 1] if flipped else x[i - 1]
            flipped = bool(abs(y[i] - prev_a) < abs(x[i] - prev_a))
        a_is_y[i] = flipped
    A = np.where(a_is_y, y, x)
    B = np.where(a_is_y, x, y)
    return A, B, a_is_y, ~a_is_y


def cycle_starts(tr: c.Table, cond: str) -> list[int]:
    """Rows where a cycle starts: rest at L_min, then the end of each swap after a contraction
    (the next stroke is an extension, side +1)."""
    ev = tr.str("event")
    end = "collision_after" if cond == "instant" else "arrival_after"
    side = tr["side"]
    return [0] + [i for i in range(tr.n) if ev[i] == end and side[i] > 0]


def swaps(tr: c.Table, A: np.ndarray, B: np.ndarray) -> list[dict]:
    """The dm model's swaps: from a stroke's collision_after to the arrival_before of Δm."""
    ev = tr.str("event")
    t, phase, slide = tr["t"], tr["phase"], tr["slide_y"]
    body = 0.5 * (A + B)
    out = []
    starts = [i for i in range(tr.n) if ev[i] == "collision_after" and phase[i] == 1]
    for i0 in starts:
        ends = [j for j in range(i0 + 1, tr.n) if ev[j] == "arrival_before"]
        if not ends:
            continue
        i1 = ends[0]
        # time stuck: the body is at rest from a body_stops row whose next mode is "stuck" (the
        # rows after it within the swap have slide_y = 0) until the arrival
        stuck = 0.0
        for j in range(i0, i1):
            if slide[j + 1] == 0 and t[j + 1] > t[j]:
                stuck += t[j + 1] - t[j]
        stops = [j for j in range(i0, i1 + 1) if ev[j] == "body_stops"]
        dur = t[i1] - t[i0]
        disp = body[i1] - body[i0]
        lo = float(np.min(body[i0:i1 + 1] - body[i0]))
        out.append({
            "t_start": t[i0], "duration": dur, "side": int(tr["side"][i0]),
            "kind": "after extension" if tr["side"][i0] > 0 else "after contraction",
            "body_displacement": disp, "body_min_displacement": lo,
            "body_stopped": bool(stops), "stuck_fraction": stuck / dur if dur > 0 else 0.0,
        })
    return out


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    traces = {(F, k): read_trace(args.data, F, k) for F in FORCES for k in CONDITIONS}

    values: dict = {"mu": 1.0, "forces": list(FORCES), "conditions": list(CONDITIONS)}
    derived = {}
    for (F, k), tr in traces.items():
        A, B, a_is_y, b_is_y = track_ends(tr)
        t, com = tr["t"], tr["com"]
        st = cycle_starts(tr, k)
        if len(st) < 4:
            c.fail(f"{tr.path}: expected at least three complete cycles, found {len(st) - 1}")
        per = np.diff(t[st])
        speed = np.diff(com[st]) / per
        d = np.abs(np.diff(speed))
        # a limit cycle: the cycle averages settle, their changes shrink and end below 1 %
        shrinking = bool(np.all(d[1:] <= d[:-1] * (1 + 1e-9) + 1e-12))
        last_change = float(d[-1] / abs(speed[-1]))
        sw = swaps(tr, A, B) if k != "instant" else []
        key = f"F{F}_{k}"
        derived[(F, k)] = {"A": A, "B": B, "a_is_y": a_is_y, "b_is_y": b_is_y, "starts": st,
                           "swaps": sw}
        values[f"{key}_cycle_periods"] = per
        values[f"{key}_cycle_mean_speeds"] = speed
        values[f"{key}_period_last"] = per[-1]
        values[f"{key}_speed_last"] = speed[-1]
        values[f"{key}_last_cycle_change"] = last_change
        values[f"{key}_changes_shrink"] = shrinking
        if sw:
            # the swaps of the last complete cycle (the limit cycle)
            t_last = t[st[-2]]
            last = [s for s in sw if s["t_start"] >= t_last - 1e-12]
            for s in last:
                tag = "ext" if s["side"] > 0 else "con"
                values[f"{key}_{tag}_swap_body_displacement"] = s["body_displacement"]
                values[f"{key}_{tag}_swap_body_min_displacement"] = s["body_min_displacement"]
                values[f"{key}_{tag}_swap_stuck_fraction"] = s["stuck_fraction"]
                values[f"{key}_{tag}_swap_duration"] = s["duration"]
                values[f"{key}_{tag}_swap_body_stopped"] = s["body_stopped"]
            values[f"{key}_swaps"] = [{kk: vv for kk, vv in s.items()} for s in sw]

    # --- the claims
    lim = [values[f"F{F}_{k}_changes_shrink"] and values[f"F{F}_{k}_last_cycle_change"] < 0.01
           for F in FORCES for k in CONDITIONS]
    values["limit_cycle_fraction"] = float(np.mean(lim))
    values["last_cycle_change_max"] = max(values[f"F{F}_{k}_last_cycle_change"]
                                          for F in FORCES for k in CONDITIONS)
    spreads, spreads_no_stop, period_spreads = [], [], []
    for F in FORCES:
        v = np.array([values[f"F{F}_{k}_speed_last"] for k in ("a1", "a5", "a10")])
        p = np.array([values[f"F{F}_{k}_period_last"] for k in ("a1", "a5", "a10")])
        spreads.append(float(np.ptp(v) / np.mean(v)))
        period_spreads.append(float(np.ptp(p) / np.mean(p)))
        v2 = np.array([values[f"F{F}_{k}_speed_last"] for k in ("a5", "a10")])
        spreads_no_stop.append(float(np.ptp(v2) / np.mean(v2)))
        vi = values[f"F{F}_instant_speed_last"]
        values[f"F{F}_dm_vs_instant_speed_rel"] = list((v - vi) / vi)
        values[f"F{F}_alpha_speed_spread"] = spreads[-1]
        values[f"F{F}_alpha_period_spread"] = period_spreads[-1]
    values["alpha_speed_spread_max"] = max(spreads)
    values["alpha_period_spread_max"] = max(period_spreads)
    values["alpha5_10_speed_spread_max"] = max(spreads_no_stop)

    a1_stuck = [values[f"F{F}_a1_ext_swap_stuck_fraction"] for F in FORCES]
    a1_disp = [values[f"F{F}_a1_ext_swap_body_displacement"] for F in FORCES]
    a1_min = [values[f"F{F}_a1_ext_swap_body_min_displacement"] for F in FORCES]
    values["alpha1_ext_swap_stuck_fraction_min"] = min(a1_stuck)
    values["alpha1_ext_swap_body_displacement_max_mm"] = 1e3 * max(a1_disp)
    # keeps its position: it coasts to a stop and then stands still for most of the swap, never
    # moving backward
    values["alpha1_holds"] = bool(min(a1_stuck) >= 0.5 and min(a1_min) >= -1e-12 and
                                  all(values[f"F{F}_a1_ext_swap_body_stopped"] for F in FORCES))
    back = [values[f"F{F}_{k}_ext_swap_body_displacement"] for F in FORCES for k in ("a5", "a10")]
    back_stuck = [values[f"F{F}_{k}_ext_swap_stuck_fraction"] for F in FORCES
                  for k in ("a5", "a10")]
    values["alpha5_10_ext_swap_body_displacement_mm"] = [1e3 * b for b in back]
    values["alpha5_10_ext_swap_body_displacement_max_mm"] = 1e3 * max(back)
    values["alpha5_10_backward"] = bool(max(back) < 0 and max(back_stuck) == 0.0)
    # the swap after a contraction: Δm travels only L_min backward, the reaction pushes the body
    # forward; does it ever stop?
    values["con_swap_body_stopped_any"] = any(
        values.get(f"F{F}_{k}_con_swap_body_stopped", False) for F in FORCES
        for k in ("a1", "a5", "a10"))
    # order: F = 12 N α = 1, 5, 10, then F = 20 N
    values["con_swap_body_displacement_mm"] = [
        1e3 * values[f"F{F}_{k}_con_swap_body_displacement"]
        for F in FORCES for k in ("a1", "a5", "a10")]

    # --- the figure: 2 rows (F) x 4 columns (condition), every condition in every panel,
    # the column's one highlighted (the thesis' layout); below, per F, the m–m body through the
    # last swap after an extension stroke, all four conditions in one panel, large enough to
    # read the thesis' point (α = 1 holds, α = 5, 10 move backward).
    fig = plt.figure(figsize=(13.5, 12.4))
    gs = fig.add_gridspec(4, 4, height_ratios=[1, 1, 0.16, 0.9])
    legend_ax = fig.add_subplot(gs[2, :])
    legend_ax.axis("off")
    axes = np.empty((2, 4), object)
    for r in range(2):
        for col in range(4):
            axes[r, col] = fig.add_subplot(gs[r, col], sharex=axes[r, 0] if col else None,
                                           sharey=axes[r, 0] if col else None)
            if col:
                axes[r, col].tick_params(labelleft=False)
    body_axes = [fig.add_subplot(gs[3, 0:2]), fig.add_subplot(gs[3, 2:4])]
    body_style = {"instant": dict(color="0.55", ls="-", lw=1.6),
                  "a1": dict(color="k", ls="-", lw=1.6),
                  "a5": dict(color="k", ls="--", lw=1.4),
                  "a10": dict(color="k", ls="-.", lw=1.4)}
    for r, F in enumerate(FORCES):
        t_end = max(traces[(F, k)]["t"][-1] for k in CONDITIONS)
        lo = min(min(derived[(F, k)]["A"].min(), derived[(F, k)]["B"].min()) for k in CONDITIONS)
        hi_pos = max(max(derived[(F, k)]["A"].max(), derived[(F, k)]["B"].max())
                     for k in CONDITIONS)
        for col, hk in enumerate(CONDITIONS):
            ax = axes[r, col]
            order = [k for k in CONDITIONS if k != hk] + [hk]
            for k in order:
                tr, dv = traces[(F, k)], derived[(F, k)]
                hi = k == hk
                t, z = tr["t"], tr["z"]
                color = "k" if hi else "0.72"
                lw = 1.15 if hi else 0.7
                zorder = 3 if hi else 1
                for pos, is_y in ((dv["A"], dv["a_is_y"]), (dv["B"], dv["b_is_y"])):
                    for style, mask in (("--", ~is_y), ("-", is_y)):
                        # the segments where the end has this role, joined at the switch rows
                        seg = np.where(mask, pos, np.nan)
                        ax.plot(t, seg, style, color=color, lw=lw, zorder=zorder)
                ax.plot(t, z, ":", color=color, lw=lw + 0.5, zorder=zorder)
                if hi:
                    ev = tr.str("event")
                    at = np.isin(ev, ["collision_before", "arrival_before"])
                    ax.plot(t[at], z[at], "o", ms=3.6, mfc="white", mec="k", zorder=4)
                    bs = np.flatnonzero(ev == "body_stops")
                    sticks = np.array([tr["slide_y"][min(i + 1, tr.n - 1)] == 0 for i in bs],
                                      bool)
                    for pos in (dv["A"], dv["B"]):
                        ax.plot(t[bs[sticks]], pos[bs[sticks]], "v", ms=4.2, color="k", zorder=4)
                        ax.plot(t[bs[~sticks]], pos[bs[~sticks]], "v", ms=4.2, mfc="white",
                                mec="k", zorder=4)
            ax.set_xlim(0, t_end)
            ax.set_ylim(lo - 0.04 * (hi_pos - lo), hi_pos + 0.06 * (hi_pos - lo))
            ax.set_title(f"F = {F} N — {LABEL[hk]}")
            if r == 1:
                ax.set_xlabel("t [s] from rest at L_min")
            if col == 0:
                ax.set_ylabel(f"position [m], F = {F} N:\n"
                              + ("one mass moving" if F == 12 else "two masses moving"))
        # the m–m body (mean of the end masses) through the last swap after an extension,
        # every condition, relative to the collision that starts it
        bx = body_axes[r]
        for k in CONDITIONS:
            tr, dv = traces[(F, k)], derived[(F, k)]
            ev, t = tr.str("event"), tr["t"]
            ext = [i for i in range(tr.n) if ev[i] == "collision_after"
                   and tr["side"][i] > 0 and (k == "instant" or tr["phase"][i] == 1)]
            if k == "instant":
                ext = [i for i in range(tr.n) if ev[i] == "collision_after"
                       and tr["side"][i] < 0]
            i0 = ext[-1] if ext else 0
            body = 0.5 * (dv["A"] + dv["B"])
            w = (t >= t[i0] - 0.02) & (t <= t[i0] + 0.2)
            bx.plot(t[w] - t[i0], 1e3 * (body[w] - body[i0]), label=LABEL[k], **body_style[k])
        bx.axhline(0, color="0.5", lw=0.6)
        bx.axvline(0, color="0.5", lw=0.6)
        bx.set_xlim(-0.02, 0.2)
        bx.set_title(f"F = {F} N: the m–m body in the last swap after an extension stroke")
        bx.set_xlabel("t − t_collision at L_max [s]")
        bx.set_ylabel("m–m body (mean of the\nend masses) displacement [mm]")
        bx.legend(loc="upper left")
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], ls="--", color="k", label="end mass while m (x)"),
               Line2D([], [], ls="-", color="k", label="end mass while carrying Δm (M, y)"),
               Line2D([], [], ls=":", color="k", lw=1.6, label="Δm (z)"),
               Line2D([], [], ls="", marker="o", mfc="white", mec="k",
                      label="collision / Δm arrival"),
               Line2D([], [], ls="", marker="v", color="k", label="m–m body stops and sticks"),
               Line2D([], [], ls="", marker="v", mfc="white", mec="k",
                      label="m–m body stops and turns back"),
               Line2D([], [], ls="-", color="0.72", label="the other conditions")]
    legend_ax.legend(handles=handles, loc="center", ncol=4, frameon=False)
    fig.suptitle("Fig. 2.6 — instant swap vs moving Δm (dm model, F_Δm = αF), μ = 1, four cycles "
                 "from rest at L_min", fontsize=11.5)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
