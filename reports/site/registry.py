"""The report's registry, data/thesis/figures.toml: its pages, its figures, what each figure's
script writes, and the checks that keep the registry, the scripts, the page prose, the ledger and
the built outputs in step.

Loading a malformed registry raises RegistryError (the builder's exit 2: bad input). The checks
return lists of problems, one line each, naming the file and the entry (the builder's exit 1);
they never raise, so that one build names every problem at once.

Page prose (data/thesis/pages/<id>.md) is Markdown with two additions:
  {script.key} or {script.key:.3g}   a value (ledger.TEMPLATE), expanded before Markdown;
                                     `model.<name>` reads the model constants (MODEL_VALUES)
  {{name key=value ...}}             a line of its own: a block the builder generates (BLOCKS)
"""
from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import coverage
from ledger import TEMPLATE

# ---------------------------------------------------------------------------------------------
# The registry's fields (documented in the head of data/thesis/figures.toml)

PAGE_FIELDS = {"id", "title", "nav", "prose"}
FIGURE_FIELDS = {"script", "page", "section", "study", "wide", "image", "images", "table", "body",
                 "title", "thesis", "shows", "quote", "claims"}
TEXT_FIELDS = ("title", "thesis", "shows", "quote")  # may quote values as {script.key}
# Names the builder writes itself into OUT and OUT/values; no script may take them.
RESERVED_SCRIPTS = {"claims", "model"}

# The blocks a page's prose may place, and the arguments each takes (required ones first in
# REQUIRED_ARGS). figures: the page's figures of one section (none: those without a section)
# that no `figure` block places; figure: one figure of the page; verdicts: the verdict counts,
# chapters x verdicts (chapter=N: one chapter's counts); claims: the ledger's entries of one
# chapter; ledger: the whole claims ledger, filterable; own-checks: the checks of our own
# (claims whose thesis is "not given"); pages: a link to every page; provenance: where every
# data file and this build come from; outcomes: what became of every sweep point; coverage: the
# sections the ledger measures and the entries it cannot (coverage.py).
BLOCKS = {"figures": {"section"}, "figure": {"script"}, "verdicts": {"chapter"},
          "claims": {"chapter"}, "ledger": set(), "own-checks": set(), "pages": set(),
          "provenance": set(), "outcomes": set(), "coverage": set()}
REQUIRED_ARGS = {"figure": {"script"}, "claims": {"chapter"}}
MARKER = re.compile(r"^\{\{\s*([a-z][a-z-]*)((?:\s+[a-z]+=[^\s{}=]+)*)\s*\}\}\s*$")

# The chapter of a ledger entry: the first number of its `section` (§3.5.1 -> 3, "eq. 2.6" -> 2).
CHAPTER = re.compile(r"(\d+)(?:\.\d+)*")
OWN_CHECK = "not given"  # a claim whose thesis value is exactly this is a check of our own


class RegistryError(Exception):
    """A registry that cannot be read: malformed TOML, a field of the wrong type, a duplicate."""


@dataclass
class Page:
    id: str
    title: str
    nav: str
    prose: str  # the Markdown file's name, relative to the pages folder

    @property
    def file(self) -> str:
        return f"{self.id}.html"


@dataclass
class Figure:
    script: str
    page: str
    study: str
    section: str = ""
    wide: bool = False
    images: list[str] = field(default_factory=list)
    table: str | None = None
    body: str | None = None
    claims: list[str] = field(default_factory=list)
    entry: dict = field(default_factory=dict)  # the registry entry as written (its texts)

    def outputs(self) -> list[str]:
        """Every file the script writes at the top of OUT (values/ and layout/ apart)."""
        return self.images + [f for f in (self.table, self.body) if f]

    def required(self) -> list[str]:
        """What a run of the script must have written. A body places its own images and says
        when one could not be drawn, so a figure with a body requires the body (and its table)
        only."""
        extra = [f for f in (self.table, self.body) if f]
        return extra if self.body else self.images + extra


