#!/usr/bin/python3
"""Performance: what accuracy costs, per method (work–precision).

Input: DATA/ch2_inchworm/cost.csv — methods analytic (exact event-driven integration), cvode,
odeint and gsl at several rtol for (F, μ) = (45 N, 1) and (73.575 N, 0.05), plus the closed
form (exact, the reference) and its root-finding twin (rootfind). Repeated rows of one
(case, method, rtol) are summarised by their median wall time. Output: OUT/performance.png,
OUT/performance_table.html, OUT/values/performance.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "performance"
TARGET = 1e-10  # relative error the cost table asks for
FLOOR = 1e-17  # plotted in place of an error of exactly zero
SIMULATORS = ("analytic", "cvode", "odeint", "gsl")
MARKERS = {"analytic": "o", "cvode": "s", "odeint": "^", "gsl": "D", "rootfind": "*"}
# the cost-of-accuracy page's colours for the same methods (no red: it marks measured data)
COLORS = {"rootfind": "tab:brown", "analytic": "k", "cvode": "tab:blue", "odeint": "tab:green",
          "gsl": "tab:purple"}


def case_key(F: float, mu: float) -> str:
    return f"F{F:g}_mu{mu:g}"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "cost.csv", c.SWEEP_COLUMNS + ["rtol", "wall_s", "rhs_evals",
                                                                "message"])
    meth = t["method"]
    msgs = t.str("message")
    cases = sorted({(round(float(F), 9), round(float(mu), 12)) for F, mu in zip(t["F"], t["mu"])},
                   key=lambda k: (-k[1], k[0]))
    values: dict = {"target": TARGET, "cases": [list(k) for k in cases]}
    not_built = sorted({str(m) for m, ok, msg in zip(meth, t["converged"], msgs)
                        if ok != 1 and "not built" in str(msg)})
    values["methods_not_built"] = not_built
    failed = [f"{m} rtol={r:g}: {msg}" for m, r, ok, msg in zip(meth, t["rtol"], t["converged"], msgs)
              if ok != 1 and "not built" not in str(msg)]
    values["failed_runs"] = failed

    table_rows = []
    all_err_1e6 = []
    fig, axs = plt.subplots(len(cases), 2, figsize=(8.4, 3.7 * len(cases) + 0.7), squeeze=False)
    for ci, (F, mu) in enumerate(cases):
        key = case_key(F, mu)
        s_case = np.isclose(t["F"], F) & np.isclose(t["mu"], mu)
        se = s_case & (meth == "exact") & (t["converged"] == 1)
        if not np.any(se):
            c.fail(f"{t.path}: no converged exact row for F = {F:g}, mu = {mu:g}")
        ref = float(np.median(t["v_ss"][se]))
        values[f"exact_{key}"] = ref
        values[f"wall_exact_{key}"] = float(np.median(t["wall_s"][se]))
        for method in ("exact", "rootfind") + SIMULATORS:
            sm = s_case & (meth == method) & (t["converged"] == 1)
            if not np.any(sm):
                table_rows.append((F, mu, method, None, None, None, None, None))
                continue
            rtols = sorted({float(r) for r in t["rtol"][sm]}, reverse=True)
            pts = []
            for r in rtols:
                sr = sm & np.isclose(t["rtol"], r, rtol=1e-9, atol=0)
                err = float(np.median(np.abs(t["v_ss"][sr] / ref - 1)))
                wall = float(np.median(t["wall_s"][sr]))
                rhs = float(np.median(t["rhs_evals"][sr]))
                steps = float(np.median(t["steps"][sr])) if "steps" in t.columns else 0.0
                pts.append((r, err, wall, rhs, steps))
                values[f"err_{method}_{key}_rtol{r:.0e}"] = err
                values[f"wall_{method}_{key}_rtol{r:.0e}"] = wall
                values[f"rhs_{method}_{key}_rtol{r:.0e}"] = rhs
                if method in SIMULATORS and np.isclose(r, 1e-6):
                    all_err_1e6.append(err)
            pts = np.array(pts)
            # cheapest run that reaches the target
            reach = pts[pts[:, 1] <= TARGET]
            if reach.size:
                best = reach[np.argmin(reach[:, 2])]
                table_rows.append((F, mu, method, best[0], best[1], best[2], best[3], len(pts)))
                values[f"cost_to_target_steps_{method}_{key}"] = best[4]
                values[f"cost_to_target_wall_{method}_{key}"] = best[2]
                values[f"cost_to_target_rhs_{method}_{key}"] = best[3]
                values[f"cost_to_target_rtol_{method}_{key}"] = best[0]
            else:
                table_rows.append((F, mu, method, None, float(pts[:, 1].min()), None, None,
                                   len(pts)))
                values[f"cost_to_target_wall_{method}_{key}"] = None
            values[f"best_error_{method}_{key}"] = float(pts[:, 1].min())
            if method == "exact":
                continue
            for ax, col in ((axs[ci, 0], 2), (axs[ci, 1], 3)):
                x = pts[:, col]
                label = method
                hollow = False
                if col == 3 and not np.any(x > 0):
                    # closed forms and the exact event-driven method evaluate no right-hand
                    # side; show their steps (events/phases) instead, hollow
                    x = pts[:, 4]
                    label = f"{method} (steps; no RHS evaluations)"
                    hollow = True
                ok = x > 0
                if not np.any(ok):
                    continue
                ax.loglog(x[ok], np.maximum(pts[ok, 1], FLOOR), "-",
                          marker=MARKERS.get(method, "x"), color=COLORS.get(method),
                          mfc="none" if hollow else None, ms=7 if method == "rootfind" else 4.5,
                          lw=0.9, label=label)
        axs[ci, 0].set_xlabel("wall time per solve [s]")
        axs[ci, 1].set_xlabel("right-hand-side evaluations (hollow: steps)")
        for ax in axs[ci]:
            if not ax.get_lines():
                ax.text(0.5, 0.5, "no runs with recorded work", ha="center", va="center",
                        transform=ax.transAxes, color="0.4")
                ax.set_yscale("log")
            ax.axhline(TARGET, color="k", ls=":", lw=0.8)
            ax.set_ylabel("|v_ss − exact| / exact")
            ax.set_title(f"F = {F:g} N, μ = {mu:g}")
        axs[ci, 0].axvline(values[f"wall_exact_{key}"], color="0.5", lw=0.8, ls="--")
        axs[ci, 0].text(values[f"wall_exact_{key}"], 1e-16, " closed form", color="0.4",
                        rotation=90, va="bottom")
    values["max_error_rtol_1e-06"] = max(all_err_1e6) if all_err_1e6 else None
    # one legend for all panels, under them
    from matplotlib.lines import Line2D

    shown = [m for m in dict.fromkeys(("rootfind",) + SIMULATORS) if m in MARKERS]
    handles = [Line2D([], [], color=COLORS.get(m), marker=MARKERS[m], ms=5, lw=0.9,
                      label=m + (" (hollow: steps, no RHS evaluations)" if m == "analytic"
                                 else "")) for m in shown]
    fig.legend(handles=handles, loc="lower center", ncol=3, frameon=False)
    fig.suptitle(f"Work–precision (dotted: target {TARGET:.0e}; errors of 0 drawn at {FLOOR:.0e})",
                 fontsize=10.5)
    fig.tight_layout(rect=(0, 0.6 / fig.get_size_inches()[1], 1, 1))
    c.save_figure(fig, args.out, NAME)

    out = ["<table class='data'><thead><tr><th>F [N]</th><th>μ</th><th>method</th>"
           f"<th>cheapest rtol reaching {TARGET:.0e}</th><th>its error</th><th>wall [s]</th>"
           "<th>rhs evals</th><th>runs</th></tr></thead><tbody>"]
    for F, mu, method, r, err, wall, rhs, n in table_rows:
        if n is None:
            why = "not built" if method in not_built else "no converged run"
            out.append(f"<tr><td>{F:g}</td><td>{mu:g}</td><td>{method}</td>"
                       f"<td colspan='5' class='muted'>{why}</td></tr>")
        elif r is None:
            out.append(f"<tr><td>{F:g}</td><td>{mu:g}</td><td>{method}</td>"
                       f"<td class='bad'>not reached</td><td>best {c.fmt(err, 2)}</td>"
                       f"<td>—</td><td>—</td><td>{n}</td></tr>")
        else:
            rt = "—" if method in ("exact", "rootfind") else f"{r:.0e}"
            out.append(f"<tr><td>{F:g}</td><td>{mu:g}</td><td>{html.escape(method)}</td>"
                       f"<td>{rt}</td><td>{c.fmt(err, 2)}</td><td>{c.fmt(wall, 3)}</td>"
                       f"<td>{c.fmt(rhs, 3)}</td><td>{n}</td></tr>")
    out.append("</tbody></table>")
    c.atomic_write_text(args.out / "performance_table.html", "\n".join(out) + "\n")
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
