#!/usr/bin/python3
"""Thesis Fig. 3.1 / §3.1.2: the 1-D example, Coulomb = −median, viscous-Coulomb = −mean.

Input: DATA/ch3_legged/fig3_1.csv (kind legged_1d: N feet on the body's x axis with equal loads,
foot i sliding relative to the body at v_i; both balances by the library's 2-D solvers) and its
sidecar (the given speeds of the two illustrations). Output: OUT/fig3_1.png,
OUT/values/fig3_1.json.

Panels: (a, b) the total friction force against the body velocity v_B for the given odd and
even examples, Coulomb (staircase) and viscous-Coulomb (line), with the solvers' balances;
(c) how far the viscous balance (−mean) lies from the Coulomb one (−median, or the interval for
even N), in units of the speeds' standard deviation, over 200 random draws per N and
distribution; (d) §3.1.2.3: all feet at one speed plus noise — how much each balance moves per
unit of noise.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import legged as lg  # noqa: E402

NAME = "fig3_1"
DISTS = ("uniform", "normal", "exponential")
# the three speed distributions have no thesis meaning: categorical colours, none of the laws'
COLOR = {"uniform": c.CATEGORICAL[0], "normal": c.CATEGORICAL[1], "exponential": c.CATEGORICAL[2]}
CLOSE = 0.25  # "quite close": within a quarter of the speeds' standard deviation


def speeds_of(inputs: dict, pid: int) -> np.ndarray:
    return np.array([float(x) for x in str(inputs[pid]["speeds"]).split(",")])


def force_curves(ax, v: np.ndarray, v_c: float, v_v: float, lo: float, hi: float, title: str):
    """Σ of −(1/N) sign(v_B + v_i) and −(1/N)(v_B + v_i) over v_B."""
    n = v.size
    span = np.ptp(v) if np.ptp(v) > 0 else 1.0
    vb = np.linspace(-v.max() - 0.25 * span, -v.min() + 0.25 * span, 2001)
    coul = -np.sign(vb[:, None] + v[None, :]).sum(axis=1) / n
    visc = -(vb[:, None] + v[None, :]).sum(axis=1) / n
    ax.axhline(0, color="0.5", lw=0.8)
    ax.plot(vb, coul, color=c.COULOMB, lw=1.8, label="Coulomb: −(μN/N) Σ sign(v_B + v_i)")
    ax.plot(vb, visc, color=c.VISCOUS, lw=1.8, label="viscous-Coulomb: −(μN/N) Σ (v_B + v_i)")
    for x in -v:
        ax.axvline(x, color="0.8", lw=0.7, ls=":")
    if hi > lo:
        ax.axvspan(lo, hi, color=c.COULOMB, alpha=0.12,
                   label=f"Coulomb balances [{lo:g}, {hi:g}] (not unique)")
    ax.plot([v_c], [0], "o", ms=9, mfc="none", mec=c.COULOMB, mew=2,
            label=f"solve_coulomb: {v_c:.4g} (−median {-np.median(v):.4g})")
    ax.plot([v_v], [0], "*", ms=13, color=c.VISCOUS,
            label=f"solve_viscous_coulomb: {v_v:.4g} (−mean {-np.mean(v):.4g})")
    ax.set_xlabel("body velocity v_B [m/s]  (dotted: −v_i, where foot i is at rest)")
    ax.set_ylabel("total friction force / μN")
    ax.set_title(title)
    lo_y = min(coul.min(), visc.min())
    ax.set_ylim(lo_y - 1.2, max(coul.max(), visc.max()) + 0.15)  # room for the legend below
    ax.legend(loc="lower left")


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = lg.table(args.data, NAME, ["id", "N", "trial", "distribution", "scale", "offset",
                                   "v_coulomb", "v_viscous", "neg_median", "neg_mean",
                                   "interval_lo", "interval_hi", "in_interval", "unique",
                                   "static_feet", "w_coulomb", "speed_sd", "speed_range",
                                   "converged"])
    inputs = lg.point_inputs(lg.sidecar(args.data, NAME))
    dist = t.str("distribution")
    N = t["N"].astype(int)
    vc, vv = t["v_coulomb"], t["v_viscous"]
    med, mean = t["neg_median"], t["neg_mean"]
    lo, hi = t["interval_lo"], t["interval_hi"]
    rng = np.maximum(t["speed_range"], 1e-300)
    sd = t["speed_sd"]
    offset = t["offset"]
    values: dict = {"converged_fraction": float(np.mean(t["converged"] == 1)), "rows": t.n}

    # ---- the random draws (offset 0): the claims of §3.1.2.1-2 ---------------------------------
    rnd = np.isin(dist, DISTS) & (offset == 0)
    odd, even = rnd & (N % 2 == 1), rnd & (N % 2 == 0)
    values["odd_trials"], values["even_trials"] = int(odd.sum()), int(even.sum())
    if not odd.any() or not even.any():
        c.fail(f"{t.path}: needs random trials (offset 0) with odd and even N")
    d_med = np.abs(vc - med) / rng
    values["coulomb_median_max_rel_diff"] = float(d_med[odd].max())
    values["coulomb_is_median"] = bool(d_med[odd].max() <= 1e-7)
    values["even_in_interval_fraction"] = float(np.mean(t["in_interval"][even] == 1))
    values["even_nonunique_fraction"] = float(np.mean(t["unique"][even] == 0))
    values["odd_unique_fraction"] = float(np.mean(t["unique"][odd] == 1))
    values["even_interval_and_nonunique"] = bool(values["even_in_interval_fraction"] == 1.0
                                                 and values["even_nonunique_fraction"] == 1.0)
    d_mean = np.abs(vv - mean) / rng
    values["viscous_mean_max_rel_diff"] = float(d_mean[rnd].max())
    values["viscous_is_mean"] = bool(d_mean[rnd].max() <= 1e-12)
    values["rotation_max"] = float(np.nanmax(np.abs(t["w_coulomb"][rnd])))
    # distance from −mean to the Coulomb set (a point or an interval), in standard deviations
    with np.errstate(divide="ignore", invalid="ignore"):
        gap = np.maximum(np.maximum(lo - vv, vv - hi), 0.0) / sd
    values["close_threshold_sd"] = CLOSE
    Ns = sorted(set(N[rnd].tolist()))
    values["N_values"] = Ns
    for d in DISTS:
        m = rnd & (dist == d)
        values[f"gap_sd_median_{d}"] = float(np.median(gap[m]))
        values[f"close_fraction_{d}"] = float(np.mean(gap[m] < CLOSE))
        values[f"gap_sd_median_by_N_{d}"] = [float(np.median(gap[m & (N == n)])) for n in Ns]
    sym = rnd & np.isin(dist, ("uniform", "normal"))
    values["close_fraction_symmetric"] = float(np.mean(gap[sym] < CLOSE))
    values["close_fraction_all"] = float(np.mean(gap[rnd] < CLOSE))
    big = rnd & (N >= 16)
    values["gap_sd_median_exponential_N16plus"] = float(np.median(gap[big & (dist == "exponential")]))
    values["exponential_mean_minus_median_limit_sd"] = float(1.0 - np.log(2.0))

    # ---- §3.1.2.3: equal speeds, then equal speeds + noise ---------------------------------------
    given = dist == "given"
    eq_ids = [pid for pid, p in inputs.items() if "speeds" in p
              and len(set(float(x) for x in str(p["speeds"]).split(","))) == 1]
    eq = given & np.isin(t["id"].astype(int), eq_ids)
    if eq.any():
        target = np.array([-speeds_of(inputs, int(i))[0] for i in t["id"][eq]])
        values["equal_viscous_max_abs_err"] = float(np.max(np.abs(vv[eq] - target)))
        values["equal_coulomb_max_abs_err"] = float(np.max(np.abs(vc[eq] - target)))
        values["equal_coulomb_all_static"] = bool(np.all(t["static_feet"][eq] == N[eq]))
    noise = (offset != 0) & np.isfinite(offset) & ~given
    scales = sorted(set(t["scale"][noise].tolist()))
    values["noise_scales"] = scales
    amp_c = np.abs(vc + offset) / t["scale"]
    amp_v = np.abs(vv + offset) / t["scale"]
    # The exact answers (−median, −mean) move by as much: the ratio to them is the solver's share.
    amp_med = np.abs(med + offset) / t["scale"]
    if noise.any():
        values["noise_coulomb_amplification_max"] = float(amp_c[noise].max())
        values["noise_viscous_amplification_max"] = float(amp_v[noise].max())
        values["noise_median_amplification_max"] = float(amp_med[noise].max())
        values["noise_coulomb_vs_median_max_over_noise"] = float(
            (np.abs(vc - np.clip(vc, lo, hi)) / t["scale"])[noise].max())
        values["noise_coulomb_amplification_max_by_scale"] = [float(amp_c[noise & (t["scale"] == s)].max())
                                                           for s in scales]
        values["noise_viscous_amplification_max_by_scale"] = [float(amp_v[noise & (t["scale"] == s)].max())
                                                           for s in scales]

    # ---- figure -----------------------------------------------------------------------------------
    fig, axs = plt.subplots(2, 2, figsize=(13, 10.5))
    ex = [pid for pid in sorted(inputs) if "speeds" in inputs[pid] and pid not in eq_ids]
    for ax, pid, tag in zip(axs[0], ex[:2], ("a", "b")):
        row = np.flatnonzero(t["id"] == pid)[0]
        v = speeds_of(inputs, pid)
        kind = "odd" if v.size % 2 else "even"
        force_curves(ax, v, vc[row], vv[row], lo[row], hi[row],
                     f"({tag}) N = {v.size} ({kind}), foot speeds v_i = {', '.join(f'{x:g}' for x in v)}")
        values[f"example_{kind}_v_coulomb"] = float(vc[row])
        values[f"example_{kind}_v_viscous"] = float(vv[row])
        values[f"example_{kind}_neg_median"] = float(med[row])
        values[f"example_{kind}_neg_mean"] = float(mean[row])
    ax = axs[1, 0]
    for d in DISTS:
        m = rnd & (dist == d)
        for parity, ls, mk in ((1, "-", "o"), (0, "--", "s")):
            ns = [n for n in Ns if n % 2 == parity]
            med_gap = [float(np.median(gap[m & (N == n)])) for n in ns]
            label = (f"{d}: {values[f'close_fraction_{d}']:.0%} of draws < {CLOSE} σ"
                     if parity == 1 else None)
            ax.plot(ns, med_gap, ls=ls, marker=mk, color=COLOR[d], ms=4.5, lw=1.6, label=label)
    ax.plot([], [], "-o", color=c.REFERENCE, ms=4.5, label="odd N: |mean − median| / σ")
    ax.plot([], [], "--s", color=c.REFERENCE, ms=4.5,
            label="even N: −mean to the Coulomb interval / σ")
    ax.axhline(CLOSE, color=c.REFERENCE, ls=":", lw=0.9)
    ax.axhline(1 - np.log(2), color=COLOR["exponential"], ls=":", lw=0.9)
    ax.text(2, 1 - np.log(2), "exponential, N → ∞: 1 − ln 2", ha="left", va="bottom",
            color=COLOR["exponential"])
    ax.set_xscale("log", base=2)
    # every N up to 8, then the powers of two, and the largest unless one of those is near it:
    # labels that do not collide
    ticks = sorted({n for n in Ns if n <= 8 or n & (n - 1) == 0})
    if Ns[-1] > 1.3 * ticks[-1]:
        ticks.append(Ns[-1])
    ax.set_xticks(ticks)
    ax.set_xticklabels([str(n) for n in ticks])
    ax.minorticks_off()
    ax.set_xlabel("number of feet N (speeds uniform on [−1, 1], standard normal, or exponential)")
    ax.set_ylabel("(viscous − Coulomb balance) / σ of the speeds")
    ax.set_title("(c) how close −mean is to the Coulomb balance\n(median of 200 random draws per "
                 "N and distribution)")
    ax.set_ylim(0, 0.75)
    ax.legend(loc="upper right")
    ax = axs[1, 1]
    if noise.any():
        for k, s_ in enumerate(scales):
            m = noise & (t["scale"] == s_)
            jit = np.linspace(-0.12, 0.12, int(m.sum()))
            ax.plot(k - 0.2 + jit, amp_c[m], ".", ms=3, alpha=0.45, color=c.COULOMB,
                    label="Coulomb (solve_coulomb)" if k == 0 else None)
            ax.plot(k + 0.2 + jit, amp_v[m], ".", ms=3, alpha=0.45, color=c.VISCOUS,
                    label="viscous-Coulomb" if k == 0 else None)
        ax.set_xticks(range(len(scales)))
        ax.set_xticklabels([f"σ = {s_:g} m/s" for s_ in scales])
        ax.set_xlim(-0.6, len(scales) - 0.4)
        ax.set_ylim(0, 2.0 * max(values["noise_coulomb_amplification_max"],
                                  values["noise_viscous_amplification_max"]))
        ax.set_xlabel("noise σ on the feet's common speed 1 m/s (N = 4, 5, 6; 200 draws each)")
        ax.set_ylabel("|v_B − (−1 m/s)| / σ")
        ax.set_title("(d) §3.1.2.3: all feet at one speed (no foot slips) plus noise")
        ax.legend(markerscale=4, loc="upper right")
        ax.text(0.02, 0.97,
                f"equal speeds: both give −v_1\n(errors "
                f"{values.get('equal_coulomb_max_abs_err', float('nan')):.1g} and "
                f"{values.get('equal_viscous_max_abs_err', float('nan')):.1g} m/s)\n"
                "with noise, at every σ:\n"
                f"Coulomb moves ≤ {values['noise_coulomb_amplification_max']:.2g} σ, "
                f"viscous ≤ {values['noise_viscous_amplification_max']:.2g} σ\n"
                f"solve_coulomb within {values['noise_coulomb_vs_median_max_over_noise']:.2g} σ"
                "\nof the exact Coulomb set",
                transform=ax.transAxes, va="top")
    fig.suptitle("Fig. 3.1: a body on the x axis driven by N feet with equal loads — Coulomb "
                 "friction balances at −median(v_i), viscous-Coulomb at −mean(v_i)")
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
