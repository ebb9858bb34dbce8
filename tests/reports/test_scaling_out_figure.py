"""The scaling-out report script (reports/figures/scaling_out.py) measures what its ledger entries
say, on hand-made study files whose answers are known: parallel efficiencies paired round by
round with the serial run, byte-identity over every mode, the coordinator's median rate and the
saturation R_sat = points / CPU s × mean point time from the other studies' sidecars. Run by
ctest with the interpreter that has Debian's matplotlib."""
import csv
import json
import math
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "reports" / "figures" / "scaling_out.py"

EFFICIENCY_COLUMNS = ["id", "workload", "mode", "workers", "repeat", "points", "wall_s",
                      "process_wall_s", "same_bytes", "exit_code", "message"]
COORDINATOR_COLUMNS = ["id", "points", "ranks", "jobs", "repeat", "wall_s", "coordinator_cpu_s",
                       "messages", "remote_points", "points_per_s", "points_per_cpu_s",
                       "points_per_message", "exit_code", "message"]
# Wall times per round. Paired per round, MPI's efficiencies are 2/2.2 = 0.909, 4/5 = 0.8 and
# 3/3 = 1: median 0.909, where the ratio of the medians would give 3/(2 × 1.5) = 1.
WALL = {"serial": [2.0, 4.0, 3.0], "mpi": [1.1, 2.5, 1.5], "threads": [1.25, 2.5, 1.875],
        "shards": [1.0, 2.0, 1.5]}
EFF = {"mpi": 2.0 / 2.2, "threads": 0.8, "shards": 1.0}
PER_CPU_S = [9e4, 1e5, 2e5]  # median 1e5
PER_S = [3000.0, 3100.0, 2900.0]  # median 3000
# Sidecars (study, file, point_seconds or None): ch3_legged's two sweeps average
# 3 s / 150 points = 0.02 s, so R_sat = 1e5 × 0.02 = 2000; ch2_inchworm's 1e-4 s gives 10;
# ch5_planning's merged sweep 0.1 s gives 1e4 (its leftover shard sidecar is not counted twice).
SIDECARS = [("ch3_legged", "a.json", {"count": 100, "sum": 1.0}),
            ("ch3_legged", "b.json", {"count": 50, "sum": 2.0}),
            ("ch2_inchworm", "sweep.json", {"count": 1000, "sum": 0.1}),
            ("ch2_inchworm", "old.json", None),
            ("ch5_planning", "cost.json", {"count": 10, "sum": 1.0}),
            ("ch5_planning", "cost.shard-1-of-2.json", {"count": 999, "sum": 999.0})]


def write(path: Path, header: list[str], rows: list[list]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def efficiency_rows(no_mpi: bool = False, differs: str = "") -> list[list]:
    rows = []
    for r in range(3):
        for mode in ("serial", "threads", "mpi", "shards"):
            workers = 1 if mode == "serial" else 2
            if mode == "mpi" and no_mpi:
                rows.append([len(rows), "inchworm_vss", mode, workers, r, 64, "nan", "nan", 0, -1,
                             "this build has no MPI"])
                continue
            wall = WALL[mode][r]
            same = 0 if (mode == differs and r == 1) else 1
            rows.append([len(rows), "inchworm_vss", mode, workers, r, 64, wall, wall + 0.3, same,
                         0, ""])
    return rows


def coordinator_rows() -> list[list]:
    rows = []
    for r, (cpu_rate, rate) in enumerate(zip(PER_CPU_S, PER_S)):
        points = 20000
        rows.append([r, points, 2, 1, r, points / rate, points / cpu_rate, 2 * points, points,
                     rate, cpu_rate, 0.5, 0, ""])
    return rows


def make(data: Path, **efficiency) -> None:
    write(data / "scaling_out" / "efficiency.csv", EFFICIENCY_COLUMNS,
          efficiency_rows(**efficiency))
    write(data / "scaling_out" / "coordinator.csv", COORDINATOR_COLUMNS, coordinator_rows())
    # this study's own sidecar: the machine, and point times that are no study's
    (data / "scaling_out" / "efficiency.json").write_text(json.dumps(
        {"point_seconds": {"count": 1, "sum": 1e-9},
         "provenance": {"machine": {"logical_cores": 2, "load_average_1min": 0.5}}}))
    for study, name, ps in SIDECARS:
        doc = {"study": study, "name": name}
        if ps is not None:
            doc["point_seconds"] = {**ps, "mean": ps["sum"] / ps["count"], "median": None}
        (data / study).mkdir(parents=True, exist_ok=True)
        (data / study / name).write_text(json.dumps(doc))


def run(data: Path, out: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), "--data", str(data), "--out", str(out)],
                          capture_output=True, text=True)


def values_of(data: Path, out: Path) -> dict:
    proc = run(data, out)
    if proc.returncode != 0:
        raise AssertionError(f"scaling_out.py failed: {proc.stderr}")
    return json.loads((out / "values" / "scaling_out.json").read_text())


