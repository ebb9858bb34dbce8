#!/usr/bin/python3
"""Builds the report: runs every registered figure script, evaluates the claims ledger, writes the pages.

    /usr/bin/python3 reports/site/build_report.py --data DATA --out OUT [--quick]

The registry data/thesis/figures.toml drives everything: its [[page]] entries are the pages
(OUT/<id>.html, each from the Markdown prose data/thesis/pages/<id>.md, see registry.py for the
block markers), its [[figure]] entries the scripts that run (reports/figures/<script>.py, with
this interpreter, sys.executable) and the files each writes. A figure whose data folder is
missing is skipped and its block says how to build it.

The build fails, naming every problem and writing no page, when the registry and
reports/figures/ disagree, a page's prose does not place every figure of its page, a figure
names a claim the ledger does not have, a script wrote less or more than its entry declares, or
a claim, figure or page quotes a value key no script wrote (a value that cannot be measured
carries <key>_reason instead).

Scripts write into a staging folder inside OUT; only when everything succeeded are the images,
values and layouts moved into OUT and then the pages (each written whole, then renamed), so a
failed build leaves no partial page and no mix of old and new values. HTML fragments the scripts
write (tables, page bodies) are inlined into the pages and never reach OUT. Files a previous
build left in OUT (.html and .png at its top, values/*.json, layout/*.json) that this build did
not write are removed; nothing else in OUT is touched.

Exit status: 0 built (whatever the verdicts), 1 a script failed or a check above failed, 2 bad
input (no study data, a malformed registry or ledger).
"""
from __future__ import annotations

import argparse
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "plotting"))
sys.path.insert(0, str(HERE))
import common as c  # noqa: E402
import pages  # noqa: E402
import registry as reg  # noqa: E402
from ledger import Values, evaluate  # noqa: E402

REGISTRY = c.REPO / "data" / "thesis" / "figures.toml"
FIGURES = HERE.parent / "figures"
# The model constants page prose may quote as {model.<name>} (reports/plotting/common.py, the
# defaults of lib/inchworm/params.hpp; thesis §2.3).
MODEL_VALUES = {"m": c.m, "M": c.M, "dm": c.M - c.m, "L_min": c.L_MIN, "L_max": c.L_MAX,
                "g": c.G, "dm_over_m": (c.M - c.m) / c.m}


def error(msg: str) -> None:
    print(f"build_report.py: error: {msg}", file=sys.stderr)


def warn(msg: str) -> None:
    print(f"build_report.py: warning: {msg}", file=sys.stderr)


def run_script(script: Path, data: Path, out: Path, claims: Path) -> tuple[str, int, str, float]:
    start = time.monotonic()
    env = dict(os.environ, SLIPWALK_CLAIMS=str(claims))
    proc = subprocess.run([sys.executable, str(script), "--data", str(data), "--out", str(out)],
                          capture_output=True, text=True, env=env)
    return script.stem, proc.returncode, (proc.stdout + proc.stderr).strip(), time.monotonic() - start


def referenced_keys(registry: reg.Registry, claims: list[dict], ledger_path: Path,
                    prose: dict[str, tuple[str, str]]) -> dict[str, list[str]]:
    """Every value key a claim, a figure's texts or a page's prose quotes -> where."""
    keys: dict[str, list[str]] = {}
    for cl in claims:
        for k in reg.claim_keys(cl):
            keys.setdefault(k, []).append(f"{ledger_path}: claim {cl.get('id')}")
    for fg in registry.figures:
        for name in reg.TEXT_FIELDS:
            for k in reg.template_keys(fg.entry.get(name)):
                keys.setdefault(k, []).append(f"{registry.path}: [[figure]] {fg.script}")
    for text, where in prose.values():
        for k in reg.template_keys(text):
            keys.setdefault(k, []).append(where)
    return keys


def stale_outputs(out: Path, written: set[str]) -> list[Path]:
    """What a previous build left in OUT that this one did not write: only the kinds of file the
    builder writes (.html and .png at the top, values/*.json, layout/*.json)."""
    stale = [p for p in out.iterdir() if p.is_file() and p.suffix in (".html", ".png")]
    for sub in ("values", "layout"):
        if (out / sub).is_dir():
            stale += [p for p in (out / sub).iterdir() if p.is_file() and p.suffix == ".json"]
    return [p for p in stale if p.relative_to(out).as_posix() not in written]


