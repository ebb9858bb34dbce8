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
FOOT_COLORS = ["tab:purple", "tab:green", "tab:cyan", "tab:olive", "tab:brown", "tab:pink"]
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
    fig = plt.figure(figsize=(14.5, 9.6))
    gs = fig.add_gridspec(2, 3, width_ratios=[1.15, 1.15, 1.0])
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
        fig.colorbar(cs, ax=ax, label="‖Σ F_xy‖ [N]  (μ = 1, Mg = 1 N)")
        for k in range(qx.size):
            ax.plot(-qdx[k], -qdy[k], "o", ms=7, color=FOOT_COLORS[k % len(FOOT_COLORS)],
                    mec="w", mew=1.0)
        for other, i, mk in (("coulomb", bc, "*"), ("viscous", bv, "*")):
            own = other == lw
            ax.plot(t["vx"][i], t["vy"][i], mk, ms=15 if own else 11,
                    mfc="red" if own else "none", mec="red", mew=1.5,
                    label=f"{other} balance" + (" (this law)" if own else ""))
        ax.set_xlabel("body velocity V_x [m/s]")
        ax.set_ylabel("body velocity V_y [m/s]")
        ax.set_title(title)
        ax.set_aspect("equal")
        ax.legend(fontsize=7, loc="lower left", framealpha=0.85)
    # the robot
    for k in range(qx.size):
        col = FOOT_COLORS[k % len(FOOT_COLORS)]
        ax_r.plot(qx[k], qy[k], "o", ms=9, color=col)
        ax_r.annotate("", xy=(qx[k] + 0.25 * qdx[k], qy[k] + 0.25 * qdy[k]), xytext=(qx[k], qy[k]),
                      arrowprops=dict(arrowstyle="->", color=col, lw=2))
        # the label on the side away from the arrow
        sx = 1.0 if qx[k] >= 0 else -1.0
        sy = 1.0 if qy[k] >= 0 else -1.0
        ax_r.text(qx[k] + 0.04 * sx, qy[k] + 0.09 * sy,
                  f"foot {k}: q_dot = ({qdx[k]:g}, {qdy[k]:g}) m/s\nF_z = {Fz[k]:.3g} N",
                  fontsize=7, color=col, ha="left" if sx > 0 else "right",
                  va="bottom" if sy > 0 else "top")
    ax_r.plot([qx.min(), qx.max(), qx.max(), qx.min(), qx.min()],
              [qy.min(), qy.min(), qy.max(), qy.max(), qy.min()], color="0.5", lw=1)
    ax_r.plot(0, 0, "k+", ms=10)
    ax_r.set_aspect("equal")
    ax_r.set_xlim(qx.min() - 0.7, qx.max() + 0.7)
    ax_r.set_ylim(qy.min() - 0.35, qy.max() + 0.35)
    ax_r.set_xlabel("x [m] (body frame, forward)")
    ax_r.set_ylabel("y [m]")
    ax_r.set_title("(c) the robot: feet and their velocities\nrelative to the body (arrows: 0.25 s)")
    # the ε-family
    if eps.size:
        for j, (name, col) in enumerate((("v_x [m/s]", "tab:blue"), ("v_y [m/s]", "tab:green"),
                                         ("ω [rad/s]", "tab:red"))):
            ax_e.plot(eps, ev[:, j], "o-", ms=3, color=col, label=name)
            ax_e.axhline(values["coulomb_balance"][j], color=col, ls="--", lw=0.8)
            ax_e.axhline(values["viscous_balance"][j], color=col, ls=":", lw=0.8)
        ax_e.set_xscale("log")
        ax_e.set_xlabel("ε of eq. 3.14 [m/s]  (dashed: Coulomb, dotted: viscous-Coulomb)")
        ax_e.set_ylabel("balance body velocity")
        ax_e.set_title("(d) eq. 3.14: from viscous-Coulomb (ε → ∞) to Coulomb (ε → 0)")
        ax_e.legend(fontsize=7)
    # random robots
    for n in Ns:
        ax_n.plot(spreads, med[n], "o-", ms=3.5, label=f"N = {n} legs on a circle")
    ax_n.plot(spreads, values["compare_median_per_spread"] * np.array(spreads), "k:", lw=1,
              label=f"{values['compare_median_per_spread']:.2f} × spread")
    ax_n.axhline(SIMILAR, color="k", ls="--", lw=0.8)
    ax_n.axvline(0.2, color="0.5", ls=":", lw=0.8)
    ax_n.set_xlabel("spread of the foot velocities around (−1, 0) m/s [m/s per component]")
    ax_n.set_ylabel("‖Δ(v_x, v_y, R ω)‖ / mean foot speed (median of 200)")
    ax_n.set_title("(e) beyond one robot: how far apart the two balances are")
    ax_n.legend(fontsize=7)
    ax_t.axis("off")
    lines = [
        "This robot (panels a–c):",
        f"  viscous balance   (v_x, v_y, ω) = ({values['viscous_balance'][0]:.3f}, "
        f"{values['viscous_balance'][1]:.3f}, {values['viscous_balance'][2]:.3f})",
        f"  Coulomb balance   (v_x, v_y, ω) = ({values['coulomb_balance'][0]:.3f}, "
        f"{values['coulomb_balance'][1]:.3f}, {values['coulomb_balance'][2]:.3f})",
        f"  apart by {values['balance_distance']:.3f} m/s (with L ω, L = {L:.2f} m)",
        f"  = {values['balance_rel_distance']:.0%} of the mean foot speed {mean_speed:.3f} m/s",
        f"  foot velocities spread {values['rest_velocity_spread']:.0%} of their mean speed",
        "",
        f"‖Σ F‖² fitted by a quadratic in (V_x, V_y): max residual",
        f"  viscous-Coulomb {values['viscous_F2_quadratic_residual']:.1e},  "
        f"Coulomb {values['coulomb_F2_quadratic_residual']:.2f}",
        "",
        "Random robots (panel e), spread 0.2 m/s:",
        f"  median {values.get('compare_spread02_median_rel_diff', float('nan')):.1%}, "
        f"90th percentile {values.get('compare_spread02_p90_rel_diff', float('nan')):.1%}",
    ]
    ax_t.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace", fontsize=7.6,
              transform=ax_t.transAxes)
    fig.suptitle("Fig. 3.2: a 4-legged robot slipping under Coulomb or viscous-Coulomb friction "
                 "(dots: body velocities that put a foot at rest, colour as in c; stars: "
                 "balances)", fontsize=10)
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
