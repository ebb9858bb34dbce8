"""The report's pages as HTML: the frame every page shares (header, navigation bar, quick-run
banner), page prose from Markdown with values expanded, and the blocks a page's prose places
(registry.BLOCKS): figures, verdict counts, ledger tables, links to every page, provenance.

Nothing here runs a script or writes a file; build_report.py does both.
"""
from __future__ import annotations

import datetime
import html
import json
import platform
import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

import markdown

import registry as reg
from coverage import coverage_html
from ledger import CAUSE_UNKNOWN, EXPLAINED, TEMPLATE, VERDICT_CLASS, Values, fmt_value, render

# The project's top-level folders (DESIGN.md): a path recorded on another machine is shown from
# the last of these it passes through, never as that machine's absolute path.
PROJECT_DIRS = ("studies", "data", "reports", "lib", "sweeps", "tests")
CHAPTERS = ("2", "3", "4", "5")  # the thesis chapters the summary always lists

# The look of every page. A 1400 px window gives a wide figure at least 1300 CSS px (14 px
# padding on each side of main, 10 px inside a figure's frame, room for a scroll bar); a narrow
# one is at most 760 px with its text beside it; wide tables scroll inside their wrapper.
CSS = """
*,*::before,*::after{box-sizing:border-box}
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0;color:#222;background:#fafafa;line-height:1.45}
header{background:#1f3040;color:#fff;padding:12px 14px}
header .site{color:#c8d4de;font-size:.9em}
header .site a{color:#c8d4de;text-decoration:none}
header h1{margin:2px 0 0;font-size:1.35em}
nav{position:sticky;top:0;background:#2c4255;padding:6px 14px;z-index:2}
nav a{color:#fff;margin-right:16px;text-decoration:none;font-size:.95em;white-space:nowrap;display:inline-block}
nav a:hover{text-decoration:underline}
nav a.here{font-weight:700;border-bottom:2px solid #c8d4de}
main{padding:6px 14px 40px;max-width:1500px}
section{margin-top:26px}
h2{border-bottom:2px solid #1f3040;padding-bottom:3px}
.quick{background:#fff3cd;border:1px solid #e0c36a;padding:8px 12px;margin:12px 0;font-weight:600}
.fig{display:flex;gap:22px;align-items:flex-start;flex-wrap:wrap;background:#fff;border:1px solid #ddd;padding:10px;margin:14px 0}
.fig img{max-width:760px;width:100%;border:1px solid #eee;flex:0 1 760px}
.fig .text{flex:1;min-width:340px;max-width:100%}
.fig.wide{flex-direction:column;align-items:stretch}
.fig.wide img{max-width:none;flex:none}
.figbody{margin:14px 0}
blockquote{margin:6px 0;padding:4px 10px;border-left:3px solid #8aa;color:#444;background:#f4f7f7;font-style:italic}
.scroll{max-width:100%;overflow-x:auto}
table{border-collapse:collapse;font-size:.86em;margin:8px 0}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#e8edf1}
td.num{text-align:right}
tr.group td{background:#eef2f5;font-weight:600}
tr.muted td,td.muted{color:#888}
tr.bad td,td.bad{background:#fde8e8}
.v{display:inline-block;padding:1px 6px;border-radius:3px;font-size:.9em;white-space:nowrap}
.v.ok{background:#d8f0d8;color:#1d5e1d}
.v.explained{background:#fff0cc;color:#6b4e00}
.v.unknown{background:#fbdcc4;color:#7a3d00}
.v.bad{background:#f7d4d4;color:#7a1515}
.v.nodata{background:#e2e2f2;color:#333366}
.v.notcovered{background:#e6e6e6;color:#4a4a4a}
.v.own{border:1px dashed currentColor;font-style:italic}
.small{font-size:.85em;color:#555}
.regen{font-size:.85em;color:#555;margin:6px 0 0}
.regen code{white-space:pre-wrap;overflow-wrap:anywhere}
code{background:#eef;padding:0 3px;overflow-wrap:anywhere;font-size:max(.9em,11px)}
pre{overflow-x:auto;max-width:100%}
details{margin:4px 0}
form.filters{margin:8px 0}
form.filters label{margin-right:16px}
"""

