#!/usr/bin/python3
"""Thesis Fig. 2.3: steady-state CoM speed v_ss vs actuator force F for μ = 1 and μ = 0.2.

Input: DATA/ch2_inchworm/fig2_3.csv (methods exact and analytic over F in (μmg, 5Mg]).
Numerical points are the event-driven simulation ("analytic"); each regime gets its own
least-squares line (regime I: F ≤ μ_s·Mg, regime II: F > μ_s·Mg); solid curves are the exact
closed form. Output: OUT/fig2_3.png, OUT/values/fig2_3.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig2_3"


def mu_key(mu: float) -> str:
    return f"mu{mu:g}"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "fig2_3.csv", c.SWEEP_COLUMNS + ["regime", "c0", "period"])
    method = t["method"]
    mu_all = t["mu"]
    mus_all = c.mu_static(t)
    F_all = t["F"]
    for need in ("exact", "analytic"):
        if not np.any(method == need):
            c.fail(f"{t.path}: no rows with method '{need}'")

    values: dict = {}
    # Regime boundary: the regime the run reports vs F ≤ μ_s M g (§2.3.1).
    expected_regime = np.where(F_all <= mus_all * c.M * c.G, 1, 2)
    ok_rows = t["converged"] == 1
    values["regime_agreement"] = float(np.mean(t["regime"][ok_rows] == expected_regime[ok_rows]))
    values["regime_disagreements"] = int(np.sum(t["regime"][ok_rows] != expected_regime[ok_rows]))

    ana = method == "analytic"
    values["converged_fraction"] = float(np.mean(t["converged"][ana] == 1))
    values["n_analytic"] = int(np.sum(ana))
    values["F_max"] = float(np.max(F_all))
    values["F_max_over_Mg"] = float(np.max(F_all) / (c.M * c.G))
    values["F_max_over_total_weight"] = float(np.max(F_all) / ((c.m + c.M) * c.G))
    moving = ana & (t["converged"] == 1) & (t["v_ss"] > 0)
    values["min_F_over_mu_s_m_g"] = float(np.min(F_all[moving] / (mus_all[moving] * c.m * c.G)))
    values["vss_all_positive"] = bool(np.all(t["v_ss"][t["converged"] == 1] > 0))

    # eq. 2.11 with the run's own c0 and stroke period reproduces its v_ss (exact rows).
    ex = method == "exact"
    kappa = F_all[ex] / (F_all[ex] + mu_all[ex] * c.M * c.G)
    v211 = 0.5 * (1 + kappa) * t["c0"][ex] + c.RHO * c.DL / (2 * t["period"][ex])
    values["eq2_11_max_rel_diff"] = float(np.max(np.abs(v211 / t["v_ss"][ex] - 1)))
    # Cross-checks of the C++ closed form against the Python one (μ_s = μ rows only), and the
    # closed form with eq. 2.9 as printed (no ½ on the t2² term).
    same = ex & (mus_all == mu_all)
    py = np.array([c.closed_form(F, mu)["v_ss"] for F, mu in zip(F_all[same], mu_all[same])])
    printed = np.array([c.closed_form(F, mu, "printed")["v_ss"]
                        for F, mu in zip(F_all[same], mu_all[same])])
    values["python_closed_form_max_rel_diff"] = float(np.max(np.abs(py / t["v_ss"][same] - 1)))
    rel_printed = np.abs(printed / t["v_ss"][same] - 1)
    values["eq2_9_printed_max_rel_diff"] = float(np.max(rel_printed))
    values["eq2_9_printed_min_rel_diff"] = float(np.min(rel_printed))

    fig, ax = plt.subplots(figsize=(7.2, 4.8))
    mus = sorted({round(float(v), 12) for v in mu_all}, reverse=True)
    r2s, rel_all, slope_diffs = [], [], []
    for i, mu in enumerate(mus):
        color = "k" if i == 0 else ("0.55" if i == 1 else f"C{i}")
        key = mu_key(mu)
        sel = np.isclose(mu_all, mu, rtol=0, atol=1e-12)
        e = sel & ex
        a = sel & ana & (t["converged"] == 1)
        order = np.argsort(F_all[e])
        Fe, ve = F_all[e][order], t["v_ss"][e][order]
        ax.plot(Fe, ve, "-", color=color, lw=1.3, label=f"μ = {mu:g}: exact (§2.4)")
        # analytic vs exact at the same F
        va = t["v_ss"][a]
        ve_at = np.interp(F_all[a], Fe, ve)
        exact_match = np.array([np.any(np.isclose(Fe, f, rtol=1e-12)) for f in F_all[a]])
        rel = np.abs(va / ve_at - 1)[exact_match]
        rel_all.extend(rel.tolist())
        values[f"max_rel_diff_analytic_exact_{key}"] = float(np.max(rel)) if rel.size else None
        boundary = float(np.median(mus_all[sel])) * c.M * c.G
        values[f"boundary_F_{key}"] = boundary
        values[f"regime_I_width_{key}"] = boundary - float(np.median(mus_all[sel])) * c.m * c.G
        ax.axvline(boundary, color=color, lw=0.6, ls=(0, (1, 3)))
        fits = {}
        for reg, marker, mask in (("I", "x", F_all[a] <= boundary), ("II", ".", F_all[a] > boundary)):
            Fa, vaa = F_all[a][mask], va[mask]
            fit = c.linfit(Fa, vaa)
            fits[reg] = fit
            values[f"n_{reg}_{key}"] = fit["n"]
            values[f"k_{reg}_{key}"] = fit["k"]
            values[f"b_{reg}_{key}"] = fit["b"]
            values[f"r2_{reg}_{key}"] = fit["r2"]
            # sensitivity to the grid: the same fit without the lowest force
            drop = c.linfit(Fa[Fa > Fa.min()], vaa[Fa > Fa.min()]) if Fa.size else fit
            values[f"r2_{reg}_{key}_without_lowest_F"] = drop["r2"]
            if fit["r2"] is None:
                values[f"r2_{reg}_{key}_reason"] = f"only {fit['n']} point(s) in regime {reg}: a line needs 3"
            else:
                r2s.append(fit["r2"])
            lab = (f"μ = {mu:g}, regime {reg}: simulation" +
                   (f"; fit R² = {fit['r2']:.4f}" if fit["r2"] is not None else
                    f" ({fit['n']} pt, no fit)"))
            ax.plot(Fa, vaa, marker, color=color, ms=5 if marker == "." else 4, ls="none",
                    label=lab)
            if fit["r2"] is not None:
                xx = np.array([Fa.min(), Fa.max()])
                ax.plot(xx, fit["k"] * xx + fit["b"], "--", color=color, lw=1.0)
        if fits["I"]["k"] is not None and fits["II"]["k"] is not None:
            ratio = fits["II"]["k"] / fits["I"]["k"]
            values[f"slope_ratio_II_over_I_{key}"] = ratio
            slope_diffs.append(abs(ratio - 1))
    values["mus"] = mus
    values["r2_min"] = min(r2s) if r2s else None
    values["max_rel_diff_analytic_exact"] = max(rel_all) if rel_all else None
    values["regime_slopes_min_rel_difference"] = min(slope_diffs) if slope_diffs else None
    if not slope_diffs:
        values["regime_slopes_min_rel_difference_reason"] = "no μ has a line in both regimes"
    ax.plot([], [], "k--", lw=1.0, label="least-squares line per regime")
    ax.set_xlabel("actuator force F [N]")
    ax.set_ylabel("steady-state CoM speed v_ss [m/s]")
    ax.set_title("Fig. 2.3 — v_ss vs F (dotted verticals: regime boundary F = μMg)")
    ax.legend(loc="lower right", ncol=1)
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