class ScalingOutFigure(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        root = Path(cls.tmp.name)
        cls.data, cls.out = root / "data", root / "out"
        make(cls.data)
        cls.v = values_of(cls.data, cls.out)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_efficiency_is_the_median_over_rounds_of_each_round_against_its_serial_run(self):
        for mode, eff in EFF.items():
            self.assertAlmostEqual(self.v[f"efficiency_{mode}"], eff, places=12, msg=mode)
            self.assertEqual(self.v[f"efficiency_{mode}_rounds"], 3)
        self.assertAlmostEqual(self.v["speedup_mpi"], 2 * EFF["mpi"], places=12)
        self.assertTrue(self.v["efficiency_mpi_goal_met"])  # 0.909 ≥ 0.9
        self.assertAlmostEqual(self.v["wall_s_serial"], 3.0, places=12)
        self.assertAlmostEqual(self.v["process_wall_s_mpi"], 1.8, places=12)
        self.assertEqual(self.v["rounds"], 3)
        self.assertEqual(self.v["logical_cores"], 2)

    def test_every_mode_wrote_the_serial_bytes(self):
        self.assertTrue(self.v["same_bytes_all"])
        for mode in EFF:
            self.assertTrue(self.v[f"same_bytes_{mode}"])

    def test_the_coordinator_rate_is_the_median_over_repeats(self):
        self.assertAlmostEqual(self.v["coordinator_points_per_cpu_s"], 1e5, places=6)
        self.assertAlmostEqual(self.v["coordinator_points_per_s"], 3000.0, places=9)
        self.assertAlmostEqual(self.v["coordinator_points_per_message"], 0.5, places=12)
        self.assertEqual(self.v["coordinator_ranks"], 2)

    def test_saturation_is_the_rate_times_the_mean_point_time_of_each_study(self):
        v = self.v
        self.assertAlmostEqual(v["point_mean_s_ch3_legged"], 0.02, places=12)
        self.assertAlmostEqual(v["rsat_ch3_legged"], 2000.0, places=6)
        self.assertAlmostEqual(v["rsat_ch2_inchworm"], 10.0, places=9)
        self.assertAlmostEqual(v["rsat_ch5_planning"], 1e4, places=6)
        self.assertEqual(v["points_ch5_planning"], 10)  # the shard's sidecar is not counted
        self.assertEqual(v["sidecars_skipped_ch2_inchworm"], 1)
        self.assertNotIn("scaling_out", v["studies"])
        self.assertAlmostEqual(v["rsat_min_multilegged"], 2000.0, places=6)
        self.assertEqual(v["rsat_min_study"], "ch3_legged")
        self.assertTrue(v["rsat_goal_met"])
        self.assertEqual(v["multilegged_timed"], ["ch3_legged", "ch5_planning"])
        self.assertAlmostEqual(v["rsat_min_all"], 10.0, places=9)

    def test_it_writes_the_figure_and_the_table(self):
        self.assertTrue((self.out / "scaling_out.png").is_file())
        table = (self.out / "scaling_out_table.html").read_text()
        self.assertIn("2 MPI ranks", table)
        self.assertIn("ch3_legged (multi-legged)", table)

    def test_a_mode_that_differs_from_the_serial_bytes_is_caught(self):
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data", differs="shards")
            v = values_of(Path(d) / "data", Path(d) / "out")
            self.assertFalse(v["same_bytes_shards"])
            self.assertTrue(v["same_bytes_mpi"])
            self.assertFalse(v["same_bytes_all"])

    def test_a_build_without_mpi_leaves_its_values_unmeasured_with_the_reason(self):
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data", no_mpi=True)
            v = values_of(Path(d) / "data", Path(d) / "out")
            self.assertIsNone(v["efficiency_mpi"])
            self.assertIn("this build has no MPI", v["efficiency_mpi_reason"])
            self.assertIsNone(v["same_bytes_all"])
            self.assertIn("no MPI", v["same_bytes_all_reason"])
            self.assertAlmostEqual(v["efficiency_threads"], EFF["threads"], places=12)

    def test_a_missing_file_exits_2_naming_it_and_the_study(self):
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data")
            (Path(d) / "data" / "scaling_out" / "coordinator.csv").unlink()
            proc = run(Path(d) / "data", Path(d) / "out")
            self.assertEqual(proc.returncode, 2)
            self.assertIn("coordinator.csv: input file missing", proc.stderr)
            self.assertIn("slipwalk reproduce scaling_out", proc.stderr)
            self.assertFalse((Path(d) / "out" / "values" / "scaling_out.json").exists())

    def test_a_missing_column_or_a_malformed_sidecar_exits_2_naming_the_file(self):
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data")
            write(Path(d) / "data" / "scaling_out" / "efficiency.csv", EFFICIENCY_COLUMNS[:-3],
                  [r[:-3] for r in efficiency_rows()])
            proc = run(Path(d) / "data", Path(d) / "out")
            self.assertEqual(proc.returncode, 2)
            self.assertIn("efficiency.csv: column 'same_bytes' missing", proc.stderr)
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data")
            (Path(d) / "data" / "ch3_legged" / "a.json").write_text(
                json.dumps({"point_seconds": {"count": "many"}}))
            proc = run(Path(d) / "data", Path(d) / "out")
            self.assertEqual(proc.returncode, 2)
            self.assertIn("a.json: point_seconds must hold a count and a sum", proc.stderr)

    def test_a_sidecar_count_of_zero_times_no_point(self):
        self.assertTrue(math.isfinite(self.v["rsat_ch2_inchworm"]))
        with tempfile.TemporaryDirectory() as d:
            make(Path(d) / "data")
            for name in ("a.json", "b.json"):
                (Path(d) / "data" / "ch3_legged" / name).write_text(
                    json.dumps({"point_seconds": {"count": 0, "sum": 0.0}}))
            v = values_of(Path(d) / "data", Path(d) / "out")
            self.assertIsNone(v["rsat_ch3_legged"])
            self.assertEqual(v["multilegged_timed"], ["ch5_planning"])
            self.assertAlmostEqual(v["rsat_min_multilegged"], 1e4, places=6)


if __name__ == "__main__":
    unittest.main()
