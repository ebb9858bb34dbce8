#!/usr/bin/python3
"""Cost of accuracy, the multi-legged model: the friction solvers' work-precision (thesis §3.4, §3.6.1).

Input: DATA/cost_of_accuracy/friction.csv (studies/cost_of_accuracy/friction.toml, point kind
legged_cost): for a BigANT-like hexapod and a 50-leg disk robot, on the same random frames,
viscous-Coulomb (one linear solve), the eps-family of eq. 3.14 over eps and the Coulomb solver
over its certificate target tol; per point the error of the body velocity and of the foot forces
against a Coulomb solution certified to 1e-14 (median, p95, max over the frames) and the thread
CPU time per frame (median over repeats of the mean over the frames), all in one run.

Outputs: OUT/cost_friction.png (work-precision diagrams), OUT/cost_friction_body.html (the
multi-legged section of the cost-of-accuracy page, which build_report.py appends to
cost_of_accuracy.html), OUT/values/cost_friction.json. A data folder without friction.csv (made
before this study existed) gives a section that says so and no values.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "cost_friction"
STUDY = "cost_of_accuracy"
CSV = "friction.csv"
TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)
FLOOR = 1e-17  # drawn in place of an error of exactly zero
ROBOTS = (("hexapod", 6), ("disk", 50))
COLUMNS = ["robot", "N", "method", "eps", "tol", "frames", "time_ns", "err_v_median", "err_v_p95",
           "err_v_max", "err_F_median", "err_F_p95", "err_F_max", "error_frames", "nonunique",
           "ref_unconverged", "iterations_mean", "unconverged", "contacts_mean", "contacts_min",
           "contacts_max", "ref_static_mean", "repeats"]
STYLE = {"viscous": ("viscous-Coulomb", "k", "o"), "epsilon": ("ε-family (eq. 3.14)", "C1", "s"),
         "coulomb": ("Coulomb, certificate ≤ tol", "C0", "^")}


def tkey(x: float) -> str:
    return f"{x:.0e}"


def robot_key(robot: str, n: int) -> str:
    return robot if robot == "hexapod" else f"disk{n}"


def robot_title(robot: str, n: int) -> str:
    return "BigANT-like hexapod" if robot == "hexapod" else f"disk robot, N = {n}"


def us(ns) -> str:
    """A time in ns, printed in µs."""
    return "—" if ns is None else f"{c.fmt(ns / 1000.0, 3)} µs"


def curves(t: c.Table, robot: str, n: int) -> dict:
    """method -> rows sorted by the knob, loosest first (ε and tol descending)."""
    out = {}
    base = (t["robot"] == robot) & (t["N"] == n)
    for method in STYLE:
        s = base & (t["method"] == method)
        if not np.any(s):
            continue
        knob = t["eps"] if method == "epsilon" else t["tol"]
        idx = np.flatnonzero(s)
        idx = idx[np.argsort(-np.nan_to_num(knob[idx], nan=np.inf), kind="stable")]
        out[method] = {k: t[k][idx] for k in COLUMNS if k not in ("robot", "method")}
        out[method]["knob"] = knob[idx]
    return out


def short(x: float) -> str:
    """1e-06 -> 1e-6, 1e+01 -> 1e1."""
    return f"{x:.0e}".replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")


def knob_text(method: str, knob: float) -> str:
    if method == "viscous":
        return "—"
    return f"ε = {knob:.0e} m/s" if method == "epsilon" else f"tol = {knob:.0e}"


def figure(plt, data: dict, out) -> None:
    # 8.4 in at 9.5 pt: readable at the narrow page width too; one legend under the panels
    fig, axs = plt.subplots(2, 2, figsize=(8.4, 9.4), squeeze=False)
    for col, (robot, n) in enumerate(ROBOTS):
        cv = data.get(robot_key(robot, n), {})
        for row, (q, qlabel) in enumerate((("v", "body velocity error\n‖(Δv_x, Δv_y, LΔω)‖ / V"),
                                           ("F", "foot force error\nmax_k ‖ΔF_k‖ / (μ_k F_z,k)"))):
            ax = axs[row, col]
            for method, r in cv.items():
                name, color, marker = STYLE[method]
                x = r["time_ns"] / 1000.0
                p95 = np.maximum(r[f"err_{q}_p95"], FLOOR)
                med = np.maximum(r[f"err_{q}_median"], FLOOR)
                ax.loglog(x, p95, "-", color=color, marker=marker, ms=5, lw=1.2,
                          label=f"{name}: p95 over frames")
                ax.loglog(x, med, "--", color=color, marker=marker, mfc="none", ms=4, lw=0.8,
                          label=f"{name}: median")
                if method != "viscous":
                    # label the knob at the ends of the curve and where the error has moved
                    # 3 decades since the last label (more would not be readable)
                    last = None
                    for i, (xi, yi, k) in enumerate(zip(x, p95, r["knob"])):
                        here = np.log10([xi, yi])
                        end = i in (0, len(x) - 1)
                        if last is not None and not end and abs(here[1] - last[1]) < 3.0:
                            continue
                        if last is not None and abs(here[1] - last[1]) < 1.2 and \
                                abs(here[0] - last[0]) < 0.15:
                            continue
                        last = here
                        ax.annotate(short(k), (xi, yi), textcoords="offset points",
                                    xytext=(5, 2), color=color)
            xs = np.concatenate([r["time_ns"] / 1000.0 for r in cv.values()]) if cv else []
            if len(xs):
                ax.set_xlim(np.min(xs) / 1.5, np.max(xs) * 1.8)  # room for the labels
            for tg in TARGETS:
                ax.axhline(tg, color="0.5", ls=":", lw=0.7)
            ax.set_xlabel("CPU time per frame [µs]")
            ax.set_ylabel(qlabel)
            ax.set_ylim(FLOOR / 3, 30)
            ax.set_title(f"({'ab'[col] if row == 0 else 'cd'[col]}) {robot_title(robot, n)}")
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, frameon=False)
    fig.suptitle("Work–precision of the friction solvers against Coulomb certified to 1e-14\n"
                 "labels: ε in m/s (orange), tol (blue); dotted: 1e-3, 1e-6, 1e-9, 1e-12; "
                 f"0 drawn at {FLOOR:.0e}", fontsize=10.5)
    fig.tight_layout(rect=(0, 1.0 / fig.get_size_inches()[1], 1, 1))
    c.save_figure(fig, out, NAME)


def cheapest(cv: dict, target: float) -> dict | None:
    """The run of least time whose p95 velocity error is ≤ target."""
    best = None
    for method, r in cv.items():
        for i in range(len(r["time_ns"])):
            if r["err_v_p95"][i] <= target and r["unconverged"][i] == 0:
                if best is None or r["time_ns"][i] < best["time_ns"]:
                    best = {"method": method, "knob": float(r["knob"][i]),
                            "time_ns": float(r["time_ns"][i]),
                            "err_v_p95": float(r["err_v_p95"][i]),
                            "err_v_max": float(r["err_v_max"][i]),
                            "err_F_p95": float(r["err_F_p95"][i])}
    return best


def measure(t: c.Table) -> tuple[dict, dict, str]:
    values: dict = {}
    data: dict = {}
    rows = []
    for robot, n in ROBOTS:
        key = robot_key(robot, n)
        cv = curves(t, robot, n)
        data[key] = cv
        if "viscous" not in cv or "coulomb" not in cv or "epsilon" not in cv:
            c.fail(f"{t.path}: {robot} N = {n} needs viscous, epsilon and coulomb rows")
        vis = cv["viscous"]
        values[f"{key}_contacts_mean"] = float(vis["contacts_mean"][0])
        values[f"{key}_contacts_min"] = int(vis["contacts_min"][0])
        values[f"{key}_contacts_max"] = int(vis["contacts_max"][0])
        values[f"{key}_frames"] = int(vis["frames"][0])
        values[f"{key}_error_frames"] = int(vis["error_frames"][0])
        values[f"{key}_ref_static_mean"] = float(vis["ref_static_mean"][0])
        values[f"{key}_viscous_ns"] = float(vis["time_ns"][0])
        for q in ("v", "F"):
            for stat in ("median", "p95", "max"):
                values[f"{key}_viscous_err_{q}_{stat}"] = float(vis[f"err_{q}_{stat}"][0])
        for method in ("epsilon", "coulomb"):
            r = cv[method]
            for i, k in enumerate(r["knob"]):
                p = f"{key}_{method}_{tkey(k)}"
                values[f"{p}_ns"] = float(r["time_ns"][i])
                values[f"{p}_err_v_p95"] = float(r["err_v_p95"][i])
                values[f"{p}_err_v_median"] = float(r["err_v_median"][i])
                values[f"{p}_err_F_p95"] = float(r["err_F_p95"][i])
                values[f"{p}_iterations"] = float(r["iterations_mean"][i])
                values[f"{p}_unconverged"] = int(r["unconverged"][i])
            values[f"{key}_{method}_ns_min"] = float(np.min(r["time_ns"]))
            values[f"{key}_{method}_ns_max"] = float(np.max(r["time_ns"]))
        eps = cv["epsilon"]
        cou = cv["coulomb"]
        values[f"{key}_epsilon_smallest"] = float(eps["knob"][-1])
        values[f"{key}_epsilon_smallest_err_v_p95"] = float(eps["err_v_p95"][-1])
        # the ε runs cheaper than the Coulomb solver at its tightest tol, and their best error
        cheaper = eps["time_ns"] < cou["time_ns"][-1]
        values[f"{key}_epsilon_cheaper_than_coulomb_count"] = int(np.count_nonzero(cheaper))
        values[f"{key}_epsilon_count"] = int(eps["knob"].size)
        values[f"{key}_epsilon_cheaper_best_err_v_p95"] = (
            float(np.min(eps["err_v_p95"][cheaper])) if np.any(cheaper) else None)
        values[f"{key}_epsilon_best_err_v_p95"] = float(np.min(eps["err_v_p95"]))
        # The ε-family's rate: the slope of log err against log ε over its three smallest ε
        # (√ε: a foot that Coulomb holds static slips at s ~ √ε under eq. 3.14).
        small = np.argsort(eps["knob"])[:3]
        good = small[eps["err_v_median"][small] > 0]
        values[f"{key}_epsilon_rate"] = (
            float(np.polyfit(np.log(eps["knob"][good]), np.log(eps["err_v_median"][good]), 1)[0])
            if good.size >= 2 else None)
        # ε at which the family first beats viscous-Coulomb by 10× (p95 velocity error)
        beat = [float(k) for k, e in zip(eps["knob"], eps["err_v_p95"])
                if e <= 0.1 * vis["err_v_p95"][0]]
        values[f"{key}_epsilon_10x_better_than_viscous"] = max(beat) if beat else None
        values[f"{key}_coulomb_tightest_ns"] = float(cou["time_ns"][-1])
        values[f"{key}_coulomb_tol_loosest"] = float(cou["knob"][0])
        values[f"{key}_coulomb_tol_tightest"] = float(cou["knob"][-1])
        values[f"{key}_coulomb_err_v_p95_over_tol_max"] = float(
            np.max(cou["err_v_p95"] / cou["knob"]))
        values[f"{key}_coulomb_over_viscous_tightest"] = float(cou["time_ns"][-1] /
                                                               vis["time_ns"][0])
        values[f"{key}_coulomb_tight_over_loose"] = float(cou["time_ns"][-1] / cou["time_ns"][0])
        values[f"{key}_epsilon_smallest_over_coulomb_tightest"] = float(
            eps["time_ns"][-1] / cou["time_ns"][-1])
        values[f"{key}_coulomb_unconverged"] = int(np.sum(cou["unconverged"]))
        values[f"{key}_nonunique"] = int(np.max(cou["nonunique"]))
        values[f"{key}_ref_unconverged"] = int(np.max(cou["ref_unconverged"]))
        for tg in TARGETS:
            b = cheapest(cv, tg)
            values[f"{key}_cheapest_{tkey(tg)}_method"] = b["method"] if b else None
            values[f"{key}_cheapest_{tkey(tg)}_ns"] = b["time_ns"] if b else None
            if b:
                rows.append(
                    f"<tr><td>{html.escape(robot_title(robot, n))}</td><td>{tg:.0e}</td>"
                    f"<td>{html.escape(STYLE[b['method']][0])}</td>"
                    f"<td>{html.escape(knob_text(b['method'], b['knob']))}</td>"
                    f"<td>{us(b['time_ns'])}</td><td>{c.fmt(b['err_v_p95'], 2)}</td>"
                    f"<td>{c.fmt(b['err_v_max'], 2)}</td><td>{c.fmt(b['err_F_p95'], 2)}</td>"
                    f"<td>{c.fmt(b['time_ns'] / vis['time_ns'][0], 3)}×</td></tr>")
            else:
                rows.append(f"<tr><td>{html.escape(robot_title(robot, n))}</td><td>{tg:.0e}</td>"
                            "<td colspan='7' class='bad'>not reached by any run</td></tr>")
    table = ("<table class='data'><thead><tr><th>robot</th><th>target (p95 of the velocity "
             "error)</th><th>cheapest method</th><th>setting</th><th>CPU time per frame</th>"
             "<th>p95 error v</th><th>max error v</th><th>p95 error F</th>"
             "<th>÷ viscous-Coulomb</th></tr></thead><tbody>" + "\n".join(rows) +
             "</tbody></table>")
    return values, data, table


def solver_table(data: dict) -> str:
    """Every run: the numbers behind the figure."""
    out = ["<table class='data'><thead><tr><th>robot</th><th>method</th><th>setting</th>"
           "<th>CPU time per frame</th><th>error v: median / p95 / max</th>"
           "<th>error F: median / p95 / max</th><th>iterations (mean)</th>"
           "<th>not certified</th></tr></thead><tbody>"]
    for robot, n in ROBOTS:
        for method, r in data[robot_key(robot, n)].items():
            for i in range(len(r["time_ns"])):
                ev = " / ".join(c.fmt(r[f"err_v_{s}"][i], 2) for s in ("median", "p95", "max"))
                eF = " / ".join(c.fmt(r[f"err_F_{s}"][i], 2) for s in ("median", "p95", "max"))
                bad = " class='bad'" if r["unconverged"][i] > 0 else ""
                out.append(f"<tr{bad}><td>{html.escape(robot_title(robot, n))}</td>"
                           f"<td>{html.escape(STYLE[method][0])}</td>"
                           f"<td>{html.escape(knob_text(method, r['knob'][i]))}</td>"
                           f"<td>{us(r['time_ns'][i])}</td><td>{ev}</td><td>{eF}</td>"
                           f"<td>{c.fmt(r['iterations_mean'][i], 3)}</td>"
                           f"<td>{int(r['unconverged'][i])}</td></tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def paragraphs(v: dict) -> list[tuple[str, str]]:
    h, d = "hexapod", "disk50"

    def g(k):
        return v.get(k)

    def f2(x):
        return c.fmt(x, 2)

    def eps_cheaper(k):
        n, m = g(f"{k}_epsilon_cheaper_than_coulomb_count"), g(f"{k}_epsilon_count")
        if not n:
            return ("Every ε costs more than the Coulomb solver at its tightest tol "
                    f"(hexapod).")
        return (f"{n} of its {m} ε settings are cheaper than the Coulomb solver at its tightest "
                f"tol (hexapod), but the best of those leaves a p95 velocity error of "
                f"{f2(g(f'{k}_epsilon_cheaper_best_err_v_p95'))} (viscous-Coulomb: "
                f"{f2(g(f'{k}_viscous_err_v_p95'))}).")

    def coulomb_rate():
        r = [g(f"{k}_coulomb_err_v_p95_over_tol_max") for k in (h, d)]
        if any(x is None for x in r):
            return ""
        head = (f"The largest ratio of its p95 velocity error to tol over all tolerances is "
                f"{f2(r[0])} (hexapod) and {f2(r[1])} (disk)")
        return head + (": its error is at or below the order of tol, so tol is an honest knob."
                       if max(r) <= 10 else
                       ": its error can exceed tol, the gap bounds dissipation, not velocity.")

    eps10 = [g(f"{k}_epsilon_10x_better_than_viscous") for k in (h, d)]
    eps10_txt = ("It never comes within a tenth of viscous-Coulomb's error over this sweep."
                 if all(e is None for e in eps10) else
                 "It beats viscous-Coulomb's p95 error tenfold only from ε = " + " (hexapod) and ".join(
                     f"{e:.0e}" if e is not None else "— (never)" for e in eps10) +
                 " m/s (disk) down.")
    rates = [g(f"{k}_epsilon_rate") for k in (h, d)]
    rate_txt = (f"the velocity error falls like ε^{f2(rates[0])} (hexapod) and ε^{f2(rates[1])} "
                "(disk) over its three smallest ε. A foot that Coulomb friction holds still "
                "creeps under eq. 3.14 at s ~ √ε (the force magnitude s(ε + s)/(ε + s²) reaches "
                "the Coulomb value only for slip speeds s ≫ √ε), so frames with a static foot "
                "converge like √ε and the others faster; Coulomb friction holds "
                f"{f2(g(f'{h}_ref_static_mean'))} feet static per hexapod frame on average and "
                f"{f2(g(f'{d}_ref_static_mean'))} per disk frame")
    slower = [g(f"{k}_epsilon_smallest_over_coulomb_tightest") for k in (h, d)]
    direct = ("both cheaper and certified to any tolerance"
              if all(x is not None and x > 1 for x in slower) else
              "certified to any tolerance at a comparable cost")
    loose = [g(f"{k}_coulomb_tight_over_loose") for k in (h, d)]
    flat = all(x is not None and x < 2 for x in loose)
    return [
        ("viscous", f"One 3 × 3 linear solve: {us(g(f'{h}_viscous_ns'))} per frame for the "
         f"hexapod, {us(g(f'{d}_viscous_ns'))} for 50 legs. It is a different friction law, not "
         "an approximation with a knob: against Coulomb friction its body velocity is off by "
         f"{f2(g(f'{h}_viscous_err_v_median'))} of the fastest foot's speed (median; p95 "
         f"{f2(g(f'{h}_viscous_err_v_p95'))}) on the hexapod and "
         f"{f2(g(f'{d}_viscous_err_v_median'))} (p95 {f2(g(f'{d}_viscous_err_v_p95'))}) on the "
         "50-leg disk — many feet average the differences out — and even after the best common "
         "scale of the forces (as the thesis fits one per frame) a foot's force is off by "
         f"{f2(g(f'{h}_viscous_err_F_median'))} of its friction limit μF_z (median of the worst "
         "foot). Pick it when speed matters most or the model sits inside an optimizer or a "
         "planner (its answer is linear in the foot velocities: the local connection), and when "
         "errors of this size are below the uncertainty of the inputs (measured slip velocities, "
         "fitted μ) — as in the thesis' BigANT comparison. Do not pick it to predict which feet "
         "stick or the individual foot forces."),
        ("epsilon", "The smoothed family of eq. 3.14 between the two laws, solved by Newton's "
         f"method: {us(g(f'{h}_epsilon_ns_min'))} to {us(g(f'{h}_epsilon_ns_max'))} per hexapod "
         f"frame over ε, against {us(g(f'{h}_coulomb_ns_min'))} to "
         f"{us(g(f'{h}_coulomb_ns_max'))} for the Coulomb solver over all its tolerances. "
         f"{eps_cheaper(h)} It converges to Coulomb friction slowly: {rate_txt}; at the smallest ε = "
         f"{g(f'{h}_epsilon_smallest'):.0e} m/s its p95 error is still "
         f"{f2(g(f'{h}_epsilon_smallest_err_v_p95'))} (hexapod) and "
         f"{f2(g(f'{d}_epsilon_smallest_err_v_p95'))} (disk). {eps10_txt} ε also carries units (it enters as ε + s and ε + s²), so its "
         "meaning changes with the speed scale. Pick it only when a smooth force law is itself "
         "wanted (a differentiable simulation, a gradient-based fit); as a route to Coulomb "
         f"friction, solving the Coulomb problem directly is {direct}."),
        ("coulomb", "Classical Coulomb friction as a convex program with a certificate (the "
         f"relative duality gap). {coulomb_rate()} "
         f"{'The cost hardly depends on tol' if flat else 'The cost grows with tightening tol'}: "
         f"from tol = {g(f'{h}_coulomb_tol_loosest'):.0e} to "
         f"{g(f'{h}_coulomb_tol_tightest'):.0e} it grows "
         f"{f2(g(f'{h}_coulomb_tight_over_loose'))}× (hexapod) and "
         f"{f2(g(f'{d}_coulomb_tight_over_loose'))}× (disk)"
         f"{', because the final active-set polish converges quadratically once the static feet are identified' if flat else ''}. "
         "At the tightest tol it "
         f"costs {f2(g(f'{h}_coulomb_over_viscous_tightest'))}× the viscous-Coulomb solve "
         f"(hexapod; disk: {f2(g(f'{d}_coulomb_over_viscous_tightest'))}×), "
         f"{us(g(f'{h}_coulomb_tightest_ns'))} per hexapod frame. Pick it whenever the forces of "
         "individual feet, which feet stick, or the body velocity beyond the viscous ansatz's "
         "accuracy matter (contact-force prediction, slip detection, a reference for the other "
         "two); ask for a tight tol (1e-9 or below), since accuracy is nearly free. Check "
         "friction.unique: where Coulomb friction has a continuum of balances, no tolerance "
         "picks one."),
    ]


def body(v: dict, figure_ok: bool, cheap_table: str, all_table: str) -> str:
    machine = (f"{html.escape(str(v.get('machine_cpu')))}, {v.get('machine_logical_cores')} "
               f"logical cores (1-minute load average {v.get('machine_load_average')} when the "
               f"sweep started), {html.escape(str(v.get('compiler')))}, {v.get('threads')} sweep "
               f"threads taking turns for their timed loops; run {v.get('date')}")
    paras = "".join(f"<p><b>{html.escape(STYLE[m][0].split(':')[0])}.</b> {html.escape(t)}</p>"
                    for m, t in paragraphs(v))
    h, d = "hexapod", "disk50"
    return f"""