@dataclass
class Registry:
    path: Path
    site_title: str
    pages: list[Page]
    figures: list[Figure]
    stray: dict = field(default_factory=dict)  # tables the registry does not define

    def page(self, page_id: str) -> Page | None:
        return next((p for p in self.pages if p.id == page_id), None)

    def figure(self, script: str) -> Figure | None:
        return next((f for f in self.figures if f.script == script), None)

    def studies(self) -> list[str]:
        """The data folders the figures read, in registry order."""
        return list(dict.fromkeys(f.study for f in self.figures))


def _text(entry: dict, key: str, where: str, required: bool = True) -> str:
    value = entry.get(key)
    if value is None and not required:
        return ""
    if not isinstance(value, str) or (required and not value.strip()):
        raise RegistryError(f"{where}: '{key}' must be a non-empty string")
    return value


def _name_list(entry: dict, key: str, where: str) -> list[str]:
    value = entry.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        raise RegistryError(f"{where}: '{key}' must be a list of strings")
    return value


def load(path: Path) -> Registry:
    """Reads and validates the form of the registry (not yet its agreement with anything)."""
    try:
        raw = tomllib.loads(path.read_text())
    except (OSError, UnicodeDecodeError) as e:
        raise RegistryError(f"{path}: cannot read: {e}") from e
    except tomllib.TOMLDecodeError as e:
        raise RegistryError(f"{path}: {e}") from e
    unknown = {k: raw[k] for k in sorted(set(raw) - {"site", "page", "figure"})}
    site = raw.get("site", {})
    if not isinstance(site, dict):
        raise RegistryError(f"{path}: [site] must be a table")
    site_title = _text(site, "title", f"{path}: [site]")

    pages: list[Page] = []
    for i, entry in enumerate(raw.get("page", [])):
        where = f"{path}: [[page]] {entry.get('id', f'#{i + 1}')}"
        extra = sorted(set(entry) - PAGE_FIELDS)
        if extra:
            raise RegistryError(f"{where}: unknown fields {', '.join(extra)}")
        pid = _text(entry, "id", where)
        if not re.fullmatch(r"[a-z0-9_]+", pid):
            raise RegistryError(f"{where}: 'id' must be lower-case letters, digits and _")
        title = _text(entry, "title", where)
        pages.append(Page(pid, title, _text(entry, "nav", where, False) or title,
                          _text(entry, "prose", where)))
    ids = [p.id for p in pages]
    if len(set(ids)) != len(ids):
        raise RegistryError(f"{path}: duplicate page ids "
                            f"{sorted({i for i in ids if ids.count(i) > 1})}")
    if "index" not in ids:
        raise RegistryError(f"{path}: no [[page]] with id = \"index\" (the summary page)")

    figures: list[Figure] = []
    for i, entry in enumerate(raw.get("figure", [])):
        where = f"{path}: [[figure]] {entry.get('script', f'#{i + 1}')}"
        extra = sorted(set(entry) - FIGURE_FIELDS)
        if extra:
            raise RegistryError(f"{where}: unknown fields {', '.join(extra)}")
        script = _text(entry, "script", where)
        if not re.fullmatch(r"[a-z0-9_]+", script) or script in RESERVED_SCRIPTS:
            raise RegistryError(f"{where}: 'script' must be a file name of reports/figures/ "
                                f"without .py (lower case), not one of {sorted(RESERVED_SCRIPTS)}")
        for key in ("wide", "image"):
            if key in entry and not isinstance(entry[key], bool):
                raise RegistryError(f"{where}: '{key}' must be true or false")
        for key in TEXT_FIELDS:
            _text(entry, key, where, False)
        images = _name_list(entry, "images", where)
        if "images" in entry and "image" in entry:
            raise RegistryError(f"{where}: give 'images' or 'image', not both")
        if "images" not in entry:
            images = [f"{script}.png"] if entry.get("image", True) else []
        if not all(n.endswith(".png") and "/" not in n for n in images):
            raise RegistryError(f"{where}: 'images' must name .png files in OUT")
        fragments = {}
        for key in ("table", "body"):
            name = _text(entry, key, where, False) or None
            if name is not None and (not name.endswith(".html") or "/" in name):
                raise RegistryError(f"{where}: '{key}' must name an .html file in OUT")
            fragments[key] = name
        figures.append(Figure(
            script=script, page=_text(entry, "page", where), study=_text(entry, "study", where),
            section=str(entry.get("section", "")), wide=bool(entry.get("wide", False)),
            images=images, table=fragments["table"], body=fragments["body"],
            claims=_name_list(entry, "claims", where), entry=entry))
    scripts = [f.script for f in figures]
    if len(set(scripts)) != len(scripts):
        raise RegistryError(f"{path}: scripts registered twice "
                            f"{sorted({s for s in scripts if scripts.count(s) > 1})}")
    owners: dict[str, str] = {}
    for f in figures:
        for name in f.outputs():
            if name in owners or name in {p.file for p in pages}:
                raise RegistryError(f"{path}: {name} is declared by both {owners.get(name, 'a page')}"
                                    f" and {f.script}")
            owners[name] = f.script
    return Registry(path, site_title, pages, figures, unknown)


