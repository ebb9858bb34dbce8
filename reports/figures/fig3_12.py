#!/usr/bin/python3
"""Thesis Fig. 3.12: a trotting quadruped with and without the IIR filter (synthetic analog).

Input: DATA/ch3_robots/trot_raw.csv (no filter) and trot_filter.csv (y_n = γy_{n−1} + (1−γ)x_n,
γ = 0.15 per 10 ms step, §3.5.2.2; its vx_model … are the unfiltered predictions of the same
run). Output: OUT/fig3_12.png, OUT/values/fig3_12.json.

Rows: v_x, v_y (only where it is not zero to rounding: a mirror-symmetric trot has none), ω, raw
(orange) and filtered (blue), the thesis' colours; bottom: the trajectories, and the power
spectral densities (Welch-style averaged periodograms) of v_x — the filter is a low-pass that
removes the model's spurious high-frequency content. The thesis' Spirit motion tracking (red) is
not ours; its γ was tuned to match that tracking's PSD.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_12"
HIGH_HZ = 10.0  # Hz: above twice the trot's 1 Hz harmonics of interest, "high frequency"


def psd(x: np.ndarray, dt: float, seg: int = 128) -> tuple[np.ndarray, np.ndarray]:
    """Averaged periodogram of 50 %-overlapping Hann-windowed segments (one-sided)."""
    x = np.asarray(x, float) - np.mean(x)
    seg = min(seg, x.size)
    win = np.hanning(seg)
    starts = range(0, x.size - seg + 1, max(1, seg // 2))
    spec = np.mean([np.abs(np.fft.rfft(win * x[s:s + seg])) ** 2 for s in starts], axis=0)
    spec *= 2.0 * dt / np.sum(win ** 2)
    return np.fft.rfftfreq(seg, dt), spec


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    raw = rb.Run(args.data, "trot_raw")
    flt = rb.Run(args.data, "trot_filter")
    gamma = float(flt.meta.get("scene", {}).get("filter", {}).get("gamma", float("nan")))
    t = raw.time
    values: dict = {"gamma": gamma, "dt": raw.dt}
    comps = (("vx", "heading velocity v_x [m/s]", 1.0), ("vy", "side velocity v_y [m/s]", 1.0),
             ("omega", "turning rate ω [deg/s]", 180 / np.pi))
    for col, _, _ in comps:
        # the same model velocity drives both runs (flat ground: the feet do not see the pose)
        values[f"model_same_{col}"] = bool(np.allclose(raw[col], flt[f"{col}_model"],
                                                       atol=1e-12))
        dv = np.diff(raw[col])
        df = np.diff(flt[col])
        values[f"step_change_rms_ratio_{col}"] = rb.rms(df) / max(rb.rms(dv), 1e-300)
    # a component that is zero to rounding in both runs (a mirror-symmetric trot: v_y) gets no
    # row of its own; the title says so
    vy_max = float(np.max(np.abs(np.r_[raw["vy"], flt["vy"]])))
    values["vy_max_abs"] = vy_max
    shown = [cp for cp in comps if cp[0] != "vy" or vy_max >= 1e-9]
    fig = plt.figure(figsize=(12, 3.0 * len(shown) + 4.0))
    gs = fig.add_gridspec(len(shown) + 1, 2, hspace=0.55, wspace=0.25,
                          height_ratios=[1] * len(shown) + [1.4], top=0.86, bottom=0.06,
                          left=0.08, right=0.98)
    for i, (col, title, scale) in enumerate(shown):
        a = fig.add_subplot(gs[i, :])
        a.plot(t, scale * raw[col], color=c.VISCOUS, lw=1.0)
        a.plot(flt.time, scale * flt[col], color=c.FILTERED, lw=1.3)
        a.set_title(title)
        a.set_xlabel("t [s]")
    a = fig.add_subplot(gs[-1, 0])
    a.plot(raw["x"], raw["y"], color=c.VISCOUS, lw=1.2)
    a.plot(flt["x"], flt["y"], color=c.FILTERED, lw=1.2, ls="--")
    a.set_aspect("equal", adjustable="datalim")
    a.set_xlabel("x [m]")
    a.set_ylabel("y [m]")
    a.set_title("trajectory")
    a = fig.add_subplot(gs[-1, 1])
    f, p_raw = psd(raw["vx"], raw.dt)
    _, p_flt = psd(flt["vx"], flt.dt)
    a.semilogy(f, p_raw, color=c.VISCOUS, lw=1.3)
    a.semilogy(f, p_flt, color=c.FILTERED, lw=1.3)
    # the filter's gain |1-γ| / |1 - γ e^{-iωdt}|, squared, times the raw PSD
    gain2 = (1 - gamma) ** 2 / np.abs(1 - gamma * np.exp(-2j * np.pi * f * raw.dt)) ** 2
    a.semilogy(f, gain2 * p_raw, color=c.REFERENCE, lw=1.0, ls=":")
    a.set_xlabel("frequency [Hz]")
    a.set_ylabel("PSD of v_x [(m/s)²/Hz]")
    a.set_title("power spectral density of v_x")
    handles = [Line2D([], [], color=c.VISCOUS, lw=1.5, label="model, no filter"),
               Line2D([], [], color=c.FILTERED, lw=1.5, label=f"filtered, γ = {gamma:g}"),
               Line2D([], [], color=c.REFERENCE, lw=1.0, ls=":",
                      label="no filter × the filter's |H|² (PSD only)")]
    fig.legend(handles=handles, loc="upper center", ncol=3, bbox_to_anchor=(0.5, 0.94),
               frameon=False)
    hi = f >= HIGH_HZ
    values["high_freq_power_ratio_vx"] = float(np.sum(p_flt[hi]) / max(np.sum(p_raw[hi]), 1e-300))
    values["filter_gain2_at_high_hz"] = float(np.mean(gain2[hi]))
    values["end_distance_m"] = float(np.hypot(raw["x"][-1] - flt["x"][-1],
                                              raw["y"][-1] - flt["y"][-1]))
    values["displacement_raw_m"] = float(np.hypot(raw["x"][-1], raw["y"][-1]))
    fig.suptitle("Trotting quadruped, viscous-Coulomb, with and without the inertia filter "
                 "(synthetic: the thesis' Spirit tracking needs its data)"
                 + ("" if vy_max >= 1e-9 else
                    f"\nv_y ≡ 0 to rounding in both runs ({vy_max:.0e} m/s, a mirror-symmetric "
                    "trot): not drawn"), y=0.995)
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