# Without JavaScript the filter form stays hidden and every row shows.
FILTER_SCRIPT = """
(function(){
  var form=document.getElementById('filters');
  if(!form) return;
  form.hidden=false;
  var v=document.getElementById('f-verdict'), c=document.getElementById('f-chapter');
  function apply(){
    document.querySelectorAll('tr[data-verdict]').forEach(function(tr){
      tr.hidden=!((v.value===''||tr.dataset.verdict===v.value)&&(c.value===''||tr.dataset.chapter===c.value));
    });
  }
  v.addEventListener('change',apply); c.addEventListener('change',apply); apply();
})();
"""


def esc(x) -> str:
    return html.escape(str(x), quote=True)


def verdict_badge(v: str) -> str:
    return f"<span class='v {VERDICT_CLASS.get(v, 'bad')}'>{esc(v)}</span>"


# A check of our own judges our implementation, not a statement of the thesis: its badge says so
# in words and in its outline, wherever an entry is shown (the counts keep one column per verdict).
OWN_CHECK_WORDS = {"reproduced": "holds", EXPLAINED: "fails — explained",
                   CAUSE_UNKNOWN: "fails — cause unknown"}


def claim_badge(cl: dict, v: str) -> str:
    if not reg.is_own_check(cl):
        return verdict_badge(v)
    return (f"<span class='v own {VERDICT_CLASS.get(v, 'bad')}' title='{esc(v)}'>our check: "
            f"{esc(OWN_CHECK_WORDS.get(v, v))}</span>")


def thesis_text(v) -> str:
    if isinstance(v, list):
        return ", ".join(thesis_text(x) for x in v)
    return str(v)


def scrolling(fragment: str) -> str:
    """Every table of an HTML fragment inside a wrapper that scrolls sideways when it is wider
    than the page."""
    fragment = re.sub(r"<table\b", "<div class='scroll'><table", fragment)
    return fragment.replace("</table>", "</table></div>")


def project_path(text: str) -> str:
    """A path as the project names it: from its last top-level project folder (studies/x.toml),
    else its file name; text that is not an absolute path is returned as it is."""
    if not text.startswith("/"):
        return text
    parts = Path(text).parts
    for i in range(len(parts) - 1, 0, -1):
        if parts[i] in PROJECT_DIRS:
            return "/".join(parts[i:])
    return parts[-1]


def relative_paths(x):
    """A sidecar's spec with every absolute path shown as the project names it."""
    if isinstance(x, dict):
        return {k: relative_paths(v) for k, v in x.items()}
    if isinstance(x, list):
        return [relative_paths(v) for v in x]
    if isinstance(x, str):
        return project_path(x)
    return x


# ---------------------------------------------------------------------------------------------
# Values in texts


def expand(text: str, values: Values, markdown_text: bool = False) -> str:
    """{script.key[:spec]} replaced by the value; a value not measured says so (with its
    <key>_reason when the script gave one). In Markdown the value is escaped for Markdown and
    HTML; otherwise the caller escapes the whole text."""
    def value_text(mt) -> str:
        key, spec = f"{mt.group(1)}.{mt.group(2)}", mt.group(3)
        reason_key = key + "_reason"
        if values.has(key) and values.get(key) is not None:
            out = fmt_value(values.get(key), spec)
        elif values.has(reason_key):
            out = f"not measured ({values.get(reason_key)})"
        elif values.has(key):
            out = "—"
        else:
            out = f"[not measured: {key}]"
        if markdown_text:
            out = re.sub(r"([\\`*_\[\]])", r"\\\1", html.escape(out, quote=False))
        return out

    return TEMPLATE.sub(value_text, text or "")


def markdown_html(text: str, values: Values) -> str:
    md = markdown.Markdown(extensions=["tables", "attr_list", "sane_lists"])
    return scrolling(md.convert(expand(text, values, markdown_text=True)))


