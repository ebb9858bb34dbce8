"""The §5.3 report scripts (reports/figures/fig5_5.py, fig5_6.py, residual_training.py) measure
what their ledger entries say, on hand-made study files whose answers are known in closed form:
a periodic error B removes exactly and a constant drift it cannot, a share of the asymmetry's
error, and a training curve whose stopping point is known. Run by ctest with the interpreter
that has Debian's matplotlib."""
import csv
import json
import math
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
FIGURES = REPO / "reports" / "figures"
sys.path.insert(0, str(REPO / "reports" / "plotting"))

import residual as rs  # noqa: E402

FREQS = (0.3, 1.2)
PER_CYCLE = 100  # samples per gait cycle
AMP = {"x": 0.02, "y": 0.03, "w": 0.2}  # the periodic error B removes
DRIFT = {"x": 0.0, "y": -0.004, "w": 0.0}  # a constant the model misses and B cannot remove
TRAIN_RMSE = 0.005  # every train_rmse_fit_* of errors.csv: test/train = |drift| / this
SYM_MODEL, ASYM_MODEL, ASYM_FIT = 0.02, 0.05, 0.011  # side-velocity RMSEs of errors.csv


def snapshots(f: float) -> list[float]:
    """Recorded cycles 2-8, whole cycles evenly sampled, so a sine averages to zero."""
    return [(1.0 + i / PER_CYCLE) / f for i in range(7 * PER_CYCLE)]


