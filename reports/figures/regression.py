#!/usr/bin/python3
"""Thesis §2.3.1: regime II lines v_ss = k F + b per μ, then k(μ) and b(μ).

Input: DATA/ch2_inchworm/regression.csv (regime II, μ in [0.05, 1], F in [μMg, 5Mg], method
exact). The thesis fitted k = k2 μ² + k0 ("quadratic regression") and b = b1 μ + b0; we fit
both that form and a full quadratic k = k2 μ² + k1 μ + k0. Output: OUT/regression.png,
OUT/regression_table.html, OUT/values/regression.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "regression"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "regression.csv", c.SWEEP_COLUMNS)
    sel = (t["method"] == "exact") & (t["converged"] == 1)
    if not np.any(sel):
        c.fail(f"{t.path}: no converged rows with method 'exact'")
    t = t.subset(sel)
    mus_static = c.mu_static(t)
    mus = np.array(sorted({round(float(v), 12) for v in t["mu"]}))
    if mus.size < 3:
        c.fail(f"{t.path}: need at least 3 values of mu for the k(μ), b(μ) fits, have {mus.size}")

    rows = []
    curves = {}
    for mu in mus:
        s = np.isclose(t["mu"], mu, rtol=0, atol=1e-12)
        # regime II as the thesis sampled it: F in [μMg, 5Mg]
        s &= t["F"] >= mus_static * c.M * c.G * (1 - 1e-9)
        F, v = t["F"][s], t["v_ss"][s]
        o = np.argsort(F)
        curves[mu] = (F[o], v[o])
        fit = c.linfit(F, v)
        rows.append({"mu": mu, **fit, "F_min": F.min(), "F_max": F.max()})
    k = np.array([r["k"] for r in rows], float)
    b = np.array([r["b"] for r in rows], float)
    r2 = np.array([r["r2"] for r in rows], float)

    # k(μ): the thesis' form k2 μ² + k0, and a full quadratic; b(μ) linear.
    (k2, k0), k_r2 = c.lstsq_fit([mus**2, np.ones_like(mus)], k)
    (q2, q1, q0), q_r2 = c.lstsq_fit([mus**2, mus, np.ones_like(mus)], k)
    (b1, b0), b_r2 = c.lstsq_fit([mus, np.ones_like(mus)], b)

    # The thesis' k(μ), b(μ) against ours.
    tk2, tk0 = float(c.thesis("2.3.1-k2")), float(c.thesis("2.3.1-k0"))
    tb1, tb0 = float(c.thesis("2.3.1-b1")), float(c.thesis("2.3.1-b0"))
    k_thesis = tk2 * mus**2 + tk0
    b_thesis = tb1 * mus + tb0

    # "Intermediate values of μ interpolate those plotted" (Fig. 2.3): at fixed F in the range
    # common to all μ, is v_ss monotone in μ?
    F_lo = max(cv[0].min() for cv in curves.values())
    F_hi = min(cv[0].max() for cv in curves.values())
    grid = np.linspace(F_lo, F_hi, 50)
    V = np.array([np.interp(grid, *curves[mu]) for mu in mus])  # rows: μ ascending
    dV = np.diff(V, axis=0)
    monotone_inc = np.all(dV >= 0, axis=0)
    monotone_dec = np.all(dV <= 0, axis=0)
    monotone_fraction = float(np.mean(monotone_inc | monotone_dec))

    values = {
        "mus": mus, "k": k, "b": b, "r2": r2,
        "n_mu": int(mus.size),
        "mu_min": float(mus.min()), "mu_max": float(mus.max()),
        "r2_min": float(np.nanmin(r2)), "r2_max": float(np.nanmax(r2)),
        "mu_at_r2_min": float(mus[np.nanargmin(r2)]),
        "k_fit_k2": k2, "k_fit_k0": k0, "k_fit_r2": k_r2,
        "k_quad_k2": q2, "k_quad_k1": q1, "k_quad_k0": q0, "k_quad_r2": q_r2,
        "b_fit_b1": b1, "b_fit_b0": b0, "b_fit_r2": b_r2,
        "k_thesis_max_rel_diff": float(np.max(np.abs(k / k_thesis - 1))),
        "b_thesis_max_rel_diff": float(np.max(np.abs(b / b_thesis - 1))),
        "monotone_in_mu_fraction": monotone_fraction,
        "monotone_in_mu_direction": ("increasing" if np.all(monotone_inc) else
                                     "decreasing" if np.all(monotone_dec) else "mixed"),
        "monotone_F_range": [F_lo, F_hi],
        "points_per_mu": [int(r["n"]) for r in rows],
    }

    # ---- figure: (a) the lines, (b) R², (c) k(μ), (d) b(μ)
    # the thesis' fits and threshold in purple (red marks measured data in the report)
    th_col = "tab:purple"
    fig, axs = plt.subplots(2, 2, figsize=(8.4, 9.6), height_ratios=[1, 1.05])
    ax = axs[0, 0]
    cmap = plt.get_cmap("viridis")
    for i, mu in enumerate(mus):
        col = cmap(i / max(1, mus.size - 1))
        F, v = curves[mu]
        ax.plot(F, v, ".", color=col, ms=2.5)
        ax.plot(F, rows[i]["k"] * F + rows[i]["b"], "-", color=col, lw=0.7)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(mus.min(), mus.max()))
    fig.colorbar(sm, ax=ax, label="μ")
    ax.set_xlabel("F [N]")
    ax.set_ylabel("v_ss (exact) [m/s]")
    ax.set_title("(a) regime II: exact points and per-μ lines")
    ax = axs[0, 1]
    ax.plot(mus, r2, "ko-", ms=3)
    ax.axhline(float(c.thesis("2.1-linear-R2")), color=th_col, ls="--", lw=1.0,
               label=f"thesis §2.1: R² > {c.thesis('2.1-linear-R2'):g}")
    ax.set_xlabel("μ")
    ax.set_ylabel("R² of v_ss = kF + b")
    ax.set_title("(b) linearity per μ")
    ax.legend(loc="lower right")
    mm = np.linspace(mus.min(), mus.max(), 200)
    ax = axs[1, 0]
    ax.plot(mus, k * 1e3, "ko", ms=3.5, label="k per μ (ours)")
    ax.plot(mm, (k2 * mm**2 + k0) * 1e3, "-", color="tab:blue", lw=1.2,
            label=f"ours: k = {k2 * 1e3:.2f}e-3 μ² + {k0 * 1e3:.2f}e-3\n(R² = {k_r2:.3f})")
    ax.plot(mm, (q2 * mm**2 + q1 * mm + q0) * 1e3, ":", color="tab:green", lw=1.5,
            label=f"ours, full quadratic (R² = {q_r2:.4f})")
    ax.plot(mm, (tk2 * mm**2 + tk0) * 1e3, "--", color=th_col, lw=1.2,
            label=f"thesis: k = {tk2 * 1e3:g}e-3 μ² + {tk0 * 1e3:g}e-3")
    ax.set_xlabel("μ")
    ax.set_ylabel("k [10⁻³ (m/s)/N]")
    ax.set_title("(c) slope k(μ)")
    below = dict(loc="upper center", bbox_to_anchor=(0.5, -0.15))  # under the panel
    ax.legend(**below)
    ax = axs[1, 1]
    ax.plot(mus, b, "ko", ms=3.5, label="b per μ (ours)")
    ax.plot(mm, b1 * mm + b0, "-", color="tab:blue", lw=1.2,
            label=f"ours: b = {b1:.3f} μ + {b0:.3f}\n(R² = {b_r2:.3f})")
    ax.plot(mm, tb1 * mm + tb0, "--", color=th_col, lw=1.2,
            label=f"thesis: b = {tb1:g} μ + {tb0:g}")
    ax.set_xlabel("μ")
    ax.set_ylabel("b [m/s]")
    ax.set_title("(d) intercept b(μ)")
    ax.legend(**below)
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)

    # ---- table fragment
    cells = [f"<details><summary>regime II line for each of the {len(rows)} values of μ</summary>"
             "<table class='data'><thead><tr><th>μ</th><th>points</th><th>F range [N]</th>"
             "<th>k [(m/s)/N]</th><th>b [m/s]</th><th>R²</th></tr></thead><tbody>"]
    for r in rows:
        cells.append(f"<tr><td>{r['mu']:g}</td><td>{r['n']}</td>"
                     f"<td>{r['F_min']:.3g}–{r['F_max']:.3g}</td><td>{c.fmt(r['k'], 5)}</td>"
                     f"<td>{c.fmt(r['b'], 5)}</td><td>{c.fmt(r['r2'], 5)}</td></tr>")
    cells.append("</tbody></table></details>")
    fits = [
        ("k = k2 μ² + k0 (thesis' form)", f"k2 = {c.fmt(k2)}, k0 = {c.fmt(k0)}", k_r2,
         f"k2 = {tk2:g}, k0 = {tk0:g}, R² {c.thesis('2.3.1-k-R2'):g}"),
        ("k = k2 μ² + k1 μ + k0", f"k2 = {c.fmt(q2)}, k1 = {c.fmt(q1)}, k0 = {c.fmt(q0)}", q_r2,
         "—"),
        ("b = b1 μ + b0", f"b1 = {c.fmt(b1)}, b0 = {c.fmt(b0)}", b_r2,
         f"b1 = {tb1:g}, b0 = {tb0:g}, R² {c.thesis('2.3.1-b-R2'):g}"),
    ]
    cells.append("<table class='data'><thead><tr><th>fit over μ</th><th>ours</th><th>R²</th>"
                 "<th>thesis</th></tr></thead><tbody>")
    for name, ours, rr, th in fits:
        cells.append(f"<tr><td>{html.escape(name)}</td><td>{html.escape(ours)}</td>"
                     f"<td>{c.fmt(rr, 4)}</td><td>{html.escape(th)}</td></tr>")
    cells.append("</tbody></table>")
    c.atomic_write_text(args.out / "regression_table.html", "\n".join(cells) + "\n")
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
