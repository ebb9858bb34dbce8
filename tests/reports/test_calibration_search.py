"""The chapter 4 forensics' search (reports/plotting/calibration_search.py) on small tables whose
answers are known: the numbers per noise scale are the ones written in, the first noise scale that
holds every entry is the one found, and a scale that holds some entries only is not taken."""
import csv
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "reports" / "plotting"))

import calibration as cal  # noqa: E402
import calibration_search as cs  # noqa: E402
import common as c  # noqa: E402

THESIS = {"table4.2-cv-error": [12, 17, 62, 105], "4.5-cv-factor-8": 8,
          "fig4.6-force-rmse": [0.63, 0.66, 0.61, 0.13],
          "fig4.6-torque-rmse": [0.9, 0.61, 0.95, 0.78]}


def table(folder: Path, name: str, header: list[str], rows: list[list]) -> c.Table:
    path = folder / name
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    return c.Table(path)


def models(noise: float, cv: list[float]) -> list[list]:
    return [[m, 1, 1.0, x, 0.0, 0, noise] for m, x in zip(cal.MODELS, cv)]


def poses(noise: float, naive: float, full: float) -> list[list]:
    """Residuals ±naive and ±full on every component: every reduction is 1 − full/naive."""
    out = []
    for pose, sign in enumerate((1.0, -1.0)):
        for method, r in (("naive", naive), ("full", full)):
            out.append([pose, method] + [sign * r] * 6 + [noise])
    return out


class Search(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        folder = Path(self._tmp.name)
        head_m = cal.MODEL_COLUMNS + ["noise_scale"]
        head_p = cal.POSE_COLUMNS + ["noise_scale"]
        # noise 1: CV out of order; 0.5: CV holds but the reductions (50 %) do not; 0.2: all hold
        # (reductions 96 %); 0.1: all hold too, but 0.2 comes first in the grid's order.
        self.cv = table(folder, "cv.csv", head_m,
                        models(1.0, [1, 1.1, 3, 2.9]) + models(0.5, [1, 1.2, 5, 9])
                        + models(0.2, [1, 1.3, 6, 12]) + models(0.1, [1, 1.4, 7, 20]))
        self.poses = table(folder, "poses.csv", head_p,
                           poses(1.0, 1.0, 0.9) + poses(0.5, 1.0, 0.5) + poses(0.2, 1.0, 0.04)
                           + poses(0.1, 1.0, 0.02))

    def tearDown(self):
        self._tmp.cleanup()

    def test_the_first_setting_that_holds_every_entry_is_found(self):
        settings, hit = cs.search(self.cv, self.poses, THESIS)
        self.assertEqual([s["noise_scale"] for s in settings], [1.0, 0.5, 0.2, 0.1])
        self.assertEqual(hit["noise_scale"], 0.2)
        self.assertAlmostEqual(hit["cv_factor"], 12.0)
        for got in hit["force"] + hit["torque"]:
            self.assertAlmostEqual(got, 0.96)

    def test_a_setting_that_holds_some_entries_only_is_not_taken(self):
        settings, _ = cs.search(self.cv, self.poses, THESIS)
        half = settings[1]
        self.assertTrue(half["holds"]["table4.2-cv-error"])
        self.assertTrue(half["holds"]["4.5-cv-factor-8"])
        self.assertFalse(half["holds"]["fig4.6-force-rmse"])
        self.assertFalse(half["all"])
        self.assertFalse(settings[0]["holds"]["table4.2-cv-error"])

    def test_no_setting_is_found_when_none_holds_them_all(self):
        strict = dict(THESIS, **{"4.5-cv-factor-8": 100})
        _, hit = cs.search(self.cv, self.poses, strict)
        self.assertIsNone(hit)


if __name__ == "__main__":
    unittest.main()
