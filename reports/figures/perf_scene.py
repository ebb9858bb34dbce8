#!/usr/bin/python3
"""Performance of composed scenes: what each effect costs per step.

Input: DATA/scene_effects/scene_cost.csv (studies/scene_effects/scene_cost.toml, point kind
scene_cost): CPU time per step of BigANT's tripod through the hand-written flat isotropic viscous
kernel and through composed scenes with none or exactly one effect, all cases interleaved in one
run; per case the median over repeats, the median of the per-repeat ratios to the hand-written
kernel, and the median extra time over the composed flat scene.

Outputs: OUT/perf_scene_body.html (the block build_report.py puts into the index's performance
section: the table and the flat scene's target, met or not), OUT/values/perf_scene.json. A data folder
without scene_cost.csv gives a block that says so and no values.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "perf_scene"
STUDY = "scene_effects"
CSV = "scene_cost.csv"
COLUMNS = ["case", "kernel", "steps", "repeats", "ns_per_step", "ns_per_step_p25",
           "ns_per_step_p75", "ratio_to_handwritten", "extra_ns_per_step", "share_of_flat"]
LABEL = {
    "handwritten": "hand-written kernel (flat, isotropic viscous only)",
    "none": "composed scene, no effect (flat, isotropic viscous)",
    "anisotropic": "+ anisotropic friction (w per leg, eq. 3.19)",
    "coulomb": "+ Coulomb friction instead of viscous (certified, tol 1e-10)",
    "filter": "+ inertia filter (γ = 0.15, §3.5.2.2)",
    "residual": "+ residual B (§5.3.1)",
    "noise": "+ measurement noise on the pose",
    "slope": "+ slope 10° (§5.2.1)",
    "stairs": "+ stairs 0.3 m / 0.12 m (§5.2.2)",
}
TARGET_RATIO = 1.05  # the flat isotropic viscous scene within 5 % of the hand-written


def block_missing(path) -> str:
    return ("<p class='bad' id='perf-scene'>Scene effects' cost not built: "
            f"<code>{html.escape(str(path))}</code> is missing (run "
            f"<code>slipwalk reproduce {STUDY}</code>).</p>\n")


def row_html(r: dict) -> str:
    added = r["case"] not in ("handwritten", "none")
    extra = c.fmt(r["extra_ns_per_step"], 3) if added else "—"
    share = f"{r['share_of_flat']:+.0%}" if added else "—"
    return (f"<tr><td>{html.escape(LABEL.get(r['case'], r['case']))}</td>"
            f"<td><code>{html.escape(r['kernel'])}</code></td>"
            f"<td>{c.fmt(r['ns_per_step'], 4)}</td>"
            f"<td>{c.fmt(r['ns_per_step_p25'], 4)} – {c.fmt(r['ns_per_step_p75'], 4)}</td>"
            f"<td>{c.fmt(r['ratio_to_handwritten'], 3)}</td><td>{extra}</td><td>{share}</td></tr>")


def body(v: dict, rows: list[dict]) -> str:
    ok = v["target_met"]
    verdict = ("<span class='v ok'>met</span>" if ok else "<span class='v bad'>not met</span>")
    table = "".join(row_html(r) for r in rows)
    return f"""
<div class="fig wide" id="perf-scene"><div class="text">
<h3>Scenes: only the effects they call for</h3>
<p>CPU time per step of BigANT's tripod ({int(v['steps'])} steps of 0.01 s per run, the median
of {int(v['repeats'])} repeats, every case once per repeat in one run) through a kernel written
by hand for the flat isotropic viscous case and through the simulator <code>scene::compose</code>
assembles from a scene file with none or exactly one effect. The composed flat scene runs at
{c.fmt(v['ratio_flat'], 3)}× the hand-written kernel (median of the per-repeat ratios; target
≤ {TARGET_RATIO}×: {verdict}): an effect that is off is an identity policy the compiler removes.
The table gives what each effect adds per step on top of the flat scene. Anisotropy costs nothing
extra because the viscous-Coulomb solver handles w for every leg in one pass (w = 0 is the
isotropic law, not a separate path).</p>
<table class='data'><thead><tr><th>case</th><th>kernel</th><th>ns / step</th><th>p25 – p75</th>
<th>÷ hand-written</th><th>extra ns / step</th><th>share of flat</th></tr></thead>
<tbody>{table}</tbody></table>
<p class="small">From <code>DATA/{STUDY}/{CSV}</code> by <code>reports/figures/{NAME}.py</code>; numbers in
<code>values/{NAME}.json</code>. The same cases as a Google Benchmark:
<code>build/bin/bench_scene</code>.</p>
</div></div>
"""


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    path = args.data / STUDY / CSV
    if not path.is_file():
        c.atomic_write_text(args.out / f"{NAME}_body.html", block_missing(path))
        print(f"{NAME}.py: warning: {path}: missing, block not built")
        return
    t = c.Table(path, COLUMNS)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    rows = []
    for i in range(t.n):
        r = {k: float(t[k][i]) for k in COLUMNS if k not in ("case", "kernel")}
        r["case"] = str(t.str("case")[i])
        r["kernel"] = str(t.str("kernel")[i])
        rows.append(r)
    by = {r["case"]: r for r in rows}
    for need in ("handwritten", "none"):
        if need not in by:
            c.fail(f"{path}: no row for case {need}")
    v = {
        "steps": float(np.max(t["steps"])),
        "repeats": float(np.max(t["repeats"])),
        "ratio_flat": by["none"]["ratio_to_handwritten"],
        "target_ratio": TARGET_RATIO,
        "target_met": bool(by["none"]["ratio_to_handwritten"] <= TARGET_RATIO),
        "flat_ns_per_step": by["none"]["ns_per_step"],
        "handwritten_ns_per_step": by["handwritten"]["ns_per_step"],
    }
    for r in rows:
        if r["case"] not in ("handwritten", "none"):
            v[f"extra_ns_{r['case']}"] = r["extra_ns_per_step"]
            v[f"share_{r['case']}"] = r["share_of_flat"]
    side = c.read_sidecar(path) or {}
    v["date"] = side.get("date") if isinstance(side, dict) else None
    c.atomic_write_text(args.out / f"{NAME}_body.html", body(v, rows))
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
