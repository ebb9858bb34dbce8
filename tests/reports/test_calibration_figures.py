"""The chapter-4 report scripts (reports/figures/table4_1.py, fig4_4.py, fig4_5.py, fig4_6.py,
table4_2.py, calib_accuracy.py) measure what their ledger entries say, on hand-made study files
whose answers are known in closed form: estimates a known number of standard errors from the
truth, a CoM that is an exact sinusoid, hanging residuals whose orientation means are a known
number of SDs apart, pose residuals of known RMSE, Table 4.2 from the BIC formula, errors that
fall as 1/√P. Run by ctest with the interpreter that has Debian's matplotlib."""
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

import calibration as cal  # noqa: E402

SCRIPTS = ("table4_1", "fig4_4", "fig4_5", "fig4_6", "table4_2", "calib_accuracy")
SE = 0.01
ZERO_ERR = 3e-14  # every error of the noiseless robot
# z of each parameter, by its index in cal.PARAMETERS and the leg's: one force offset 3.5 SE off
# (HL offset_fx), one torque offset −2.5, the rest ±0.5
Z_SPECIAL = {("HL", "offset_fx"): 3.5, ("ML", "offset_ty"): -2.5}
POSES = 100
NAIVE = {"fx": 4.0, "fy": 3.0, "fz": 6.0, "tx": 1.0, "ty": 2.0, "tz": 0.5}  # RMSE of each
FULL = {"fx": 0.4, "fy": 0.3, "fz": 3.0, "tx": 0.1, "ty": 0.1, "tz": 0.05}
LITERAL_TX = 0.3  # the literal fit's constant T_x bias on top of FULL
HANG_SD, HANG_SHIFT = 0.05, 0.15  # within-orientation SD; ±shift of the orientations without ŝ
RSS = {"full": 50.0, "shared_translation": 60.0, "translations_only": 200.0, "com_only": 400.0}
DOF = {"full": 36, "shared_translation": 21, "translations_only": 18, "com_only": 3}
CV = {"full": 0.1, "shared_translation": 0.12, "translations_only": 0.5, "com_only": 0.9}
START_COSTS = [100.0, 101.0, 100.5, 102.0]  # alternating: spread 2 %
SEEDS_Z = [0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 3.5, -3.5]  # per seed, cycled over the parameters


