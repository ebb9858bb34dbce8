"""The report's registry drives the build (reports/site/build_report.py, registry.py): each check
the builder makes bites on a small synthetic project (a temporary folder with a tiny registry,
pages, ledger, data and figure scripts), and the shipped registry agrees with reports/figures/.
Run by ctest with the interpreter that has Debian's matplotlib and python3-markdown."""
import json
import re
import subprocess
import sys
import tempfile
import textwrap
import tomllib
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
BUILDER = REPO / "reports" / "site" / "build_report.py"
sys.path.insert(0, str(REPO / "reports" / "site"))

import registry as reg  # noqa: E402

# A figure script: writes each file of WRITES (a PNG's bytes do not matter here) with its
# layout beside a PNG, and VALUES as values/<name>.json.
SCRIPT = """\
import argparse, json, pathlib
ap = argparse.ArgumentParser(); ap.add_argument("--data"); ap.add_argument("--out")
out = pathlib.Path(ap.parse_args().out)
for f in {writes!r}:
    (out / f).write_text("<p>fragment of " + f + "</p>" if f.endswith(".html") else "png")
    if f.endswith(".png"):
        (out / "layout" / (f[:-4] + ".json")).write_text("{{}}")
(out / "values" / "{name}.json").write_text(json.dumps({values!r}))
"""

REGISTRY = """\
[site]
title = "test report"

[[page]]
id = "index"
title = "Summary"
prose = "index.md"

[[page]]
id = "ch2"
title = "Chapter 2"
prose = "ch2.md"

[[figure]]
script = "fa"
page = "ch2"
study = "s1"
title = "Figure A, {fa.x:.2f}"
claims = ["c-1"]

[[figure]]
script = "fb"
page = "ch2"
study = "s1"
wide = true
table = "fb_table.html"
"""

LEDGER = """\
[[claim]]
id = "c-1"
section = "§2.1"
statement = "x is small"
thesis = 1.0
ours = "fa.x"
compare = "at_most"

[[claim]]
id = "own-1"
section = "§5.2"
statement = "ours only"
thesis = "not given"
ours = "fb.y"
compare = "at_least"
target = 0.0
"""

PAGES = {
    "index.md": "Summary with {fa.x:.1f}.\n\n{{verdicts}}\n\n{{pages}}\n",
    "ch2.md": "Chapter two.\n\n{{figures}}\n",
}


class Project:
    """A synthetic project in a temporary folder: figures/, thesis/ (registry, ledger, pages),
    data/<study>/ and out/."""

    def __init__(self, root: Path):
        self.root = root
        self.figures = root / "figures"
        self.thesis = root / "thesis"
        self.data = root / "data"
        self.out = root / "out"
        for d in (self.figures, self.thesis / "pages", self.data / "s1"):
            d.mkdir(parents=True)
        self.registry(REGISTRY)
        (self.thesis / "claims.toml").write_text(LEDGER)
        for name, text in PAGES.items():
            self.page(name, text)
        self.script("fa", ["fa.png"], {"x": 0.5})
        self.script("fb", ["fb.png", "fb_table.html"], {"y": 2.0})

    def registry(self, text: str) -> None:
        (self.thesis / "figures.toml").write_text(text)

    def page(self, name: str, text: str) -> None:
        (self.thesis / "pages" / name).write_text(text)

    def script(self, name: str, writes: list[str], values: dict) -> None:
        (self.figures / f"{name}.py").write_text(SCRIPT.format(writes=writes, values=values,
                                                                name=name))

    def build(self, *extra: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [sys.executable, str(BUILDER), "--data", str(self.data), "--out", str(self.out),
             "--registry", str(self.thesis / "figures.toml"),
             "--claims", str(self.thesis / "claims.toml"), "--figures", str(self.figures),
             "--jobs", "2", *extra], capture_output=True, text=True, timeout=300)

    def pages_written(self) -> list[str]:
        return sorted(p.name for p in self.out.glob("*.html")) if self.out.is_dir() else []


