#!/usr/bin/python3
"""§2.5.2: the four motion regimes of the dm model over (F, α), simulated vs the two conditions.

Input: DATA/ch2_dm_swap/regime_map.csv (μ = 0.1, 0.6, 1.0; F log-spaced over (μmg, 5Mg], α
log-spaced 0.05–20; dm model by event-driven simulation, "analytic", and by its closed form,
"exact", where available). Each cell is classified by what the simulation did in its limit cycle:
the stroke regime (one mass moving: M stays stuck; two masses moving: M slides back) and whether
the m–m body stopped and stuck during a swap. On top, the analytic boundaries of §2.5.2:
F = μ_s M g and αF = μ g (2m + Δm). Output: OUT/regime_map.png, OUT/values/regime_map.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "regime_map"
STUDY = "ch2_dm_swap"
DM = c.M - c.m
CLASSES = [  # (regime, stopped) -> label, colour (blues and greens: red marks measured data)
    ((1, 1), "one mass moving, stop during swap", "#9ecae1"),
    ((1, 0), "one mass moving, no stop", "#2171b5"),
    ((2, 1), "two masses moving, stop during swap", "#a1d99b"),
    ((2, 0), "two masses moving, no stop", "#238b45"),
]


def class_index(regime: np.ndarray, stopped: np.ndarray) -> np.ndarray:
    out = np.full(regime.shape, -1)
    for i, ((r, s), _, _) in enumerate(CLASSES):
        out[(regime == r) & (stopped == s)] = i
    return out


def edges(centers: np.ndarray) -> np.ndarray:
    """Cell edges of log-spaced centres (geometric midpoints, ends mirrored)."""
    lc = np.log(centers)
    mid = 0.5 * (lc[1:] + lc[:-1])
    return np.exp(np.concatenate([[2 * lc[0] - mid[0]], mid, [2 * lc[-1] - mid[-1]]]))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    path = c.study_file(args.data, "regime_map.csv", STUDY)
    t = c.Table(path, c.SWEEP_COLUMNS + ["mu_s", "regime", "alpha", "swap_stopped", "model"])
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    if not np.all(t["model"] == "dm"):
        c.fail(f"{path}: expected only dm-model rows")
    method = t["method"]
    mu_all, mus_all, F_all, a_all = t["mu"], c.mu_static(t), t["F"], t["alpha"]
    ok = t["converged"] == 1
    sim = (method == "analytic")
    if not np.any(sim):
        c.fail(f"{path}: no rows by the method 'analytic'")
    ex = (method == "exact") & ok

    # the analytic conditions of §2.5.2
    regime_an = np.where(F_all <= mus_all * c.M * c.G, 1, 2)
    stop_an = np.where(a_all * F_all <= mus_all * c.G * (2 * c.m + DM), 1, 0)
    cls_sim = class_index(t["regime"], t["swap_stopped"])
    cls_an = class_index(regime_an, stop_an)

    values: dict = {"classes": [lab for _, lab, _ in CLASSES]}
    values["converged_fraction"] = float(np.mean(ok[sim]))
    mus = sorted({round(float(m), 12) for m in mu_all})
    values["mus"] = mus
    agree_all = []
    present = []
    mismatches = []
    for mu in mus:
        sel = sim & ok & np.isclose(mu_all, mu)
        agree = cls_sim[sel] == cls_an[sel]
        agree_all.append(agree)
        k = f"mu{mu:g}"
        values[f"{k}_cells"] = int(np.sum(sel))
        values[f"{k}_agreement"] = float(np.mean(agree))
        values[f"{k}_regime_agreement"] = float(np.mean(t["regime"][sel] == regime_an[sel]))
        values[f"{k}_stop_agreement"] = float(np.mean(t["swap_stopped"][sel] == stop_an[sel]))
        counts = {lab: int(np.sum(cls_sim[sel] == i)) for i, (_, lab, _) in enumerate(CLASSES)}
        values[f"{k}_class_counts"] = counts
        present.append(sum(1 for n in counts.values() if n > 0))
        for i in np.flatnonzero(sel)[~agree]:
            mismatches.append({"mu": mu, "F": F_all[i], "alpha": a_all[i],
                               "simulated": CLASSES[cls_sim[i]][1] if cls_sim[i] >= 0 else "?",
                               "analytic": CLASSES[cls_an[i]][1],
                               "alpha_F_over_body_friction":
                                   a_all[i] * F_all[i] / (mu_all[i] * c.G * (2 * c.m + DM))})
    allv = np.concatenate(agree_all)
    values["agreement_fraction"] = float(np.mean(allv))
    values["cells"] = int(allv.size)
    values["mismatch_count"] = len(mismatches)
    values["mismatches"] = mismatches[:40]
    values["classes_present_min"] = min(present)
    values["classes_present_per_mu"] = present
    # how close to the stop boundary the grid comes (the condition is sharp at the boundary)
    ratio = a_all[sim] * F_all[sim] / (mu_all[sim] * c.G * (2 * c.m + DM))
    values["closest_cell_to_stop_boundary"] = float(np.min(np.abs(np.log(ratio))))

    # exact (dm closed form) against the simulation, cell by cell
    if np.any(ex):
        idx = {(round(mu_all[i], 12), round(F_all[i], 12), round(a_all[i], 12)): i
               for i in np.flatnonzero(ex)}
        same, rel = [], []
        for i in np.flatnonzero(sim & ok):
            j = idx.get((round(mu_all[i], 12), round(F_all[i], 12), round(a_all[i], 12)))
            if j is not None:
                same.append(cls_sim[i] == cls_sim[j])
                rel.append(abs(t["v_ss"][i] - t["v_ss"][j]) / abs(t["v_ss"][j]))
        values["exact_cells"] = len(same)
        values["exact_class_agreement"] = float(np.mean(same)) if same else None
        values["exact_vs_analytic_max_rel_diff"] = float(max(rel)) if rel else None
    else:
        values["exact_cells"] = 0
        values["exact_class_agreement"] = None
        values["exact_class_agreement_reason"] = "the dm closed form ('exact') gave no result"
        values["exact_vs_analytic_max_rel_diff"] = None

    # --- figure
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    from matplotlib.lines import Line2D

    cmap = ListedColormap([col for _, _, col in CLASSES])
    fig, axes = plt.subplots(1, len(mus), figsize=(min(13.5, 4.5 * len(mus)), 5.6))
    axes = np.atleast_1d(axes)
    for ax, mu in zip(axes, mus):
        sel = sim & np.isclose(mu_all, mu)
        Fs = np.unique(F_all[sel])
        As = np.unique(a_all[sel])
        grid = np.full((As.size, Fs.size), np.nan)
        bad = np.zeros((As.size, Fs.size), bool)
        fi = np.searchsorted(Fs, F_all[sel])
        ai = np.searchsorted(As, a_all[sel])
        vals = np.where(ok[sel], cls_sim[sel], -1).astype(float)
        vals[vals < 0] = np.nan
        grid[ai, fi] = vals
        bad[ai, fi] = (cls_sim[sel] != cls_an[sel]) & ok[sel]
        ax.grid(False)
        if Fs.size > 1 and As.size > 1:
            ax.pcolormesh(edges(Fs), edges(As), grid, cmap=cmap, vmin=-0.5, vmax=3.5,
                          shading="flat")
        else:
            ax.scatter(F_all[sel], a_all[sel], c=vals, cmap=cmap, vmin=-0.5, vmax=3.5, s=40)
        if np.any(bad):
            yy, xx = np.nonzero(bad)
            ax.plot(Fs[xx], As[yy], "kx", ms=4, label="simulation ≠ conditions")
        mus_s = float(np.max(mus_all[sel]))
        Fb = mus_s * c.M * c.G
        ax.axvline(Fb, color="k", lw=1.4)
        Fl = np.geomspace(edges(Fs)[0], edges(Fs)[-1], 200)
        ax.plot(Fl, mus_s * c.G * (2 * c.m + DM) / Fl, "k--", lw=1.4)
        for a in (1.0, 5.0, 10.0):
            ax.axhline(a, color="white", lw=0.6, ls=":")
        if abs(mu - 1.0) < 1e-12:
            for F in (12.0, 20.0):
                ax.plot([F] * 3, [1.0, 5.0, 10.0], "o", ms=5, mfc="white", mec="k")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(edges(Fs)[0], edges(Fs)[-1])
        ax.set_ylim(edges(As)[0], edges(As)[-1])
        c.log_ticks(ax.xaxis, *ax.get_xlim())
        c.log_ticks(ax.yaxis, *ax.get_ylim())
        ax.set_xlabel("F [N]")
        ax.set_ylabel("α  (F_Δm = αF)")
        k = f"mu{mu:g}"
        ax.set_title(f"μ = {mu:g}: {values[k + '_agreement']:.1%} of {values[k + '_cells']} "
                     "cells as predicted")
    handles = [Patch(color=col, label=lab) for _, lab, col in CLASSES]
    handles += [Line2D([], [], color="k", lw=1.4, label="F = μ_s M g"),
                Line2D([], [], color="k", ls="--", lw=1.4, label="αF = μ g (2m + Δm)"),
                Line2D([], [], color="0.6", ls=":", label="α = 1, 5, 10 (Fig. 2.7)"),
                Line2D([], [], ls="", marker="o", mfc="white", mec="k",
                       label="Fig. 2.6 conditions")]
    if values["mismatch_count"]:
        handles.append(Line2D([], [], ls="", marker="x", color="k",
                              label="simulation ≠ conditions"))
    fig.legend(handles=handles, loc="lower center", ncol=4, frameon=False)
    fig.suptitle("§2.5.2 — motion regimes of the dm model (simulation, colours) and the two "
                 "analytic conditions (lines)", fontsize=11)
    fig.tight_layout(rect=(0, 0.12, 1, 0.95))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
