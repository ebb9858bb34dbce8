"""What the ledger covers is said by the ledger (reports/site/coverage.py): the {{coverage}}
block against a small ledger whose sections are known, and the check that no page states
coverage or a count in its own words — it bites on the sentence the summary page carried while
the ledger had long covered §5.3 and §5.4, and lets generated values, headings and blocks pass.
The shipped pages pass it in test_registry.py (ShippedRegistry, reg.check_pages)."""
import re
import sys
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "reports" / "site"))

import coverage as cv  # noqa: E402

LEDGER = [
    {"id": "a", "section": "§2.1", "compare": "at_most"},
    {"id": "b", "section": "§2.3.1, Fig. 2.2", "compare": "at_least"},
    {"id": "c", "section": "§2.2.2", "compare": "rel"},
    {"id": "d", "section": "§2.5", "compare": "rel"},
    {"id": "e", "section": "§3.5.1.4, §3.6.1", "compare": "is_true"},
    {"id": "f", "section": "Fig. 3.5 caption", "compare": "rel"},
    {"id": "g", "section": "§5.3.2", "compare": "not_covered"},
    {"id": "h", "section": "§4.1.1", "compare": "needs_data"},
    {"id": "i", "section": "Table 4.1", "compare": "needs_data"},
]


def text(html: str) -> str:
    return re.sub(r"<[^>]*>", "", html)


class CoverageBlock(unittest.TestCase):
    def test_consecutive_sections_merge_into_runs(self):
        self.assertEqual(cv.ranges({1, 3, 4, 5, 7}), [(1, 1), (3, 5), (7, 7)])
        self.assertEqual(cv.chapter_sections(3, {1, 3, 4, 5, 6}), "§3.1, 3.3–3.6")

    def test_a_section_counts_by_the_first_section_its_entry_cites(self):
        cov = cv.coverage(LEDGER)
        self.assertEqual(cov.measured, {2: {1, 2, 3, 5}, 3: {5}})
        self.assertEqual([c["id"] for c in cov.unmeasured["not_covered"]], ["g"])
        self.assertEqual([c["id"] for c in cov.unmeasured["needs_data"]], ["h", "i"])

    def test_the_sentence_counts_entries_and_names_what_is_left(self):
        said = text(cv.coverage_html(LEDGER))
        self.assertIn("Of the ledger's 9 entries, 6 measure statements of chapter 2 "
                      "(§2.1–2.3, 2.5) and chapter 3 (§3.5)", said)
        self.assertIn("1 entry is not covered yet (in §5.3).", said)
        self.assertIn("2 entries need data we do not have (in §4.1, 1 citing a figure or table "
                      "only).", said)

    def test_a_ledger_with_nothing_left_says_every_entry_is_covered(self):
        said = text(cv.coverage_html(LEDGER[:4]))
        self.assertIn("Every entry is covered by a study.", said)
        self.assertNotIn("need data", said)


class HandWritten(unittest.TestCase):
    def test_the_stale_summary_sentence_is_caught_at_its_line(self):
        prose = ("slipwalk reproduces the thesis: chapter 5, slopes and stairs (§5.2).\n"
                 "Not covered yet: §5.3, §5.4. Every figure comes from data.\n")
        problems = cv.hand_written(prose, "index.md")
        self.assertEqual(len(problems), 1, problems)
        self.assertTrue(problems[0].startswith("index.md:2: coverage or a count written by hand"))
        self.assertIn("Not covered yet: §5.3, §5.4.", problems[0])

    def test_a_literal_count_of_entries_is_caught(self):
        for sentence in ("Of 178 ledger entries, 93 are reproduced.",
                         "41 of 178 entries differ with a cause unknown.",
                         "The ledger holds 1,204 claims."):
            self.assertEqual(len(cv.hand_written(sentence + "\n", "p.md")), 1, sentence)

    def test_values_headings_blocks_and_chapter_numbers_pass(self):
        prose = ("## The ledger's chapter 4 entries\n\n"
                 "The fit has {fig.n_entries:.0f} entries and the model covers {fig.k} legs.\n"
                 "The chapter 4 entries are listed below; eq. 2.9 covers the stroke.\n\n"
                 "{{coverage}}\n")
        self.assertEqual(cv.hand_written(prose, "p.md"), [])


if __name__ == "__main__":
    unittest.main()
