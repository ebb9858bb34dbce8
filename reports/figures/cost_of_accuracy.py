#!/usr/bin/python3
"""Cost of accuracy: work-precision of every integrator, and the three error sources.

Inputs, DATA/cost_of_accuracy/ (studies/cost_of_accuracy/): reference.csv (the closed form of
each case), work_precision.csv (every event-locating method over rtol), fixed_step.csv (RK4
without event location over its step h), integration.csv (events at the exact times: the
integration error alone), event_location.csv (the guard-location tolerance event_tol swept at
tight rtol and target), stopping_rule.csv (the thesis' consecutive-difference rule against our
estimated remaining error, exact event-driven integration). Errors are |v_ss - closed form| /
closed form; times are the median CPU time of one solve over the spec's repeats, all measured in
one run on the machine named in the sidecars.

Outputs: OUT/cost_of_accuracy_{time,rhs,sources}.png (instant swap) and
OUT/cost_of_accuracy_{time,rhs,sources}_dm.png (moving Δm), OUT/cost_of_accuracy_body.html (the
page body, wrapped by build_report.py into cost_of_accuracy.html),
OUT/values/cost_of_accuracy.json.
"""
from __future__ import annotations

import sys

import html
import math
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "cost_of_accuracy"
STUDY = "cost_of_accuracy"
TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)
FLOOR = 1e-16  # drawn in place of an error of exactly zero
THESIS_TARGET = 1e-4  # the thesis' consecutive-difference threshold (§2.2.2)

# Every simulation method: label, colour, marker, line style.
METHODS = {
    "analytic": ("exact piecewise (analytic)", "k", "o", "-"),
    "cvode": ("CVODE Adams", "C0", "s", "-"),
    "cvode_bdf": ("CVODE BDF", "C9", "s", "--"),
    "odeint": ("odeint dopri5", "C2", "^", "-"),
    "odeint_rkf78": ("odeint rkf78", "C8", "^", "--"),
    "gsl": ("GSL rk8pd", "C4", "D", "-"),
    "gsl_rkf45": ("GSL rkf45", "C6", "D", "--"),
    "gsl_msadams": ("GSL msadams", "C1", "v", "-."),
    # grey, not red: red marks measured data in the report
    "fixed_rk4": ("fixed-step RK4, no event location", "0.45", "x", ":"),
}
LOCATED = [m for m in METHODS if m not in ("analytic", "fixed_rk4")]


def label(m: str) -> str:
    return METHODS[m][0]


def style(m: str) -> dict:
    _, color, marker, ls = METHODS[m]
    return {"color": color, "marker": marker, "ls": ls, "ms": 4.5, "lw": 1.2}


def read(data: Path, name: str, required: list[str]) -> c.Table:
    path = c.study_file(data, name, STUDY)
    t = c.Table(path, required)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    return t


# ---------------------------------------------------------------------------------------------
# Cases


def case_of(model, F, mu, alpha) -> tuple:
    a = float(alpha)
    return (str(model), round(float(F), 9), round(float(mu), 12), 0.0 if math.isnan(a) else a)


def case_keys(t: c.Table) -> list[tuple]:
    return [case_of(*row) for row in zip(t["model"], t["F"], t["mu"], t["alpha"])]


def case_id(k: tuple) -> str:
    model, F, mu, a = k
    return f"{model}_F{F:g}_mu{mu:g}" + (f"_a{a:g}" if model == "dm" else "")


def case_title(k: tuple, role: str) -> str:
    model, F, mu, a = k
    what = "instant swap" if model == "instant" else f"moving Δm, α = {a:g}"
    return f"{what}: F = {F:g} N, μ = {mu:g} ({role})"


def two_lines(title: str) -> str:
    """A case title for a small panel: the parameters, then the role."""
    return title.replace(" (", "\n(", 1)


def role_of(k: tuple, contraction: float) -> str:
    _, F, mu, _ = k
    eps = F / (mu * c.M * c.G) - 1.0
    if abs(eps) < 1e-5:
        return f"regime boundary: F = μMg(1 + {eps:.0e})"
    if contraction is not None and contraction > 0.9:
        return f"slow, λ = {contraction:.3f}/cycle"
    return "fast" if contraction is None else f"fast, λ = {contraction:.2g}/cycle"


# ---------------------------------------------------------------------------------------------
# Runs


class Runs:
    """The rows of one CSV with their case and their error against the reference."""

    def __init__(self, t: c.Table, ref: dict):
        self.t = t
        self.case = case_keys(t)
        self.method = t.str("method")
        self.ok = t["converged"] == 1
        refs = np.array([ref.get(k, np.nan) for k in self.case])
        self.err = np.abs(t["v_ss"] / refs - 1.0)

    def select(self, case: tuple, **eq) -> np.ndarray:
        s = np.array([k == case for k in self.case])
        for col, val in eq.items():
            col_values = self.t.str(col) if isinstance(val, str) else self.t[col]
            s &= ((col_values == val) if isinstance(val, str) else
                  np.isclose(col_values, val, rtol=1e-9, atol=0.0))
        return s


def knob(t: c.Table, s: np.ndarray, method: str) -> np.ndarray:
    return t["h"][s] if method == "fixed_rk4" else t["rtol"][s]


def curves(runs: Runs, case: tuple, method: str) -> dict | None:
    """One method's runs at one case, ordered from the loosest knob to the tightest."""
    s = runs.select(case, method=method)
    if not np.any(s):
        return None
    t = runs.t
    k = knob(t, s, method)
    o = np.argsort(-k)
    pick = lambda a: np.asarray(a)[o]  # noqa: E731
    return {
        "knob": pick(k), "err": pick(runs.err[s]), "cpu": pick(t["cpu_s"][s]),
        "wall": pick(t["wall_s"][s]), "rhs": pick(t["rhs_evals"][s]),
        "guard": pick(t["guard_evals"][s]), "events": pick(t["events"][s]),
        "strokes": pick(t["strokes"][s]), "ok": pick(runs.ok[s]),
        "message": pick(t.str("message")[s]),
    }


