#!/usr/bin/python3
"""Thesis Fig. 2.7: v_ss vs F for μ = 0.1, 0.6, 1.0, dm model α = 1, 5, 10 and the instant swap.

Input: DATA/ch2_dm_swap/fig2_7.csv (the dm model by event-driven simulation, "analytic", and by
its closed form, "exact", where that is available; the instant swap by its closed form). Points
are the simulation; each (μ, α) curve gets a least-squares line per stroke regime (one mass
moving: F ≤ μ_s M g; two masses moving) and, where the "stop during swap" regime covers part of
a stroke regime, per (regime, stop) segment as well. Output: OUT/fig2_7.png,
OUT/values/fig2_7.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import re

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig2_7"
STUDY = "ch2_dm_swap"
ALPHAS = (1.0, 5.0, 10.0)
# the fitted lines: a colour apart from the thesis' black and greys (red is kept for measured data)
FIT_COLOR = "tab:blue"
MARKER = {1.0: ".", 5.0: "+", 10.0: "*"}
# the thesis' styles, with the caption's first "μ = 1 (black)" read as μ = 0.1 (see the ledger)
STYLE = {0.1: dict(color="k", lw=1.0), 0.6: dict(color="0.45", lw=2.2),
         1.0: dict(color="0.62", lw=1.0)}
CAPTION_ID = "fig2.7-caption-mu"


def key(x: float) -> str:
    return f"{x:g}"


def label(name: str) -> str:
    """'mu1_a10_R2_nostop' -> 'μ = 1, α = 10, two masses moving, no stop'"""
    out = []
    for part in name.split("_"):
        if part.startswith("mu"):
            out.append(f"μ = {part[2:]}")
        elif part.startswith("a") and part[1:2].isdigit():
            out.append(f"α = {part[1:]}")
        elif part in ("R1", "R2"):
            out.append("one mass moving" if part == "R1" else "two masses moving")
        elif part in ("stop", "nostop"):
            out.append("stop during swap" if part == "stop" else "no stop")
        else:
            out.append(part)
    return ", ".join(out)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    path = c.study_file(args.data, "fig2_7.csv", STUDY)
    t = c.Table(path, c.SWEEP_COLUMNS + ["regime", "model", "alpha", "swap_stopped", "message"])
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    model, method = t["model"], t["method"]
    mu_all, F_all, v_all = t["mu"], t["F"], t["v_ss"]
    alpha_all, stop_all, reg_all = t["alpha"], t["swap_stopped"], t["regime"]
    ok = t["converged"] == 1
    mus = sorted({round(float(m), 12) for m in mu_all})
    dm = model == "dm"
    ana = dm & (method == "analytic")
    ex_dm = dm & (method == "exact")
    inst = (model == "instant") & (method == "exact") & ok
    if not np.any(ana):
        c.fail(f"{path}: no dm rows by the method 'analytic'")
    if not np.any(inst):
        c.fail(f"{path}: no instant-swap rows by the method 'exact'")

    values: dict = {"mus": mus, "alphas": list(ALPHAS)}
    values["dm_converged_fraction"] = float(np.mean(ok[ana]))
    values["n_dm_analytic"] = int(np.sum(ana))
    # the dm closed form, where it is available, is the reference for the simulation
    ex_ok = ex_dm & ok
    values["dm_exact_available"] = bool(np.any(ex_ok))
    values["dm_exact_converged_fraction"] = float(np.mean(ok[ex_dm])) if np.any(ex_dm) else None
    if np.any(ex_dm) and not np.any(ex_ok):
        msgs = sorted({str(m) for m in t["message"][ex_dm]})
        values["dm_exact_unavailable_reason"] = "; ".join(msgs)[:300]
    rel, stop_diff, reg_diff = [], 0, 0
    if np.any(ex_ok):
        idx = {(round(mu_all[i], 12), round(F_all[i], 12), alpha_all[i]): i
               for i in np.flatnonzero(ex_ok)}
        for i in np.flatnonzero(ana & ok):
            j = idx.get((round(mu_all[i], 12), round(F_all[i], 12), alpha_all[i]))
            if j is None:
                continue
            rel.append(abs(v_all[i] - v_all[j]) / abs(v_all[j]))
            stop_diff += int(stop_all[i] != stop_all[j])
            reg_diff += int(reg_all[i] != reg_all[j])
        values["analytic_vs_exact_max_rel_diff"] = float(max(rel)) if rel else None
        values["analytic_vs_exact_pairs"] = len(rel)
        values["analytic_vs_exact_class_disagreements"] = stop_diff + reg_diff
    else:
        values["analytic_vs_exact_max_rel_diff"] = None
        values["analytic_vs_exact_pairs"] = 0
        values["analytic_vs_exact_max_rel_diff_reason"] = values.get(
            "dm_exact_unavailable_reason", "no exact rows")

    # --- the stop-during-swap regime: where it appears, against αF ≤ μ g (2m + Δm)
    sim = ana & ok
    predicted = alpha_all * F_all <= mu_all * c.G * (2 * c.m + (c.M - c.m))
    values["stop_points"] = {f"mu{key(mu)}_a{key(a)}": int(np.sum(
        sim & np.isclose(mu_all, mu) & (alpha_all == a) & (stop_all == 1)))
        for mu in mus for a in ALPHAS}
    values["stop_points_total"] = int(np.sum(sim & (stop_all == 1)))
    counts = values["stop_points"]
    values["stop_points_text"] = "; ".join(
        f"μ = {key(mu)}: " + ", ".join(f"α = {key(a)} {counts[f'mu{key(mu)}_a{key(a)}']}"
                                       for a in ALPHAS) for mu in mus)
    values["stop_matches_condition_fraction"] = float(np.mean((stop_all[sim] == 1) ==
                                                              predicted[sim]))
    values["stop_regime_appears"] = bool(
        values["stop_points_total"] > 0 and values["stop_matches_condition_fraction"] == 1.0)
    for mu in mus:
        s = sim & np.isclose(mu_all, mu) & (alpha_all == 1.0) & (stop_all == 1)
        values[f"mu{key(mu)}_a1_stop_F_max"] = float(np.max(F_all[s])) if np.any(s) else None
        values[f"mu{key(mu)}_a1_stop_F_bound"] = mu * c.G * (2 * c.m + (c.M - c.m))

    # --- fits: per (μ, α or instant, stroke regime), and per (regime, stop) segment
    fits: dict = {}
    seg_fits: dict = {}
    r2_by_regime: dict = {1: [], 2: []}
    r2_seg_by_regime: dict = {1: [], 2: []}
    nostop_minus_instant = []

    def fit_of(mask):
        return c.linfit(F_all[mask], v_all[mask])

    for mu in mus:
        m_mu = np.isclose(mu_all, mu, rtol=0, atol=1e-12)
        for reg in (1, 2):
            ri = inst & m_mu & (reg_all == reg)
            fi = fit_of(ri)
            fits[f"mu{key(mu)}_instant_R{reg}"] = fi
            for a in ALPHAS:
                base = sim & m_mu & (alpha_all == a) & (reg_all == reg)
                f = fit_of(base)
                name = f"mu{key(mu)}_a{key(a)}_R{reg}"
                fits[name] = f
                if f["r2"] is not None:
                    r2_by_regime[reg].append((f["r2"], name))
                for stop in (0, 1):
                    sm = base & (stop_all == stop)
                    if np.sum(sm) == 0:
                        continue
                    fs = fit_of(sm)
                    sname = f"{name}_{'stop' if stop else 'nostop'}"
                    seg_fits[sname] = fs
                    if fs["r2"] is not None:
                        r2_seg_by_regime[reg].append((fs["r2"], sname))
                    if stop == 0 and fs["r2"] is not None and fi["r2"] is not None:
                        # the same forces for the instant swap
                        Fs = F_all[sm]
                        im = ri & np.isin(np.round(F_all, 9), np.round(Fs, 9))
                        fi_same = fit_of(im)
                        if fi_same["r2"] is not None:
                            nostop_minus_instant.append(
                                (fs["r2"] - fi_same["r2"], sname, fs["k"] > 0))
    values["fits"] = fits
    values["segment_fits"] = seg_fits
    for reg in (1, 2):
        lo = min(r2_by_regime[reg]) if r2_by_regime[reg] else (None, None)
        values[f"r2_R{reg}_min"], values[f"r2_R{reg}_min_at"] = lo[0], label(lo[1] or "")
        lo = min(r2_seg_by_regime[reg]) if r2_seg_by_regime[reg] else (None, None)
        values[f"r2_R{reg}_segments_min"] = lo[0]
        values[f"r2_R{reg}_segments_min_at"] = label(lo[1] or "")
        ins = [f["r2"] for k, f in fits.items() if "instant" in k and k.endswith(f"R{reg}")
               and f["r2"] is not None]
        values[f"r2_R{reg}_instant_min"] = min(ins) if ins else None
    # regime I without its lowest force (v_ss rises steeply just above μ m g, see Fig. 2.3)
    low_cut = []
    for mu in mus:
        for a in ALPHAS:
            sel = sim & np.isclose(mu_all, mu) & (alpha_all == a) & (reg_all == 1)
            if np.sum(sel) > 3:
                keep = sel & (F_all > np.min(F_all[sel]))
                f = fit_of(keep)
                if f["r2"] is not None:
                    low_cut.append(f["r2"])
    values["r2_R1_min_without_lowest_F"] = min(low_cut) if low_cut else None
    values["n_R1_per_curve"] = int(np.sum(sim & np.isclose(mu_all, mus[0]) &
                                          (alpha_all == 1.0) & (reg_all == 1)))
    values["min_F_over_mu_m_g"] = float(np.min(F_all[sim] / (mu_all[sim] * c.m * c.G)))
    if nostop_minus_instant:
        worst = min(nostop_minus_instant)
        values["nostop_r2_minus_instant_min"] = worst[0]
        values["nostop_r2_minus_instant_min_at"] = label(worst[1])
        values["nostop_slopes_positive"] = bool(all(p for _, _, p in nostop_minus_instant))
        values["nostop_r2_min"] = min(seg_fits[n]["r2"] for _, n, _ in nostop_minus_instant)
    # dm against the instant swap at the same force (no-stop points)
    rel_inst = []
    for i in np.flatnonzero(sim & (stop_all == 0)):
        j = np.flatnonzero(inst & np.isclose(mu_all, mu_all[i]) & np.isclose(F_all, F_all[i],
                                                                             rtol=1e-12))
        if j.size:
            rel_inst.append(((v_all[i] - v_all[j[0]]) / v_all[j[0]], i))
    if rel_inst:
        lo, hi = min(rel_inst), max(rel_inst)
        values["nostop_dm_vs_instant_rel_min"] = float(lo[0])
        values["nostop_dm_vs_instant_rel_max"] = float(hi[0])

        def at(i):
            return (f"μ = {key(mu_all[i])}, α = {key(alpha_all[i])}, F = {F_all[i]:.3g} N = "
                    f"{F_all[i] / (mu_all[i] * c.m * c.G):.3g} μmg")

        values["nostop_dm_vs_instant_rel_min_at"] = at(lo[1])
        values["nostop_dm_vs_instant_rel_max_at"] = at(hi[1])
    else:
        values["nostop_dm_vs_instant_rel_min"] = values["nostop_dm_vs_instant_rel_max"] = None

    # --- the caption's μ: three distinct curves in our data, two distinct values in the caption
    curves = {}
    F_common = None
    for mu in mus:
        s = inst & np.isclose(mu_all, mu)
        curves[mu] = (F_all[s], v_all[s])
        lo, hi = float(np.min(F_all[s])), float(np.max(F_all[s]))
        F_common = (lo, hi) if F_common is None else (max(F_common[0], lo), min(F_common[1], hi))
    grid = np.linspace(F_common[0], F_common[1], 50)
    gaps = []
    for i, a in enumerate(mus):
        for b in mus[i + 1:]:
            va = np.interp(grid, *sorted_xy(*curves[a]))
            vb = np.interp(grid, *sorted_xy(*curves[b]))
            gaps.append(float(np.mean(np.abs(va - vb) / np.maximum(va, vb))))
    values["distinct_mu_curves"] = len(mus)
    values["mu_curves_min_mean_rel_gap"] = min(gaps) if gaps else None
    caption = str(c.thesis(CAPTION_ID))
    caption_mus = [float(x) for x in re.findall(r"μ = ([0-9]+(?:\.[0-9]+)?)", caption)]
    if not caption_mus:
        c.fail(f"{c.LEDGER}: claim {CAPTION_ID}: no 'μ = <number>' in its thesis text")
    values["caption_mu_values"] = caption_mus
    values["caption_distinct_mu"] = len(set(caption_mus))
    values["caption_matches_curves"] = bool(
        len(set(caption_mus)) == len(mus) and (min(gaps) if gaps else 0) > 0.05)
    # at each force the speeds order with μ: which μ is slowest?
    at = {mu: float(np.interp(0.5 * sum(F_common), *sorted_xy(*curves[mu]))) for mu in mus}
    values["instant_v_at_common_F_by_mu"] = {key(mu): v for mu, v in at.items()}
    values["slowest_mu_at_common_F"] = min(at, key=at.get)

    # --- the figure: (a) the thesis' combined plot; (b–d) one panel per μ with the fits
    fig = plt.figure(figsize=(13.5, 11.0))
    gs = fig.add_gridspec(2, 3, height_ratios=[1.2, 1.0])
    ax0 = fig.add_subplot(gs[0, :])
    axs = [fig.add_subplot(gs[1, i]) for i in range(3)]

    def draw(ax, mu, with_fits: bool):
        st = STYLE.get(mu, dict(color="C0", lw=1.0))
        m_mu = np.isclose(mu_all, mu)
        s = inst & m_mu
        o = np.argsort(F_all[s])
        ax.plot(F_all[s][o], v_all[s][o], "--", color=st["color"], lw=st["lw"] * 0.9,
                label=f"μ = {mu:g}: instant swap" if with_fits else None)
        for a in ALPHAS:
            sel = sim & m_mu & (alpha_all == a)
            o = np.argsort(F_all[sel])
            Fa, va, sa = F_all[sel][o], v_all[sel][o], stop_all[sel][o]
            ms = 7 if MARKER[a] == "." else 5
            # the no-stop part: solid through the points; the stop part: dotted, big circles
            ax.plot(np.where(sa == 0, Fa, np.nan), np.where(sa == 0, va, np.nan), "-",
                    color=st["color"], lw=st["lw"] * 0.6, marker=MARKER[a], ms=ms,
                    label=f"α = {a:g}" if with_fits else None)
            if np.any(sa == 1):
                stop_idx = np.flatnonzero(sa == 1)
                # join the stop segment to its neighbour so the regime change is visible
                lo_i, hi_i = stop_idx.min(), min(stop_idx.max() + 1, len(Fa) - 1)
                ax.plot(Fa[lo_i:hi_i + 1], va[lo_i:hi_i + 1], ":", color=st["color"],
                        lw=st["lw"] * 0.9)
                ax.plot(Fa[sa == 1], va[sa == 1], "o", ms=6.5, mfc="none",
                        mec=st["color"], mew=1.0,
                        label="stop during swap" if (with_fits and a == 1.0) else None)
            if with_fits:
                for reg in (1, 2):
                    for stop in (0, 1):
                        f = seg_fits.get(f"mu{key(mu)}_a{key(a)}_R{reg}_"
                                         f"{'stop' if stop else 'nostop'}")
                        if not f or f["k"] is None:
                            continue
                        msk = (reg_all[sel][o] == reg) & (sa == stop)
                        xs = np.array([Fa[msk].min(), Fa[msk].max()])
                        ax.plot(xs, f["k"] * xs + f["b"], "-", color=FIT_COLOR, lw=0.9,
                                alpha=0.8)
        ax.axvline(mu * c.M * c.G, color=st["color"], lw=0.6, ls="-.", alpha=0.8)

    for mu in mus:
        draw(ax0, mu, False)
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=STYLE[mu]["color"], lw=STYLE[mu]["lw"], label=f"μ = {mu:g}")
               for mu in mus if mu in STYLE]
    handles += [Line2D([], [], color="k", ls="", marker=MARKER[a], ms=7 if a == 1.0 else 5,
                       label=f"α = {a:g}") for a in ALPHAS]
    handles += [Line2D([], [], color="k", ls="--", label="instant swap (closed form)"),
                Line2D([], [], color="k", ls=":", marker="o", mfc="none",
                       label="stop during swap"),
                Line2D([], [], color="k", ls="-.", lw=0.6, label="F = μMg (regime boundary)")]
    ax0.legend(handles=handles, loc="upper left", ncol=3)
    ax0.set_xlabel("F [N]")
    ax0.set_ylabel("v_ss [m/s]")
    ax0.set_title("(a) Fig. 2.7 — v_ss vs F, dm model (simulation) and instant swap; μ = 0.1 "
                  "black, 0.6 thick grey, 1.0 grey")
    for ax, mu in zip(axs, mus):
        draw(ax, mu, True)
        lines = []
        for a in ALPHAS:
            parts = []
            for reg in (1, 2):
                for stop in (1, 0):
                    f = seg_fits.get(f"mu{key(mu)}_a{key(a)}_R{reg}_{'stop' if stop else 'nostop'}")
                    if f and f["r2"] is not None:
                        parts.append(f"{'I' if reg == 1 else 'II'}{' stop' if stop else ''} "
                                     f"{c.fmt(f['r2'], 4)}")
            lines.append(f"α = {a:g}: " + ", ".join(parts))
        # the R² of every line, under the panel (inside it would hide points)
        txt = "R² per segment (regime, stop):\n" + "\n".join(lines)
        ax.text(0.0, -0.16, txt, transform=ax.transAxes, ha="left", va="top")
        ax.set_title(f"({'bcd'[mus.index(mu)]}) μ = {mu:g}: points and per-segment lines")
        ax.set_xlabel("F [N]")
        ax.set_ylabel("v_ss [m/s]")
        if mu == mus[0]:
            ax.legend(handles=[Line2D([], [], color=FIT_COLOR, lw=0.9,
                                      label="least-squares line\nper regime and stop segment")],
                      loc="upper left")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


def sorted_xy(x, y):
    o = np.argsort(x)
    return x[o], y[o]


if __name__ == "__main__":
    main()
