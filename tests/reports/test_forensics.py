"""The chapter 2 forensics' search (reports/plotting/forensics_search.py) against known truths:
the regressions recover the coefficients of data built from them (lines per μ, eq. 2.6's law);
the search finds a setting planted in synthetic "thesis numbers" made by the code itself; and it
refuses to call a group reproduced when each number is matched only by a setting of its own."""
import importlib.util
import math
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "reports" / "plotting"))

import forensics_search as fs  # noqa: E402

MUS = [round(0.05 * i, 12) for i in range(1, 21)]
M, G, L = 1.5, 9.81, 0.5


def variant(speed) -> fs.Variant:
    """v_ss = speed(F, μ) on forces 0.5, 1, ..., 100 N above μ m g, for μ = 0.05 .. 1."""
    v = fs.Variant("synthetic", 1.0, M, G, L)
    for mu in MUS:
        F = np.arange(0.5, 100.0 + 1e-9, 0.5)
        F = F[F > mu * 1.0 * G * (1 + 1e-9)]
        v.by_mu[mu] = (F, speed(F, mu))
    return v


def curved(F, mu):
    """Curved in F and in μ, so that the fits depend on where the grid starts and ends."""
    return 0.3 + 0.25 * mu + (0.011 - 0.002 * mu**2) * F - 4e-5 * F**2 / (0.3 + mu)


def group(nums: dict, keys: list[str], tol: float) -> fs.Group:
    return fs.Group("g", "synthetic", {k: k for k in keys}, {k: nums[k] for k in keys},
                    {k: tol for k in keys})


EQ = (0.073, 0.178, 0.11, 0.20)


class Regressions(unittest.TestCase):
    def test_lines_per_mu_recover_k_and_b_as_functions_of_mu(self):
        k2, k0, b1, b0 = -1.9e-3, 11e-3, 0.24, 0.46
        v = variant(lambda F, mu: (k2 * mu**2 + k0) * F + b1 * mu + b0)
        got = fs.numbers(fs.per_mu(v, fs.Grid("muMg", 0.5, 73.5)), MUS, EQ)
        for key, want in (("k2", k2), ("k0", k0), ("b1", b1), ("b0", b0)):
            self.assertAlmostEqual(got[key], want, delta=1e-12 * max(1.0, abs(want)) + 1e-14)
        self.assertAlmostEqual(got["k_r2"], 1.0, places=12)
        self.assertAlmostEqual(got["b_r2"], 1.0, places=12)

    def test_eq2_6_is_refitted_exactly_and_its_own_law_has_no_error(self):
        a, cc, d, e = EQ

        def law(F, mu):
            f = F / (mu * M * G)
            return (a * mu * (1 - cc * mu**2) * f + d * mu + e) * math.sqrt(L * G)

        got = fs.numbers(fs.per_mu(variant(law), fs.Grid(10.0, 1.0, 80.0)), MUS, EQ)
        for key, want in zip("acde", EQ):
            self.assertAlmostEqual(got[key], want, places=10)
        self.assertLess(got["eq2_6_max_error"], 1e-12)

    def test_a_grid_holds_the_multiples_of_its_step_from_its_start_above_the_floor(self):
        F = np.arange(0.5, 20.0 + 1e-9, 0.5)
        keep = fs.on_grid(F, fs.Grid(5.0, 2.5, 15.0), floor=7.0)
        self.assertEqual(F[keep].tolist(), [7.5, 10.0, 12.5, 15.0])
        keep = fs.on_grid(F, fs.Grid("muMg", 5.0, 20.0), floor=7.0)
        self.assertEqual(F[keep].tolist(), [10.0, 15.0, 20.0])


class Search(unittest.TestCase):
    def setUp(self):
        self.v = {"synthetic": variant(curved)}
        self.mu_sets = {"all": MUS, "tenths": [m for m in MUS if round(m * 10, 9) % 1 == 0],
                        "fifths": [0.2, 0.4, 0.6, 0.8, 1.0]}
        self.candidates = fs.settings(["synthetic"], ["muMg", 5.0, 10.0, 15.0, 20.0],
                                      [60.0, 73.5, 80.0, 100.0], [0.5, 1.0, 2.5],
                                      list(self.mu_sets))
        self.keys = ["k2", "k0", "k_r2", "b1", "b0", "b_r2"]

    def numbers_of(self, setting: fs.Setting) -> dict:
        return fs.numbers(fs.per_mu(self.v[setting.variant], setting.grid),
                          self.mu_sets[setting.mu_set], EQ)

    def test_the_search_finds_a_setting_planted_in_the_thesis_numbers(self):
        planted = fs.Setting("synthetic", fs.Grid(15.0, 1.0, 80.0), "tenths")
        g = group(self.numbers_of(planted), self.keys, tol=1e-6)
        found, = fs.search(self.v, self.candidates, self.mu_sets, [g], EQ)
        self.assertEqual(found.best, planted)
        self.assertLess(found.best_distance, 1e-3)
        self.assertTrue(found.joint)
        # the data discriminate: almost no other setting comes within the tolerance
        within = [s for s, d in found.scores if d <= 1.0]
        self.assertEqual(within, [planted])

    def test_numbers_matched_only_by_a_setting_each_are_not_called_joint(self):
        a = fs.Setting("synthetic", fs.Grid("muMg", 0.5, 60.0), "all")
        b = fs.Setting("synthetic", fs.Grid(20.0, 2.5, 100.0), "fifths")
        na, nb = self.numbers_of(a), self.numbers_of(b)
        self.assertGreater(abs(na["k2"] - nb["k2"]), 1e-3 * abs(na["k2"]))
        mixed = {"k2": na["k2"], "b0": nb["b0"]}
        g = group(mixed, ["k2", "b0"], tol=1e-7)
        found, = fs.search(self.v, self.candidates, self.mu_sets, [g], EQ)
        self.assertFalse(found.joint, found.best)
        self.assertTrue(found.per_number_only)
        self.assertEqual(found.per_number["k2"][1], a)
        self.assertEqual(found.per_number["b0"][1], b)
        self.assertGreater(found.best_distance, 1.0)


class SearchFile(unittest.TestCase):
    """data/thesis/forensics.toml is a file a user widens: a broken one is exit 2, named."""

    @staticmethod
    def script():
        spec = importlib.util.spec_from_file_location(
            "forensics_figure", REPO / "reports" / "figures" / "forensics.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module

    def load(self, text: str):
        module = self.script()
        with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
            f.write(text)
        return module.load_search(Path(f.name))

    def test_the_shipped_search_file_loads(self):
        module = self.script()
        cfg = module.load_search(module.SEARCH)
        self.assertTrue(cfg["grid"]["F_start"])

    def test_bad_toml_and_a_missing_grid_list_exit_2(self):
        for text in ("[grid\n", "[grid]\nF_start = []\nF_end = [1.0]\nF_step = [0.5]\n"
                     "[mu_sets]\n[[group]]\nname = 'g'\nclaims = {}\n"):
            with self.assertRaises(SystemExit) as e:
                self.load(text)
            self.assertEqual(e.exception.code, 2, text)


if __name__ == "__main__":
    unittest.main()