def inline_markdown(text: str) -> str:
    out = markdown.markdown(text)
    return re.sub(r"^<p>(.*)</p>$", r"\1", out, flags=re.S)


# ---------------------------------------------------------------------------------------------
# The build's state that blocks read


@dataclass
class Build:
    registry: reg.Registry
    claims: list[dict]
    results: dict  # claim id -> ledger.evaluate's result
    values: Values
    staging: Path  # where the scripts wrote their outputs
    ran: set  # the scripts that ran (their data folder exists)
    data: Path
    data_name: str  # the data folder as the pages name it
    repo: Path
    script_times: dict
    quick: bool

    def chapter_of(self, claim: dict) -> str:
        return reg.claim_chapter(claim)

    def verdicts(self) -> list[str]:
        """Every verdict the ledger can give, then any other that occurs."""
        seen = [r["verdict"] for r in self.results.values()]
        return list(VERDICT_CLASS) + sorted(set(seen) - set(VERDICT_CLASS))

    def chapters(self) -> list[str]:
        found = {self.chapter_of(c) for c in self.claims}
        return sorted(set(CHAPTERS) | (found - {""}), key=int) + (["—"] if "" in found else [])


# ---------------------------------------------------------------------------------------------
# Claim tables


def claim_notes(cl: dict, r: dict, values: Values) -> str:
    notes = []
    if cl.get("criterion"):
        notes.append(f"<div class='small'><b>criterion:</b> {esc(render(cl['criterion'], values))}</div>")
    if r["verdict"].startswith("differs") and cl.get("explanation"):
        label = "why" if r["verdict"] == EXPLAINED else "hypothesis (no check run)"
        notes.append(f"<div><b>{label}:</b> {esc(render(cl['explanation'], values))}</div>")
    if r["verdict"] == EXPLAINED:
        shown = "; ".join(f"{k} = {fmt_value(values.get(k))}" for k in r.get("check", []))
        notes.append(f"<div class='small'><b>check:</b> {esc(shown)}</div>")
    if r.get("reason"):
        label = "not measured" if r["verdict"] == "not measured" else "note"
        notes.append(f"<div><b>{label}:</b> {esc(r['reason'])}</div>")
    if cl.get("note"):
        notes.append(f"<div class='small'>{esc(render(cl['note'], values))}</div>")
    return "".join(notes)


def ours_cell(cl: dict, r: dict) -> str:
    keys = cl.get("ours")
    src = ", ".join(keys) if isinstance(keys, list) else (keys or "—")
    return f"{esc(fmt_value(r['ours']))}<div class='small'><code>{esc(src)}</code></div>"


def ledger_rows(b: Build, claims: list[dict], with_thesis: bool) -> str:
    out = []
    for cl in claims:
        r = b.results[cl["id"]]
        cls = "bad" if r["verdict"] == "not measured" else ""
        thesis = f"<td>{esc(thesis_text(cl.get('thesis', '')))}</td>" if with_thesis else ""
        out.append(
            f"<tr id='claim-{esc(cl['id'])}' class='{cls}' data-verdict='{esc(r['verdict'])}' "
            f"data-chapter='{esc(b.chapter_of(cl) or '—')}'><td>{esc(cl['id'])}</td>"
            f"<td>{esc(cl.get('section', ''))}</td>"
            f"<td>{esc(render(cl.get('statement', ''), b.values))}</td>{thesis}"
            f"<td>{ours_cell(cl, r)}</td><td>{claim_badge(cl, r['verdict'])}</td>"
            f"<td>{claim_notes(cl, r, b.values)}</td></tr>")
    return "\n".join(out)


def ledger_table(b: Build, claims: list[dict], with_thesis: bool = True) -> str:
    head = ("<th>id</th><th>where</th><th>statement</th>" + ("<th>thesis</th>" if with_thesis else "")
            + "<th>ours</th><th>verdict</th><th>criterion, explanation, notes</th>")
    return (f"<div class='scroll'><table class='data ledger'><thead><tr>{head}</tr></thead><tbody>\n"
            f"{ledger_rows(b, claims, with_thesis)}\n</tbody></table></div>")


