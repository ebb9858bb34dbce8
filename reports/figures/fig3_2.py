#!/usr/bin/python3
"""Thesis Fig. 3.2 / §3.1.2.4: total planar force of a 4-legged robot, Coulomb vs viscous-Coulomb.

Inputs: DATA/ch3_legged/fig3_2.csv (kind legged_force_map: ‖Σ F‖ over a grid of body velocities
(v_x, v_y) at ω = 0 under both laws, the feet's rest velocities, each law's force-moment balance
and the ε-family of eq. 3.14 between them) and DATA/ch3_legged/compare.csv (kind legged_compare:
both balances for N legs on a circle with random foot velocities of a given spread).
Output: OUT/fig3_2.png, OUT/values/fig3_2.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import legged as lg  # noqa: E402

NAME = "fig3_2"
FOOT_COLORS = c.CATEGORICAL  # the feet have no thesis meaning: none of the laws' colours
LAW_COLOR = {"coulomb": c.COULOMB, "viscous": c.VISCOUS}
SIMILAR = 0.1  # "very similar": balances apart by at most 10 % of the feet's mean speed


def grid(t: c.Table, law: str):
    m = (t.str("row") == "grid") & (t.str("law") == law)
    vx, vy, f = t["vx"][m], t["vy"][m], t["F_norm"][m]
    xs, ys = np.unique(vx), np.unique(vy)
    if xs.size * ys.size != f.size:
        c.fail(f"{t.path}: the {law} grid is not rectangular")
    order = np.lexsort((vx, vy))  # y slowest, as written
    return xs, ys, f[order].reshape(ys.size, xs.size), vx[order].reshape(ys.size, xs.size), \
        vy[order].reshape(ys.size, xs.size)


def quadratic_fit_residual(X, Y, Z) -> float:
    """max |Z − fit| / max Z for the least-squares quadratic in (x, y) through Z."""
    x, y, z = X.ravel(), Y.ravel(), Z.ravel()
    A = np.column_stack([np.ones_like(x), x, y, x * x, x * y, y * y])
    coef, *_ = np.linalg.lstsq(A, z, rcond=None)
    return float(np.max(np.abs(A @ coef - z)) / np.max(np.abs(z)))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = lg.table(args.data, NAME, ["row", "law", "epsilon", "foot", "vx", "vy", "omega", "F_norm",
                                   "qx", "qy", "qdx", "qdy", "Fz", "unique", "converged",
                                   "residual"])
    cmp_t = lg.table(args.data, "compare", ["N", "spread", "rel_diff", "diff", "converged"])
    row, law = t.str("row"), t.str("law")
    feet = row == "foot"
    if not feet.any():
        c.fail(f"{t.path}: no foot rows")
    bal = {lw: np.flatnonzero((row == "balance") & (law == lw)) for lw in ("coulomb", "viscous")}
    for lw, idx in bal.items():
        if idx.size != 1:
            c.fail(f"{t.path}: expected one {lw} balance row")
    bc, bv = bal["coulomb"][0], bal["viscous"][0]
    values: dict = {}
    for lw, i in (("coulomb", bc), ("viscous", bv)):
        values[f"{lw}_balance"] = [float(t["vx"][i]), float(t["vy"][i]), float(t["omega"][i])]
        values[f"{lw}_converged"] = bool(t["converged"][i] == 1)
        values[f"{lw}_unique"] = bool(t["unique"][i] == 1)
        values[f"{lw}_residual"] = float(t["residual"][i])
    qx, qy, qdx, qdy, Fz = (t[k][feet] for k in ("qx", "qy", "qdx", "qdy", "Fz"))
    L = float(np.max(np.hypot(qx, qy)))
    mean_speed = float(np.mean(np.hypot(qdx, qdy)))
    d = np.array(values["coulomb_balance"]) - np.array(values["viscous_balance"])
    values["lever_L"] = L
    values["mean_foot_speed"] = mean_speed
    values["balance_distance_vxy"] = float(np.hypot(d[0], d[1]))
    values["balance_distance_omega"] = float(abs(d[2]))
    values["balance_distance"] = float(np.sqrt(d[0] ** 2 + d[1] ** 2 + (L * d[2]) ** 2))
    values["balance_rel_distance"] = values["balance_distance"] / mean_speed
    values["rest_velocity_spread"] = float(np.sqrt(np.mean((qdx - qdx.mean()) ** 2 +
                                                           (qdy - qdy.mean()) ** 2)) / mean_speed)
    values["loads"] = Fz.tolist()
    # the ε-family: from viscous-Coulomb (large ε) to Coulomb (small ε)
    em = (row == "balance") & (law == "epsilon")
    eps = t["epsilon"][em]
    if eps.size:
        o = np.argsort(eps)
        ev = np.column_stack([t["vx"][em], t["vy"][em], t["omega"][em]])[o]
        eps = eps[o]
        dist_c = np.sqrt(((ev[:, :2] - np.array(values["coulomb_balance"][:2])) ** 2).sum(1)
                         + (L * (ev[:, 2] - values["coulomb_balance"][2])) ** 2)
        dist_v = np.sqrt(((ev[:, :2] - np.array(values["viscous_balance"][:2])) ** 2).sum(1)
                         + (L * (ev[:, 2] - values["viscous_balance"][2])) ** 2)
        values["eps_min"], values["eps_max"] = float(eps[0]), float(eps[-1])
        values["eps_min_rel_distance_to_coulomb"] = float(dist_c[0] / mean_speed)
        values["eps_max_rel_distance_to_viscous"] = float(dist_v[-1] / mean_speed)
        values["eps_converged_fraction"] = float(np.mean(t["converged"][em] == 1))
    # maps: the viscous |F|² is a quadratic in (v_x, v_y) (exactly, up to rounding); Coulomb's not
    xs, ys, Fc, X, Y = grid(t, "coulomb")
    _, _, Fv, _, _ = grid(t, "viscous")
    values["viscous_F2_quadratic_residual"] = quadratic_fit_residual(X, Y, Fv ** 2)
    values["coulomb_F2_quadratic_residual"] = quadratic_fit_residual(X, Y, Fc ** 2)
    values["viscous_is_quadratic"] = bool(values["viscous_F2_quadratic_residual"] < 1e-9)
    values["grid_n"] = int(xs.size)

    # random robots (compare.csv)
    Ns = sorted(set(cmp_t["N"].astype(int).tolist()))
    spreads = sorted(set(cmp_t["spread"].tolist()))
    values["compare_converged_fraction"] = float(np.mean(cmp_t["converged"] == 1))
    values["compare_N"], values["compare_spreads"] = Ns, spreads
    med = {}
    for n in Ns:
        med[n] = [float(np.median(cmp_t["rel_diff"][(cmp_t["N"] == n) & (cmp_t["spread"] == s)]))
                  for s in spreads]
        values[f"compare_median_rel_diff_N{n}"] = med[n]
    if 0.2 in spreads:
        m = cmp_t["spread"] == 0.2
        values["compare_spread02_median_rel_diff"] = float(np.median(cmp_t["rel_diff"][m]))
        values["compare_spread02_p90_rel_diff"] = float(np.percentile(cmp_t["rel_diff"][m], 90))
        values["compare_spread02_max_median_over_N"] = float(max(med[n][spreads.index(0.2)]
                                                                 for n in Ns))
    # least-squares line through the origin of the medians against the spread
    sx = np.array([s for n in Ns for s in spreads])
    sy = np.array([v for n in Ns for v in med[n]])
    values["compare_median_per_spread"] = float(sx @ sy / (sx @ sx))

    # ---- figure -----------------------------------------------------------------------------------
    fig = plt.figure(figsize=(14, 11))
    gs = fig.add_gridspec(2, 3, width_ratios=[1.12, 1.12, 0.9])
    ax_c, ax_v = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[1, 0])
    ax_r = fig.add_subplot(gs[0, 2])
    ax_e = fig.add_subplot(gs[0, 1])
    ax_n = fig.add_subplot(gs[1, 1])
    ax_t = fig.add_subplot(gs[1, 2])
    from matplotlib.ticker import MaxNLocator

    for ax, F, title, lw in ((ax_c, Fc, "(a) Coulomb friction: ‖Σ F‖ at ω = 0", "coulomb"),
                             (ax_v, Fv, "(b) viscous-Coulomb ansatz: ‖Σ F‖ at ω = 0", "viscous")):
        levels = MaxNLocator(nbins=20).tick_values(0.0, float(F.max()))
        cs = ax.contourf(xs, ys, F, levels=levels, cmap="viridis")
        ax.contour(xs, ys, F, levels=cs.levels, colors="k", linewidths=0.3, alpha=0.4)
        fig.colorbar(cs, ax=ax, label="‖Σ F_xy‖ [N]  (μ = 1, Mg = 1 N)", shrink=0.9)
        for k in range(qx.size):
            ax.plot(-qdx[k], -qdy[k], "o", ms=8, color=FOOT_COLORS[k % len(FOOT_COLORS)],
                    mec="w", mew=1.2)
        # the balances as stars in each law's colour (the thesis' are red, the colour this
        # report keeps for measurements); this panel's own law filled
        for other, i in (("coulomb", bc), ("viscous", bv)):
            own = other == lw
            ax.plot(t["vx"][i], t["vy"][i], "*", ms=19 if own else 15,
                    mfc=LAW_COLOR[other] if own else "none",
                    mec=LAW_COLOR[other] if not own else "k", mew=2.0 if not own else 0.8,
                    label=f"{'Coulomb' if other == 'coulomb' else 'viscous'} balance")
        ax.set_xlabel("body velocity V_x [m/s]")
        ax.set_ylabel("body velocity V_y [m/s]")
        ax.set_title(title)
        ax.set_aspect("equal")
        ax.legend(loc="lower left", framealpha=0.85)
    # the robot: feet numbered as in the text panel
    for k in range(qx.size):
        col = FOOT_COLORS[k % len(FOOT_COLORS)]
        ax_r.plot(qx[k], qy[k], "o", ms=10, color=col)
        ax_r.annotate("", xy=(qx[k] + 0.25 * qdx[k], qy[k] + 0.25 * qdy[k]), xytext=(qx[k], qy[k]),
                      arrowprops=dict(arrowstyle="->", color=col, lw=2))
        # the number on the side away from the arrow
        ax_r.annotate(str(k), (qx[k], qy[k]), textcoords="offset points",
                      xytext=(-14 * np.sign(qdx[k] or 1), -14 * np.sign(qdy[k] or 1)),
                      ha="center", va="center", color=col, fontweight="bold", fontsize=11)
    ax_r.plot([qx.min(), qx.max(), qx.max(), qx.min(), qx.min()],
              [qy.min(), qy.min(), qy.max(), qy.max(), qy.min()], color="0.5", lw=1)
    ax_r.plot(0, 0, "k+", ms=10)
    ax_r.set_aspect("equal")
    ax_r.set_xlim(qx.min() - 0.35, qx.max() + 0.35)
    ax_r.set_ylim(qy.min() - 0.35, qy.max() + 0.35)
    ax_r.set_xlabel("x [m] (body frame, forward)")
    ax_r.set_ylabel("y [m]")
    ax_r.set_title("(c) the robot: feet and their velocities\nrelative to the body (arrows: 0.25 s)")
    # the ε-family; the three components have no thesis colour
    if eps.size:
        for j, (name, col) in enumerate((("v_x [m/s]", c.CATEGORICAL[0]),
                                         ("v_y [m/s]", c.CATEGORICAL[1]),
                                         ("ω [rad/s]", c.CATEGORICAL[2]))):
            ax_e.plot(eps, ev[:, j], "o-", ms=4, lw=1.6, color=col, label=name)
            ax_e.axhline(values["coulomb_balance"][j], color=col, ls="--", lw=1.0)
            ax_e.axhline(values["viscous_balance"][j], color=col, ls=":", lw=1.2)
        ax_e.set_xscale("log")
        ax_e.set_xlabel("ε of eq. 3.14 [m/s]")
        ax_e.set_ylabel("balance body velocity")
        ax_e.set_title("(d) eq. 3.14: from viscous-Coulomb (ε → ∞)\nto Coulomb (ε → 0); "
                       "dashed: Coulomb, dotted: viscous")
        ax_e.legend(loc="center right")
    # random robots: N in a sequential colour scale
    cmap = plt.get_cmap("viridis")
    for i, n in enumerate(Ns):
        ax_n.plot(spreads, med[n], "o-", ms=4, lw=1.6, color=cmap(i / max(len(Ns) - 1, 1) * 0.9),
                  label=f"N = {n} legs on a circle")
    ax_n.plot(spreads, values["compare_median_per_spread"] * np.array(spreads), ":",
              color=c.REFERENCE, lw=1.2, label=f"{values['compare_median_per_spread']:.2f} × spread")
    ax_n.axhline(SIMILAR, color=c.REFERENCE, ls="--", lw=0.9)
    ax_n.axvline(0.2, color="0.5", ls=":", lw=0.9)
    ax_n.set_xlabel("spread of the foot velocities around (−1, 0) m/s\n[m/s per component]")
    ax_n.set_ylabel("‖Δ(v_x, v_y, R ω)‖ / mean foot speed\n(median of 200 robots)")
    ax_n.set_title("(e) beyond one robot:\nhow far apart the two balances are")
    ax_n.legend(loc="upper left")
    ax_t.axis("off")
    vb, cb = values["viscous_balance"], values["coulomb_balance"]
    lines = [
        "Feet (c): q_dot [m/s], F_z [N]",
        *[f" {k}: ({qdx[k]:g}, {qdy[k]:g}), {Fz[k]:.3g}" for k in range(qx.size)],
        "",
        "Balances (v_x, v_y, ω):",
        f" viscous ({vb[0]:.3f}, {vb[1]:.3f}, {vb[2]:.3f})",
        f" Coulomb ({cb[0]:.3f}, {cb[1]:.3f}, {cb[2]:.3f})",
        f" apart {values['balance_distance']:.3f} m/s (ω as Lω,",
        f" L = {L:.2f} m): {values['balance_rel_distance']:.0%} of the",
        f" mean foot speed {mean_speed:.3f} m/s;",
        f" feet spread {values['rest_velocity_spread']:.0%} of it",
        "",
        "‖Σ F‖² against a quadratic in",
        "(V_x, V_y), largest residual:",
        f" viscous {values['viscous_F2_quadratic_residual']:.1e}, "
        f"Coulomb {values['coulomb_F2_quadratic_residual']:.2f}",
        "",
        "Random robots (e), spread 0.2 m/s:",
        f" median {values.get('compare_spread02_median_rel_diff', float('nan')):.1%}, "
        f"90th pct. {values.get('compare_spread02_p90_rel_diff', float('nan')):.1%}",
    ]
    ax_t.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace",
              transform=ax_t.transAxes)
    fig.suptitle("Fig. 3.2: a 4-legged robot slipping under Coulomb or viscous-Coulomb friction "
                 "(dots: body velocities that put a foot at rest,\ncoloured as its foot in c; "
                 "stars: each law's balance, in its colour)")
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