def write(path: Path, header: list[str], rows: list[list]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def transfer_rows() -> list[list]:
    """True = model + periodic + drift; fit at the own frequency = model + periodic (B removed
    the periodic part exactly); fit from 0.3 Hz at other frequencies = model + periodic / 2."""
    rows, pid = [], 0
    for f in FREQS:
        for train_f in sorted({f, rs.BASE_FREQUENCY}):
            share = 1.0 if train_f == f else 0.5
            for t in snapshots(f):
                s = math.sin(2 * math.pi * f * t)
                model = {k: 0.1 * f for k in rs.COMPONENTS}
                true = {k: model[k] + AMP[k] * s + DRIFT[k] for k in rs.COMPONENTS}
                fit = {k: model[k] + share * AMP[k] * s for k in rs.COMPONENTS}
                rows.append([pid, train_f, f, 1.0, "pinv", 1.0, t]
                            + [d[k] for d in (true, model, fit) for k in rs.COMPONENTS])
            pid += 1
    return rows


def errors_rows() -> list[list]:
    rows, pid = [], 0
    for f in FREQS:
        for est in ("pinv", "ridge"):
            for asym in (1.0, 0.0):
                model = ASYM_MODEL if asym else SYM_MODEL
                fit = ASYM_FIT * (1.1 if est == "ridge" else 1.0) if asym else 0.5 * SYM_MODEL
                cells = {"train_rmse_model": 0.05, "train_rmse_fit": TRAIN_RMSE,
                         "test_rmse_model": model, "test_rmse_fit": fit}
                rows.append([pid, f, "0.65 0.9 1.1 1.35", f, 1.0, est, asym, 0.0, 14, 250.0, 5000]
                            + [cells[f"{s}_rmse_{w}"] for s in ("train", "test")
                               for w in ("model", "fit") for _ in rs.COMPONENTS]
                            + [0.0] * 9 + [1.0])
                pid += 1
    return rows


# Medians of the validation RMSE against k: the least is 1.99 (k = 5); within 5 % (≤ 2.0895)
# first at k = 3 for every component at 0.3 Hz. At 1.2 Hz the curve still decreases at the
# largest k run (6), so its stop lies beyond the range, written 7; the yaw rate's curve is held
# at 2.2 from k = 5 on (first within 5 % at k = 5).
CURVE = {0.3: [10.0, 5.0, 2.08, 2.2, 1.99, 2.0], 1.2: [10.0, 5.0, 3.0, 2.5, 2.2, 2.0]}


def training_rows() -> list[list]:
    rows = []
    for f, curve in CURVE.items():
        for k, med in enumerate(curve, start=1):
            yaw = max(med, 2.2) if f == 1.2 else med
            for draw, spread in enumerate((0.9, 1.0, 1.3)):  # the median is the middle draw
                rows.append([k, f, k, draw, "0.264"] + [9.0] * 3
                            + [med * spread, med * spread, yaw * spread])
    return rows


class ResidualFigures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.data, cls.out = root / "data", root / "out"
        folder = cls.data / rs.STUDY
        write(folder / "transfer.csv", rs.TRANSFER_COLUMNS, transfer_rows())
        write(folder / "errors.csv", rs.ERRORS_COLUMNS, errors_rows())
        write(folder / "training.csv", rs.TRAINING_COLUMNS, training_rows())
        cls.values = {}
        for name in ("fig5_5", "fig5_6", "residual_training"):
            proc = subprocess.run([sys.executable, str(FIGURES / f"{name}.py"), "--data",
                                   str(cls.data), "--out", str(cls.out)],
                                  capture_output=True, text=True)
            if proc.returncode != 0:
                raise AssertionError(f"{name}.py failed: {proc.stderr}")
            cls.values[name] = json.loads((cls.out / "values" / f"{name}.json").read_text())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_test_rmse_with_and_without_b_match_the_closed_form(self):
        v = self.values["fig5_5"]
        for f in FREQS:
            tg = rs.tag(f)
            for k in rs.COMPONENTS:
                model = math.sqrt(AMP[k] ** 2 / 2 + DRIFT[k] ** 2)
                self.assertAlmostEqual(v[f"{tg}_test_rmse_model_{k}"], model, places=9)
                self.assertAlmostEqual(v[f"{tg}_test_rmse_fit_{k}"], abs(DRIFT[k]), places=9)
            self.assertAlmostEqual(v[f"{tg}_reduction_y_pct"],
                                   100 * (1 - 0.004 / math.sqrt(0.03**2 / 2 + 0.004**2)), 6)

    def test_b_that_removes_the_oscillation_leaves_the_drift(self):
        v = self.values["fig5_5"]
        for f in FREQS:
            tg = rs.tag(f)
            self.assertAlmostEqual(v[f"{tg}_mean_true_y"] - v[f"{tg}_mean_model_y"], -0.004, 9)
            self.assertAlmostEqual(v[f"{tg}_drift_removed_y"], 0.0, places=9)
            self.assertAlmostEqual(v[f"{tg}_mean_bqdot_y"], 0.0, places=9)

    def test_test_over_training_is_the_ratio_of_the_two_rmses(self):
        v = self.values["fig5_5"]
        self.assertAlmostEqual(v["f0p3_test_over_train_y"], 0.004 / TRAIN_RMSE, places=9)
        # forward and yaw have no drift: B leaves no test error, a ratio of 0 to the training
        # error, whose worst reading max(r, 1/r) is unbounded (written as null)
        self.assertAlmostEqual(v["f0p3_test_rmse_fit_x"], 0.0, places=12)
        self.assertIsNone(v["test_over_train_worst"])
        self.assertEqual(v["rank_min"], 14)
        self.assertEqual(v["frequency_count"], 2)

    def test_b_from_the_base_frequency_is_compared_with_b_from_the_own_one(self):
        v = self.values["fig5_6"]
        # at 1.2 Hz B from 0.3 Hz removes half of the oscillation: RMSE of (A s / 2 − drift)
        own = abs(DRIFT["y"])
        base = math.sqrt((AMP["y"] / 2) ** 2 / 2 + DRIFT["y"] ** 2)
        self.assertAlmostEqual(v["f1p2_base_over_own_y"], base / own, places=9)
        self.assertAlmostEqual(v["top_base_over_own_y"], base / own, places=9)
        self.assertAlmostEqual(v["f0p3_base_over_own_y"], 1.0, places=12)

    def test_the_share_of_the_asymmetry_b_explains(self):
        v = self.values["fig5_6"]
        share = (ASYM_MODEL - ASYM_FIT) / (ASYM_MODEL - SYM_MODEL)
        self.assertAlmostEqual(v["asym_explained_y_min"], share, places=12)
        self.assertAlmostEqual(v["ridge_over_pinv_y_max"], 1.1, places=12)
        self.assertTrue(v["asym_explained_y_holds"])

    def test_the_stopping_point_is_the_least_k_within_five_percent_of_the_best_median(self):
        v = self.values["residual_training"]
        self.assertEqual(v["f0p3_k_stop_x"], 3)
        self.assertEqual(v["f0p3_k_stop_all"], 3)
        self.assertEqual(v["f1p2_k_stop_w"], 5)

    def test_a_curve_still_decreasing_at_the_largest_k_stops_beyond_the_range(self):
        v = self.values["residual_training"]
        self.assertEqual(v["f1p2_k_max"], 6)
        self.assertEqual(v["f1p2_k_stop_y"], 7)
        self.assertEqual(v["k_stop_all_max"], 7)


if __name__ == "__main__":
    unittest.main()
