#!/usr/bin/python3
"""Thesis Fig. 5.6 / §5.3.2: does B fitted at 0.3 Hz carry over to the higher frequencies?

Input: DATA/ch5_residual/transfer.csv (residual_transfer) and errors.csv (residual_errors),
studies/ch5_residual. Output: OUT/fig5_6.png, OUT/values/fig5_6.json.

(a-c) Per component (rows) and frequency (columns), the distribution of v − v_true over the
test trial's snapshots (Δφ = π, recorded cycles 2-8): the template model (blue, whole violin),
model + B fitted on Δφ = (0.65, 0.9, 1.1, 1.35)π at 0.3 Hz (orange, left half) and at the test
trial's own frequency (purple, right half), as the thesis draws them. (d) Beyond the thesis: the
side-velocity test RMSE of the symmetric MuJoCo robot's model (no leg-to-leg differences), of
the asymmetric robot's model, and with B (pseudo-inverse and ridge, trained at the own
frequency), from errors.csv.

Values: per frequency the RMSE with B@0.3 Hz and B@own frequency and their ratio; the share of
the asymmetric robot's extra side-velocity error that B removes,
  explained = (RMSE_model,asym − RMSE_B,asym) / (RMSE_model,asym − RMSE_model,sym),
1 when B brings the asymmetric robot's error down to the symmetric robot's model error, above 1
when B also removes error the symmetric robot has (the template is not MuJoCo), null where the
asymmetry adds no error; ridge against pseudo-inverse.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import residual as rs  # noqa: E402

NAME = "fig5_6"
# Thresholds of the ledger, fixed before the study's data existed:
ACROSS = 1.5  # "generalizes across frequencies": RMSE(B@0.3 Hz) ≤ this × RMSE(B@own)
EXPLAINS = 0.5  # B "explains the asymmetry": it removes at least this share of the extra error
OFFSET = 0.2  # violin positions: the model left, the split B violin right


def half(parts, color: str, side: str) -> None:
    """Keeps one half of each violin body (left or right of its centre)."""
    for body in parts["bodies"]:
        path = body.get_paths()[0]
        verts = path.vertices
        mid = np.mean(verts[:, 0])
        verts[:, 0] = np.clip(verts[:, 0], -np.inf, mid) if side == "left" else np.clip(
            verts[:, 0], mid, np.inf)
        body.set_facecolor(color)
        body.set_edgecolor(color)
        body.set_alpha(0.55)


def violins(ax, data: list[np.ndarray], pos: np.ndarray, color: str, side: str | None) -> None:
    parts = ax.violinplot(data, positions=pos, widths=0.36, showextrema=False,
                          showmedians=False, points=120)
    if side is None:
        for body in parts["bodies"]:
            body.set_facecolor(color)
            body.set_edgecolor(color)
            body.set_alpha(0.45)
    else:
        half(parts, color, side)
    # the median as a short line on the drawn side
    for p, d in zip(pos, data):
        lo, hi = (p - 0.15, p + 0.15) if side is None else (
            (p - 0.17, p) if side == "left" else (p, p + 0.17))
        ax.plot([lo, hi], [np.median(d)] * 2, color=color, lw=2)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    transfer = rs.load(args.data, "transfer.csv", rs.TRANSFER_COLUMNS)
    errors = rs.load(args.data, "errors.csv", rs.ERRORS_COLUMNS)
    freqs = rs.frequencies(transfer, "test_frequency")
    if not freqs:
        c.fail(f"{transfer.path}: none of the frequencies {rs.FREQUENCIES} Hz")
    v: dict = {"frequencies": freqs, "across_bound": ACROSS, "explains_bound": EXPLAINS}

    res: dict = {}  # (f, which, k) -> v − v_true
    for f in freqs:
        tg = rs.tag(f)
        own = rs.test_trial(transfer, f, f)
        base = rs.test_trial(transfer, rs.BASE_FREQUENCY, f)
        if own.n != base.n or not np.allclose(own["t"], base["t"]) or not np.allclose(
                own["v_true_y"], base["v_true_y"]):
            c.fail(f"{transfer.path}: the {f:g} Hz test trial differs between B@own and "
                   f"B@{rs.BASE_FREQUENCY:g} Hz (one trial, two fits expected)")
        for k in rs.COMPONENTS:
            res[f, "model", k] = own[f"v_model_{k}"] - own[f"v_true_{k}"]
            res[f, "base", k] = base[f"v_fit_{k}"] - base[f"v_true_{k}"]
            res[f, "own", k] = own[f"v_fit_{k}"] - own[f"v_true_{k}"]
            for w in ("model", "base", "own"):
                v[f"{tg}_rmse_{w}_{k}"] = rs.rmse(res[f, w, k])
            v[f"{tg}_base_over_own_{k}"] = rs.ratio(v[f"{tg}_rmse_base_{k}"],
                                                    v[f"{tg}_rmse_own_{k}"])
            v[f"{tg}_base_over_model_{k}"] = rs.ratio(v[f"{tg}_rmse_base_{k}"],
                                                      v[f"{tg}_rmse_model_{k}"])
        # the asymmetry: symmetric robot (asymmetry 0) against the asymmetric one, test Δφ = π
        sym = rs.error_point(errors, f, f, asymmetry=0.0)
        asym = rs.error_point(errors, f, f, asymmetry=1.0)
        ridge = rs.error_point(errors, f, f, estimator="ridge", asymmetry=1.0)
        for k in rs.COMPONENTS:
            v[f"{tg}_sym_rmse_model_{k}"] = sym[f"test_rmse_model_{k}"]
            v[f"{tg}_sym_rmse_fit_{k}"] = sym[f"test_rmse_fit_{k}"]
            v[f"{tg}_asym_rmse_model_{k}"] = asym[f"test_rmse_model_{k}"]
            v[f"{tg}_asym_rmse_fit_{k}"] = asym[f"test_rmse_fit_{k}"]
            v[f"{tg}_ridge_rmse_fit_{k}"] = ridge[f"test_rmse_fit_{k}"]
            v[f"{tg}_ridge_over_pinv_{k}"] = rs.ratio(ridge[f"test_rmse_fit_{k}"],
                                                      asym[f"test_rmse_fit_{k}"])
            extra = asym[f"test_rmse_model_{k}"] - sym[f"test_rmse_model_{k}"]
            removed = asym[f"test_rmse_model_{k}"] - asym[f"test_rmse_fit_{k}"]
            v[f"{tg}_asym_extra_{k}"] = extra
            key = f"{tg}_asym_explained_{k}"
            v[key] = removed / extra if extra > 0 else None
            if extra <= 0:
                v[key + "_reason"] = (f"at {f:g} Hz the asymmetric robot's model error is not "
                                      "above the symmetric robot's")
        v[f"{tg}_ridge_lambda"] = ridge["lambda"]
        v[f"{tg}_sym_mean_true_y"] = sym["test_mean_true_y"]
        v[f"{tg}_asym_mean_true_y"] = asym["test_mean_true_y"]

    higher = [f for f in freqs if f > rs.BASE_FREQUENCY]
    if higher:
        v["base_over_own_worst"] = max(v[f"{rs.tag(f)}_base_over_own_{k}"] for f in higher
                                       for k in rs.COMPONENTS)
        v["base_over_model_worst"] = max(v[f"{rs.tag(f)}_base_over_model_{k}"] for f in higher
                                         for k in rs.COMPONENTS)
        top = max(higher)
        v["top_frequency"] = top
        v["top_base_over_own_y"] = v[f"{rs.tag(top)}_base_over_own_y"]
    else:
        for key in ("base_over_own_worst", "base_over_model_worst", "top_frequency",
                    "top_base_over_own_y"):
            v[key] = None
            v[key + "_reason"] = f"no test frequency above {rs.BASE_FREQUENCY:g} Hz in the data"
    explained = [v[f"{rs.tag(f)}_asym_explained_y"] for f in freqs]
    # the ledger's reading: at every frequency the differences add side-velocity error to the
    # model and B takes back at least EXPLAINS of it (false where they add none)
    v["asym_explained_y_holds"] = all(e is not None and e >= EXPLAINS for e in explained)
    v["asym_adds_error_y_frequencies"] = [f for f in freqs
                                          if v[f"{rs.tag(f)}_asym_extra_y"] > 0]
    v["asym_explained_y_min"] = min(explained) if all(x is not None for x in explained) else None
    if v["asym_explained_y_min"] is None:
        v["asym_explained_y_min_reason"] = ("at some frequency the asymmetry adds no side-velocity "
                                            "error to the model")
    v["ridge_over_pinv_y_min"] = min(v[f"{rs.tag(f)}_ridge_over_pinv_y"] for f in freqs)
    v["ridge_over_pinv_y_max"] = max(v[f"{rs.tag(f)}_ridge_over_pinv_y"] for f in freqs)

    # ---- figure: a panel per component (rows) and frequency (columns), each on its own scale
    # (the velocities, and their errors, grow with the frequency)
    fig = plt.figure(figsize=(14, 12.5))
    gs = fig.add_gridspec(4, len(freqs), height_ratios=[1, 1, 1, 1.25], hspace=0.42,
                          wspace=0.3, left=0.07, right=0.99, top=0.895, bottom=0.05)
    for j, k in enumerate(rs.COMPONENTS):
        for i, f in enumerate(freqs):
            a = fig.add_subplot(gs[j, i])
            violins(a, [res[f, "model", k]], np.array([-OFFSET]), rs.MODEL, None)
            violins(a, [res[f, "base", k]], np.array([OFFSET]), rs.FIT, "left")
            violins(a, [res[f, "own", k]], np.array([OFFSET]), rs.OWN, "right")
            a.axhline(0.0, color=c.REFERENCE, lw=0.8)
            a.set_xlim(-0.5, 0.5)
            a.set_xticks([-OFFSET, OFFSET], ["model", "+ B"])
            a.grid(axis="x", visible=False)
            tg = rs.tag(f)
            a.set_title(f"({'abc'[j]}{i + 1}) {f:g} Hz: RMSE {c.fmt(v[f'{tg}_rmse_model_{k}'], 2)}"
                        f" | {c.fmt(v[f'{tg}_rmse_base_{k}'], 2)} | "
                        f"{c.fmt(v[f'{tg}_rmse_own_{k}'], 2)}", fontsize=9.5)
            if i == 0:
                a.set_ylabel(f"{rs.COMPONENT_NAME[k]}\nv − v_true [{rs.COMPONENT_UNIT[k]}]")
    from matplotlib.patches import Patch
    handles = [Patch(color=rs.MODEL, alpha=0.5, label="model A(q)q̇"),
               Patch(color=rs.FIT, alpha=0.6,
                     label=f"model + B trained at {rs.BASE_FREQUENCY:g} Hz (left half)"),
               Patch(color=rs.OWN, alpha=0.6,
                     label="model + B trained at the test's own frequency (right half)")]
    fig.legend(handles=handles, loc="upper center", ncol=3, frameon=False,
               bbox_to_anchor=(0.5, 0.952), fontsize=10)

    a = fig.add_subplot(gs[3, :])
    x = np.arange(len(freqs), dtype=float)
    bars = (("sym_rmse_model", "symmetric robot: model", c.NEUTRAL, None),
            ("asym_rmse_model", "asymmetric robot: model", rs.MODEL, None),
            ("asym_rmse_fit", "asymmetric: model + B (pseudo-inverse)", rs.OWN, None),
            ("ridge_rmse_fit", "asymmetric: model + B (ridge)", rs.OWN, "//"),
            ("sym_rmse_fit", "symmetric: model + B", c.NEUTRAL, "//"))
    width = 0.16
    for n, (key, label, color, hatch) in enumerate(bars):
        vals = [v[f"{rs.tag(f)}_{key}_y"] for f in freqs]
        a.bar(x + (n - 2) * width, vals, width, color=color if hatch is None else "white",
              edgecolor=color, hatch=hatch, label=label, alpha=0.85)
    for i, f in enumerate(freqs):
        e = v[f"{rs.tag(f)}_asym_explained_y"]
        top = max(v[f"{rs.tag(f)}_{key}_y"] for key, *_ in bars)
        a.text(x[i], top * 1.04, "explained " + (f"{e:.2f}" if e is not None else "—"),
               ha="center", va="bottom", fontsize=9.5)
    a.set_xticks(x, [f"{f:g} Hz" for f in freqs])
    a.set_ylabel("side-velocity test RMSE [m/s]")
    a.set_ylim(0, 1.18 * max(v[f"{rs.tag(f)}_{key}_y"] for f in freqs for key, *_ in bars))
    a.set_title("(d) beyond the thesis: what the leg-to-leg differences cost the model, and how "
                "much B takes back (B trained at the own frequency, test Δφ = π)")
    a.legend(loc="upper left", fontsize=9.5, ncol=2)
    a.grid(axis="x", visible=False)
    fig.suptitle("Fig. 5.6 analog: residuals v − v_true of the test trial Δφ = π (recorded "
                 "cycles 2–8), B from Δφ = (0.65, 0.9, 1.1, 1.35)π;\n"
                 "panel titles: RMSE of the model | "
                 f"B@{rs.BASE_FREQUENCY:g} Hz | B@own frequency", x=0.01, ha="left",
                 fontsize=11)
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
