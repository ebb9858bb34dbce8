#!/usr/bin/python3
"""Builds the report: runs every figure script, evaluates the claims ledger, writes index.html.

    /usr/bin/python3 reports/site/build_report.py --data DATA --out OUT [--quick]

Every figure script runs with this interpreter (sys.executable) into a staging folder inside
OUT; only when all of them succeed are their PNGs, tables and values moved into OUT, index.html
last (written whole, then renamed), so a failed build leaves no partial page and no mix of old
and new values. Exit status: 0 built (whatever the verdicts), 1 a script failed, 2 bad input.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import html
import json
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
FIGURES = HERE.parent / "figures"
sys.path.insert(0, str(HERE.parent / "plotting"))
sys.path.insert(0, str(HERE))
import common as c  # noqa: E402
from ledger import (CAUSE_UNKNOWN, EXPLAINED, VERDICT_CLASS, Values, evaluate,  # noqa: E402
                    fmt_value, render)

SCRIPTS = ["fig2_2", "fig2_3", "regression", "eq2_6", "scaling", "separation", "performance",
           "stability", "fig2_6", "fig2_7", "regime_map", "fig3_1", "fig3_2", "fig3_3_4",
           "fig3_15"]
# The data folder (under --data) each script reads; c.STUDY unless named here. A script whose
# folder is missing is skipped with a warning (its ledger entries become "not measured"), so a
# data folder from a partial run (`slipwalk reproduce STUDY...`) still builds.
SCRIPT_STUDY = {"fig2_6": "ch2_dm_swap", "fig2_7": "ch2_dm_swap", "regime_map": "ch2_dm_swap",
                "fig3_1": "ch3_legged", "fig3_2": "ch3_legged", "fig3_3_4": "ch3_legged",
                "fig3_15": "ch3_legged"}
STUDIES = [c.STUDY, "ch2_dm_swap", "ch3_legged"]
# Figures shown full width (several panels side by side).
WIDE = {"eq2_6", "fig2_6", "fig2_7", "regime_map", "fig3_1", "fig3_2", "fig3_3_4", "fig3_15"}
# §3.5.3, Fig. 3.13: MuJoCo as the peer and the parallel overhead, shown in the
# performance section ([[figure]] part = "performance").
SCRIPTS.append("fig3_13")
SCRIPT_STUDY["fig3_13"] = "ch3_peer"
STUDIES.append("ch3_peer")
WIDE.add("fig3_13")
# §3.5.4, Fig. 3.14: BigANT sim to sim, ours against MuJoCo driven by the same feet.
SCRIPTS.append("fig3_14")
SCRIPT_STUDY["fig3_14"] = "ch3_peer"
WIDE.add("fig3_14")
# What the thesis leaves open in the dm model (lib/inchworm/mass_swap.hpp), stated on the page.
DM_CHOICES = [
    "Stroke phase: Δm rides locked on one end mass (then \"M\", y); the stroke is exactly the "
    "instant-swap stroke (eqs. 2.1–2.2) and ends in a plastic collision of x with y + Δm at the "
    "length limit (eq. 2.4).",
    "Swap phase: the end masses move as one body of mass 2m at fixed distance; Δm is pushed from y "
    "toward x by F_Δm = αF and the body feels −F_Δm; friction acts on the body with the whole "
    "normal load (2m + Δm)g (Δm rides on the mechanism, not on the ground). When Δm arrives, a "
    "plastic collision gives all three one velocity and Δm's new carrier becomes y.",
    "Δm starts the swap at the end mass it rode on, with that mass's velocity (after the stroke's "
    "collision: the common velocity).",
    "The body's static friction uses μ_s like the end masses (μ_s = μ here): it is stuck while at "
    "rest and |F_Δm| ≤ μ_s g(2m + Δm); a body pushed out of its friction cone slides (backward "
    "after an extension stroke, forward after a contraction stroke) with dynamic friction, and "
    "stops and sticks again when its velocity reaches zero.",
    "Δm moves on a rail between the end masses: if its free motion would press it into the end it "
    "just left, it is held there and the three slide together until the body stops (\"held\" "
    "mode). That happens after a contraction stroke when αF < μgΔm, i.e. only for α < Δm/m = 0.5 "
    "with the thesis' masses.",
    "A cell or point counts as \"stop during swap\" when the body stopped and stuck in either "
    "swap of the limit cycle (in practice the swap after the extension stroke).",
]
# The cost-of-accuracy study (studies/cost_of_accuracy) has a page of its own,
# cost_of_accuracy.html: its script writes the page's body, the builder wraps it.
SCRIPTS.append("cost_of_accuracy")
SCRIPT_STUDY["cost_of_accuracy"] = "cost_of_accuracy"
STUDIES.append("cost_of_accuracy")
COST_PAGE = "cost_of_accuracy.html"
# The multi-legged model (§3.4, §3.6.1): the friction solvers' section of the cost page
# (cost_friction_body.html) and the per-frame cost in the index's performance section
# (perf_legged_body.html).
SCRIPTS += ["cost_friction", "perf_legged"]
SCRIPT_STUDY.update({"cost_friction": "cost_of_accuracy", "perf_legged": "ch3_legged"})
# §3.5 walking robots: synthetic analogs of Figs. 3.5-3.12 from the scene runs of
# studies/ch3_robots, in the chapter 3 section.
ROBOT_FIGS = ["fig3_5", "fig3_6_9", "fig3_7_10", "fig3_8", "fig3_11", "fig3_12"]
SCRIPTS += ROBOT_FIGS
SCRIPT_STUDY.update({name: "ch3_robots" for name in ROBOT_FIGS})
STUDIES.append("ch3_robots")
# What each scene effect costs per step (studies/scene_effects), in the performance
# section (perf_scene_body.html).
SCRIPTS.append("perf_scene")
SCRIPT_STUDY["perf_scene"] = "scene_effects"
STUDIES.append("scene_effects")
WIDE.update(ROBOT_FIGS)
# §5.2 slopes and stairs: Figs. 5.2 and 5.3 from studies/ch5_terrain, in the chapter 5
# section ([[figure]] part = "5").
CH5_FIGS = ["fig5_2", "fig5_3"]
SCRIPTS += CH5_FIGS
SCRIPT_STUDY.update({name: "ch5_terrain" for name in CH5_FIGS})
STUDIES.append("ch5_terrain")
WIDE.update(CH5_FIGS)


# ---------------------------------------------------------------------------------------------
# Running the scripts


def run_script(name: str, data: Path, out: Path, claims: Path) -> tuple[str, int, str, float]:
    start = time.monotonic()
    env = dict(os.environ, SLIPWALK_CLAIMS=str(claims))
    proc = subprocess.run([sys.executable, str(FIGURES / f"{name}.py"), "--data", str(data),
                           "--out", str(out)], capture_output=True, text=True, env=env)
    return name, proc.returncode, (proc.stdout + proc.stderr).strip(), time.monotonic() - start


# ---------------------------------------------------------------------------------------------
# HTML

CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;color:#222;background:#fafafa;line-height:1.45}
header{background:#1f3040;color:#fff;padding:14px 28px}
header h1{margin:0;font-size:1.35em}
header .sub{color:#c8d4de;font-size:.9em}
header code{background:#34495e;color:#fff}
nav{position:sticky;top:0;background:#2c4255;padding:6px 28px;z-index:2}
nav a{color:#fff;margin-right:18px;text-decoration:none;font-size:.95em}
nav a:hover{text-decoration:underline}
main{padding:6px 28px 40px;max-width:1500px}
section{margin-top:26px}
h2{border-bottom:2px solid #1f3040;padding-bottom:3px}
.quick{background:#fff3cd;border:1px solid #e0c36a;padding:8px 12px;margin:12px 0;font-weight:600}
.fig{display:flex;gap:22px;align-items:flex-start;flex-wrap:wrap;background:#fff;border:1px solid #ddd;padding:12px;margin:14px 0}
.fig img{max-width:760px;width:100%;border:1px solid #eee}
.fig .text{flex:1;min-width:340px}
.fig.wide{flex-direction:column}
.fig.wide img{max-width:1400px}
blockquote{margin:6px 0;padding:4px 10px;border-left:3px solid #8aa;color:#444;background:#f4f7f7;font-style:italic}
table{border-collapse:collapse;font-size:.86em;margin:8px 0}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#e8edf1}
tr.group td{background:#eef2f5;font-weight:600}
tr.muted td,td.muted{color:#888}
tr.bad td,td.bad{background:#fde8e8}
.v{display:inline-block;padding:1px 6px;border-radius:3px;font-size:.9em;white-space:nowrap}
.v.ok{background:#d8f0d8;color:#1d5e1d}
.v.explained{background:#fff0cc;color:#6b4e00}
.v.unknown{background:#fbdcc4;color:#7a3d00}
.v.bad{background:#f7d4d4;color:#7a1515}
.v.nodata{background:#e2e2f2;color:#333366}
.small{font-size:.85em;color:#555}
code{background:#eef;padding:0 3px}
details{margin:4px 0}
"""