# ---------------------------------------------------------------------------------------------
# Page prose: Markdown chunks and block markers


@dataclass
class Block:
    name: str
    args: dict[str, str]
    line: int


def parse_prose(text: str, where: str) -> tuple[list[str | Block], list[str]]:
    """The prose as Markdown chunks and blocks, in order, and the problems of its markers."""
    parts: list[str | Block] = []
    problems: list[str] = []
    chunk: list[str] = []
    for n, line in enumerate(text.splitlines(), 1):
        mt = MARKER.match(line)
        if not mt:
            if "{{" in line or "}}" in line:
                problems.append(f"{where}:{n}: a block marker {{{{name key=value}}}} must be a "
                                f"line of its own, with key=value arguments: {line.strip()}")
            chunk.append(line)
            continue
        name = mt.group(1)
        args = dict(a.split("=", 1) for a in mt.group(2).split())
        if name not in BLOCKS:
            problems.append(f"{where}:{n}: unknown block {{{{{name}}}}} (known: "
                            f"{', '.join(sorted(BLOCKS))})")
            continue
        bad = sorted(set(args) - BLOCKS[name])
        missing = sorted(REQUIRED_ARGS.get(name, set()) - set(args))
        if bad or missing:
            problems.append(f"{where}:{n}: {{{{{name}}}}} takes "
                            f"{', '.join(sorted(BLOCKS[name])) or 'no arguments'}"
                            + (f"; unknown {', '.join(bad)}" if bad else "")
                            + (f"; missing {', '.join(missing)}" if missing else ""))
            continue
        parts.append("\n".join(chunk))
        chunk = []
        parts.append(Block(name, args, n))
    parts.append("\n".join(chunk))
    return parts, problems


def read_prose(registry: Registry, page: Page, pages_dir: Path) -> tuple[str | None, str]:
    path = pages_dir / page.prose
    try:
        return path.read_text(), str(path)
    except OSError:
        return None, str(path)