def short_claims_table(b: Build, claims: list[dict]) -> str:
    rows = []
    for cl in claims:
        r = b.results[cl["id"]]
        cls = "bad" if r["verdict"] == "not measured" else ""
        rows.append(f"<tr class='{cls}'><td><a href='ledger.html#claim-{esc(cl['id'])}'>"
                    f"{esc(cl['id'])}</a></td><td>{esc(thesis_text(cl.get('thesis', '')))}</td>"
                    f"<td>{esc(fmt_value(r['ours']))}</td><td>{claim_badge(cl, r['verdict'])}</td>"
                    "</tr>")
    return ("<div class='scroll'><table><thead><tr><th>claim</th><th>thesis</th><th>ours</th>"
            "<th>verdict</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table></div>")


# ---------------------------------------------------------------------------------------------
# Figure blocks


def regenerate(fg: reg.Figure) -> str:
    return (f"<p class='regen'>Regenerate: <code>slipwalk reproduce {esc(fg.study)}</code> then "
            f"<code>/usr/bin/python3 reports/figures/{esc(fg.script)}.py --data data --out "
            "reports/out</code></p>")


def figure_block(b: Build, fg: reg.Figure) -> str:
    e = fg.entry
    by_id = {c["id"]: c for c in b.claims}
    linked = [by_id[i] for i in fg.claims if i in by_id]
    mini = short_claims_table(b, linked) if linked else ""
    title = esc(expand(e.get("title", fg.script), b.values))
    texts = ""
    if e.get("shows"):
        label = f"<b>Thesis ({esc(expand(e['thesis'], b.values))}):</b> " if e.get("thesis") else ""
        texts += f"<p>{label}{esc(expand(e['shows'], b.values))}</p>"
    elif e.get("thesis"):
        texts += f"<p><b>Thesis:</b> {esc(expand(e['thesis'], b.values))}</p>"
    if e.get("quote"):
        texts += f"<blockquote>{esc(expand(e['quote'], b.values))}</blockquote>"
    if fg.script not in b.ran:
        return (f"<div class='fig' id='fig-{esc(fg.script)}'><div class='text'><h3>{title}</h3>"
                f"<p class='bad'>Not built: run <code>slipwalk reproduce {esc(fg.study)}</code> "
                f"(the data folder <code>{esc(fg.study)}</code> is missing).</p>{texts}{mini}"
                f"{regenerate(fg)}</div></div>")
    ours = (f"<p class='small'><b>Ours:</b> <code>reports/figures/{esc(fg.script)}.py</code>; "
            f"numbers in <code>values/{esc(fg.script)}.json</code>.</p>")
    table = scrolling((b.staging / fg.table).read_text()) if fg.table else ""
    if fg.body:
        heading = f"<h3>{title}</h3>" if e.get("title") else ""
        return (f"<div class='figbody' id='fig-{esc(fg.script)}'>{heading}{texts}"
                f"{scrolling((b.staging / fg.body).read_text())}{table}{mini}{regenerate(fg)}</div>")
    images = "".join(f"<img src='{esc(name)}' alt='{title}'>" for name in fg.images
                     if (b.staging / name).is_file())
    wide = " wide" if fg.wide else ""
    return (f"<div class='fig{wide}' id='fig-{esc(fg.script)}'>{images}<div class='text'>"
            f"<h3>{title}</h3>{texts}{ours}{mini}{table}{regenerate(fg)}</div></div>")


# ---------------------------------------------------------------------------------------------
# Summary blocks


def own_and_reproductions(b: Build) -> tuple[list[dict], list[dict]]:
    own = [c for c in b.claims if reg.is_own_check(c)]
    return [c for c in b.claims if not reg.is_own_check(c)], own