def verdict_badge(v: str) -> str:
    return f"<span class='v {VERDICT_CLASS.get(v, 'bad')}'>{html.escape(v)}</span>"


def thesis_text(v) -> str:
    if isinstance(v, list):
        return ", ".join(thesis_text(x) for x in v)
    return str(v)


def claim_rows(claims: list[dict], results: dict, values: Values, short: bool) -> str:
    out = []
    for cl in claims:
        r = results[cl["id"]]
        ours = fmt_value(r["ours"])
        notes = []
        if cl.get("criterion"):
            notes.append(f"<div class='small'><b>criterion:</b> {html.escape(render(cl['criterion'], values))}</div>")
        if r["verdict"].startswith("differs") and cl.get("explanation"):
            label = "why" if r["verdict"] == EXPLAINED else "hypothesis (no check run)"
            notes.append(f"<div><b>{label}:</b> {html.escape(render(cl['explanation'], values))}</div>")
        if r["verdict"] == EXPLAINED:
            shown = "; ".join(f"{k} = {fmt_value(values.get(k))}" for k in r["check"])
            notes.append(f"<div class='small'><b>check:</b> {html.escape(shown)}</div>")
        if r.get("reason"):
            label = "not measured" if r["verdict"] == "not measured" else "note"
            notes.append(f"<div><b>{label}:</b> {html.escape(r['reason'])}</div>")
        if cl.get("note"):
            notes.append(f"<div class='small'>{html.escape(render(cl['note'], values))}</div>")
        cls = "bad" if r["verdict"] == "not measured" else ""
        if short:
            out.append(f"<tr class='{cls}'><td><a href='#claim-{html.escape(cl['id'])}'>"
                       f"{html.escape(cl['id'])}</a></td><td>{html.escape(thesis_text(cl.get('thesis', '')))}</td>"
                       f"<td>{html.escape(ours)}</td><td>{verdict_badge(r['verdict'])}</td></tr>")
        else:
            ours_key = cl.get("ours")
            src = ", ".join(ours_key) if isinstance(ours_key, list) else (ours_key or "—")
            out.append(
                f"<tr id='claim-{html.escape(cl['id'])}' class='{cls}'><td>{html.escape(cl['id'])}</td>"
                f"<td>{html.escape(cl.get('section', ''))}</td>"
                f"<td>{html.escape(render(cl.get('statement', ''), values))}</td>"
                f"<td>{html.escape(thesis_text(cl.get('thesis', '')))}</td>"
                f"<td>{html.escape(ours)}<div class='small'><code>{html.escape(src)}</code></div></td>"
                f"<td>{verdict_badge(r['verdict'])}</td><td>{''.join(notes)}</td></tr>")
    return "\n".join(out)