class RegistryChecks(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.p = Project(Path(self._tmp.name))

    def tearDown(self):
        self._tmp.cleanup()

    def assertFails(self, proc, *needles):
        """Exit 1, every needle named on stderr, and no page written."""
        self.assertEqual(proc.returncode, 1, proc.stderr)
        for needle in needles:
            self.assertIn(needle, proc.stderr)
        self.assertEqual(self.p.pages_written(), [], "a failed build wrote pages")

    # -- the fixture itself builds, and what it builds is clean

    def test_the_fixture_builds_every_page_and_only_what_the_builder_owns(self):
        self.p.out.mkdir()
        (self.p.out / "stale_body.html").write_text("old fragment")
        (self.p.out / "old.png").write_text("old image")
        (self.p.out / "notes.txt").write_text("not the builder's")
        (self.p.out / "values").mkdir()
        (self.p.out / "values" / "gone.json").write_text("{}")
        proc = self.p.build("--quick")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(self.p.pages_written(), ["ch2.html", "index.html"])
        self.assertFalse((self.p.out / "fb_table.html").exists(), "a fragment reached OUT")
        self.assertFalse((self.p.out / "stale_body.html").exists())
        self.assertFalse((self.p.out / "old.png").exists())
        self.assertFalse((self.p.out / "values" / "gone.json").exists())
        self.assertTrue((self.p.out / "notes.txt").exists(), "removed a file it does not own")
        self.assertTrue((self.p.out / "values" / "claims.json").exists())
        self.assertEqual([p.name for p in self.p.out.iterdir() if p.name.startswith(".")], [])
        ch2 = (self.p.out / "ch2.html").read_text()
        self.assertIn("Figure A, 0.50", ch2)
        self.assertIn("<p>fragment of fb_table.html</p>", ch2)  # the table, inlined
        self.assertIn("slipwalk reproduce s1", ch2)
        self.assertIn("reports/figures/fa.py --data data --out reports/out", ch2)
        for page in ("index.html", "ch2.html"):
            text = (self.p.out / page).read_text()
            self.assertIn("class='quick'", text, page)
            self.assertIn("<nav>", text, page)
            self.assertNotIn(str(self.p.root), text, f"{page} shows a machine path")
        index = (self.p.out / "index.html").read_text()
        self.assertIn("Summary with 0.5.", index)
        self.assertIn("Checks of our own", index)

    def test_a_missing_data_folder_skips_its_figures_and_says_how_to_build_them(self):
        (self.p.data / "s1").rmdir()
        (self.p.data / "s2").mkdir()
        self.p.registry(REGISTRY + '\n[[figure]]\nscript = "fc"\npage = "ch2"\nstudy = "s2"\n')
        self.p.script("fc", ["fc.png"], {})
        proc = self.p.build()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("Not built: run <code>slipwalk reproduce s1</code>",
                      (self.p.out / "ch2.html").read_text())

    # -- what a script writes against what its entry declares

    def test_a_figure_that_wrote_no_png_fails(self):
        self.p.script("fa", [], {"x": 0.5})
        self.assertFails(self.p.build(), "fa.py: wrote no fa.png")

    def test_a_named_table_that_was_not_written_fails(self):
        self.p.script("fb", ["fb.png"], {"y": 2.0})
        self.assertFails(self.p.build(), "fb.py: wrote no fb_table.html")

    def test_an_image_false_figure_needs_no_png(self):
        self.p.registry(REGISTRY.replace('script = "fa"\n', 'script = "fa"\nimage = false\n'))
        self.p.script("fa", [], {"x": 0.5})
        self.assertEqual(self.p.build().returncode, 0)

    def test_a_png_no_entry_declares_fails(self):
        self.p.script("fa", ["fa.png", "fa_extra.png"], {"x": 0.5})
        self.assertFails(self.p.build(), "fa_extra.png: written by a figure script but declared")

    def test_an_html_fragment_no_entry_declares_fails(self):
        self.p.script("fa", ["fa.png", "fa_body.html"], {"x": 0.5})
        self.assertFails(self.p.build(), "fa_body.html: written by a figure script but declared")

    def test_declared_images_and_a_body_are_accepted(self):
        self.p.registry(REGISTRY.replace(
            'script = "fa"\n', 'script = "fa"\nimages = ["fa_1.png", "fa_2.png"]\n'
            'body = "fa_body.html"\n'))
        self.p.script("fa", ["fa_1.png", "fa_2.png", "fa_body.html"], {"x": 0.5})
        proc = self.p.build()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("<p>fragment of fa_body.html</p>", (self.p.out / "ch2.html").read_text())
        self.assertTrue((self.p.out / "fa_2.png").exists())
        self.assertFalse((self.p.out / "fa_body.html").exists())

    # -- the registry against reports/figures/

    def test_a_script_that_is_not_registered_fails(self):
        self.p.script("fz", ["fz.png"], {})
        self.assertFails(self.p.build(), "fz.py: not registered")

    def test_a_registered_script_that_is_missing_fails(self):
        (self.p.figures / "fb.py").unlink()
        self.assertFails(self.p.build(), "[[figure]] fb:", "fb.py does not exist")

    # -- claims and values

    def test_a_claim_quoting_a_value_no_script_wrote_fails(self):
        (self.p.thesis / "claims.toml").write_text(LEDGER.replace('ours = "fa.x"', 'ours = "fa.nope"'))
        self.assertFails(self.p.build(), "claim c-1: value fa.nope does not exist")

    def test_a_claim_on_a_value_that_is_not_a_registered_script_fails(self):
        (self.p.thesis / "claims.toml").write_text(LEDGER.replace('ours = "fb.y"', 'ours = "fq.y"'))
        self.assertFails(self.p.build(), "value fq.y: 'fq' is not a registered script")

    def test_a_value_in_a_figure_text_or_page_that_no_script_wrote_fails(self):
        self.p.page("ch2.md", "Chapter {fb.missing:.2f}.\n\n{{figures}}\n")
        self.p.registry(REGISTRY.replace("{fa.x:.2f}", "{fa.gone}"))
        self.assertFails(self.p.build(), "ch2.md: value fb.missing", "[[figure]] fa: value fa.gone")

    def test_a_value_with_a_reason_is_not_measured_and_not_an_error(self):
        self.p.script("fa", ["fa.png"], {"x_reason": "no rows in regime I"})
        self.p.registry(REGISTRY.replace("{fa.x:.2f}", "{fa.x}"))
        proc = self.p.build()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        claims = json.loads((self.p.out / "values" / "claims.json").read_text())
        self.assertEqual({c["id"]: c["verdict"] for c in claims}["c-1"], "not measured")
        self.assertIn("not measured (no rows in regime I)", (self.p.out / "ch2.html").read_text())

    def test_a_figure_naming_a_claim_the_ledger_lacks_fails(self):
        self.p.registry(REGISTRY.replace('claims = ["c-1"]', 'claims = ["c-1", "c-9"]'))
        self.assertFails(self.p.build(), "[[figure]] fa: claim 'c-9' is not in")

    def test_a_claim_in_the_registry_instead_of_the_ledger_fails(self):
        self.p.registry(REGISTRY + '\n[[claim]]\nid = "c-2"\nsection = "§2"\n')
        self.assertFails(self.p.build(), "[[claim]] entries belong in the claims ledger")

    # -- pages and their prose

    def test_a_figure_its_page_does_not_place_fails(self):
        self.p.page("ch2.md", "Chapter two, no figures.\n")
        self.assertFails(self.p.build(), "figure fa (page ch2) has no place")

    def test_an_unknown_block_marker_fails(self):
        self.p.page("ch2.md", "{{figures}}\n\n{{figurez}}\n")
        self.assertFails(self.p.build(), "ch2.md:3: unknown block {{figurez}}")

    def test_a_page_stating_coverage_by_hand_fails_and_the_block_says_it_from_the_ledger(self):
        self.p.page("index.md", "Not covered yet: §5.3.\n\n{{verdicts}}\n")
        self.assertFails(self.p.build(), "index.md:1: coverage or a count written by hand")
        self.p.page("index.md", "Summary.\n\n{{coverage}}\n\n{{pages}}\n")
        proc = self.p.build()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        said = re.sub(r"<[^>]*>", "", (self.p.out / "index.html").read_text())
        self.assertIn("Of the ledger's 2 entries, 2 measure statements of chapter 2 (§2.1) and "
                      "chapter 5 (§5.2)", said)

    def test_a_figure_on_a_page_that_is_not_registered_fails(self):
        self.p.registry(REGISTRY.replace('page = "ch2"\nstudy = "s1"\nwide', 'page = "ch9"\nstudy = "s1"\nwide'))
        self.assertFails(self.p.build(), "[[figure]] fb: page 'ch9' is not a [[page]]")

    def test_a_single_figure_marker_and_sections_place_figures(self):
        self.p.registry(REGISTRY.replace('script = "fb"\n', 'script = "fb"\nsection = "2.5"\n'))
        self.p.page("ch2.md", "{{figure script=fa}}\n\n## 2.5\n\n{{figures section=2.5}}\n")
        proc = self.p.build()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        ch2 = (self.p.out / "ch2.html").read_text()
        self.assertLess(ch2.index("id='fig-fa'"), ch2.index("<h2"))
        self.assertLess(ch2.index("<h2"), ch2.index("id='fig-fb'"))


class ShippedRegistry(unittest.TestCase):
    """The registry in data/thesis/figures.toml against reports/figures/, data/thesis/pages/,
    studies/ and the claims ledger."""

    @classmethod
    def setUpClass(cls):
        cls.registry = reg.load(REPO / "data" / "thesis" / "figures.toml")

    def test_every_script_in_reports_figures_is_registered_and_every_registered_one_exists(self):
        self.assertEqual(reg.check_scripts(self.registry, REPO / "reports" / "figures"), [])

    def test_every_page_has_its_prose_and_places_every_figure(self):
        self.assertEqual(reg.check_pages(self.registry, REPO / "data" / "thesis" / "pages"), [])

    def test_every_study_is_a_folder_of_studies(self):
        for study in self.registry.studies():
            self.assertTrue((REPO / "studies" / study).is_dir(), study)

    def test_the_registry_holds_no_claims_and_every_figure_claim_is_in_the_ledger(self):
        ledger = tomllib.loads((REPO / "data" / "thesis" / "claims.toml").read_text())
        self.assertEqual(reg.check_tables(self.registry), [])
        self.assertEqual(reg.check_claim_ids(self.registry, ledger.get("claim", []),
                                             "claims.toml"), [])


class VerdictCounts(unittest.TestCase):
    """The summary's table: chapters from each claim's section, checks of our own apart, and a
    column for every verdict (one the ledger does not list yet included)."""

    def test_chapters_own_checks_and_any_verdict(self):
        import pages  # noqa: PLC0415 (needs python3-markdown)

        registry = reg.Registry(Path("figures.toml"), "t",
                                [reg.Page("index", "Summary", "Summary", "index.md"),
                                 reg.Page("ch5", "Chapter 5", "Chapter 5", "ch5.md")], [])
        claims = [{"id": "a", "section": "§5.2.1, Fig. 5.2", "thesis": 1.0},
                  {"id": "b", "section": "§3.5.1", "thesis": 1.0},
                  {"id": "c", "section": "§5.2.1", "thesis": "not given"},
                  {"id": "d", "section": "§4.2", "thesis": 2.0}]
        results = {"a": {"verdict": "reproduced"}, "b": {"verdict": "reproduced"},
                   "c": {"verdict": "reproduced"}, "d": {"verdict": "not covered yet"}}
        b = pages.Build(registry=registry, claims=claims, results=results, values=None,
                        staging=Path("."), ran=set(), data=Path("data"), data_name="data",
                        repo=REPO, script_times={}, quick=False)
        html = pages.verdicts_table(b)
        def text(cell):
            return re.sub(r"<[^>]*>", "", cell).strip()

        cells = {}
        for row in html.split("<tr")[2:]:  # after the head
            head, _, rest = row.partition("</th>")
            cells[text(head.split("<th>", 1)[1])] = [text(c) for c in rest.split("</td>")[:-1]]
        verdicts = b.verdicts()
        self.assertIn("not covered yet", verdicts)
        col = {v: i for i, v in enumerate(verdicts)}
        self.assertEqual(cells["Chapter 5"][col["reproduced"]], "1")  # §5.2 in chapter 5
        self.assertEqual(cells["Chapter 3"][col["reproduced"]], "1")
        self.assertEqual(cells["Chapter 4"][col["not covered yet"]], "1")
        self.assertEqual(cells["Checks of our own"][col["reproduced"]], "1")
        self.assertEqual(cells["All"][-1], "4")


class Markers(unittest.TestCase):
    def test_markers_parse_and_a_marker_inside_a_line_is_a_problem(self):
        parts, problems = reg.parse_prose(textwrap.dedent("""\
            Text.
            {{figures section=2.5}}
            More {{figures}} text.
            {{figure}}
            """), "p.md")
        blocks = [p for p in parts if isinstance(p, reg.Block)]
        self.assertEqual([(b.name, b.args) for b in blocks], [("figures", {"section": "2.5"})])
        self.assertEqual(len(problems), 2, problems)
        self.assertIn("p.md:3: a block marker", problems[0])
        self.assertIn("p.md:4: {{figure}} takes script; missing script", problems[1])

    def test_the_chapter_of_a_claim_comes_from_its_section(self):
        for section, chapter in [("§2.3.1", "2"), ("Fig. 2.3 caption", "2"), ("eq. 2.6", "2"),
                                 ("§5.2.1, Fig. 5.2", "5"), ("§3.5.1.5 (about §3.5.1.4)", "3"),
                                 ("", "")]:
            self.assertEqual(reg.claim_chapter({"section": section}), chapter, section)


if __name__ == "__main__":
    unittest.main()