def cheapest(curve: dict | None, target: float) -> dict | None:
    """The converged run of least CPU time whose error is at most `target`."""
    if curve is None:
        return None
    good = curve["ok"] & (curve["err"] <= target)
    if not np.any(good):
        return None
    i = np.flatnonzero(good)[np.argmin(curve["cpu"][good])]
    return {k: (v[i] if isinstance(v, np.ndarray) else v) for k, v in curve.items()}


def best_error(curve: dict | None) -> float | None:
    if curve is None or not np.any(curve["ok"]):
        return None
    return float(np.min(curve["err"][curve["ok"]]))


def tkey(x: float) -> str:
    return f"{x:.0e}"


def ms(x) -> str:
    """CPU seconds as a readable time."""
    if x is None or not math.isfinite(float(x)):
        return "—"
    x = float(x)
    if x < 1e-3:
        return f"{x * 1e6:.3g} µs"
    if x < 1.0:
        return f"{x * 1e3:.3g} ms"
    return f"{x:.3g} s"


def ratio(a, b) -> float | None:
    return float(a) / float(b) if a is not None and b not in (None, 0) else None


def fx(r: float | None) -> str:
    if r is None:
        return "—"
    return f"{r:.2g}×" if r < 100 else f"{r:,.0f}×"


# ---------------------------------------------------------------------------------------------
# Figures


# Each figure holds one model's cases, two panels a row at the page's width (8.4 in, every text
# 9.5 pt or more), so a panel is as large as a figure of its own would be on a narrow page.
FIG_W = 8.4
PANEL_H = 3.5


def model_name(model: str) -> str:
    return "instant swap" if model == "instant" else "moving Δm (dm model)"


def panel_grid(plt, n: int, title: str):
    """Two columns; the legend takes the spare cell when n is odd, else a band under the grid.
    Returns the figure, the panels and the legend's place (an axis or None: under the grid)."""
    rows = int(math.ceil(n / 2))
    below = n % 2 == 0
    # shared axes: the cases' costs compare across panels
    fig, axs = plt.subplots(rows, 2, figsize=(FIG_W, PANEL_H * rows + (1.6 if below else 0) + 0.5),
                            squeeze=False, sharex=True, sharey=True)
    fig.suptitle(title, fontsize=11)
    axs = axs.ravel()
    for ax in axs:
        ax.xaxis.set_tick_params(labelbottom=True)
        ax.yaxis.set_tick_params(labelleft=True)
    spare = None if below else axs[n]
    if spare is not None:
        spare.axis("off")
    return fig, axs[:n], spare


def place_legend(fig, spare, handles_from: list, title: str | None = None) -> None:
    handles, labels = [], []
    for ax in handles_from:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    if spare is not None:
        spare.legend(handles, labels, loc="center", frameon=False, title=title)
        fig.tight_layout(rect=(0, 0, 1, 0.97))
    else:
        h_in = fig.get_size_inches()[1]
        fig.legend(handles, labels, loc="lower center", ncol=2, frameon=False, title=title)
        fig.tight_layout(rect=(0, 1.6 / h_in, 1, 0.97))


def work_precision_figure(plt, model: str, cases, titles, wp: Runs, fs: Runs, xkey: str,
                          out: Path, name: str, xlabel: str):
    fig, axs, spare = panel_grid(
        plt, len(cases), f"Work–precision, {model_name(model)}: error of v_ss vs "
        + ("CPU time" if xkey == "cpu" else "right-hand-side evaluations"))
    for ax, case in zip(axs, cases):
        for m in METHODS:
            cu = curves(fs if m == "fixed_rk4" else wp, case, m)
            if cu is None:
                continue
            x = cu[xkey].astype(float)
            hollow = False
            if xkey == "rhs" and m == "analytic":
                x = cu["events"].astype(float)  # no RHS at all: its events instead
                hollow = True
            ok = cu["ok"] & (x > 0)
            if not np.any(ok):
                continue
            st = style(m)
            ax.loglog(x[ok], np.maximum(cu["err"][ok], FLOOR), mfc="none" if hollow else None,
                      label=label(m) + (" (events; no RHS)" if hollow else ""), **st)
        for tg in TARGETS:
            ax.axhline(tg, color="0.6", ls=":", lw=0.8)
        ax.set_title(two_lines(titles[case].split(": ", 1)[1] if model == "instant"
                               else titles[case]), fontsize=10)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("|v_ss − exact| / exact")
        ax.set_ylim(1e-16, 10)
    place_legend(fig, spare, list(axs), title="method")
    c.save_figure(fig, out, name)