def write(path: Path, header: list[str], rows: list[list]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def truth_of(leg: str, name: str) -> float:
    """Table 4.1 for the offsets and weights (the ledger), small numbers for the mounting."""
    j = cal.LEGS.index(leg)
    for claim, names in (("table4.1-force-offsets", cal.OFFSET_FORCE),
                         ("table4.1-torque-offsets", cal.OFFSET_TORQUE),
                         ("table4.1-leg-gravity", ("weight",))):
        if name in names:
            return float(cal.thesis_table(claim)[names.index(name), j])
    return 0.001 * (j + 1)


def parameter_rows() -> list[list]:
    rows = []
    for leg in cal.LEGS:
        for i, name in enumerate(cal.PARAMETERS):
            z = Z_SPECIAL.get((leg, name), 0.5 if i % 2 else -0.5)
            t = truth_of(leg, name)
            rows.append([leg, name, t + z * SE, SE, t, z * SE, z])
    return rows


BINS = 24
AMP, SHIFT, MEAN = 0.03, 0.7, -0.05
Y_SPAN = 0.0012  # y medians alternate ±Y_SPAN/2: span Y_SPAN against the x, z span 2 AMP
FIT_OFFSET = 0.0008  # fit = truth + this: RMS of fit − truth


def com_rows() -> list[list]:
    rows = []
    for leg in cal.LEGS:
        for axis in cal.AXES:
            for b in range(BINS):
                phi = (b + 0.5) / BINS - 0.5
                if axis == "y":
                    true = 0.06
                    med = true + (Y_SPAN / 2 if b % 2 else -Y_SPAN / 2)
                else:
                    true = MEAN + AMP * math.sin(2 * math.pi * phi + SHIFT)
                    med = true
                rows.append([leg, axis, phi, med, med - 0.002, med + 0.002, med - 0.005,
                             med + 0.005, true + FIT_OFFSET, true])
    return rows


def hanging_rows() -> list[list]:
    """Per orientation ±HANG_SD alternating (mean 0, SD HANG_SD); without ŝ the orientations
    are shifted by ±HANG_SHIFT (+x, +z up; −x, −z down)."""
    rows = []
    for leg in cal.LEGS:
        for orient in cal.ORIENTATIONS:
            shift = HANG_SHIFT if orient.startswith("+") else -HANG_SHIFT
            for comp in cal.COMPONENTS:
                for model in cal.HANGING_MODELS:
                    for i in range(10):
                        r = HANG_SD if i % 2 else -HANG_SD
                        if model == "no_misalignment":
                            r += shift
                        rows.append([leg, orient, comp, model, i, r])
    return rows


def pose_rows() -> list[list]:
    """Each component alternates ±RMSE over the poses (mean 0), the literal fit adds a constant
    LITERAL_TX to T_x."""
    rows = []
    for p in range(POSES):
        s = 1.0 if p % 2 else -1.0
        for m, rms in (("naive", NAIVE), ("no_mounting", NAIVE), ("full", FULL),
                       ("literal", FULL)):
            w = [s * rms[k] for k in cal.COMPONENTS]
            if m == "literal":
                w[3] += LITERAL_TX
            rows.append([p, m] + w)
    return rows


def bic(m: str) -> float:
    return POSES * math.log(RSS[m] / POSES) + DOF[m] * math.log(POSES)


def model_rows() -> list[list]:
    best = min(cal.MODELS, key=bic)
    return [[m, DOF[m], RSS[m], CV[m], bic(m), int(m == best)] for m in cal.MODELS]


def start_rows() -> list[list]:
    rows = [[i, "alternating", cost, 10, 1, 0.1, 0.2, 1.0] for i, cost in enumerate(START_COSTS)]
    # Ceres: one start did not converge (its cost, far off, is left out of the spread)
    rows += [[i, "ceres_so3", cost, 10, int(i != 3), 0.2, 0.2, 1.0]
             for i, cost in enumerate([100.0, 100.2, 100.1, 500.0])]
    return rows


ACC_POSES = (25, 100, 400)
ROT_K, DISP_K = 1.0, 10.0  # at noise 1: error = K / √P


def accuracy_rows() -> list[list]:
    rows = []
    for s in (0.0, 1.0):
        for p in ACC_POSES:
            for seed in (1, 2):
                if s == 0:
                    errs = [1e-12] * 6
                    z = ["nan"] * 3
                else:
                    errs = [0.02, 0.01, 0.001, 0.001, ROT_K / math.sqrt(p), DISP_K / math.sqrt(p)]
                    z = [2.0, 1.0, 1.0]
                rows.append([s, p, seed] + errs + z + [0.1, 0.01 * p, 1.0])
    return rows


def seeds_rows() -> list[list]:
    rows = []
    for seed in range(1, 4):
        for n, (leg, name, est, se, t, err, _) in enumerate(parameter_rows()):
            z = SEEDS_Z[n % len(SEEDS_Z)]
            rows.append([seed, leg, name, t + z * se, se, t, z * se, z])
    return rows


def make(data: Path) -> None:
    folder = data / cal.STUDY
    # as the study: the default robot (noise 1) and the noiseless one (errors of round-off)
    zero = [[r[0], r[1], r[4] + ZERO_ERR, r[3], r[4], ZERO_ERR, ZERO_ERR / r[3]]
            for r in parameter_rows()]
    write(folder / "parameters.csv", ["noise_scale"] + cal.PARAMETER_COLUMNS,
          [[1.0] + r for r in parameter_rows()] + [[0.0] + r for r in zero])
    write(folder / "seeds.csv", ["seed"] + cal.PARAMETER_COLUMNS, seeds_rows())
    write(folder / "com.csv", cal.COM_COLUMNS, com_rows())
    write(folder / "hanging_residuals.csv", cal.HANGING_COLUMNS, hanging_rows())
    write(folder / "pose_residuals.csv", cal.POSE_COLUMNS, pose_rows())
    # the noiseless robot's models (RSS of round-off) must not enter Table 4.2
    write(folder / "models.csv", ["noise_scale", "poses"] + cal.MODEL_COLUMNS,
          [[1.0, POSES] + r for r in model_rows()]
          + [[0.0, POSES, m, DOF[m], 1e-20, 1e-24, -9e3, int(m == "com_only")]
             for m in cal.MODELS])
    write(folder / "starts.csv", cal.START_COLUMNS, start_rows())
    write(folder / "accuracy.csv", cal.ACCURACY_COLUMNS, accuracy_rows())


def run(name: str, data: Path, out: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(FIGURES / f"{name}.py"), "--data", str(data),
                           "--out", str(out)], capture_output=True, text=True)


