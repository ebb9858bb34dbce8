#!/usr/bin/python3
"""The exact scaling law: v_ss(F, μ) = √μ · v_ss(F/μ, 1), shown as a data collapse.

Input: DATA/ch2_inchworm/scaling.csv (method exact; μ ∈ {0.05, …, 1} × f̃ = F/(μMg) on a
log grid). At fixed F/μ every acceleration of the instant-swap model is μg times the same number
(see tests/inchworm/test_closed_form.cpp, ScalingLaw), so ṽ/√μ = v_ss/√(μ L_max g) is a single
function H(f̃) for every μ. Eq. 2.6 does not have this form; the figure shows its curves for the
same μ divided by √μ, which fan out. Output: OUT/scaling.png, OUT/values/scaling.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "scaling"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "scaling.csv", c.SWEEP_COLUMNS + ["f_tilde"])
    t = t.subset((t["method"] == "exact") & (t["converged"] == 1))
    if t.n < 4:
        c.fail(f"{t.path}: fewer than 4 converged exact rows")
    mu, F, v, ft = t["mu"], t["F"], t["v_ss"], t["f_tilde"]
    S = c.velocity_scale("sqrt_Lmax_g")
    h = v / (np.sqrt(mu) * S)  # ṽ / √μ

    # The collapse: at each f̃ on the grid, the spread of ṽ/√μ over μ.
    keys = np.round(ft, 9)
    spreads = []
    for k in np.unique(keys):
        s = keys == k
        if np.count_nonzero(s) > 1:
            spreads.append((h[s].max() - h[s].min()) / h[s].mean())
    spreads = np.array(spreads)
    mus = np.unique(mu)
    coef = c.eq2_6_coefficients()
    # Eq. 2.6 is stated for regime II, 1 < f̃ ≤ 5/μ (F up to 5 M g); compare it only there.
    regime2 = (ft > 1.0) & (ft <= 5.0 / mu * (1 + 1e-12))
    eq_h = c.eq2_6(F, mu, coef) / (np.sqrt(mu) * S)
    eq_spread = []
    for k in np.unique(keys[regime2]):
        s = (keys == k) & regime2
        if np.count_nonzero(s) > 1:
            eq_spread.append((eq_h[s].max() - eq_h[s].min()) / eq_h[s].mean())
    values = {
        "n_points": int(t.n),
        "mu_values": [float(m) for m in mus],
        "f_tilde_min": float(ft.min()), "f_tilde_max": float(ft.max()),
        "collapse_max_rel_spread": float(spreads.max()) if spreads.size else None,
        "eq2_6_max_rel_spread": float(max(eq_spread)) if eq_spread else None,
    }

    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    for m_, col in zip(mus, ["C3", "C1", "C2", "C4", "C0"]):
        s = np.isclose(mu, m_)
        o = np.argsort(ft[s])
        axs[0].plot(ft[s][o], v[s][o], "o-", ms=2.5, lw=1, color=col, label=f"μ = {m_:g}")
        axs[1].plot(ft[s][o], h[s][o], "o", ms=3.5 - 0.4 * list(mus).index(m_), color=col,
                    label=f"exact, μ = {m_:g}")
        r2 = s & regime2
        o2 = np.argsort(ft[r2])
        axs[1].plot(ft[r2][o2], eq_h[r2][o2], "--", lw=0.9, color=col)
    axs[1].plot([], [], "k--", lw=0.9, label="eq. 2.6 / √μ (1 < f̃ ≤ 5/μ)")
    axs[0].set_xscale("log")
    axs[0].set_xlabel("f̃ = F/(μMg)")
    axs[0].set_ylabel("v_ss [m/s]")
    axs[0].set_title("(a) v_ss: one curve per μ")
    axs[0].legend(fontsize=7)
    axs[1].set_xscale("log")
    axs[1].set_yscale("log")
    axs[1].set_xlabel("f̃ = F/(μMg)")
    axs[1].set_ylabel("v_ss / √(μ L_max g)")
    spread = values["collapse_max_rel_spread"]
    axs[1].set_title(f"(b) collapse: max spread over μ {spread:.1e}" if spread is not None
                     else "(b) collapse")
    axs[1].legend(fontsize=7)
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
