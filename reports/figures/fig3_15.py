#!/usr/bin/python3
"""Thesis Fig. 3.15 / §3.6.2: relative error of viscous-type friction against Coulomb friction.

Input: DATA/ch3_legged/fig3_15.csv (kind legged_eps_error: one foot, μF_z = 1, sliding at
v + δv near v = (1, 0); rel_error = |F − F_C| / |F_C| for the model force F calibrated to equal
F_C at δv = 0). Models: "viscous" (the viscous-Coulomb ansatz, F = −u/|v|), "tangent" (the
Coulomb force linearized at v) and "epsilon" (eq. 3.14). Output: OUT/fig3_15.png,
OUT/values/fig3_15.json.

The thesis: "with |δv| < 0.2|v|, the viscous-Coulomb force prediction for velocity v + δv will be
within 2 % of the classical Coulomb friction force prediction".
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import legged as lg  # noqa: E402

NAME = "fig3_15"
RADIUS = 0.2  # |δv| < 0.2 |v|
TOL = 0.02    # within 2 %
LEVELS = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3]
LABEL = {"viscous": "viscous-Coulomb ansatz F = −μF_z u/|v|",
         "tangent": "Coulomb force linearized at v"}


def grid(t: c.Table, model: str):
    m = (t.str("model") == model) & (t.str("shape") == "grid")
    if not m.any():
        c.fail(f"{t.path}: no grid rows for model {model}")
    x, y, e = t["dvx"][m], t["dvy"][m], t["rel_error"][m]
    xs, ys = np.unique(x), np.unique(y)
    o = np.lexsort((x, y))
    return xs, ys, e[o].reshape(ys.size, xs.size)


def circle_max(t: c.Table, m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Radii |δv|/|v| and the largest error on each circle (polar rows m)."""
    r = np.round(t["dv_rel"][m], 12)
    e = t["rel_error"][m]
    radii = np.unique(r)
    return radii, np.array([e[r == x].max() for x in radii])


def disk_max(radii, cmax, radius: float) -> float:
    """Largest error over the disk |δv| ≤ radius|v| (the errors grow with |δv| along each ray,
    so the sampled circles up to the radius hold it)."""
    return float(cmax[radii <= radius + 1e-12].max())