def csv_name(path: Path) -> str:
    """study/file.csv"""
    return f"{path.parent.name}/{path.name}"


def provenance_html(data: Path, script_times: dict, quick: bool) -> str:
    rows = []
    csvs = [p for study in STUDIES for p in sorted((data / study).glob("*.csv"))]
    for csv_path in csvs:
        side = csv_path.with_suffix(".json")
        if not side.is_file():
            rows.append(f"<tr><td>{html.escape(csv_name(csv_path))}</td><td colspan='5' class='bad'>"
                        "no sidecar</td></tr>")
            continue
        try:
            meta = json.loads(side.read_text())
        except json.JSONDecodeError as e:
            rows.append(f"<tr><td>{html.escape(csv_name(csv_path))}</td><td colspan='5' class='bad'>"
                        f"sidecar is not JSON: {html.escape(str(e))}</td></tr>")
            continue
        prov = meta.get("provenance", {}) if isinstance(meta, dict) else {}
        libs = prov.get("libraries", {})
        libs_s = (", ".join(f"{k} {v}" for k, v in libs.items()) if isinstance(libs, dict)
                  else str(libs))
        wall = meta.get("wall_s")
        spec = json.dumps(meta.get("spec", {}), indent=1)
        rows.append(
            f"<tr><td>{html.escape(csv_name(csv_path))}</td><td><code>{html.escape(str(prov.get('git_commit', '—')))}</code></td>"
            f"<td>{html.escape(str(prov.get('compiler', '—')))}</td><td>{html.escape(libs_s)}</td>"
            f"<td>{html.escape(str(meta.get('threads', '—')))}</td>"
            f"<td>{html.escape(fmt_value(wall) if wall is not None else '—')}</td>"
            f"<td><details><summary>spec</summary><pre>{html.escape(spec)}</pre></details></td></tr>")
    try:
        commit = subprocess.run(["git", "-C", str(c.REPO), "rev-parse", "HEAD"],
                                capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(c.REPO), "status", "--porcelain", "--",
                                "reports", "data/thesis"], capture_output=True, text=True,
                               timeout=10).stdout.strip()
        commit = (commit or "unknown") + (" (reports/ or ledger modified)" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        commit = "unknown (git not available)"
    import matplotlib
    import numpy

    times = ", ".join(f"{k} {v:.1f} s" for k, v in script_times.items())
    return (
        "<table class='data'><thead><tr><th>data file</th><th>git commit</th><th>compiler</th>"
        "<th>libraries</th><th>threads</th><th>wall [s]</th><th>spec</th></tr></thead><tbody>"
        + "\n".join(rows) + "</tbody></table>"
        f"<p class='small'>Data folder: <code>{html.escape(str(data))}</code>. Report built "
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC} from commit "
        f"<code>{html.escape(commit)}</code> with Python {platform.python_version()} "
        f"(<code>{html.escape(sys.executable)}</code>), numpy {numpy.__version__}, matplotlib "
        f"{matplotlib.__version__}{' — quick run' if quick else ''}. Script wall times: "
        f"{html.escape(times)}.</p>")


