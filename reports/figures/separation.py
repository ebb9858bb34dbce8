#!/usr/bin/python3
"""Thesis §2.4.1: the 'puzzling separation' between exact and numerical v_ss curves.

Inputs: DATA/ch2_inchworm/separation.csv — the event-driven simulation ("analytic") stopped when
two consecutive estimates differ by less than rtol (stop = difference, rtol ∈ 1e-4, 1e-5, 1e-6),
the estimate being either the running mean over the whole run from rest (estimator = running,
the thesis' protocol as we read it) or the last cycle's average (estimator = cycle), plus the
exact closed form; and DATA/ch2_inchworm/convergence.csv — cycle by cycle, both estimates and
their errors for (F, μ) = (45 N, 1) and (73.575 N, 0.05).

Hypothesis under test: the running mean from rest converges like 1/N, its consecutive
differences like 1/N², so a stop at threshold τ leaves a gap ~ √τ (≈ 1e-2 at τ = 1e-4) that
shrinks as τ is tightened; the last-cycle average converges geometrically and its gap is ~ τ.
Output: OUT/separation.png, OUT/values/separation.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "separation"


def tkey(tau: float) -> str:
    return f"{tau:.0e}"


def case_key(F: float, mu: float) -> str:
    return f"F{F:g}_mu{mu:g}"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "separation.csv",
                     c.SWEEP_COLUMNS + ["rtol", "stop", "estimator", "last_difference", "strokes"])
    cv = c.read_table(args.data, "convergence.csv",
                      ["mu", "F", "cycle", "cycle_average", "running_mean", "exact", "err_cycle",
                       "err_running"])

    ex = (t["method"] == "exact") & (t["converged"] == 1)
    if not np.any(ex):
        c.fail(f"{t.path}: no exact rows")
    exact = {(round(float(mu), 12), round(float(F), 9)): float(v)
             for mu, F, v in zip(t["mu"][ex], t["F"][ex], t["v_ss"][ex])}
    sim = (t["method"] == "analytic") & (t["stop"] == "difference")
    if not np.any(sim):
        c.fail(f"{t.path}: no analytic rows with stop = difference")
    est_all = t.str("estimator")
    values: dict = {}
    protocols = {}
    for est in ("running", "cycle"):
        for tau in sorted({float(v) for v in t["rtol"][sim & (est_all == est)]}, reverse=True):
            s = sim & (est_all == est) & np.isclose(t["rtol"], tau, rtol=1e-9, atol=0)
            keys = [(round(float(mu), 12), round(float(F), 9)) for mu, F in zip(t["mu"][s], t["F"][s])]
            have = np.array([k in exact for k in keys])
            ref = np.array([exact.get(k, np.nan) for k in keys])
            gap = t["v_ss"][s] / ref - 1
            conv = t["converged"][s] == 1
            use = have & conv
            protocols[(est, tau)] = {"F": t["F"][s][use], "mu": t["mu"][s][use], "gap": gap[use],
                                     "v": t["v_ss"][s][use]}
            k = f"{est}_{tkey(tau)}"
            values[f"max_gap_{k}"] = float(np.max(np.abs(gap[use]))) if np.any(use) else None
            values[f"median_gap_{k}"] = float(np.median(np.abs(gap[use]))) if np.any(use) else None
            values[f"mean_signed_gap_{k}"] = float(np.mean(gap[use])) if np.any(use) else None
            values[f"converged_fraction_{k}"] = float(np.mean(conv))
            values[f"max_strokes_{k}"] = int(np.max(t["strokes"][s]))
            values[f"median_strokes_{k}"] = float(np.median(t["strokes"][s]))
            for mu in sorted({round(float(v), 12) for v in t["mu"][s]}):
                sm = use & np.isclose(t["mu"][s], mu)
                values[f"max_gap_{k}_mu{mu:g}"] = (float(np.max(np.abs(gap[sm])))
                                                   if np.any(sm) else None)
            if est == "running" and np.isclose(tau, 1e-4):
                ld = t["last_difference"][s][conv]
                values["thesis_protocol_max_last_difference"] = float(np.max(ld)) if ld.size else None

    # Our stopping rule (stop = estimate: estimated remaining error of the cycle averages).
    ours = (t["method"] == "analytic") & (t.str("stop") == "estimate")
    ours_pts = {}
    for tau in sorted({float(v) for v in t["rtol"][ours]}, reverse=True):
        s = ours & np.isclose(t["rtol"], tau, rtol=1e-9, atol=0) & (t["converged"] == 1)
        keys = [(round(float(mu), 12), round(float(F), 9)) for mu, F in zip(t["mu"][s], t["F"][s])]
        ref = np.array([exact.get(k, np.nan) for k in keys])
        gap = np.abs(t["v_ss"][s] / ref - 1)
        ok = np.isfinite(gap)
        ours_pts[tau] = (t["F"][s][ok], gap[ok])
        values[f"max_gap_estimate_{tkey(tau)}"] = float(gap[ok].max()) if np.any(ok) else None
        values[f"estimate_within_target_{tkey(tau)}"] = (bool(np.all(gap[ok] <= tau))
                                                         if np.any(ok) else None)

    def taus(est):
        return sorted([tau for (e, tau) in protocols if e == est], reverse=True)

    for est in ("running", "cycle"):
        ts = taus(est)
        gaps = [values[f"max_gap_{est}_{tkey(tau)}"] for tau in ts]
        meds = [values[f"median_gap_{est}_{tkey(tau)}"] for tau in ts]
        values[f"{est}_gap_shrinks"] = bool(len(gaps) >= 2 and all(
            g is not None and h is not None and h < g for g, h in zip(gaps, gaps[1:])))
        # exponent p in gap ∝ τ^p (median gaps over all points)
        ok = [(tau, m) for tau, m in zip(ts, meds) if m is not None and m > 0]
        values[f"gap_exponent_{est}"] = (float(np.polyfit(np.log([o[0] for o in ok]),
                                                          np.log([o[1] for o in ok]), 1)[0])
                                         if len(ok) >= 2 else None)
    g_r = values.get("max_gap_running_1e-04")
    g_c = values.get("max_gap_cycle_1e-04")
    values["gap_ratio_running_over_cycle_1e-04"] = (g_r / g_c if g_r is not None and g_c else None)

    # ---- convergence, cycle by cycle
    cases = sorted({(round(float(F), 9), round(float(mu), 12)) for F, mu in zip(cv["F"], cv["mu"])})
    conv_curves = {}
    for F, mu in cases:
        s = np.isclose(cv["F"], F) & np.isclose(cv["mu"], mu)
        o = np.argsort(cv["cycle"][s])
        cyc = cv["cycle"][s][o]
        n = cyc - cyc.min() + 1  # cycles completed (the CSV may count from 0 or from 1)
        ec, er = cv["err_cycle"][s][o], cv["err_running"][s][o]
        conv_curves[(F, mu)] = (n, ec, er)
        key = case_key(F, mu)
        # cycle average: geometric, log(err) linear in N while above round-off
        ok = (ec > 1e-13) & (n >= 3)
        lam = float(np.exp(np.polyfit(n[ok], np.log(ec[ok]), 1)[0])) if np.sum(ok) >= 3 else None
        values[f"contraction_{key}"] = lam
        # running mean: power law over the second half of the run
        ok = (er > 0) & (n >= max(3, n.max() / 2))
        slope = float(np.polyfit(np.log(n[ok]), np.log(er[ok]), 1)[0]) if np.sum(ok) >= 3 else None
        values[f"running_slope_{key}"] = slope
        values[f"cycles_recorded_{key}"] = int(n.max())
        values[f"final_err_running_{key}"] = float(er[-1])
        values[f"final_err_cycle_{key}"] = float(ec[-1])
        for tol in (1e-4, 1e-6):
            for nm, e in (("cycle", ec), ("running", er)):
                below = np.flatnonzero(e < tol)
                # first cycle after which the error stays below tol
                stays = None
                if below.size and e[-1] < tol:
                    above = np.flatnonzero(e >= tol)
                    stays = int(n[above[-1] + 1]) if above.size else int(n[0])
                values[f"cycles_to_{tkey(tol)}_{nm}_{key}"] = stays

    # ---- figure
    from matplotlib.lines import Line2D

    fig, axs = plt.subplots(2, 2, figsize=(8.4, 10.2))
    ax = axs[0, 0]
    mus = sorted({round(float(v), 12) for v in t["mu"][ex]}, reverse=True)
    for i, mu in enumerate(mus):
        color = "k" if i == 0 else "0.55"
        se = ex & np.isclose(t["mu"], mu)
        o = np.argsort(t["F"][se])
        ax.plot(t["F"][se][o], t["v_ss"][se][o], "-", color=color, lw=1.2,
                label=f"exact μ = {mu:g}")
        p = protocols.get(("running", 1e-4))
        if p is not None:
            sm = np.isclose(p["mu"], mu)
            ax.plot(p["F"][sm], p["v"][sm], "o", mfc="none", color=color, ms=4,
                    label=f"running mean, stop 1e-4, μ = {mu:g}")
    ax.set_xlabel("F [N]")
    ax.set_ylabel("v_ss [m/s]")
    ax.set_title("(a) thesis protocol vs exact (cf. Fig. 2.3)")
    ax.legend(loc="upper left")
    # colour: the stop threshold; marker: μ (filled μ = 1, hollow μ = 0.2); no red, which marks
    # measured data in the report
    colors = {1e-4: "tab:purple", 1e-5: "tab:blue", 1e-6: "tab:green"}
    for ax, est, title in ((axs[0, 1], "running", "(b) running mean from rest"),
                           (axs[1, 0], "cycle", "(c) last-cycle average")):
        for tau in taus(est):
            p = protocols[(est, tau)]
            for i, mu in enumerate(mus):
                sm = np.isclose(p["mu"], mu)
                ax.semilogy(p["F"][sm], np.maximum(np.abs(p["gap"][sm]), 1e-17),
                            "o" if i == 0 else "s", ms=4, color=colors.get(tau, "C0"),
                            mfc=None if i == 0 else "none")
            ax.axhline(tau, color=colors.get(tau, "C0"), lw=0.8, ls=":")
        if est == "cycle":
            for tau, (Fo, go) in ours_pts.items():
                ax.semilogy(Fo, np.maximum(go, 1e-17), "+", ms=5, color=colors.get(tau, "C0"),
                            alpha=0.7)
        ax.set_xlabel("F [N]")
        ax.set_ylabel("|v − exact| / exact")
        ax.set_title(title)
        if est == "running":
            lo, hi = ax.get_ylim()
            ax.set_ylim(lo / 10, hi)  # room for the legend below the points
        stops = [Line2D([], [], color=colors[tau], ls=":", marker="o", ms=4,
                        label=f"stop {tau:.0e}") for tau in taus(est) if tau in colors]
        marks = [Line2D([], [], color="0.3", ls="", marker="o" if i == 0 else "s", ms=4,
                        mfc=None if i == 0 else "none", label=f"thesis rule, μ = {mu:g}")
                 for i, mu in enumerate(mus)]
        if est == "cycle":
            marks.append(Line2D([], [], color="0.3", ls="", marker="+", ms=5,
                                label="ours: estimated-error stop"))
        # one legend: thresholds in the first column, markers in the second; (c) is full of
        # points, so its legend goes under the panel
        where = (dict(loc="lower center") if est == "running" else
                 dict(loc="upper center", bbox_to_anchor=(0.5, -0.13)))
        ax.legend(handles=stops + marks, ncol=2, **where)
    ax = axs[1, 1]
    for j, ((F, mu), (n, ec, er)) in enumerate(conv_curves.items()):
        col = f"C{j}"
        ax.loglog(n, np.maximum(er, 1e-17), "-", color=col, lw=1.4,
                  label=f"running mean, F = {F:g} N, μ = {mu:g}")
        ax.loglog(n, np.maximum(ec, 1e-17), "--", color=col, lw=1.2,
                  label=f"last cycle, F = {F:g} N, μ = {mu:g}")
    nn = np.array([1.0, max(n.max() for n, _, _ in conv_curves.values())])
    e0 = max(er[0] for _, _, er in conv_curves.values())
    ax.loglog(nn, e0 / nn, "k:", lw=0.8, label="∝ 1/N")
    ax.set_ylim(1e-16, 2)
    ax.set_xlabel("cycles N")
    ax.set_ylabel("relative error vs exact")
    ax.set_title("(d) convergence from rest")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13))
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
