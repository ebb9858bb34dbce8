"""The page check (reports/site/check_pages.py) bites: fixture pages, each with one fault — a
broken image, a page wider than the viewport, 6 px HTML text, a figure whose layout file gives
text too small as shown, links to a missing file and a missing anchor — are each reported, and a
clean page passes. Needs Chromium (the Debian package `chromium`, a declared dependency): without
it these tests fail, they do not skip. Run by ctest with the report's interpreter."""
import json
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

SITE = Path(__file__).resolve().parents[2] / "reports" / "site"
SCRIPT = SITE / "check_pages.py"
sys.path.insert(0, str(SITE))

import check_pages  # noqa: E402

HEAD = "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>{t}</title>" \
       "<style>body{{margin:0;font:16px sans-serif}} img{{display:block}}</style></head><body>\n"


def png(path: Path, width: int, height: int) -> None:
    """A plain light-grey PNG, written with zlib only."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    rows = b"".join(b"\0" + b"\xee" * width for _ in range(height))
    path.write_bytes(b"\x89PNG\r\n\x1a\n"
                     + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def png_size(path: Path) -> tuple[int, int]:
    return struct.unpack(">II", path.read_bytes()[16:24])


def layout(out: Path, stem: str, width_in: float, text_min_pt: float) -> None:
    """OUT/layout/<stem>.json as save_figure (reports/plotting/common.py) writes it."""
    (out / "layout").mkdir(exist_ok=True)
    (out / "layout" / f"{stem}.json").write_text(json.dumps({
        "width_in": width_in, "height_in": width_in / 2, "dpi": 100, "texts": 2,
        "text_min_pt": text_min_pt,
        "smallest": [{"pt": text_min_pt, "text": "tick 0"}, {"pt": 12, "text": "title"}]}))


def page(out: Path, name: str, body: str) -> None:
    (out / name).write_text(HEAD.format(t=name) + body + "\n</body></html>\n")


def write_clean(out: Path) -> None:
    """A readable page: a figure shown 700 px wide whose smallest text is 10 pt in a 7-inch
    figure (10 x 700 / (96 x 7) = 10.4 pt on the page), a figure without a layout file (a note,
    not a failure), 16 px text, links that resolve, and a height that needs three tiles."""
    png(out / "fig_ok.png", 700, 350)
    layout(out, "fig_ok", 7.0, 10.0)
    png(out / "photo.png", 200, 100)
    page(out, "clean.html",
         "<h1 id='top'>Clean</h1><p>Readable text.</p>"
         "<img src='fig_ok.png' style='width:700px' alt='ok figure'>"
         "<img src='photo.png' alt='no layout file'>"
         "<p><a href='#top'>top</a> <a href='clean.html#top'>self</a> "
         "<a href='https://example.org/x'>elsewhere</a></p>"
         "<div style='height:4200px'></div><p>end</p>")


class CheckPages(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if check_pages.find_chromium(None) is None:
            raise AssertionError("Chromium not found: install the Debian package `chromium` "
                                 "(`make deps-test`); the page check cannot run without it")
        cls.tmp = tempfile.TemporaryDirectory(prefix="check_pages_test.")
        root = Path(cls.tmp.name)

        cls.clean_out = root / "clean"
        cls.clean_out.mkdir()
        write_clean(cls.clean_out)
        cls.clean_run = cls.run_check(cls.clean_out)

        out = cls.bad_out = root / "bad"
        out.mkdir()
        write_clean(out)
        page(out, "broken.html", "<p>A figure that is not there:</p>"
                                 "<img src='missing.png' alt='missing'>")
        page(out, "wide.html", "<p>Too wide:</p><div id='slab' style='width:2000px'>x</div>")
        page(out, "tiny.html", "<p>Fine.</p><p class='fine-print' style='font-size:6px'>"
                               "six pixels</p>")
        # Shown 700 px wide, a 13-inch figure's 7 pt text is 7 x 700 / (96 x 13) = 3.9 pt.
        png(out / "fig_small.png", 1300, 500)
        layout(out, "fig_small", 13.0, 7.0)
        page(out, "smallfig.html", "<img src='fig_small.png' style='width:700px' alt='small'>")
        page(out, "links.html", "<a href='nowhere.html'>gone</a> "
                                "<a href='clean.html#no-such-id'>bad anchor</a> "
                                "<a href='clean.html#top'>good</a>")
        (out / "fragment_body.html").write_text("<section><img src='missing.png'></section>")
        cls.bad_run = cls.run_check(out)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    @classmethod
    def run_check(cls, out: Path, *extra: str):
        res = out / "results.json"
        proc = subprocess.run([sys.executable, str(SCRIPT), str(out), "--json", str(res), *extra],
                              capture_output=True, text=True, timeout=300)
        results = {r["page"]: r for r in json.loads(res.read_text())} if res.exists() else {}
        return proc, results

    def problems(self, name: str) -> list[str]:
        return self.bad_run[1][name]["problems"]

    def test_clean_page_passes(self):
        proc, results = self.clean_run
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        r = results["clean.html"]
        self.assertEqual(r["problems"], [])
        self.assertIn("photo.png: not measurable (no layout/photo.json)", r["notes"])
        self.assertAlmostEqual(r["figure_min_pt"], 10 * 700 / (96 * 7), places=2)
        self.assertAlmostEqual(r["text_min_pt"], 12.0, places=2)
        self.assertRegex(proc.stdout, r"clean\.html: ok — ")

    def test_screenshots_are_tiles_of_the_page_width(self):
        proc, results = self.clean_run
        shots = [Path(p) for p in results["clean.html"]["screens"]]
        self.assertEqual([p.name for p in shots],
                         ["clean-01.png", "clean-02.png", "clean-03.png"])
        sizes = [png_size(p) for p in shots]
        self.assertTrue(all(w == 1400 for w, _ in sizes), sizes)
        self.assertEqual(sum(h for _, h in sizes), results["clean.html"]["height"])

    def test_failures_exit_1_and_list_each_page(self):
        proc, results = self.bad_run
        self.assertEqual(proc.returncode, 1, proc.stdout + proc.stderr)
        self.assertEqual(results["clean.html"]["problems"], [])
        for name in ("broken.html", "wide.html", "tiny.html", "smallfig.html", "links.html"):
            self.assertIn(f"\n{name}: ", proc.stdout)
        self.assertNotIn("fragment_body.html", results)  # fragments are not pages

    def test_broken_image(self):
        self.assertEqual(self.problems("broken.html"),
                         ["broken image: 'missing.png' (no such file) at img"])

    def test_page_wider_than_viewport(self):
        [p] = self.problems("wide.html")
        self.assertIn("page is 2000 px wide in a 1400 px viewport: div#slab 2000 px wide", p)

    def test_small_html_text(self):
        [p] = self.problems("tiny.html")
        self.assertIn("HTML text too small: 4.5 pt (6 px) in p.fine-print", p)

    def test_small_figure_text(self):
        [p] = self.problems("smallfig.html")
        self.assertIn("figure text too small: fig_small.png shown 700 px wide, 13 in figure: "
                      "smallest text 3.9 pt < 8 ('tick 0' 7 pt -> 3.9, 'title' 12 pt -> 6.7)",
                      p)

    def test_links_to_missing_files_and_anchors(self):
        self.assertEqual(self.problems("links.html"), [
            "link to a missing anchor: clean.html#no-such-id (no id 'no-such-id' in clean.html)",
            "link to a missing file: nowhere.html"])

    def test_min_pt_is_a_parameter(self):
        proc, results = self.run_check(self.clean_out, "--min-pt", "11")
        self.assertEqual(proc.returncode, 1)
        self.assertTrue(any(p.startswith("figure text too small: fig_ok.png")
                            for p in results["clean.html"]["problems"]))

    def test_a_page_that_never_loads_is_reported_not_waited_for(self):
        out = Path(self.tmp.name) / "hang"
        out.mkdir()
        page(out, "a_hang.html", "<p>busy</p><script>while (true) {}</script>")
        write_clean(out)
        proc, results = self.run_check(out, "--timeout", "3")
        self.assertEqual(proc.returncode, 1)
        self.assertRegex(results["a_hang.html"]["problems"][0],
                         r"^not checked: Chromium did not answer in time")
        self.assertEqual(results["clean.html"]["problems"], [])  # a fresh browser goes on

    def test_missing_chromium_exits_2_naming_the_package(self):
        proc, _ = self.run_check(self.clean_out, "--chromium", "/nonexistent/chromium")
        self.assertEqual(proc.returncode, 2)
        self.assertIn("install the Debian package `chromium`", proc.stderr)


if __name__ == "__main__":
    unittest.main()