def sources_figure(plt, case, title, integ: Runs, loc: Runs, fs: Runs, stop: Runs, out: Path,
                   name: str):
    """The three error sources of one case, one panel each, stacked; legends right of them."""
    fig, axs = plt.subplots(3, 1, figsize=(FIG_W, 3.1 * 3 + 0.6))
    fig.suptitle(f"The three error sources, separated\n{title}", fontsize=11)
    right = dict(loc="center left", bbox_to_anchor=(1.02, 0.5), frameon=False)
    # (a) integration alone: events at the exact times, target 1e-13
    ax = axs[0]
    for m in LOCATED + ["fixed_rk4"]:
        cu = curves(integ, case, m)
        if cu is None or not np.any(cu["ok"]):
            continue
        ok = cu["ok"]
        ax.loglog(cu["knob"][ok], np.maximum(cu["err"][ok], FLOOR),
                  label=label(m) + (" (x: h [s])" if m == "fixed_rk4" else ""), **style(m))
    ax.set_xlabel("rtol (fixed-step RK4: h in s)")
    ax.set_title("(a) integration alone (exact event times)")
    ax.invert_xaxis()
    ax.legend(**right)
    # (b) event location: event_tol at rtol 1e-12, target 1e-13; fixed step against h
    ax = axs[1]
    for m in ("odeint", "gsl", "gsl_msadams", "cvode"):
        s = loc.select(case, method=m)
        if not np.any(s):
            continue
        tol = loc.t["event_tol"][s]
        o = np.argsort(-tol)
        e = np.maximum(loc.err[s][o], FLOOR)
        okm = loc.ok[s][o]
        st = style(m)
        ax.loglog(tol[o], e, label=label(m), **{**st, "marker": None})
        ax.loglog(tol[o][okm], e[okm], ls="none", marker=st["marker"], color=st["color"],
                  ms=4.5)
        ax.loglog(tol[o][~okm], e[~okm], ls="none", marker=st["marker"], color=st["color"],
                  mfc="none", ms=6.5)
    cu = curves(fs, case, "fixed_rk4")
    if cu is not None and np.any(cu["ok"]):
        ok = cu["ok"]
        ax.loglog(cu["knob"][ok], np.maximum(cu["err"][ok], FLOOR),
                  label=label("fixed_rk4") + " (x: h)", **style("fixed_rk4"))
    xs = np.array([1e-12, 1e-1])
    ax.loglog(xs, xs, color="0.6", lw=0.8, ls=":", label="error = τ (in s)")
    ax.set_xlabel("event time tolerance event_tol, or fixed step h [s]")
    ax.set_title("(b) event location alone (rtol 1e-12; hollow: stopped at the stroke budget, "
                 "short of 1e-13)")
    ax.invert_xaxis()
    ax.legend(**right)
    # (c) the stopping rule, exact integration
    ax = axs[2]
    for stop_rule, est, lab, color, mk in (
            ("difference", "running", "thesis: Δ of running mean ≤ target", "tab:purple", "o"),
            ("difference", "cycle", "thesis rule on the cycle average", "tab:orange", "s"),
            ("estimate", "cycle", "ours: estimated remaining error ≤ target", "tab:green", "^")):
        s = stop.select(case, stop=stop_rule, estimator=est)
        if not np.any(s):
            continue
        tg = stop.t["target"][s]
        o = np.argsort(-tg)
        e = np.maximum(stop.err[s][o], FLOOR)
        okm = stop.ok[s][o]
        ax.loglog(tg[o], e, color=color, lw=1.2, label=lab)
        ax.loglog(tg[o][okm], e[okm], ls="none", marker=mk, color=color, ms=4.5)
        ax.loglog(tg[o][~okm], e[~okm], ls="none", marker=mk, color=color, mfc="none", ms=6.5)
    xs = np.array([1e-12, 1e-2])
    ax.loglog(xs, xs, color="0.6", lw=0.8, ls=":", label="error = target")
    ax.axvline(THESIS_TARGET, color="0.4", lw=0.9, ls="--", label="the thesis' 1e-4")
    ax.set_xlabel("stop target")
    ax.set_title("(c) stopping rule alone (exact integration; hollow: at the stroke budget)")
    ax.invert_xaxis()
    ax.legend(**right)
    for a in axs:
        a.set_ylim(1e-16, 10)
        a.set_ylabel("|v_ss − exact| / exact")
    # the same axes width in all three panels, the legends in the right 45 %
    fig.subplots_adjust(left=0.1, right=0.55, top=0.9, bottom=0.06, hspace=0.42)
    c.save_figure(fig, out, name)