def build_html(ledger: dict, results: dict, values: Values, staging: Path, data: Path,
               script_times: dict, quick: bool) -> str:
    claims = ledger.get("claim", [])
    by_id = {cl["id"]: cl for cl in claims}
    def chapter_summary(ch3: bool) -> str:
        counts: dict[str, int] = {}
        for cid, r in results.items():
            if str(by_id[cid].get("section", "")).startswith(("§3", "Fig. 3")) == ch3:
                counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
        return " · ".join(f"{verdict_badge(k)} {n}" for k, n in sorted(counts.items())) or "—"

    summary, summary3 = chapter_summary(False), chapter_summary(True)

    figs = []
    figs_25 = []
    figs_3 = []
    figs_perf = []
    figs_5 = []
    for fg in ledger.get("figure", []):
        script = fg["script"]
        part = str(fg.get("part", ""))
        target = (figs_25 if part == "2.5" else figs_3 if part == "3" else
                  figs_perf if part == "performance" else figs_5 if part == "5" else figs)
        linked = [by_id[i] for i in fg.get("claims", []) if i in by_id]
        table = ""
        if fg.get("table") and (staging / fg["table"]).is_file():
            table = (staging / fg["table"]).read_text()
        mini = ("<table><thead><tr><th>claim</th><th>thesis</th><th>ours</th><th>verdict</th>"
                "</tr></thead><tbody>" + claim_rows(linked, results, values, True) +
                "</tbody></table>") if linked else ""
        wide = " wide" if script in WIDE else ""
        image = (f"<img src='{html.escape(script)}.png' alt='{html.escape(fg.get('title', script))}'>"
                 if (staging / f"{script}.png").is_file() else
                 f"<p class='bad'>Not built: the data folder "
                 f"<code>{html.escape(SCRIPT_STUDY.get(script, c.STUDY))}</code> is missing.</p>")
        target.append(
            f"<div class='fig{wide}' id='fig-{html.escape(script)}'>"
            f"{image}"
            f"<div class='text'><h3>{html.escape(fg.get('title', script))}</h3>"
            f"<p><b>Thesis ({html.escape(fg.get('thesis', ''))}):</b> {html.escape(render(fg.get('shows', ''), values))}</p>"
            f"<blockquote>{html.escape(fg.get('quote', ''))}</blockquote>"
            f"<p><b>Ours:</b> the figure, from <code>reports/{html.escape(script)}.py</code>; "
            f"numbers in <code>values/{html.escape(script)}.json</code>.</p>{mini}{table}</div></div>")

    # A data folder produced by only some studies still builds: what is missing says so.
    missing = "<p class='bad'>Not built: the data folder <code>{}</code> is missing.</p>"
    perf_table = ((staging / "performance_table.html").read_text()
                  if (staging / "performance_table.html").is_file() else missing.format(c.STUDY))
    perf_legged = ((staging / "perf_legged_body.html").read_text()
                   if (staging / "perf_legged_body.html").is_file() else missing.format("ch3_legged"))
    perf_scene = ((staging / "perf_scene_body.html").read_text()
                  if (staging / "perf_scene_body.html").is_file() else missing.format("scene_effects"))
    stab_table = ((staging / "stability_table.html").read_text()
                  if (staging / "stability_table.html").is_file() else missing.format(c.STUDY))
    v = values.by_script
    scale = v.get("eq2_6", {}).get("velocity_scale_value")
    quick_banner = ("<div class='quick'>Quick run: fewer sweep points than the full study; fits "
                    "and verdicts may differ from a full run.</div>") if quick else ""
    ledger_rows = claim_rows(claims, results, values, False)
    f27, rmap = v.get("fig2_7", {}), v.get("regime_map", {})
    if f27.get("analytic_vs_exact_max_rel_diff") is not None:
        dm_check = (f"Simulation against the closed form: largest relative difference of v_ss "
                    f"{fmt_value(f27['analytic_vs_exact_max_rel_diff'])} over "
                    f"{f27.get('analytic_vs_exact_pairs')} Fig. 2.7 points and "
                    f"{fmt_value(rmap.get('exact_vs_analytic_max_rel_diff'))} over "
                    f"{rmap.get('exact_cells')} regime-map cells; the same regime in "
                    f"{fmt_value(rmap.get('exact_class_agreement'), '.1%')} of the cells.")
    elif f27:
        dm_check = ("The dm closed form gave no result in this build ("
                    f"{html.escape(str(f27.get('dm_exact_unavailable_reason', 'no exact rows')))}"
                    "); only the simulation is shown.")
    else:
        dm_check = ""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>slipwalk — thesis reproduction report{' (quick run)' if quick else ''}</title>