def verdict_counts(b: Build, claims: list[dict]) -> dict[str, int]:
    counts: dict[str, int] = {}
    for cl in claims:
        v = b.results[cl["id"]]["verdict"]
        counts[v] = counts.get(v, 0) + 1
    return counts


def verdicts_table(b: Build) -> str:
    repro, own = own_and_reproductions(b)
    verdicts = b.verdicts()
    rows = []

    def row(label: str, claims: list[dict], cls: str = "") -> str:
        counts = verdict_counts(b, claims)
        cells = "".join(f"<td class='num{'' if counts.get(v) else ' muted'}'>{counts.get(v, 0)}</td>"
                        for v in verdicts)
        return f"<tr class='{cls}'><th>{label}</th>{cells}<td class='num'>{len(claims)}</td></tr>"

    for ch in b.chapters():
        claims = [c for c in repro if (b.chapter_of(c) or "—") == ch]
        page = b.registry.page(f"ch{ch}")
        label = f"<a href='{page.file}'>Chapter {esc(ch)}</a>" if page else f"Chapter {esc(ch)}"
        rows.append(row(label, claims))
    rows.append(row("<a href='ledger.html#own-checks'>Checks of our own</a>", own))
    rows.append(row("All", b.claims, "group"))
    head = "".join(f"<th>{verdict_badge(v)}</th>" for v in verdicts)
    return ("<div class='scroll'><table class='data verdicts'><thead><tr><th></th>"
            f"{head}<th>entries</th></tr></thead><tbody>{''.join(rows)}</tbody></table></div>")


def chapter_verdicts(b: Build, chapter: str) -> str:
    repro, _ = own_and_reproductions(b)
    claims = [c for c in repro if b.chapter_of(c) == chapter]
    counts = verdict_counts(b, claims)
    shown = " · ".join(f"{verdict_badge(v)} {counts[v]}" for v in b.verdicts() if counts.get(v))
    return (f"<p>Verdicts of chapter {esc(chapter)} ({len(claims)} ledger entries; checks of our "
            f"own apart): {shown or '—'}. Every entry: the <a href='ledger.html'>claims "
            "ledger</a>.</p>")


def chapter_claims(b: Build, chapter: str) -> str:
    claims = [c for c in b.claims if b.chapter_of(c) == chapter]
    if not claims:
        return f"<p class='small'>The ledger has no chapter {esc(chapter)} entries yet.</p>"
    return ledger_table(b, claims)


def ledger_block(b: Build) -> str:
    repro, _ = own_and_reproductions(b)
    verdicts = "".join(f"<option value='{esc(v)}'>{esc(v)}</option>" for v in b.verdicts())
    chapters = "".join(f"<option value='{esc(ch)}'>{esc(ch)}</option>" for ch in b.chapters())
    return ("<form class='filters' id='filters' hidden><label>Verdict <select id='f-verdict'>"
            f"<option value=''>all</option>{verdicts}</select></label><label>Chapter "
            f"<select id='f-chapter'><option value=''>all</option>{chapters}</select></label>"
            "</form>" + ledger_table(b, repro) + f"<script>{FILTER_SCRIPT}</script>")


def own_checks_block(b: Build) -> str:
    _, own = own_and_reproductions(b)
    if not own:
        return "<p class='small' id='own-checks'>No checks of our own in the ledger.</p>"
    return f"<div id='own-checks'>{ledger_table(b, own, with_thesis=False)}</div>"


def pages_block(b: Build, current: reg.Page) -> str:
    items = "".join(f"<li><a href='{p.file}'>{esc(p.title)}</a></li>"
                    for p in b.registry.pages if p.id != current.id)
    return f"<ul>{items}</ul>"


# ---------------------------------------------------------------------------------------------
# Provenance