# ---------------------------------------------------------------------------------------------
# Main


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    base = ["id", "mu", "F", "method", "v_ss", "converged", "model", "alpha", "rtol", "cpu_s",
            "wall_s", "rhs_evals", "guard_evals", "events", "strokes", "message", "target",
            "event_tol", "h"]
    ref_t = read(args.data, "reference.csv", base + ["contraction"])
    ok = (ref_t["converged"] == 1) & (ref_t.str("method") == "exact")
    if not np.any(ok):
        c.fail(f"{ref_t.path}: no converged closed-form rows")
    ref, lam = {}, {}
    cases = []
    for k, v, la, good in zip(case_keys(ref_t), ref_t["v_ss"], ref_t["contraction"], ok):
        if good and k not in ref:
            ref[k] = float(v)
            lam[k] = float(la) if math.isfinite(la) else None
            cases.append(k)
    roles = {k: role_of(k, lam[k]) for k in cases}
    titles = {k: case_title(k, roles[k]) for k in cases}
    wp = Runs(read(args.data, "work_precision.csv", base), ref)
    fs = Runs(read(args.data, "fixed_step.csv", base), ref)
    integ = Runs(read(args.data, "integration.csv", base + ["event_times"]), ref)
    loc = Runs(read(args.data, "event_location.csv", base), ref)
    stop = Runs(read(args.data, "stopping_rule.csv", base + ["stop", "estimator"]), ref)

    side = c.read_sidecar(wp.t.path) or {}
    prov = side.get("provenance", {}) if isinstance(side, dict) else {}
    machine = prov.get("machine", {}) if isinstance(prov, dict) else {}
    spec = side.get("spec", {}) if isinstance(side, dict) else {}
    repeats = (spec.get("params", {}) or {}).get("repeats") if isinstance(spec, dict) else None
    if side.get("quick"):
        repeats = 1
    values: dict = {
        "cases": [case_id(k) for k in cases],
        "case_titles": {case_id(k): titles[k] for k in cases},
        "machine_cpu": machine.get("cpu"), "machine_logical_cores": machine.get("logical_cores"),
        "machine_os": machine.get("os"), "threads": side.get("threads"),
        "machine_load_average": machine.get("load_average_1min"),
        "repeats": repeats, "date": side.get("date"), "compiler": prov.get("compiler"),
        "libraries": prov.get("libraries"), "quick": bool(side.get("quick")),
    }

    # ---- the knobs as run
    rtols = wp.t["rtol"][wp.method != "analytic"]
    values.update({"rtol_max": float(np.max(rtols)), "rtol_min": float(np.min(rtols)),
                   "rtol_count": len(set(np.round(np.log10(rtols), 6))),
                   "h_max": float(np.max(fs.t["h"])), "h_min": float(np.min(fs.t["h"])),
                   "h_count": len(set(np.round(np.log10(fs.t["h"]), 6))),
                   "fixed_target": float(np.median(fs.t["target"]))})
    fs_side = c.read_sidecar(fs.t.path) or {}
    fs_spec = fs_side.get("spec", {}) if isinstance(fs_side, dict) else {}
    max_steps = (fs_spec.get("params", {}) or {}).get("max_steps")
    if fs_side.get("quick"):
        max_steps = ((fs_spec.get("quick", {}) or {}).get("params", {}) or {}).get("max_steps",
                                                                                 max_steps)
    values["fixed_max_steps"] = max_steps

    # ---- per case and method: cost to reach each target, best error
    cost: dict = {}
    for case in cases:
        cid = case_id(case)
        values[f"exact_{cid}"] = ref[case]
        values[f"contraction_{cid}"] = lam[case]
        for m in METHODS:
            cu = curves(fs if m == "fixed_rk4" else wp, case, m)
            values[f"best_error_{m}_{cid}"] = best_error(cu)
            if cu is not None:
                values[f"failed_runs_{m}_{cid}"] = int(np.count_nonzero(~cu["ok"]))
            for tg in TARGETS:
                ch = cheapest(cu, tg)
                cost[(case, m, tg)] = ch
                k = f"{m}_{cid}_{tkey(tg)}"
                values[f"cpu_to_{k}"] = float(ch["cpu"]) if ch else None
                values[f"knob_to_{k}"] = float(ch["knob"]) if ch else None
                values[f"rhs_to_{k}"] = float(ch["rhs"]) if ch else None

    # ---- the cheapest-method table
    rows_html = []
    cheapest_counts: dict = {m: 0 for m in METHODS}
    numeric_counts: dict = {m: 0 for m in METHODS}
    for case in cases:
        cid = case_id(case)
        rows_html.append(f"<tr class='group'><td colspan='8'>{html.escape(titles[case])}; "
                         f"closed form v_ss = {ref[case]:.10g} m/s</td></tr>")
        for tg in TARGETS:
            reach = [(m, cost[(case, m, tg)]) for m in METHODS if cost[(case, m, tg)]]
            if not reach:
                rows_html.append(f"<tr><td>{tg:.0e}</td><td colspan='7' class='bad'>no method "
                                 "reached it</td></tr>")
                continue
            reach.sort(key=lambda mc: float(mc[1]["cpu"]))
            best_m, best = reach[0]
            cheapest_counts[best_m] += 1
            num = [(m, r) for m, r in reach if m in LOCATED]
            second = reach[1] if len(reach) > 1 else None
            k = f"{cid}_{tkey(tg)}"
            values[f"cheapest_{k}"] = best_m
            values[f"cheapest_cpu_{k}"] = float(best["cpu"])
            values[f"runner_up_ratio_{k}"] = (ratio(second[1]["cpu"], best["cpu"]) if second
                                              else None)
            num_cell = "<td colspan='3' class='muted'>none reached it</td>"
            if num:
                nm, nr = num[0]
                numeric_counts[nm] += 1
                values[f"cheapest_numeric_{k}"] = nm
                values[f"cheapest_numeric_cpu_{k}"] = float(nr["cpu"])
                values[f"cheapest_numeric_over_analytic_{k}"] = (
                    ratio(nr["cpu"], cost[(case, "analytic", tg)]["cpu"])
                    if cost[(case, "analytic", tg)] else None)
                over = values[f"cheapest_numeric_over_analytic_{k}"]
                over_cell = (fx(over) if over is not None else
                             "exact piecewise did not reach it (best "
                             f"{c.fmt(values[f'best_error_analytic_{cid}'], 2)})")
                num_cell = (f"<td>{html.escape(label(nm))} (rtol {nr['knob']:.0e})</td>"
                            f"<td>{ms(nr['cpu'])}</td><td>{over_cell}</td>")
            fixed = cost[(case, "fixed_rk4", tg)]
            if fixed:
                values[f"fixed_over_cheapest_{k}"] = ratio(fixed["cpu"], best["cpu"])
                fixed_cell = (f"<td>h = {fixed['knob']:.0e} s: {ms(fixed['cpu'])} "
                              f"({fx(values[f'fixed_over_cheapest_{k}'])})</td>")
            else:
                be = values[f"best_error_fixed_rk4_{cid}"]
                fixed_cell = (f"<td class='bad'>not reached (best {c.fmt(be, 2)})</td>")
            knob_txt = "" if best_m == "analytic" else (
                f" (h = {best['knob']:.0e} s)" if best_m == "fixed_rk4" else
                f" (rtol {best['knob']:.0e})")
            rows_html.append(
                f"<tr><td>{tg:.0e}</td><td><b>{html.escape(label(best_m))}</b>{knob_txt}</td>"
                f"<td>{ms(best['cpu'])}</td><td>{c.fmt(best['err'], 2)}</td>{num_cell}"
                f"{fixed_cell}</tr>")
    values["cheapest_counts"] = cheapest_counts
    values["cheapest_numeric_counts"] = numeric_counts
    cheap_table = (
        "<table class='data'><thead><tr><th>target error</th><th>cheapest method</th>"
        "<th>CPU per v_ss</th><th>its error</th><th>cheapest event-locating integrator</th>"
        "<th>CPU</th><th>÷ exact piecewise</th><th>fixed-step RK4 (÷ cheapest)</th></tr>"
        "</thead><tbody>" + "\n".join(rows_html) + "</tbody></table>")

    # ---- CPU ratios to the exact piecewise method, same run, at 1e-6
    ratio_rows = []
    for m in METHODS:
        cells = []
        for case in cases:
            a = cost[(case, "analytic", 1e-6)]
            r = cost[(case, m, 1e-6)]
            q = ratio(r["cpu"], a["cpu"]) if (a and r) else None
            values[f"cpu_ratio_1e-06_{m}_{case_id(case)}"] = q
            cells.append(f"<td>{fx(q) if q is not None else '<span class=muted>not reached</span>'}"
                         "</td>")
        ratio_rows.append(f"<tr><td>{html.escape(label(m))}</td>{''.join(cells)}</tr>")
    head = "".join(f"<th>{html.escape(titles[k].split(' (')[0])}</th>" for k in cases)
    ratio_table = ("<table class='data'><thead><tr><th>method</th>" + head + "</tr></thead><tbody>"
                   + "\n".join(ratio_rows) + "</tbody></table>")

    # ---- error sources: numbers
    integ_rows = []
    integ_rtols = sorted({float(r) for r, mm in zip(integ.t["rtol"], integ.method)
                          if mm != "fixed_rk4"}, reverse=True)
    for m in LOCATED + ["fixed_rk4"]:
        cells = []
        for case in cases:
            cu = curves(integ, case, m)
            if cu is None:
                cells.append("<td>—</td>")
                continue
            okc = cu["ok"]
            worst = float(np.max(cu["err"][okc])) if np.any(okc) else None
            best = float(np.min(cu["err"][okc])) if np.any(okc) else None
            values[f"integration_worst_{m}_{case_id(case)}"] = worst
            values[f"integration_best_{m}_{case_id(case)}"] = best
            cells.append(f"<td>{c.fmt(worst, 2)} … {c.fmt(best, 2)}</td>")
        integ_rows.append(f"<tr><td>{html.escape(label(m))}</td>{''.join(cells)}</tr>")
    for m in LOCATED + ["fixed_rk4"]:
        w = [values.get(f"integration_worst_{m}_{case_id(k)}") for k in cases]
        w = [x for x in w if x is not None]
        values[f"integration_worst_{m}"] = max(w) if w else None
        b = [values.get(f"integration_best_{m}_{case_id(k)}") for k in cases]
        b = [x for x in b if x is not None]
        values[f"integration_best_{m}"] = max(b) if b else None
    integ_table = ("<table class='data'><thead><tr><th>method (events at the exact times)</th>"
                   + head + "</tr></thead><tbody>" + "\n".join(integ_rows) + "</tbody></table>")

    for m in ("odeint", "gsl", "gsl_msadams", "cvode"):
        for case in cases:
            s = loc.select(case, method=m)
            if not np.any(s):
                continue
            for tol in sorted({float(x) for x in loc.t["event_tol"][s]}):
                ss = s & np.isclose(loc.t["event_tol"], tol, rtol=1e-9, atol=0.0)
                values[f"location_err_{m}_{case_id(case)}_{tkey(tol)}"] = float(loc.err[ss][0])
                values[f"location_converged_{m}_{case_id(case)}_{tkey(tol)}"] = bool(loc.ok[ss][0])
        okk = [values.get(f"location_converged_{m}_{case_id(k)}_{tkey(t)}")
               for k in cases for t in (1e-3, 1e-4, 1e-5)]
        values[f"location_unconverged_loose_{m}"] = int(sum(1 for x in okk if x is False))
    # error per unit event_tol of dopri5 (the integration is exact there)
    per = [values[k] / float(k.rsplit("_", 1)[1]) for k in list(values)
           if k.startswith("location_err_odeint_") and values[k] is not None
           and float(k.rsplit("_", 1)[1]) >= 1e-8 and values[k] > 1e-13]
    values["location_err_per_event_tol_odeint_max"] = max(per) if per else None
    values["location_err_per_event_tol_odeint_median"] = float(np.median(per)) if per else None
    # the fixed step's error per unit h
    per_h = []
    for case in cases:
        cu = curves(fs, case, "fixed_rk4")
        if cu is None:
            continue
        good = cu["ok"] & (cu["knob"] <= 1e-3)
        per_h += list(cu["err"][good] / cu["knob"][good])
        fit = c.linfit(np.log10(cu["knob"][good]), np.log10(np.maximum(cu["err"][good], FLOOR)))
        values[f"fixed_slope_{case_id(case)}"] = fit["k"]
    values["fixed_err_per_h_median"] = float(np.median(per_h)) if per_h else None
    values["fixed_err_per_h_max"] = float(np.max(per_h)) if per_h else None
    values["fixed_budget_failures"] = int(sum(1 for msg in fs.t.str("message")
                                              if "step budget" in str(msg)))
    values["fixed_failures"] = int(np.count_nonzero(~fs.ok))
    values["fixed_runs"] = int(fs.t.n)

    stop_rows = []
    for case in cases:
        cid = case_id(case)
        cells = []
        for stop_rule, est, key in (("difference", "running", "thesis_running"),
                                    ("difference", "cycle", "thesis_cycle"),
                                    ("estimate", "cycle", "ours")):
            s = stop.select(case, stop=stop_rule, estimator=est)
            for tg in sorted({float(x) for x in stop.t["target"][s]}):
                ss = s & np.isclose(stop.t["target"], tg, rtol=1e-9, atol=0.0)
                values[f"stop_err_{key}_{cid}_{tkey(tg)}"] = float(stop.err[ss][0])
                values[f"stop_strokes_{key}_{cid}_{tkey(tg)}"] = int(stop.t["strokes"][ss][0])
                values[f"stop_converged_{key}_{cid}_{tkey(tg)}"] = bool(stop.ok[ss][0])
            e = values.get(f"stop_err_{key}_{cid}_{tkey(THESIS_TARGET)}")
            n = values.get(f"stop_strokes_{key}_{cid}_{tkey(THESIS_TARGET)}")
            cells.append(f"<td>{c.fmt(e, 2)}</td><td>{n if n is not None else '—'}</td>")
        stop_rows.append(f"<tr><td>{html.escape(titles[case])}</td>{''.join(cells)}</tr>")
    stop_table = (
        "<table class='data'><thead><tr><th rowspan='2'>case</th>"
        "<th colspan='2'>thesis: running mean</th><th colspan='2'>thesis rule, cycle average</th>"
        "<th colspan='2'>ours: estimated error</th></tr><tr><th>error</th><th>strokes</th>"
        "<th>error</th><th>strokes</th><th>error</th><th>strokes</th></tr></thead><tbody>"
        + "\n".join(stop_rows) + "</tbody></table>")
    for key in ("thesis_running", "thesis_cycle", "ours"):
        errs = [values.get(f"stop_err_{key}_{case_id(k)}_{tkey(THESIS_TARGET)}") for k in cases]
        errs = [e for e in errs if e is not None]
        values[f"stop_err_{key}_1e-04_max"] = max(errs) if errs else None
        ratios = []
        for k in cases:
            for tg in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
                e = values.get(f"stop_err_{key}_{case_id(k)}_{tkey(tg)}")
                if e is not None and values.get(f"stop_converged_{key}_{case_id(k)}_{tkey(tg)}"):
                    ratios.append(e / tg)
        values[f"stop_err_over_target_{key}_max"] = max(ratios) if ratios else None

    # ---- figures: one model per figure (instant swap: NAME_time, NAME_rhs, NAME_sources; moving
    # Δm: the same names with _dm)
    figures = []
    for model, suffix in (("instant", ""), ("dm", "_dm")):
        mc = [k for k in cases if k[0] == model]
        if not mc:
            continue
        work_precision_figure(plt, model, mc, titles, wp, fs, "cpu", args.out,
                              NAME + "_time" + suffix, "CPU time per v_ss [s]")
        work_precision_figure(plt, model, mc, titles, wp, fs, "rhs", args.out,
                              NAME + "_rhs" + suffix, "right-hand-side evaluations per v_ss")
        slow = [k for k in mc if roles[k].startswith("slow")]
        src = slow[0] if slow else mc[0]
        sources_figure(plt, src, titles[src], integ, loc, fs, stop, args.out,
                       NAME + "_sources" + suffix)
        figures.append((model, suffix, src))
    values["source_figure_cases"] = [case_id(src) for _, _, src in figures]
    values["figures"] = [NAME + kind + suffix for _, suffix, _ in figures
                         for kind in ("_time", "_rhs", "_sources")]

    body = page_body(values, cases, titles, cheap_table, ratio_table, integ_table, integ_rtols,
                     stop_table, [(model_name(m), sx) for m, sx, _ in figures])
    c.atomic_write_text(args.out / f"{NAME}_body.html", body)
    c.write_values(args.out, NAME, values)


