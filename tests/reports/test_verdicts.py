"""The claims ledger's verdict rule (reports/site/ledger.py): a failed comparison is "differs —
explained" only when its explanation names a check whose result is in the values; otherwise the
cause is unknown. A claim no study covers yet is "not covered yet", whatever values exist. Run by
ctest with the interpreter that has Debian's matplotlib."""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "reports" / "site"))

import ledger as b  # noqa: E402


class FakeValues:
    """The part of build_report.Values that evaluate() reads: has(key) and get(key)."""

    def __init__(self, d):
        self.d = d

    def has(self, key):
        return key in self.d

    def get(self, key, default=None):
        return self.d.get(key, default)


def claim(**fields):
    base = {"id": "t", "ours": "fig.x", "compare": "at_most", "thesis": 1.0}
    base.update(fields)
    return base


class VerdictRule(unittest.TestCase):
    def test_a_passing_comparison_is_reproduced_whatever_else_it_carries(self):
        r = b.evaluate(claim(explanation="why"), FakeValues({"fig.x": 0.5}))
        self.assertEqual(r["verdict"], "reproduced")

    def test_a_failure_with_an_explanation_but_no_check_is_cause_unknown(self):
        r = b.evaluate(claim(explanation="the grid starts too low"), FakeValues({"fig.x": 2.0}))
        self.assertEqual(r["verdict"], b.CAUSE_UNKNOWN)

    def test_a_failure_without_any_explanation_is_cause_unknown(self):
        r = b.evaluate(claim(), FakeValues({"fig.x": 2.0}))
        self.assertEqual(r["verdict"], b.CAUSE_UNKNOWN)

    def test_a_failure_whose_named_check_has_a_value_is_explained(self):
        values = FakeValues({"fig.x": 2.0, "fig.with_half": 1.0})
        r = b.evaluate(claim(explanation="eq. 2.9 misses a 1/2", check="fig.with_half"), values)
        self.assertEqual(r["verdict"], b.EXPLAINED)
        self.assertEqual(r["check"], ["fig.with_half"])

    def test_a_check_whose_value_is_missing_or_null_does_not_explain(self):
        for values in ({"fig.x": 2.0}, {"fig.x": 2.0, "fig.check": None}):
            r = b.evaluate(claim(explanation="why", check=["fig.check"]), FakeValues(values))
            self.assertEqual(r["verdict"], b.CAUSE_UNKNOWN, values)

    def test_a_check_without_the_explanation_it_supports_is_a_ledger_error(self):
        with self.assertRaises(ValueError):
            b.evaluate(claim(check="fig.check"), FakeValues({"fig.x": 2.0, "fig.check": 1.0}))

    def test_a_check_must_name_value_keys(self):
        with self.assertRaises(ValueError):
            b.evaluate(claim(explanation="why", check=3), FakeValues({"fig.x": 2.0}))

    def test_a_claim_not_covered_yet_says_so_without_values(self):
        r = b.evaluate({"id": "t", "compare": "not_covered", "thesis": 0.63,
                        "note": "the calibration study (ch. 4)"}, FakeValues({}))
        self.assertEqual(r["verdict"], b.NOT_COVERED)
        self.assertEqual(b.VERDICT_CLASS[b.NOT_COVERED], "notcovered")

    def test_a_claim_not_covered_yet_shows_ours_but_is_not_judged_by_it(self):
        for ours in (0.0, 0.63, 5.0):
            r = b.evaluate({"id": "t", "compare": "not_covered", "thesis": 0.63, "ours": "fig.x",
                            "note": "study"}, FakeValues({"fig.x": ours}))
            self.assertEqual(r["verdict"], b.NOT_COVERED)
            self.assertEqual(r["ours"], ours)

    def test_a_claim_not_covered_yet_must_name_its_study(self):
        with self.assertRaises(ValueError):
            b.evaluate({"id": "t", "compare": "not_covered", "thesis": 0.63}, FakeValues({}))


def shipped_ledger() -> list[dict]:
    import tomllib  # noqa: PLC0415 (3.11+: Debian's python3)

    return tomllib.loads((Path(b.__file__).resolve().parents[2] / "data" / "thesis" /
                          "claims.toml").read_text())["claim"]


class ShippedLedger(unittest.TestCase):
    def test_names_only_well_formed_checks(self):
        for cl in shipped_ledger():
            b.check_keys(cl)  # raises for a malformed check or one without an explanation

    def test_ids_are_unique(self):
        ids = [cl.get("id") for cl in shipped_ledger()]
        self.assertNotIn(None, ids)
        self.assertEqual(sorted({i for i in ids if ids.count(i) > 1}), [])

    def test_every_entry_has_a_section_a_statement_a_thesis_value_and_a_known_rule(self):
        rules = {"at_least", "at_most", "abs_tol", "rel_tol", "is_true", "needs_data",
                 "not_covered"}
        for cl in shipped_ledger():
            with self.subTest(claim=cl.get("id")):
                for field in ("section", "statement", "thesis"):
                    self.assertTrue(cl.get(field) not in (None, ""), field)
                self.assertIn(cl.get("compare"), rules)

    def test_entries_not_covered_yet_name_their_study(self):
        for cl in shipped_ledger():
            if cl.get("compare") == "not_covered":
                with self.subTest(claim=cl["id"]):
                    self.assertTrue(cl.get("note"))

    def test_a_check_of_our_own_says_not_given_exactly(self):
        for cl in shipped_ledger():
            t = cl.get("thesis")
            if isinstance(t, str) and "not given" in t.lower():
                with self.subTest(claim=cl["id"]):
                    self.assertEqual(t, b.NOT_GIVEN)


if __name__ == "__main__":
    unittest.main()