def csv_row(path: Path) -> str:
    name = f"{path.parent.name}/{path.name}"
    side = path.with_suffix(".json")
    if not side.is_file():
        return f"<tr><td>{esc(name)}</td><td colspan='6' class='bad'>no sidecar</td></tr>"
    try:
        meta = json.loads(side.read_text())
    except json.JSONDecodeError as e:
        return (f"<tr><td>{esc(name)}</td><td colspan='6' class='bad'>sidecar is not JSON: "
                f"{esc(e)}</td></tr>")
    meta = meta if isinstance(meta, dict) else {}
    prov = meta.get("provenance", {}) if isinstance(meta.get("provenance"), dict) else {}
    libs = prov.get("libraries", {})
    libs_s = ", ".join(f"{k} {v}" for k, v in libs.items()) if isinstance(libs, dict) else str(libs)
    wall = meta.get("wall_s")
    spec = json.dumps(relative_paths(meta.get("spec", {})), indent=1, ensure_ascii=False)
    spec_file = project_path(str(meta.get("spec_file", "")))
    spec_label = f"spec <code>{esc(spec_file)}</code>" if spec_file else "spec"
    return (f"<tr><td>{esc(name)}</td><td><code>{esc(prov.get('git_commit', '—'))}</code></td>"
            f"<td>{esc(prov.get('compiler', '—'))}</td><td>{esc(libs_s)}</td>"
            f"<td>{esc(meta.get('threads', '—'))}</td>"
            f"<td>{esc(fmt_value(wall) if wall is not None else '—')}</td>"
            f"<td><details><summary>{spec_label}</summary><pre>{esc(spec)}</pre></details></td></tr>")


def sweep_outcomes(data: Path, studies: list[str]) -> list[dict]:
    """Every sweep sidecar's failed and at-budget points: study, name, kind, counts, messages."""
    out = []
    for study in studies:
        folder = data / study
        for side in sorted(folder.glob("*.json")) if folder.is_dir() else []:
            try:
                meta = json.loads(side.read_text())
            except (OSError, json.JSONDecodeError):
                continue
            if not isinstance(meta, dict) or "failed_point_count" not in meta:
                continue  # not a sweep's sidecar (a trace, a scene run)
            out.append({"study": study, "name": meta.get("name", side.stem),
                        "kind": meta.get("kind", "?"), "points": meta.get("point_count", 0),
                        "failed": meta.get("failed_point_count", 0),
                        "budget": meta.get("budget_point_count", 0),
                        "first": next((p.get("message", "") for p in
                                       meta.get("failed_points", []) + meta.get("budget_points", [])
                                       if isinstance(p, dict)), "")})
    return out


def outcomes_block(b: Build) -> str:
    """The sweeps whose points failed (something that should not happen) and those with points
    stopped at a budget their spec sets (a designed outcome, recorded with its status)."""
    rows = sweep_outcomes(b.data, b.registry.studies())
    failed = [r for r in rows if r["failed"]]
    budget = [r for r in rows if r["budget"] and not r["failed"]]
    n_failed = sum(r["failed"] for r in rows)
    n_budget = sum(r["budget"] for r in rows)
    head = (f"<p><b>{n_failed} failed points</b> in "
            f"{len(rows)} sweeps ({sum(r['points'] for r in rows)} points); {n_budget} points "
            "stopped at a budget their study sets on purpose (not failures: their rows carry "
            "the status).</p>")
    if not failed and not budget:
        return head

    def row(r: dict) -> str:
        cls = " class='bad'" if r["failed"] else ""
        return (f"<tr{cls}><td>{esc(r['study'])}/{esc(r['name'])}</td><td><code>{esc(r['kind'])}"
                f"</code></td><td>{r['points']}</td><td>{r['failed']}</td><td>{r['budget']}</td>"
                f"<td class='small'>{esc(str(r['first'])[:200])}</td></tr>")
    return head + (
        "<div class='scroll'><table class='data'><thead><tr><th>sweep</th><th>kind</th>"
        "<th>points</th><th>failed</th><th>at budget</th><th>first message</th></tr></thead>"
        "<tbody>" + "\n".join(row(r) for r in failed + budget) + "</tbody></table></div>")