# ---------------------------------------------------------------------------------------------
# The page


def geo_range(xs) -> str:
    xs = [x for x in xs if x is not None]
    if not xs:
        return "—"
    lo, hi = min(xs), max(xs)
    return fx(lo) if abs(hi / lo - 1) < 0.15 else f"{fx(lo)}–{fx(hi)}"


def method_paragraphs(v: dict, cases) -> list[tuple[str, str]]:
    """One paragraph per method, every number and comparison from the values."""
    ids = [case_id(k) for k in cases]

    def med(xs):
        xs = [x for x in xs if x is not None]
        return float(np.median(xs)) if xs else None

    def r6(m):
        return geo_range([v.get(f"cpu_ratio_1e-06_{m}_{i}") for i in ids])

    def m6(m):
        return med([v.get(f"cpu_ratio_1e-06_{m}_{i}") for i in ids])

    def rhs6(m):
        """Median over the cases of m's RHS evaluations to 1e-6 over dopri5's."""
        return med([ratio(v.get(f"rhs_to_{m}_{i}_1e-06"), v.get(f"rhs_to_odeint_{i}_1e-06"))
                    for i in ids])

    def cpu_span(m, tg):
        xs = [v.get(f"cpu_to_{m}_{i}_{tkey(tg)}") for i in ids]
        xs = [x for x in xs if x is not None]
        return f"{ms(min(xs))} to {ms(max(xs))}" if xs else "—"

    # the event-locating integrators ordered by their median CPU ratio to 1e-6
    ranked = sorted((m for m in LOCATED if m6(m) is not None), key=m6)
    place = {m: i + 1 for i, m in enumerate(ranked)}
    ordinal = {1: "cheapest", 2: "second cheapest", 3: "third cheapest"}

    def rank(m):
        p = place.get(m)
        if p is None:
            return "never reached 1e-6"
        if p == len(ranked):
            return f"the most expensive of the {len(ranked)} event-locating integrators"
        return (f"the {ordinal.get(p, f'{p}th cheapest')} of the {len(ranked)} event-locating "
                "integrators")

    def integ(m):
        w, b = v.get(f"integration_worst_{m}"), v.get(f"integration_best_{m}")
        if w is None:
            return "no integration-only runs"
        if w < 1e-11:
            return f"no integration error beyond round-off (at most {c.fmt(w, 2)}) at any rtol"
        shrink = ", shrinking with rtol" if b is not None and b < 1e-3 * w else ""
        return f"an integration error up to {c.fmt(w, 2)} at the loosest rtol{shrink}"

    n_pairs = sum(v["cheapest_counts"].values())
    num = v["cheapest_numeric_counts"]
    fixed_reach = {tg: sum(1 for i in ids if v.get(f"cpu_to_fixed_rk4_{i}_{tkey(tg)}") is not None)
                   for tg in TARGETS}
    fixed_ratio = geo_range([v.get(f"fixed_over_cheapest_{i}_1e-03") for i in ids])
    paras = [
        ("analytic", f"The cheapest method in {v['cheapest_counts']['analytic']} of the "
         f"{n_pairs} (case, target) pairs; one v_ss to 1e-12 costs {cpu_span('analytic', 1e-12)} "
         "of CPU. It solves each mode's quadratic motion in closed form and each affine guard as "
         "a quadratic root, so it has no integration and no event-location error: what is left "
         "is the stopping rule's, which our target controls. Pick it whenever the system is "
         "what this library's hybrid layer describes (constant accelerations per mode, affine "
         "guards) — every inchworm study here does — and use the numeric integrators to check "
         "it or for fields it cannot describe."),
        ("odeint", f"The cheapest event-locating integrator in {num.get('odeint', 0)} of the "
         f"{n_pairs} pairs, {rank('odeint')} by median; to 1e-6 it takes {r6('odeint')} the "
         f"exact piecewise method's CPU time. Dormand–Prince 5(4) makes {integ('odeint')} (a "
         "mode's motion is quadratic in t), its order-4 dense output locates guards without "
         "extra steps, and its error in v_ss follows the stopping target. Pick it for a "
         "general smooth, non-stiff hybrid system when the modes have no closed form."),
        ("gsl_rkf45", f"{rank('gsl_rkf45').capitalize()}; to 1e-6: {r6('gsl_rkf45')} the exact "
         f"piecewise time. It makes {integ('gsl_rkf45')}; its guard search re-integrates the "
         "step from its start for every trial time (5 stages each). Pick it when GSL is the "
         "library at hand and the field is smooth with moderate tolerances."),
        ("gsl", f"{rank('gsl').capitalize()}; to 1e-6: {r6('gsl')} the exact piecewise time. It "
         f"makes {integ('gsl')}, so its eighth order buys nothing here, and each trial of its "
         "guard search re-integrates with 12 stages. Pick it for smooth fields that are not "
         "polynomial in t and tight tolerances, where its long steps pay."),
        ("odeint_rkf78", f"{rank('odeint_rkf78').capitalize()}; to 1e-6: {r6('odeint_rkf78')} "
         f"the exact piecewise time. It makes {integ('odeint_rkf78')}; Boost 1.74 gives it no "
         "dense output, so its guard search re-integrates from the step start (12 stages per "
         "trial). Pick it only for very tight tolerances on fields with high-order structure, "
         "where dopri5's steps become short."),
        ("gsl_msadams", f"{rank('gsl_msadams').capitalize()}; to 1e-6: {r6('gsl_msadams')} the "
         "exact piecewise time. A multistep method restarts at order 1 in every mode segment: "
         f"it makes {integ('gsl_msadams')} (events at the exact times) and takes many short "
         "steps; its guards are located on a cubic Hermite interpolant (no extra field "
         "evaluations). Pick it for long smooth segments with few events, not for event-dense "
         "hybrid systems like this one."),
        ("cvode", f"{rank('cvode').capitalize()}; to 1e-6: {r6('cvode')} the exact piecewise "
         f"time, with {c.fmt(rhs6('cvode'), 2)}× dopri5's right-hand-side evaluations (median): "
         "its cost is per-step overhead, not field evaluations. Adams with a fixed-point "
         f"corrector, restarted at every event, makes {integ('cvode')}; its rootfinder places "
         "events to ~1e-15 s whatever event_tol says. Pick it when a right-hand-side "
         "evaluation is expensive (many unknowns) or SUNDIALS' robustness matters more than "
         "speed."),
        ("cvode_bdf", f"{rank('cvode_bdf').capitalize()}; to 1e-6: {r6('cvode_bdf')} the exact "
         "piecewise time: a Newton iteration with a dense LU per Jacobian update buys stability "
         f"these flows do not need; it makes {integ('cvode_bdf')}. Pick it only for stiff "
         "fields (stiff springs, viscous contact models), not for the Coulomb-mode inchworm."),
        ("fixed_rk4", "What a plain script does: RK4 is exact within a mode, so all of its "
         "error comes from events found at step ends; it falls about linearly with h (median "
         f"{c.fmt(v.get('fixed_err_per_h_median'), 2)} × h/s). It reached 1e-3 in "
         f"{fixed_reach[1e-3]} of {len(ids)} cases ({fixed_ratio} the cheapest method's CPU "
         f"time), 1e-6 in {fixed_reach[1e-6]}, within a budget that "
         f"{v.get('fixed_budget_failures')} of its {v.get('fixed_runs')} runs exhausted. Do not "
         "use it for a hybrid system: locate the events."),
    ]
    return paras


