#!/usr/bin/python3
"""Stability: the long run of the Coulomb solver on random stress frames.

Input: DATA/stability/coulomb_long_run.csv (studies/stability/coulomb_long_run.toml, point kind
coulomb_long_run): one row per chunk of frames — certified, not converged, non-unique,
non-finite, rejected by the independent duality oracle, invalid robots, the solver's routes
(direct, fast path, smoothing path without and after the fast path) overall and per layout of
the feet, the largest certificate, oracle gap and residual, and the CPU time. Outputs:
OUT/coulomb_long_run.png (the share of frames per layout that needed the smoothing path),
OUT/coulomb_long_run_table.html, OUT/values/coulomb_long_run.json.
"""
from __future__ import annotations

import html
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "coulomb_long_run"
STUDY = "stability"
CSV = "coulomb_long_run.csv"
LAYOUTS = ("general", "line", "near_line", "coincident", "one_point", "circle", "mirror")
LAYOUT_LABEL = {
    "general": "general position",
    "line": "all on one line",
    "near_line": "nearly on one line",
    "coincident": "pairs of coincident feet",
    "one_point": "all at one point",
    "circle": "on a circle (disk robot)",
    "mirror": "mirror-symmetric",
}
COUNTS = ("frames", "certified", "not_converged", "non_unique", "non_finite", "oracle_fail",
          "invalid_robots", "route_direct", "route_fast", "route_path", "route_fallback",
          "support_unbalanced", "wide_weights", "not_converged_wide")