def place_figures(registry: Registry, page: Page, parts: list, where: str
                  ) -> tuple[dict[int, list[Figure]], list[str]]:
    """Which figures each block of a page shows (by the block's index in parts), and the
    problems: a figure of the page no block places, a figure placed twice or on another page."""
    mine = [f for f in registry.figures if f.page == page.id]
    placed: dict[int, list[Figure]] = {}
    problems: list[str] = []
    singles = {}
    for i, part in enumerate(parts):
        if isinstance(part, Block) and part.name == "figure":
            fg = registry.figure(part.args["script"])
            if fg is None or fg.page != page.id:
                problems.append(f"{where}:{part.line}: {{{{figure script={part.args['script']}}}}}"
                                f": no figure of page '{page.id}' has that script")
                continue
            if fg.script in singles:
                problems.append(f"{where}:{part.line}: figure {fg.script} placed twice")
                continue
            singles[fg.script] = i
            placed[i] = [fg]
    sections_seen: set[str] = set()
    for i, part in enumerate(parts):
        if isinstance(part, Block) and part.name == "figures":
            section = part.args.get("section", "")
            if section in sections_seen:
                problems.append(f"{where}:{part.line}: {{{{figures"
                                f"{' section=' + section if section else ''}}}}} appears twice")
                continue
            sections_seen.add(section)
            placed[i] = [f for f in mine if f.section == section and f.script not in singles]
    for f in mine:
        if f.script not in singles and f.section not in sections_seen:
            marker = "{{figures" + (f" section={f.section}" if f.section else "") + "}}"
            problems.append(f"{where}: figure {f.script} (page {page.id}"
                            f"{', section ' + f.section if f.section else ''}) has no place: "
                            f"add a line {marker} or {{{{figure script={f.script}}}}}")
    return placed, problems


# ---------------------------------------------------------------------------------------------
# Ledger entries


def claim_chapter(claim: dict) -> str:
    """The thesis chapter of a ledger entry, from its `section` ("" when it names none)."""
    mt = CHAPTER.search(str(claim.get("section", "")))
    return mt.group(1) if mt else ""


def is_own_check(claim: dict) -> bool:
    return claim.get("thesis") == OWN_CHECK


def claim_keys(claim: dict) -> list[str]:
    """Every value key a ledger entry reads: ours, check, and the values its texts quote."""
    keys: list[str] = []
    for field_name in ("ours", "check"):
        v = claim.get(field_name)
        keys += [v] if isinstance(v, str) else [k for k in (v or []) if isinstance(k, str)]
    for field_name in ("statement", "criterion", "note", "explanation"):
        keys += template_keys(claim.get(field_name))
    return keys


def template_keys(text) -> list[str]:
    if not isinstance(text, str):
        return []
    return [f"{m.group(1)}.{m.group(2)}" for m in TEMPLATE.finditer(text)]


# ---------------------------------------------------------------------------------------------
# Checks, each a list of problems


def check_tables(registry: Registry) -> list[str]:
    """The registry holds its own tables only: a [[claim]] here would be read by nobody."""
    problems = []
    for name, value in registry.stray.items():
        ids = [str(e.get("id")) for e in value if isinstance(e, dict)] if isinstance(value, list) else []
        hint = (" ([[claim]] entries belong in the claims ledger, data/thesis/claims.toml)"
                if name == "claim" else "")
        problems.append(f"{registry.path}: '{name}' is not a table of the registry{hint}"
                        + (f": {', '.join(ids)}" if ids else ""))
    return problems


def check_scripts(registry: Registry, figures_dir: Path) -> list[str]:
    """Every script in the figures folder is registered, and every registered one is there."""
    present = {p.stem for p in figures_dir.glob("*.py") if not p.name.startswith("_")}
    registered = {f.script for f in registry.figures}
    problems = [f"{figures_dir / (s + '.py')}: not registered in {registry.path} (add a "
                f"[[figure]] entry with script = \"{s}\")" for s in sorted(present - registered)]
    problems += [f"{registry.path}: [[figure]] {s}: {figures_dir / (s + '.py')} does not exist"
                 for s in sorted(registered - present)]
    return problems