<section id="coa-legged"><h2>The multi-legged model: friction solvers</h2>
<p>What the friction balance of chapter 3 (§3.4) costs per frame with each solver, against the
error it leaves, on the same {v[f'{h}_frames']} random frames per robot: a BigANT-like hexapod
({c.fmt(v[f'{h}_contacts_mean'], 3)} feet down on average, {v[f'{h}_contacts_min']}–{v[f'{h}_contacts_max']})
and a disk robot with 50 legs on a 0.3 m rim ({c.fmt(v[f'{d}_contacts_mean'], 3)} feet down).
Feet slide back at 0.1 m/s with a 50 % spread and a random turn; the spring support (Alg. 1)
decides contacts and loads. The reference is the Coulomb solution certified to a relative
duality gap of 1e-14 (it is unique and certified on {v[f'{h}_error_frames']} of the hexapod's
and {v[f'{d}_error_frames']} of the disk's frames, over which the errors are taken; Coulomb friction holds on average {c.fmt(v[f'{h}_ref_static_mean'], 2)} and
{c.fmt(v[f'{d}_ref_static_mean'], 2)} feet static). Errors: body velocity
‖(Δv_x, Δv_y, L Δω)‖ / V (V the fastest foot in contact, L the largest lever arm); foot forces
max_k ‖ΔF_k‖ / (μ_k F_z,k), for the viscous-type laws after the least-squares common scale σ (their
forces are in other units; the thesis fits σ per frame, §3.5.1.4). Times: thread CPU time per
frame, the median of {v.get('repeats')} repeats of a loop over all frames; ratios are between runs
of the same sweep. <b>Machine:</b> {machine}.</p>
{"<div class='fig wide'><img src='" + NAME + ".png' alt='friction work-precision'></div>" if figure_ok else ""}
<h3>The cheapest solver to reach 1e-3, 1e-6, 1e-9, 1e-12 in body velocity</h3>
<p class="small">Among the runs whose p95 velocity error over the frames is at or below the
target (and that certified every frame), the one of least CPU time per frame; tolerances are
sampled once per decade.</p>
{cheap_table}
<h3>Which friction solver to pick</h3>
{paras}
<details><summary>Every run</summary>{all_table}</details>
<p class="small">From <code>DATA/cost_of_accuracy/{CSV}</code> (spec
<code>studies/cost_of_accuracy/friction.toml</code>, point kind <code>legged_cost</code>) by
<code>reports/figures/{NAME}.py</code>; numbers in <code>values/{NAME}.json</code>. The per-frame cost
against the number of legs and our per-frame cost targets: the index's
<a href="performance.html#perf-legged">performance page</a>.</p>
</section>
"""


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    path = args.data / STUDY / CSV
    if not path.is_file():
        c.atomic_write_text(args.out / f"{NAME}_body.html",
                            "<section id='coa-legged'><h2>The multi-legged model: friction "
                            f"solvers</h2><p class='bad'>Not built: <code>{html.escape(c.shown_path(path))}"
                            "</code> is missing (run <code>slipwalk reproduce cost_of_accuracy"
                            "</code>).</p></section>\n")
        print(f"{NAME}.py: warning: {path}: missing, section not built")
        return
    plt = c.setup_matplotlib()
    t = c.Table(path, COLUMNS)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    values, data, cheap_table = measure(t)
    side = c.read_sidecar(path) or {}
    prov = side.get("provenance", {}) if isinstance(side, dict) else {}
    machine = prov.get("machine", {}) if isinstance(prov, dict) else {}
    values.update({
        "machine_cpu": machine.get("cpu"), "machine_logical_cores": machine.get("logical_cores"),
        "machine_load_average": machine.get("load_average_1min"), "threads": side.get("threads"),
        "compiler": prov.get("compiler"), "date": side.get("date"),
        "timing": side.get("timing"), "repeats": int(np.max(t["repeats"])),
    })
    figure(plt, data, args.out)
    c.atomic_write_text(args.out / f"{NAME}_body.html",
                        body(values, True, cheap_table, solver_table(data)))
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