def report_problems(problems: list[str]) -> int:
    for p in problems:
        error(p)
    error(f"{len(problems)} problem(s); no page written")
    return 1


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True, type=Path)
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true", help="mark every page as a quick run")
    ap.add_argument("--claims", type=Path, default=c.LEDGER, help="the claims ledger (TOML)")
    ap.add_argument("--registry", type=Path, default=REGISTRY,
                    help="the figure registry (TOML); its pages' prose is in pages/ beside it")
    ap.add_argument("--figures", type=Path, default=FIGURES, help="the figure scripts' folder")
    ap.add_argument("--jobs", type=int, default=min(4, os.cpu_count() or 1))
    args = ap.parse_args()
    claims_path = args.claims.resolve()
    pages_dir = args.registry.resolve().parent / "pages"

    try:
        registry = reg.load(args.registry.resolve())
    except reg.RegistryError as e:
        error(str(e))
        return 2
    studies = registry.studies()
    if not any((args.data / study).is_dir() for study in studies):
        error(f"{args.data}: no study data folder ({', '.join(studies)}; run `slipwalk "
              "reproduce` first)")
        return 2
    ledger = c.load_ledger(claims_path)
    claims = ledger.get("claim", [])
    ids = [cl.get("id") for cl in claims]
    dup = {i for i in ids if ids.count(i) > 1}
    if dup or None in ids:
        error(f"{claims_path}: duplicate or missing ids {sorted(map(str, dup))}")
        return 2

    # The registry against the scripts, the pages' prose and the ledger: before anything runs.
    problems = (reg.check_tables(registry) + reg.check_scripts(registry, args.figures)
                + reg.check_pages(registry, pages_dir)
                + reg.check_claim_ids(registry, claims, claims_path))
    if problems:
        return report_problems(problems)
    prose = {p.id: reg.read_prose(registry, p, pages_dir) for p in registry.pages}

    ran = set()
    for fg in registry.figures:
        folder = args.data / fg.study
        if folder.is_dir():
            ran.add(fg.script)
        else:
            warn(f"{folder}: data folder missing, {fg.script}.py skipped (run `slipwalk "
                 f"reproduce {fg.study}`)")

    args.out.mkdir(parents=True, exist_ok=True)
    staging = args.out / f".staging-{os.getpid()}"
    if staging.exists():
        shutil.rmtree(staging)
    (staging / "values").mkdir(parents=True)
    (staging / "layout").mkdir()
    try:
        times = {}
        failed = []
        runnable = [fg.script for fg in registry.figures if fg.script in ran]
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            for name, rc, output, dt in pool.map(
                    lambda s: run_script(args.figures / f"{s}.py", args.data, staging, claims_path),
                    runnable):
                times[name] = dt
                if rc != 0:
                    failed.append((name, rc, output))
                elif output:
                    print(f"[{name}] {output}", file=sys.stderr)
        if failed:
            for name, rc, output in failed:
                error(f"{name}.py failed (exit {rc}):\n{output}")
            return 1

        # What the scripts wrote against what the registry declares, and every value quoted.
        values = Values(staging / "values")
        values.by_script["model"] = dict(MODEL_VALUES)
        problems = reg.check_outputs(registry, staging, ran)
        key_problems, key_warnings = reg.check_keys(
            referenced_keys(registry, claims, claims_path, prose), values, ran,
            {fg.script for fg in registry.figures})
        for w in key_warnings:
            warn(w)
        if problems or key_problems:
            return report_problems(problems + key_problems)
        try:
            results = {cl["id"]: evaluate(cl, values) for cl in claims}
        except ValueError as e:
            error(f"{claims_path}: {e}")
            return 2

        build = pages.Build(registry=registry, claims=claims, results=results, values=values,
                            staging=staging, ran=ran, data=args.data.resolve(),
                            data_name=c.shown_path(args.data), repo=c.REPO, script_times=times,
                            quick=args.quick)
        built = staging / ".pages"
        built.mkdir()
        machine_paths = {str(c.REPO), str(args.data.resolve()), str(Path.home())}
        for page in registry.pages:
            text = pages.page_html(build, page, prose[page.id][0], prose[page.id][1])
            for path in sorted(machine_paths):
                if path and path != "/" and path in text:
                    warn(f"{page.file}: shows the machine path {path} (a script's fragment?)")
            c.atomic_write_text(built / page.file, text)
        verdicts = [{**r, "statement": next(cl.get("statement") for cl in claims
                                             if cl["id"] == r["id"])} for r in results.values()]
        c.atomic_write_text(staging / "values" / "claims.json",
                            json.dumps(c.to_jsonable(verdicts), indent=1) + "\n")

        # Into OUT: images, values and layouts first, then the pages, the index last, so that
        # a page never points at a missing file; then what an earlier build left behind.
        written: set[str] = set()
        moves = [p for fg in registry.figures for p in (staging / n for n in fg.images)
                 if p.is_file()]
        moves += sorted((staging / "values").glob("*.json")) + sorted((staging / "layout").glob("*.json"))
        moves += [built / p.file for p in registry.pages if p.id != "index"] + [built / "index.html"]
        for p in moves:
            rel = p.relative_to(built if p.parent == built else staging)
            dest = args.out / rel
            dest.parent.mkdir(parents=True, exist_ok=True)
            os.replace(p, dest)
            written.add(rel.as_posix())
        for p in stale_outputs(args.out, written):
            p.unlink()
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    counts: dict[str, int] = {}
    for r in results.values():
        counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    print(f"report: {args.out / 'index.html'} ({len(registry.pages)} pages) — " +
          ", ".join(f"{k}: {n}" for k, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