def check_pages(registry: Registry, pages_dir: Path) -> list[str]:
    """Every figure's page exists, every page's prose exists, its markers parse and place every
    figure of the page exactly once, and it states no coverage or count in its own words."""
    problems = [f"{registry.path}: [[figure]] {f.script}: page '{f.page}' is not a [[page]]"
                for f in registry.figures if registry.page(f.page) is None]
    for page in registry.pages:
        text, where = read_prose(registry, page, pages_dir)
        if text is None:
            problems.append(f"{registry.path}: [[page]] {page.id}: prose {where} does not exist")
            continue
        parts, bad = parse_prose(text, where)
        problems += bad + coverage.hand_written(text, where)
        problems += place_figures(registry, page, parts, where)[1]
    return problems


def check_claim_ids(registry: Registry, claims: list[dict], ledger_path) -> list[str]:
    """Every id a figure names is an entry of the ledger."""
    ids = {c.get("id") for c in claims}
    return [f"{registry.path}: [[figure]] {f.script}: claim '{cid}' is not in {ledger_path}"
            for f in registry.figures for cid in f.claims if cid not in ids]


def check_outputs(registry: Registry, staging: Path, ran: set[str]) -> list[str]:
    """Every script that ran wrote what its entry requires, and nothing was written that no entry
    declares: a PNG or HTML file at the top of the staging folder, values/<x>.json for a script x
    that is not registered, layout/<x>.json for an image x.png that is not declared."""
    problems = []
    for f in registry.figures:
        if f.script not in ran:
            continue
        for name in f.required():
            if not (staging / name).is_file():
                problems.append(f"reports/figures/{f.script}.py: wrote no {name} (declared in "
                                f"{registry.path}; declare what it writes: image = false, "
                                "images = [...], table, body)")
    declared = {name: f.script for f in registry.figures for name in f.outputs()}
    for p in sorted(staging.iterdir()):
        if p.is_file() and p.suffix in (".png", ".html") and p.name not in declared:
            problems.append(f"{p.name}: written by a figure script but declared by no [[figure]] "
                            f"entry of {registry.path} (images = [...], table or body)")
    scripts = {f.script for f in registry.figures}
    for p in sorted((staging / "values").glob("*.json")):
        if p.stem not in scripts:
            problems.append(f"values/{p.name}: written for '{p.stem}', which is not a registered "
                            "script")
    for p in sorted((staging / "layout").glob("*.json")):
        if f"{p.stem}.png" not in declared:
            problems.append(f"layout/{p.name}: the layout of {p.stem}.png, which no [[figure]] "
                            "entry declares")
    return problems


def check_keys(keys: dict[str, list[str]], values, ran: set[str], registered: set[str]
               ) -> tuple[list[str], list[str]]:
    """Every value key referenced (key -> where it is referenced) exists: problems, and warnings
    for the keys of scripts that ran but wrote no values at all (their output says why). Keys of
    scripts that did not run (their data folder is missing) are not measured by design. A key
    that is absent but has `<key>_reason` is a value that was legitimately not measured, as is a
    key whose value is null."""
    problems: list[str] = []
    unmeasured: dict[str, list[str]] = {}
    for key, wheres in sorted(keys.items()):
        script, _, name = key.partition(".")
        where = "; ".join(dict.fromkeys(wheres))
        if script == "model":
            if not values.has(key):
                problems.append(f"{where}: {{{key}}}: no model constant '{name}'")
            continue
        if script not in registered:
            problems.append(f"{where}: value {key}: '{script}' is not a registered script")
        elif script not in ran:
            continue  # skipped for a missing data folder: the builder has said so
        elif script not in values.by_script:
            unmeasured.setdefault(script, []).append(key)
        elif not values.has(key) and not values.has(key + "_reason"):
            problems.append(f"{where}: value {key} does not exist in values/{script}.json "
                            f"(a value that cannot be measured carries {name}_reason)")
    warnings = [f"{script}.py wrote no values: {len(keys_)} quoted value(s) not measured ("
                f"{', '.join(keys_[:3])}{', …' if len(keys_) > 3 else ''})"
                for script, keys_ in unmeasured.items()]
    return problems, warnings
