"""What the ledger covers, said by the ledger: the thesis sections its entries measure, and the
entries it cannot measure yet. The summary and ledger pages place it as the `{{coverage}}` block;
no page may state coverage or count entries in its own words (`hand_written`), since such a
sentence goes stale the day an entry is added.

The section of an entry is the first §c.s its `section` cites ("§3.5.1.4, §3.6.1" -> §3.5, the
same reference registry.claim_chapter reads the chapter from); an entry citing only a figure,
a table or an equation counts in no section. A section is measured when at least one of its
entries is measured (any rule but not_covered and needs_data).
"""
from __future__ import annotations

import html
import re
from dataclasses import dataclass, field

SECTION_REF = re.compile(r"§(\d+)\.(\d+)")
# The rules that measure nothing, and what is said of one entry or of several under each.
UNMEASURED = {"not_covered": ("is not covered yet", "are not covered yet"),
              "needs_data": ("needs data we do not have", "need data we do not have")}


def claim_section(claim: dict) -> tuple[int, int] | None:
    mt = SECTION_REF.search(str(claim.get("section", "")))
    return (int(mt.group(1)), int(mt.group(2))) if mt else None


@dataclass
class Coverage:
    entries: int = 0
    measured: dict[int, set[int]] = field(default_factory=dict)  # chapter -> sections
    unmeasured: dict[str, list[dict]] = field(default_factory=dict)  # rule -> its entries


def coverage(claims: list[dict]) -> Coverage:
    cov = Coverage(entries=len(claims), unmeasured={rule: [] for rule in UNMEASURED})
    for cl in claims:
        rule = cl.get("compare")
        if rule in UNMEASURED:
            cov.unmeasured[rule].append(cl)
            continue
        sec = claim_section(cl)
        if sec:
            cov.measured.setdefault(sec[0], set()).add(sec[1])
    return cov


def ranges(numbers: set[int]) -> list[tuple[int, int]]:
    """Consecutive runs: {1, 3, 4, 5} -> [(1, 1), (3, 5)]."""
    runs: list[tuple[int, int]] = []
    for n in sorted(numbers):
        if runs and n == runs[-1][1] + 1:
            runs[-1] = (runs[-1][0], n)
        else:
            runs.append((n, n))
    return runs


def chapter_sections(chapter: int, sections: set[int]) -> str:
    """§2.1–2.5 for a run, §3.1, 3.3–3.6 for two."""
    parts = [f"{chapter}.{a}" if a == b else f"{chapter}.{a}–{chapter}.{b}"
             for a, b in ranges(sections)]
    return "§" + ", ".join(parts)


def entry_list(entries: list[dict]) -> str:
    """The sections some entries cite (§3.5, §3.6), and how many cite none."""
    cited = sorted({sec for sec in map(claim_section, entries) if sec})
    shown = ", ".join(f"§{ch}.{sec}" for ch, sec in cited)
    bare = sum(1 for cl in entries if claim_section(cl) is None)
    if bare:
        shown += (", " if shown else "") + f"{bare} citing a figure or table only"
    return shown


def coverage_html(claims: list[dict]) -> str:
    cov = coverage(claims)
    chapters = [f"chapter {ch} ({chapter_sections(ch, secs)})"
                for ch, secs in sorted(cov.measured.items())]
    measured = (", ".join(chapters[:-1]) + " and " + chapters[-1] if len(chapters) > 1
                else "".join(chapters) or "no section")
    left = sum(len(got) for got in cov.unmeasured.values())
    text = (f"Of the ledger's {cov.entries} entries, {cov.entries - left} measure statements of "
            f"{measured} (a section counts when one of its entries is measured).")
    for rule, (one, several) in UNMEASURED.items():
        got = cov.unmeasured[rule]
        if got:
            text += (f" {len(got)} {'entry' if len(got) == 1 else 'entries'} "
                     f"{one if len(got) == 1 else several} (in {entry_list(got)}).")
        elif rule == "not_covered":
            text += " Every entry is covered by a study."
    return f"<p class='coverage'>{text}</p>"


# ---------------------------------------------------------------------------------------------
# Statements of coverage or counts written by hand

SENTENCE = re.compile(r".*?(?:[.!?](?=\s|$)|$)")
COVER_WORD = re.compile(r"\bcover(?:s|ed|age)?\b", re.I)
SECTION_CITED = re.compile(r"§\s*\d")
COUNT = re.compile(r"(?<![\w§.])(?<!chapter )(?<!Chapter )\d[\d,]*\s+(?:of\s+(?:the\s+)?\d[\d,]*\s+)?"
                   r"(?:ledger\s+)?(?:entries|claims)\b")
VALUE = re.compile(r"\{[^{}]*\}")


def hand_written(text: str, where: str) -> list[str]:
    """The sentences of a page's prose that state coverage (a section cited beside 'covered') or a
    count of entries in literal digits; values ({script.key}), headings and block lines are
    generated or titles and not read. One problem per sentence, at the line it starts on."""
    problems = []
    paragraph: list[tuple[int, str]] = []

    def flush():
        starts, flat = [], ""
        for n, line in paragraph:
            starts.append((len(flat), n))
            flat += VALUE.sub("{v}", line) + " "
        for mt in SENTENCE.finditer(flat):
            sentence = mt.group(0).strip()
            if sentence and ((COVER_WORD.search(sentence) and SECTION_CITED.search(sentence))
                             or COUNT.search(sentence)):
                begins = mt.start() + len(mt.group(0)) - len(mt.group(0).lstrip())
                line = max(n for offset, n in starts if offset <= begins)
                problems.append(f"{where}:{line}: coverage or a count written by hand (it goes "
                                "stale; place {{coverage}} or {{verdicts}}): " + sentence[:120])
        paragraph.clear()

    for n, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if not stripped or stripped.startswith(("#", "{{")):
            flush()
        else:
            paragraph.append((n, stripped))
    flush()
    return problems