class CalibrationFigures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.data, cls.out = root / "data", root / "out"
        make(cls.data)
        cls.values = {}
        for name in SCRIPTS:
            proc = run(name, cls.data, cls.out)
            if proc.returncode != 0:
                raise AssertionError(f"{name}.py failed: {proc.stderr}")
            cls.values[name] = json.loads((cls.out / "values" / f"{name}.json").read_text())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_table_4_1_measures_each_block_in_standard_errors_of_the_truth(self):
        v = self.values["table4_1"]
        self.assertAlmostEqual(v["force_offset_z_abs_max"], 3.5, places=12)
        self.assertAlmostEqual(v["torque_offset_z_abs_max"], 2.5, places=12)
        self.assertAlmostEqual(v["weight_z_abs_max"], 0.5, places=12)
        self.assertTrue(v["force_offset_within_bound"])  # 3.5 ≤ 4
        # 78 parameters, one beyond 3 SE
        self.assertEqual(v["parameters"], 78)
        self.assertAlmostEqual(v["within_3se_fraction"], 77 / 78, places=12)
        self.assertAlmostEqual(v["HL_offset_fx_estimate"], 1.47 + 3.5 * SE, places=12)

    def test_table_4_1_shows_the_default_noise_and_measures_the_noiseless_robot(self):
        v = self.values["table4_1"]
        self.assertAlmostEqual(v["HL_offset_fx_z"], 3.5, places=12)  # not the noiseless 1.0
        for block in ("force_offset", "torque_offset", "weight", "rotation", "displacement"):
            self.assertAlmostEqual(v[f"zero_noise_{block}_error_max"], ZERO_ERR, places=20)

    def test_table_4_1_knows_its_truth_is_the_thesis_table(self):
        v = self.values["table4_1"]
        self.assertTrue(v["truth_is_table"])
        self.assertEqual(v["truth_table_max_abs_diff"], 0.0)
        html = (self.out / "table4_1_table.html").read_text()
        self.assertIn("-8.490", html)  # HR's x force offset, the truth beside its estimate
        self.assertEqual(html.count("class='bad'"), 1)  # the one |z| > 3

    def test_fig_4_4_recognises_an_exact_sinusoid_and_a_flat_y(self):
        v = self.values["fig4_4"]
        self.assertAlmostEqual(v["xz_sine_r2_min"], 1.0, places=12)
        self.assertAlmostEqual(v["HL_x_sine_amplitude_m"], AMP, places=12)
        self.assertAlmostEqual(v["y_span_over_xz_max"], Y_SPAN / v["HL_x_span_m"], places=12)
        self.assertTrue(v["com_shape_as_thesis"])
        self.assertAlmostEqual(v["com_fit_err_rms_max_m"], FIT_OFFSET, places=12)
        self.assertAlmostEqual(v["FR_y_median_err_max_m"], Y_SPAN / 2, places=12)

    def test_fig_4_5_measures_the_sd_and_how_far_apart_the_orientations_lie(self):
        v = self.values["fig4_5"]
        self.assertAlmostEqual(v["exact_force_sd_max"], HANG_SD, places=12)
        self.assertAlmostEqual(v["no_misalignment_force_sd_max"],
                               math.hypot(HANG_SD, HANG_SHIFT), places=12)
        self.assertAlmostEqual(v["exact_force_separation_max"], 0.0, places=9)
        self.assertAlmostEqual(v["no_misalignment_force_separation_max"],
                               2 * HANG_SHIFT / HANG_SD, places=9)
        self.assertTrue(v["exact_unimodal"])
        self.assertTrue(v["no_misalignment_multimodal"])

    def test_fig_4_6_reductions_are_one_minus_the_rmse_ratio(self):
        v = self.values["fig4_6"]
        for k in cal.COMPONENTS:
            self.assertAlmostEqual(v[f"naive_{k}_rmse"], NAIVE[k], places=12)
            self.assertAlmostEqual(v[f"reduction_{k}"], 1 - FULL[k] / NAIVE[k], places=12)
        pooled = lambda d, ks: math.sqrt(sum(d[k] ** 2 for k in ks) / 3)  # noqa: E731
        self.assertAlmostEqual(v["reduction_force"], 1 - pooled(FULL, cal.FORCES)
                               / pooled(NAIVE, cal.FORCES), places=12)
        self.assertAlmostEqual(v["naive_horizontal_over_weight"],
                               math.hypot(NAIVE["fx"], NAIVE["fy"]) / cal.robot_weight(), 12)
        self.assertAlmostEqual(cal.robot_weight(), 8.18 * 9.81, places=9)

    def test_fig_4_6_finds_the_literal_targets_constant_torque_bias(self):
        v = self.values["fig4_6"]
        self.assertAlmostEqual(v["full_torque_bias_Nm"], 0.0, places=12)
        self.assertAlmostEqual(v["literal_torque_bias_Nm"], LITERAL_TX, places=12)
        full = math.sqrt((FULL["tx"] ** 2 + FULL["ty"] ** 2 + FULL["tz"] ** 2) / 3)
        lit = math.sqrt(((FULL["tx"] ** 2 + LITERAL_TX ** 2) + FULL["ty"] ** 2
                         + FULL["tz"] ** 2) / 3)
        self.assertAlmostEqual(v["literal_over_full_torque_rmse"], lit / full, places=12)

    def test_table_4_2_recomputes_the_bic_and_reads_the_selection(self):
        v = self.values["table4_2"]
        self.assertEqual(v["poses"], POSES)
        self.assertLess(v["bic_formula_max_abs_diff"], 1e-9)
        self.assertEqual(v["selected_model"], min(cal.MODELS, key=bic))
        self.assertTrue(v["selected_is_min_bic"])
        self.assertTrue(v["cv_order_as_thesis"])
        self.assertTrue(v["rss_nested"])
        self.assertAlmostEqual(v["cv_factor_com_only_over_full"], 9.0, places=12)
        self.assertAlmostEqual(v["thesis_cv_factor"], 105 / 12, places=12)

    def test_models_that_do_not_nest_are_caught(self):
        with tempfile.TemporaryDirectory() as d:
            data = Path(d) / "data"
            make(data)
            rows = model_rows()
            rows[0][2] = 500.0  # the full model above the one-translation model
            write(data / cal.STUDY / "models.csv", cal.MODEL_COLUMNS, rows)
            proc = run("table4_2", data, Path(d) / "out")
            self.assertEqual(proc.returncode, 0, proc.stderr)
            v = json.loads((Path(d) / "out" / "values" / "table4_2.json").read_text())
            self.assertFalse(v["rss_nested"])

    def test_accuracy_finds_the_inverse_square_root_law_and_zero_noise_recovery(self):
        v = self.values["calib_accuracy"]
        self.assertAlmostEqual(v["noise1_rotation_err_max_deg_slope"], -0.5, places=9)
        self.assertAlmostEqual(v["noise1_displacement_err_max_mm_slope"], -0.5, places=9)
        self.assertAlmostEqual(v["noise1_rotation_err_max_deg_at_most_poses"],
                               ROT_K / math.sqrt(max(ACC_POSES)), places=12)
        self.assertTrue(v["zero_noise_recovered"])
        self.assertAlmostEqual(v["zero_noise_weight_err_max"], 1e-12, places=20)

    def test_accuracy_counts_the_seeds_z_scores(self):
        v = self.values["calib_accuracy"]
        self.assertEqual(v["seeds_count"], 3)
        # 78 parameters cycle through SEEDS_Z: 78 = 9 × 8 + 6, |z| > 3 at indices 6, 7 of a cycle
        beyond = 9 * 2 + 0
        self.assertAlmostEqual(v["seeds_within_3se_fraction"], 1 - beyond / 78, places=12)
        zs = [SEEDS_Z[n % 8] for n in range(78)]
        mean = sum(zs) / 78
        sd = math.sqrt(sum((z - mean) ** 2 for z in zs) / 78)
        self.assertAlmostEqual(v["seeds_z_sd"], sd, places=12)

    def test_multistart_spread_leaves_out_starts_that_did_not_converge(self):
        v = self.values["calib_accuracy"]
        self.assertAlmostEqual(v["starts_alternating_cost_spread"], 0.02, places=12)
        self.assertAlmostEqual(v["starts_ceres_so3_cost_spread"], 0.002, places=12)
        self.assertAlmostEqual(v["starts_ceres_so3_converged_fraction"], 0.75, places=12)
        self.assertAlmostEqual(v["starts_cost_spread"], 0.02, places=12)

    def test_a_missing_column_exits_2_naming_the_file(self):
        with tempfile.TemporaryDirectory() as d:
            data = Path(d) / "data"
            make(data)
            write(data / cal.STUDY / "com.csv", cal.COM_COLUMNS[:-1],
                  [r[:-1] for r in com_rows()])
            proc = run("fig4_4", data, Path(d) / "out")
            self.assertEqual(proc.returncode, 2)
            self.assertIn("com.csv", proc.stderr)
            self.assertIn("truth", proc.stderr)

    def test_the_stand_in_generator_writes_what_every_script_reads(self):
        with tempfile.TemporaryDirectory() as d:
            proc = subprocess.run([sys.executable, str(REPO / "reports" / "dev" /
                                                       "fake_calibration.py"), "--out", d,
                                   "--quick"], capture_output=True, text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            for name in ("table4_1", "table4_2"):  # the tables: quick, no drawing
                p = run(name, Path(d), Path(d) / "out")
                self.assertEqual(p.returncode, 0, p.stderr)


if __name__ == "__main__":
    unittest.main()
