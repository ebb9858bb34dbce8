#!/usr/bin/python3
"""Thesis Fig. 4.4 / §4.3.1.3: each leg's estimated CoM against its phase.

Input: DATA/ch4_calibration/com.csv (calib_com: per leg, axis and phase bin the median, quartiles
and 2.5/97.5 % quantiles of the smoothed CoM samples over all cycles, the periodic fit and the
truth at the bin centre, m, transducer frame). Output: OUT/fig4_4.png, OUT/values/fig4_4.json.

A panel per leg (Table 4.1's order): x blue, y orange, z green as the thesis draws them; median
dots, interquartile band (dark), 95 % band (light), the periodic fit (line) and the synthetic
leg's true CoM (black dashes).

Values: per leg and axis the RMS of fit − truth over the bins and the largest |median − truth|;
the thesis' shape, measured on the medians: the R² of r(φ) = A sin(2πφ + C) + D (linear least
squares in sin, cos, 1) for x and z, and the span of y against the span of x and z.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import calibration as cal  # noqa: E402
import common as c  # noqa: E402

NAME = "fig4_4"
# Thresholds of the ledger, fixed before the study's data existed:
SINE_R2 = 0.9  # x and z "follow" A sin(2πφ + C) + D
Y_FLAT = 0.1  # y "constant": its span at most this share of the x, z span
COM_TOL = 0.003  # m: the fitted CoM within 3 mm RMS of the truth (a tenth of the motion)


def sine_fit(phi: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float | None]:
    """A sin(2πφ + C) + D by least squares in (sin 2πφ, cos 2πφ, 1): coefficients and R²."""
    return c.lstsq_fit([np.sin(2 * np.pi * phi), np.cos(2 * np.pi * phi), np.ones_like(phi)], y)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = cal.load(args.data, "com.csv", cal.COM_COLUMNS)
    legs = cal.legs_in(t)
    v: dict = {"sine_r2_bound": SINE_R2, "y_flat_bound": Y_FLAT, "com_tol_m": COM_TOL,
               "legs": legs}
    cols = 3
    nrow = math.ceil(len(legs) / cols)
    fig, axes = plt.subplots(nrow, cols, figsize=(14, 4.3 * nrow + 0.8), squeeze=False,
                             sharex=True)
    r2s, y_ratio, fit_rms = [], [], []
    for n, leg in enumerate(legs):
        ax = axes[n // cols][n % cols]
        spans = {}
        for axis in cal.AXES:
            r = cal.rows(t, leg=leg, axis=axis)
            if r.n == 0:
                c.fail(f"{t.path}: no rows for leg {leg}, axis {axis}")
            r = r.subset(np.argsort(r["phase"], kind="stable"))
            phi = r["phase"]
            col = cal.AXIS_COLOR[axis]
            ax.fill_between(phi, r["q025"] * 1e3, r["q975"] * 1e3, color=col, alpha=0.15, lw=0)
            ax.fill_between(phi, r["q25"] * 1e3, r["q75"] * 1e3, color=col, alpha=0.4, lw=0)
            ax.plot(phi, r["median"] * 1e3, "o", ms=3, color=col, label=f"{axis} median")
            ax.plot(phi, r["fit"] * 1e3, "-", lw=1.4, color=col)
            ax.plot(phi, r["truth"] * 1e3, "--", lw=1.0, color="black")
            err = r["fit"] - r["truth"]
            key = f"{leg}_{axis}"
            v[f"{key}_fit_err_rms_m"] = cal.rmse(err)
            v[f"{key}_median_err_max_m"] = float(np.max(np.abs(r["median"] - r["truth"])))
            spans[axis] = float(np.ptp(r["median"]))
            v[f"{key}_span_m"] = spans[axis]
            fit_rms.append(v[f"{key}_fit_err_rms_m"])
            if axis != "y":
                coef, r2 = sine_fit(phi, r["median"])
                v[f"{key}_sine_r2"] = r2
                v[f"{key}_sine_amplitude_m"] = float(math.hypot(coef[0], coef[1]))
                r2s.append(r2 if r2 is not None else -math.inf)
        y_ratio.append(spans["y"] / max(spans["x"], spans["z"]))
        v[f"{leg}_y_span_over_xz"] = y_ratio[-1]
        ax.set_title(f"{leg}: fit − truth RMS x {v[f'{leg}_x_fit_err_rms_m'] * 1e3:.2g}, "
                     f"y {v[f'{leg}_y_fit_err_rms_m'] * 1e3:.2g}, "
                     f"z {v[f'{leg}_z_fit_err_rms_m'] * 1e3:.2g} mm")
        if n % cols == 0:
            ax.set_ylabel("leg CoM r(φ) [mm]")
        if n // cols == nrow - 1:
            ax.set_xlabel("phase φ [turns] (0 = mid-stance)")
    for n in range(len(legs), nrow * cols):
        axes[n // cols][n % cols].set_visible(False)
    v["xz_sine_r2_min"] = float(min(r2s))
    v["y_span_over_xz_max"] = float(max(y_ratio))
    v["com_shape_as_thesis"] = bool(v["xz_sine_r2_min"] >= SINE_R2
                                    and v["y_span_over_xz_max"] <= Y_FLAT)
    v["com_fit_err_rms_max_m"] = float(max(fit_rms))
    v["com_fit_within_tol"] = bool(v["com_fit_err_rms_max_m"] <= COM_TOL)

    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    handles = ([Line2D([], [], marker="o", ls="-", color=cal.AXIS_COLOR[a], label=f"{a}: median, "
                       "fit") for a in cal.AXES]
               + [Patch(color="0.4", alpha=0.5, label="interquartile range"),
                  Patch(color="0.4", alpha=0.18, label="95 % range"),
                  Line2D([], [], ls="--", color="black", label="truth (synthetic leg)")])
    fig.legend(handles=handles, loc="upper center", ncol=6, frameon=False,
               bbox_to_anchor=(0.5, 0.965))
    fig.suptitle("Fig. 4.4 analog: estimated leg CoM against phase (transducer frame), synthetic "
                 "hanging data, all cycles per phase bin", x=0.01, ha="left", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