def within(radii, cmax, tol: float) -> float:
    """The largest sampled radius whose whole disk stays within tol."""
    ok = np.maximum.accumulate(cmax) <= tol
    return float(radii[ok].max()) if ok.any() else 0.0


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = lg.table(args.data, NAME, ["model", "epsilon", "speed", "shape", "dvx", "dvy", "dv_rel",
                                   "rel_error"])
    model, shape = t.str("model"), t.str("shape")
    values: dict = {"radius": RADIUS, "tolerance": TOL}
    curves = {}
    for m in ("viscous", "tangent"):
        sel = (model == m) & (shape == "polar")
        if not sel.any():
            c.fail(f"{t.path}: no polar rows for model {m}")
        radii, cmax = circle_max(t, sel)
        curves[m] = (radii, cmax)
        values[f"{m}_max_err_r02"] = disk_max(radii, cmax, RADIUS)
        values[f"{m}_radius_within_2pc"] = within(radii, cmax, TOL)
        # along the sliding direction and across it, at |δv| = 0.2|v|
        g = (model == m) & (shape == "grid")
        for name, (dx, dy) in (("along", (RADIUS, 0.0)), ("back", (-RADIUS, 0.0)),
                               ("across", (0.0, RADIUS))):
            k = g & np.isclose(t["dvx"], dx, atol=1e-9) & np.isclose(t["dvy"], dy, atol=1e-9)
            values[f"{m}_err_{name}_r02"] = float(t["rel_error"][k][0]) if k.any() else None
    values["viscous_within_2pc_at_r02"] = bool(values["viscous_max_err_r02"] <= TOL)
    values["tangent_within_2pc_at_r02"] = bool(values["tangent_max_err_r02"] <= TOL)
    # ε-family on the circle |δv| = 0.2|v|
    em = (model == "epsilon") & (shape == "polar")
    eps = np.unique(t["epsilon"][em])
    e_max = np.array([t["rel_error"][em & (t["epsilon"] == x)].max() for x in eps])
    values["eps_values"] = eps.tolist()
    values["eps_max_err_r02"] = e_max.tolist()
    if eps.size:
        values["eps_smallest"], values["eps_largest"] = float(eps[0]), float(eps[-1])
        values["eps_smallest_max_err_r02"] = float(e_max[0])
        values["eps_largest_max_err_r02"] = float(e_max[-1])
        values["eps_largest_minus_viscous"] = float(abs(e_max[-1] - values["viscous_max_err_r02"]))
        ok = e_max <= TOL
        values["eps_largest_within_2pc"] = float(eps[ok].max()) if ok.any() else None
        values["eps_limits_ok"] = bool(values["eps_smallest_max_err_r02"] <= 1e-2 and
                                       values["eps_largest_minus_viscous"] <= 1e-3)

    # ---- figure ---------------------------------------------------------------------------------
    fig, axs = plt.subplots(2, 2, figsize=(12.5, 11.5))
    th = np.linspace(0, 2 * np.pi, 200)
    for ax, m, tag in ((axs[0, 0], "viscous", "a"), (axs[0, 1], "tangent", "b")):
        xs, ys, E = grid(t, m)
        cf = ax.contourf(xs, ys, E, levels=[0] + LEVELS + [max(1.0, float(E.max()))],
                         cmap="magma_r")
        cs = ax.contour(xs, ys, E, levels=LEVELS, colors="k", linewidths=0.6)
        # the viscous map's small levels crowd along δv_x = 0: label from 5 % up there
        ax.clabel(cs, levels=[x for x in LEVELS if m != "viscous" or x >= 0.05],
                  fmt=lambda v: f"{v:.1%}", fontsize=9.5)
        ax.contour(xs, ys, E, levels=[TOL], colors="tab:cyan", linewidths=2.2)
        ax.plot(RADIUS * np.cos(th), RADIUS * np.sin(th), "w--", lw=1.5)
        ax.plot(0, 0, "w+", ms=10)
        ax.set_aspect("equal")
        ax.set_xlabel("δv_x / |v|  (along the sliding direction)")
        ax.set_ylabel("δv_y / |v|  (across it)")
        ax.set_title(f"({tag}) {LABEL[m]}\nlargest error for |δv| ≤ 0.2|v| (dashed): "
                     f"{values[f'{m}_max_err_r02']:.2%}\ncyan: the 2 % contour")
        fig.colorbar(cf, ax=ax, label="|F − F_C| / |F_C|", ticks=LEVELS)
    ax = axs[1, 0]
    for m, col in (("viscous", c.VISCOUS), ("tangent", c.COULOMB)):
        radii, cmax = curves[m]
        ax.plot(radii, cmax, "o-", ms=4, lw=1.6, color=col, label=f"{LABEL[m]}")
    ax.axhline(TOL, color="k", ls="--", lw=0.8, label="2 %")
    ax.axvline(RADIUS, color="0.5", ls=":", lw=0.8)
    ax.set_yscale("log")
    ax.set_ylim(1e-4, 0.5)
    ax.set_xlabel("|δv| / |v|")
    ax.set_ylabel("largest |F − F_C| / |F_C| on the circle |δv|")
    ax.set_title("(c) largest error on each circle |δv|: the viscous\nansatz errs to first order "
                 "(along v), the linearized\nCoulomb force to second order")
    ax.legend(loc="lower right")
    ax = axs[1, 1]
    if eps.size:
        ax.plot(eps, e_max, "o-", ms=4, lw=1.6, color=c.REFERENCE,
                label="eq. 3.14, calibrated at v")
        ax.axhline(values["viscous_max_err_r02"], color=c.VISCOUS, ls=":", lw=1.5,
                   label=f"viscous-Coulomb (ε → ∞): {values['viscous_max_err_r02']:.1%}")
        ax.axhline(TOL, color="k", ls="--", lw=0.8, label="2 %")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(1e-4, 0.5)
        ax.set_xlabel("ε of eq. 3.14 [m/s]  (|v| = 1 m/s)")
        ax.set_ylabel("largest error for |δv| ≤ 0.2|v|")
        ax.set_title("(d) the ε-family: Coulomb (ε → 0)\nto viscous-Coulomb (ε → ∞)")
        ax.legend(loc="lower right")
    fig.suptitle("Fig. 3.15: error of viscous-type friction against Coulomb friction around the "
                 "sliding velocity v = (1, 0) (one foot, μF_z = 1)")
    fig.tight_layout(rect=(0, 0, 1, 0.97), h_pad=2.0)
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