<style>{CSS}</style></head><body>
<header><h1>slipwalk — reproducing <i>Efficient Modeling of Multi-legged Locomotion with Slipping</i>{' — quick run' if quick else ''}</h1>
<div class="sub">Chapter 2: the inchworm crawling model (§2.1–2.5); chapter 3: the multi-legged model (§3.1–3.6); chapter 5: slopes and stairs (§5.2). Not covered yet: §5.3, §5.4 and chapter 4. Every figure from data, every number from a run; verdicts computed from the claims ledger <code>data/thesis/claims.toml</code>.</div></header>
<nav><a href="#ch2">Chapter 2</a><a href="#ch2-5">§2.5 realistic swap</a><a href="#ch3">Chapter 3</a><a href="#ch5">Chapter 5</a><a href="#ledger">Claims ledger</a><a href="#performance">Performance</a><a href="#stability">Stability</a><a href="#provenance">Provenance</a><a href="cost_of_accuracy.html">Cost of accuracy</a></nav>
<main>
{quick_banner}
<section id="ch2"><h2>Chapter 2 — inchworm crawling model</h2>
<p>Two point masses m = {c.m:g} kg and M = {c.M:g} kg on a line, Coulomb friction (μ_s = μ unless
stated), a constant actuator force F that pushes them apart to L_max = {c.L_MAX:g} m and pulls
them together to L_min = {c.L_MIN:g} m; at each length limit a plastic collision and an
instantaneous swap of the masses. Regime I: F ≤ μMg (M held by static friction); regime II:
F &gt; μMg. Our reference is the closed-form fixed point of the stroke map (§2.4, with eq. 2.9
corrected); simulations are event-driven and exact between events unless a method says
otherwise. Nondimensional speeds use ṽ = v/√(L_max g){f' (√(L_max g) = {scale:.4f} m/s)' if scale else ''} — the only reading of the
thesis' "√(Lg)" that reproduces its own numbers (ledger entry
<a href="#claim-2.3.1.1-velocity-unit">2.3.1.1-velocity-unit</a>); √(2 g L_max) does not.</p>
<p>Verdicts (all of chapter 2): {summary}</p>
{''.join(figs)}
</section>
<section id="ch2-5"><h2>§2.5 — realistic swapping: Δm pushed across by F_Δm = αF</h2>
<p>The load Δm = M − m = {c.M - c.m:g} kg is no longer teleported: after each stroke an internal
force F_Δm = αF pushes it from the end mass carrying it to the other one while the two end masses
(m each) are held at constant distance as one body, the "m–m system"; Δm arrives in a plastic
collision. Same parameters as §2.3 (μ_s = μ). Both the event-driven simulation ("analytic") and
an independent closed-form route ("exact": the fixed point of the cycle map, where it is
available in the build) are computed; the figures plot the simulation. {dm_check}</p>
<p><b>Choices where the thesis is silent</b> (from <code>lib/inchworm/mass_swap.hpp</code>):</p>
<ul class="small">{''.join(f"<li>{html.escape(x)}</li>" for x in DM_CHOICES)}</ul>
{''.join(figs_25) or "<p>No §2.5 figures in the ledger.</p>"}
</section>
<section id="ch3"><h2>Chapter 3 — the multi-legged model: contacts and friction</h2>
<p>The quasi-static model of §3.2–3.4: a spring-support search finds which feet touch the ground
and what each carries (§3.3, Alg. 1); planar force–moment balance with a friction law then gives
the body velocity (§3.4). Classical Coulomb friction (eq. 3.13) is solved as the minimization of
the total dissipation (a convex problem, with an optimality certificate); the viscous-Coulomb
ansatz (eq. 3.14 with ε → ∞) is a 3 × 3 linear solve, the local connection of eq. 3.20. The
thesis gives no numbers for the robots of Figs. 3.2–3.4; ours are frame files in
<code>studies/ch3_legged/</code>, chosen to show the same effects. The experiments of §3.5
(BigANT, Multipod, Spirit) need data we do not have; the speed of the solvers is measured
by a timed study (performance page and cost of accuracy page), not here, and so is the speed
comparison with MuJoCo as the peer simulator (Fig. 3.13, performance page). Verdicts of chapter 3: {summary3}</p>
{''.join(figs_3) or "<p>No chapter 3 figures in the ledger.</p>"}
</section>
<section id="ch5"><h2>Chapter 5 — slopes and stairs (§5.2)</h2>
<p>The model of chapter 3 on a constant slope (§5.2.1: the spring support carries Mg cos σ, the
planar balance carries gravity's component along the slope as a load) and on stairs (§5.2.2: the
pitch expanded about the stairs' slope, each toe's spring measured from its tread). Synthetic
runs of BigANT's tripod; the thesis shows no data for them either.</p>
{''.join(figs_5) or "<p>No chapter 5 figures in the ledger.</p>"}
</section>
<section id="ledger"><h2>Claims ledger</h2>
<p class="small">The quantitative statements of chapter 2 (§2.1–2.5), chapter 3 (§3.1–3.6) and §5.2 that the ledger covers so far. "ours" is
computed by the scripts from the data; the verdict is computed from the rule in the criterion column.
Verdicts: <b>reproduced</b> (the criterion holds); <b>differs — explained</b> (it fails, and the explanation
names a check that was run, whose result is shown with the entry); <b>differs — cause unknown</b> (it
fails, and no check has settled why: a stated reason is a hypothesis); <b>needs data we do not have</b>;
<b>not measured</b> (a value the scripts could not compute).</p>
<table class="data"><thead><tr><th>id</th><th>where</th><th>statement</th><th>thesis</th><th>ours</th><th>verdict</th><th>criterion, explanation, notes</th></tr></thead><tbody>
{ledger_rows}
</tbody></table></section>
<section id="performance"><h2>Performance — what accuracy costs</h2>
{''.join(figs_perf)}
<div class="fig wide"><img src="performance.png" alt="work-precision">
<div class="text"><p>Relative error against the closed form vs wall time and vs right-hand-side
evaluations, each method over its tolerances, at F = 45 N, μ = 1 (fast convergence) and
F = 73.575 N, μ = 0.05 (slowest convergence of the range). The table gives the cheapest run of each
method that reaches the target error. Every integrator over ten decades of tolerance, both models,
the fixed-step method without event location and the three error sources separated: the
<a href="cost_of_accuracy.html">cost of accuracy</a> page.</p>{perf_table}</div></div>
{perf_legged}{perf_scene}</section>
<section id="stability"><h2>Stability — hard cases</h2>
<div class="fig wide"><img src="stability.png" alt="hard cases">
<div class="text"><p>Each hard case run by every method; the closed form ("exact") is the reference.
A method that is not built in this configuration is listed as such.</p>{stab_table}</div></div></section>
<section id="provenance"><h2>Provenance</h2>
{provenance_html(data, script_times, quick)}
</section>
</main></body></html>
"""


# ---------------------------------------------------------------------------------------------


def cost_page(staging: Path, quick: bool) -> str:
    """cost_of_accuracy.html: the body cost_of_accuracy.py wrote, in the report's frame."""
    body_file = staging / "cost_of_accuracy_body.html"
    body = (body_file.read_text() if body_file.is_file() else
            "<p class='bad'>Not built: the data folder <code>cost_of_accuracy</code> is missing "
            "(run <code>slipwalk reproduce cost_of_accuracy</code>).</p>")
    legged_file = staging / "cost_friction_body.html"
    body += legged_file.read_text() if legged_file.is_file() else ""
    quick_banner = ("<div class='quick'>Quick run: one repeat and a few tolerances per method; "
                    "timings and tables are not those of the full study.</div>") if quick else ""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>slipwalk — cost of accuracy{' (quick run)' if quick else ''}</title>