def build_commit(repo: Path) -> str:
    try:
        commit = subprocess.run(["git", "-C", str(repo), "rev-parse", "HEAD"],
                                capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(repo), "status", "--porcelain", "--",
                                "reports", "data/thesis"], capture_output=True, text=True,
                               timeout=10).stdout.strip()
        return (commit or "unknown") + (" (reports/ or data/thesis/ modified)" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown (git not available)"


def provenance_block(b: Build) -> str:
    import matplotlib
    import numpy

    rows = []
    for study in b.registry.studies():
        folder = b.data / study
        if not folder.is_dir():
            rows.append(f"<tr><td>{esc(study)}/</td><td colspan='6' class='muted'>data folder "
                        f"missing: run <code>slipwalk reproduce {esc(study)}</code></td></tr>")
            continue
        rows += [csv_row(p) for p in sorted(folder.glob("*.csv"))]
    times = ", ".join(f"{k} {v:.1f} s" for k, v in sorted(b.script_times.items()))
    return (
        "<div class='scroll'><table class='data'><thead><tr><th>data file</th><th>git commit</th>"
        "<th>compiler</th><th>libraries</th><th>threads</th><th>wall [s]</th><th>spec</th></tr>"
        "</thead><tbody>" + "\n".join(rows) + "</tbody></table></div>"
        f"<p class='small'>Data folder: <code>{esc(b.data_name)}</code>. Report built "
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC} from commit "
        f"<code>{esc(build_commit(b.repo))}</code> with Python {platform.python_version()}, "
        f"numpy {numpy.__version__}, matplotlib {matplotlib.__version__}"
        f"{' — quick run' if b.quick else ''}. Script wall times: {esc(times) or '—'}.</p>")


# ---------------------------------------------------------------------------------------------
# A page


def block_html(b: Build, page: reg.Page, block: reg.Block, figures: list[reg.Figure]) -> str:
    name, args = block.name, block.args
    if name in ("figures", "figure"):
        return "".join(figure_block(b, fg) for fg in figures)
    if name == "verdicts":
        return chapter_verdicts(b, args["chapter"]) if "chapter" in args else verdicts_table(b)
    if name == "claims":
        return chapter_claims(b, args["chapter"])
    if name == "ledger":
        return ledger_block(b)
    if name == "own-checks":
        return own_checks_block(b)
    if name == "pages":
        return pages_block(b, page)
    if name == "provenance":
        return provenance_block(b)
    if name == "outcomes":
        return outcomes_block(b)
    if name == "coverage":
        return coverage_html(b.claims)
    raise ValueError(f"block {name} has no renderer")  # registry.BLOCKS and this list agree


def nav_html(b: Build, current: reg.Page) -> str:
    links = "".join(f"<a href='{p.file}'" + (" class='here' aria-current='page'"
                                              if p.id == current.id else "")
                    + f">{esc(p.nav)}</a>" for p in b.registry.pages)
    return f"<nav>{links}</nav>"


QUICK_BANNER = ("<div class='quick'>Quick run: fewer sweep points, repeats and tolerances than "
                "the full studies; fits, timings and verdicts may differ from a full run.</div>")


def page_html(b: Build, page: reg.Page, prose: str, pages_dir_name: str) -> str:
    parts, _ = reg.parse_prose(prose, pages_dir_name)
    placed, _ = reg.place_figures(b.registry, page, parts, pages_dir_name)
    body = []
    for i, part in enumerate(parts):
        if isinstance(part, reg.Block):
            body.append(block_html(b, page, part, placed.get(i, [])))
        elif part.strip():
            body.append(markdown_html(part, b.values))
    quick = " (quick run)" if b.quick else ""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{esc(page.title)} — slipwalk{quick}</title>
<style>{CSS}</style></head><body>
<header><div class="site"><a href="index.html">{inline_markdown(b.registry.site_title)}</a>{esc(quick)}</div>
<h1>{esc(page.title)}</h1></header>
{nav_html(b, page)}
<main>
{QUICK_BANNER if b.quick else ''}
{''.join(body)}
</main></body></html>
"""