def page_body(v: dict, cases, titles, cheap_table, ratio_table, integ_table, integ_rtols,
              stop_table, figures: list[tuple[str, str]]) -> str:
    def imgs(kind: str, alt: str) -> str:
        return "".join(f'<div class="fig wide"><img src="{NAME}_{kind}{sx}.png" '
                       f'alt="{html.escape(alt)}, {html.escape(model)}"></div>'
                       for model, sx in figures)

    wp_note = ("<p class='small'>Each point: one tolerance (fixed-step RK4: one step h); error "
               "against the closed form; time: median CPU time of one solve. Dotted: 1e-3, 1e-6, "
               "1e-9, 1e-12. Runs that did not converge are not drawn (see the tables): those of "
               "fixed-step RK4 at its smallest steps stopped at the study's step budget (status "
               "'step budget', a designed outcome). The exact piecewise "
               "method evaluates no right-hand side: in the second pair of figures its events "
               "are drawn, hollow.</p>")
    load = v.get("machine_load_average")
    load_txt = (f" (load average {load:.2g} when the sweep started"
                + ("; other processes competed for the cores: CPU times suffer less from that "
                   "than wall times, but are noisier than on an idle machine"
                   if load is not None and v.get("machine_logical_cores")
                   and load > 1.2 * v["machine_logical_cores"] else "") + ")"
                if load is not None else "")
    machine = (f"{html.escape(str(v.get('machine_cpu')))}, {v.get('machine_logical_cores')} "
               f"logical cores{load_txt}, {html.escape(str(v.get('machine_os')))}; "
               f"{v.get('threads')} sweep threads; {html.escape(str(v.get('compiler')))}; "
               f"libraries {html.escape(str(v.get('libraries')))}; run {v.get('date')}")
    reps = v.get("repeats")
    paras = "".join(f"<p><b>{html.escape(label(m))}.</b> {html.escape(t)}</p>"
                    for m, t in method_paragraphs(v, cases))
    r_running = v.get("stop_err_thesis_running_1e-04_max")
    r_cycle = v.get("stop_err_thesis_cycle_1e-04_max")
    r_ours = v.get("stop_err_ours_1e-04_max")
    cases_list = "".join(f"<li>{html.escape(titles[k])}</li>" for k in cases)
    slopes = ", ".join(c.fmt(v.get("fixed_slope_" + case_id(k)), 2) for k in cases)
    return f"""
<section id="coa-intro"><h2>Cost of accuracy</h2>
<p>What one steady-state speed v_ss costs with each integrator of the hybrid layer, against the
error it reaches, for both models at {len(cases)} cases:</p><ul class="small">{cases_list}</ul>
<p>Every event-locating method runs over rtol = {v['rtol_max']:.0e} … {v['rtol_min']:.0e}
({v['rtol_count']} values; rtol is both its step tolerance, atol = rtol × 1 cm, and the target of
our stopping rule, as <code>slipwalk inchworm vss --rtol</code> uses it); the fixed-step RK4
without event location runs over h = {v['h_max']:.0e} … {v['h_min']:.0e} s ({v['h_count']}
values) with a stopping target of {v['fixed_target']:.0e} and a budget of
{c.fmt(v['fixed_max_steps'])} steps per solve. Errors are against the closed
form (the algebraic fixed point, or for the dm model the Brent fixed point of the hand-derived
cycle map). Times are the median thread CPU time of one solve over {reps} repeats; ratios are
between methods measured in the same run. <b>Machine:</b> {machine}.</p>
</section>
<section id="coa-wp"><h2>Work–precision</h2>
{imgs("time", "error vs CPU time")}
{imgs("rhs", "error vs right-hand-side evaluations")}
{wp_note}
<h3>The cheapest method to reach 1e-3, 1e-6, 1e-9, 1e-12</h3>
<p class="small">Among the runs that converged with an error at or below the target, the one of
least CPU time (tolerances are sampled once per decade, so "cheapest" is to within a decade of
tolerance). "÷ exact piecewise": the CPU time of the cheapest event-locating integrator over
that of the exact piecewise method, both to that target, same run.</p>
{cheap_table}
<h3>CPU time to reach 1e-6, relative to the exact piecewise method (same run)</h3>
{ratio_table}
</section>
<section id="coa-sources"><h2>Three error sources, separated</h2>
{imgs("sources", "error sources")}
<p><b>Integration.</b> With the events placed at the exact times of the current numerical state
(<code>event_times = "exact"</code>) and a stopping target of 1e-13, only the integration error
is left. Every Runge–Kutta method here, and the fixed-step RK4, reproduces a mode's quadratic
motion to round-off at any tolerance; the multistep methods (CVODE Adams and BDF, GSL msadams),
restarted at order 1 in every segment, make an error that shrinks with rtol. Worst … best error
over rtol = {', '.join(f'{r:.0e}' for r in integ_rtols)} (fixed-step RK4: h = 1e-2, 1e-4 s):</p>
{integ_table}
<p><b>Event location.</b> At rtol = 1e-12 and target 1e-13, the guard-location tolerance
event_tol alone: for dopri5 (exact integration) the error in v_ss is at most
{c.fmt(v.get('location_err_per_event_tol_odeint_max'), 2)} per second of event_tol (median
{c.fmt(v.get('location_err_per_event_tol_odeint_median'), 2)}); the search brackets the
crossing superlinearly, so the error often falls far below event_tol. CVODE places roots with
its own rootfinder first and is unaffected. Loose tolerances (1e-3 … 1e-5 s) make the cycle map
discontinuous: GSL rk8pd never converged to 1e-13 there in
{v.get('location_unconverged_loose_gsl')} of its runs (hollow). The fixed-step RK4 finds events
only at step ends: error ≈ {c.fmt(v.get('fixed_err_per_h_median'), 2)} × h/s (median; fitted
slope of log error against log h per case: {slopes}).
The default event_tol (4ε·max(1, |t|)) makes location error vanish at no visible cost.</p>
<p><b>Stopping rule.</b> The exact event-driven method, so neither of the other errors: the
thesis' rule (stop when two consecutive estimates differ by less than the target) on the running
mean from rest, as the thesis used it, leaves an error that falls only like √target (at its
1e-4: up to {c.fmt(r_running, 2)}); the same rule on the last cycle's average leaves up to
{c.fmt(r_cycle, 2)} (a factor λ/(1 − λ) above the target at slow convergence); our estimated
remaining error leaves up to {c.fmt(r_ours, 2)} (at most
{c.fmt(v.get('stop_err_over_target_ours_max'), 2)} × its target over all cases and targets
≥ 1e-12, against {c.fmt(v.get('stop_err_over_target_thesis_cycle_max'), 2)} × for the thesis
rule on the cycle average). At the thesis' 1e-4:</p>
{stop_table}
</section>
<section id="coa-pick"><h2>Which method to pick</h2>
{paras}
<p class="small">Numbers on this page come from <code>values/{NAME}.json</code>, written by
<code>reports/figures/{NAME}.py</code> from <code>DATA/cost_of_accuracy/*.csv</code>; the specs are in
<code>studies/cost_of_accuracy/</code>.</p>
</section>
"""


if __name__ == "__main__":
    main()