<style>{CSS}</style></head><body>
<header><h1>slipwalk — cost of accuracy{' — quick run' if quick else ''}</h1>
<div class="sub">What each integrator of the hybrid layer costs to reach a given error in the
inchworm's steady speed, and where the error comes from; what each friction solver of the
multi-legged model costs per frame for its accuracy. From <code>studies/cost_of_accuracy/</code>,
<code>reports/cost_of_accuracy.py</code> and <code>reports/cost_friction.py</code>.</div></header>
<nav><a href="index.html">Report index</a><a href="#coa-wp">Work–precision</a><a href="#coa-sources">Error sources</a><a href="#coa-pick">Which method</a><a href="#coa-legged">Multi-legged friction</a><a href="index.html#performance">Performance</a><a href="index.html#provenance">Provenance</a></nav>
<main>
{quick_banner}
{body}
</main></body></html>
"""


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True, type=Path)
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="mark the page as a quick run")
    ap.add_argument("--claims", type=Path, default=c.LEDGER, help="the claims ledger (TOML)")
    ap.add_argument("--jobs", type=int, default=min(4, os.cpu_count() or 1))
    args = ap.parse_args()

    if not any((args.data / study).is_dir() for study in STUDIES):
        print(f"build_report.py: error: {args.data}: no study data folder ("
              f"{', '.join(STUDIES)}; run `slipwalk reproduce` first)", file=sys.stderr)
        return 2
    ledger = c.load_ledger(args.claims.resolve())
    import tomllib
    registry = tomllib.loads((c.REPO / "data" / "thesis" / "figures.toml").read_text())
    part_of = {("ch2", "2.5"): "2.5", ("ch3", ""): "3", ("performance", ""): "performance",
               ("ch5", ""): "5"}
    ledger = dict(ledger, figure=[dict(f, part=part_of.get((f["page"], f.get("section", "")), ""))
                                  for f in registry["figure"]])
    args.out.mkdir(parents=True, exist_ok=True)
    staging = args.out / f".staging-{os.getpid()}"
    if staging.exists():
        shutil.rmtree(staging)
    (staging / "values").mkdir(parents=True)
    try:
        times = {}
        failed = []
        runnable = []
        for name in SCRIPTS:
            folder = args.data / SCRIPT_STUDY.get(name, c.STUDY)
            if folder.is_dir():
                runnable.append(name)
            else:
                print(f"build_report.py: warning: {folder}: data folder missing, {name}.py "
                      f"skipped (run `slipwalk reproduce {folder.name}`)", file=sys.stderr)
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for name, rc, output, dt in pool.map(lambda s: run_script(s, args.data, staging, args.claims.resolve()),
                                                 runnable):
                times[name] = dt
                if rc != 0:
                    failed.append((name, rc, output))
                elif output:
                    print(f"[{name}] {output}", file=sys.stderr)
        if failed:
            for name, rc, output in failed:
                print(f"build_report.py: error: {name}.py failed (exit {rc}):\n{output}",
                      file=sys.stderr)
            return 1

        values = Values(staging / "values")
        ids = [cl.get("id") for cl in ledger.get("claim", [])]
        dup = {i for i in ids if ids.count(i) > 1}
        if dup or None in ids:
            print(f"build_report.py: error: {args.claims}: duplicate or missing ids {sorted(map(str, dup))}",
                  file=sys.stderr)
            return 2
        try:
            results = {cl["id"]: evaluate(cl, values) for cl in ledger.get("claim", [])}
        except ValueError as e:
            print(f"build_report.py: error: {args.claims}: {e}", file=sys.stderr)
            return 2
        page = build_html(ledger, results, values, staging, args.data, times, args.quick)
        c.atomic_write_text(staging / COST_PAGE, cost_page(staging, args.quick))
        # Values of skipped scripts are missing by design (their warning above says why).
        skipped = set(SCRIPTS) - set(runnable)
        unmeasured = sorted({k for k in values.missing if k.partition(".")[0] not in skipped})
        if unmeasured:
            print("build_report.py: warning: values referenced by the ledger but not measured: "
                  + ", ".join(unmeasured), file=sys.stderr)
        verdicts = [{**r, "statement": next(cl.get("statement") for cl in ledger["claim"]
                                             if cl["id"] == r["id"])} for r in results.values()]
        c.atomic_write_text(staging / "values" / "claims.json",
                            json.dumps(c.to_jsonable(verdicts), indent=1) + "\n")

        # Move the results into OUT; index.html last, so it never points at missing files.
        (args.out / "values").mkdir(exist_ok=True)
        for old in (args.out / "values").glob("*.json"):
            old.unlink()
        for p in sorted(staging.rglob("*")):
            if p.is_file():
                dest = args.out / p.relative_to(staging)
                dest.parent.mkdir(parents=True, exist_ok=True)
                os.replace(p, dest)
        c.atomic_write_text(args.out / "index.html", page)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    counts: dict[str, int] = {}
    for r in results.values():
        counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    print(f"report: {args.out / 'index.html'} — " +
          ", ".join(f"{k}: {n}" for k, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