COLUMNS = (["chunk", "seed", "tol", "first_frame", "legs_mean", "iterations_max",
            "max_certificate", "worst_frame", "max_oracle_gap", "max_oracle_imbalance",
            "max_residual", "cpu_s", "solve_ns_mean"] + list(COUNTS)
           + [f"frames_{n}" for n in LAYOUTS] + [f"smoothing_{n}" for n in LAYOUTS])


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    path = c.study_file(args.data, CSV, STUDY)
    t = c.Table(path, COLUMNS)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    v: dict = {k: int(np.sum(t[k])) for k in COUNTS}
    n = v["frames"]
    seeds = sorted({int(s) for s in t["seed"]})
    if len(seeds) != 1:
        c.fail(f"{path}: chunks of {len(seeds)} seeds; the run is one stream")
    failures = v["not_converged"] + v["non_finite"] + v["oracle_fail"]
    smoothing = v["route_path"] + v["route_fallback"]
    worst = int(np.argmax(t["max_oracle_gap"]))
    v.update({
        "seed": seeds[0],
        "chunks": t.n,
        "tol": float(np.max(t["tol"])),
        "legs_mean": float(np.sum(t["legs_mean"] * t["frames"]) / n),
        "failures": failures,
        "failure_fraction": failures / n,
        "failure_percent": 100.0 * failures / n,
        "non_unique_percent": 100.0 * v["non_unique"] / n,
        "smoothing": smoothing,
        "smoothing_percent": 100.0 * smoothing / n,
        "fallback_percent": 100.0 * v["route_fallback"] / n,
        "path_percent": 100.0 * v["route_path"] / n,
        "fast_percent": 100.0 * v["route_fast"] / n,
        "direct_percent": 100.0 * v["route_direct"] / n,
        "every_frame_certified": failures == 0 and v["invalid_robots"] == 0
                                 and v["certified"] == n,
        "max_certificate": float(np.max(t["max_certificate"])),
        "max_oracle_gap": float(t["max_oracle_gap"][worst]),
        "worst_frame": int(t["worst_frame"][worst]),
        "max_oracle_imbalance": float(np.max(t["max_oracle_imbalance"])),
        "max_residual": float(np.max(t["max_residual"])),
        "iterations_max": int(np.max(t["iterations_max"])),
        "cpu_s": float(np.sum(t["cpu_s"])),
        "solve_ns_mean": float(np.sum(t["solve_ns_mean"] * t["frames"]) / n),
    })
    named = [str(s) for s in t.str("failed_frames") if str(s) not in ("", "nan")] \
        if "failed_frames" in t.columns else []
    # The first frames each chunk names (index:what), at most ten in all: replay one with
    # chunk = index, frames = 1.
    v["failed_frames"] = " ".join(" ".join(named).split()[:10])
    per_layout = {}
    for name in LAYOUTS:
        frames = int(np.sum(t[f"frames_{name}"]))
        smooth = int(np.sum(t[f"smoothing_{name}"]))
        per_layout[name] = (frames, smooth)
        v[f"frames_{name}"] = frames
        v[f"smoothing_{name}"] = smooth
    side = c.read_sidecar(path) or {}
    wall = side.get("wall_s")
    v["wall_s"] = float(wall) if isinstance(wall, (int, float)) else None

    def row(label: str, count: int, note: str = "", bad: bool = False) -> str:
        cls = " class='bad'" if bad else ""
        return (f"<tr{cls}><td>{html.escape(label)}</td><td>{count}</td>"
                f"<td>{100.0 * count / n:.4g} %</td><td>{html.escape(note)}</td></tr>")

    rows = [
        row("certified (relative duality gap ≤ tol)", v["certified"]),
        row("not converged (the solver's own flag)", v["not_converged"],
            "the thesis' 'failed to converge'", bad=v["not_converged"] > 0),
        row("non-finite output", v["non_finite"], bad=v["non_finite"] > 0),
        row("certified, but rejected by the oracle", v["oracle_fail"],
            "independent recomputation of the gap", bad=v["oracle_fail"] > 0),
        row("invalid robot drawn (generator bug)", v["invalid_robots"],
            bad=v["invalid_robots"] > 0),
        row("weights μ_k F_z,k spanning more than 6 decades", v["wide_weights"],
            f"{v['not_converged_wide']} of the not converged are among them"),
        row("flagged non-unique (a continuum of velocities)", v["non_unique"],
            "certified all the same: the dissipation's minimum is proven"),
        row("route: direct (no Newton step)", v["route_direct"],
            "no friction, nothing moves, or at rest at the start"),
        row("route: fast path", v["route_fast"], "Newton with the kink model"),
        row("route: smoothing path, fast path not tried", v["route_path"],
            "a foot exactly at rest at the viscous start"),
        row("route: smoothing path after the fast path stalled", v["route_fallback"],
            "the solver's internal fallback (a restart)"),
    ]
    layout_rows = "".join(
        f"<tr><td>{html.escape(LAYOUT_LABEL[k])}</td><td>{f}</td><td>{s}</td>"
        f"<td>{(100.0 * s / f if f else float('nan')):.3g} %</td></tr>"
        for k, (f, s) in per_layout.items())
    table = (
        "<table class='data'><thead><tr><th>frames</th><th>count</th><th>share</th>"
        "<th>note</th></tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>\n"
        "<table class='data'><thead><tr><th>layout of the feet</th><th>frames</th>"
        "<th>smoothing path</th><th>share</th></tr></thead><tbody>\n" + layout_rows
        + "\n</tbody></table>\n"
        f"<p class='small'>{n} frames of stream seed {v['seed']} in {t.n} chunks; tolerance "
        f"{c.fmt(v['tol'], 2)}; largest certificate {c.fmt(v['max_certificate'], 2)}, largest "
        f"oracle gap {c.fmt(v['max_oracle_gap'], 2)} (frame {v['worst_frame']}), largest "
        f"imbalance {c.fmt(v['max_oracle_imbalance'], 2)}; at most {v['iterations_max']} Newton "
        f"steps; {c.fmt(v['solve_ns_mean'], 3)} ns per solve on average, {c.fmt(v['cpu_s'], 3)} s "
        "of CPU for the chunks (generation, spring support, solve and oracle)."
        + (f" First frames not certified (index:what; replay one with chunk = index, frames = 1): "
           f"{html.escape(v['failed_frames'])}."
           if v["failed_frames"] else "") + "</p>\n")
    c.atomic_write_text(args.out / f"{NAME}_table.html", table)

    fig, ax = plt.subplots(figsize=(7.6, 3.2))
    labels = [LAYOUT_LABEL[k] for k in LAYOUTS]
    share = np.array([100.0 * s / f if f else np.nan for f, s in per_layout.values()])
    y = np.arange(len(LAYOUTS))
    ax.barh(y, share, color="C1")
    for i, (f, s) in enumerate(per_layout.values()):
        ax.text((share[i] if np.isfinite(share[i]) else 0.0), i, f"  {s} of {f}",
                va="center", fontsize=9)
    ax.set_yticks(y)
    ax.set_yticklabels(labels)
    ax.invert_yaxis()
    top = np.nanmax(share) if np.any(np.isfinite(share)) else 1.0
    ax.set_xlim(0, max(top, 1e-3) * 1.6)
    ax.set_xlabel("frames that needed the smoothing path [%]")
    ax.set_title(f"Coulomb solver, {n} random frames: {failures} not certified")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
