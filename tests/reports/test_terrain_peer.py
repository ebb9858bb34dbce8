"""The referee's report module (reports/plotting/terrain_peer.py) measures what the ledger's §5.2
MuJoCo entries say, on a hand-made referee.csv whose answers are known in closed form: a body
advancing p per cycle plus a whole-cycle sine (which cancels over every cycle) climbs p per cycle
and gains h per cycle; a sine larger than the drift makes it slide back by a known amount; a
cycle that goes backwards is not a climb. Run by ctest with the interpreter that has Debian's
matplotlib and numpy."""
import csv
import math
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "reports" / "plotting"))

import terrain_peer as tp  # noqa: E402

HEADER = ["scene", "label", "source", "heading_deg", "ground_slope_deg", "frequency", "t", "x",
          "y", "bx", "by", "bz", "pitch"]
F = 0.1  # Hz: a period of 10 s
CYCLES = 3


def rows(scene, label, source, p, h, amp, pitch, heading_deg=0.0, slope_deg=21.8):
    """A run along heading ψ: s(t) = p f t + amp sin(2π f t), height h f t, constant pitch."""
    psi = math.radians(heading_deg)
    out = []
    n = 300
    for i in range(n + 1):
        t = CYCLES / F * i / n
        s = p * F * t + amp * math.sin(2 * math.pi * F * t)
        x, y = s * math.cos(psi), s * math.sin(psi)
        out.append([scene, label, source, heading_deg, slope_deg, F, t, x, y, x, y, h * F * t,
                    pitch])
    return out


def write(folder: Path, all_rows):
    path = folder / "ch5_terrain" / "referee.csv"
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(HEADER)
        w.writerows(all_rows)


class TerrainPeerValues(unittest.TestCase):
    def measure(self, all_rows, scene="bigant_stairs", stairs=True):
        with tempfile.TemporaryDirectory() as d:
            write(Path(d), all_rows)
            return tp.values(tp.load(Path(d)), scene, stairs=stairs)

    def test_progress_and_height_per_cycle_are_the_drifts_whatever_the_heading(self):
        gamma = math.atan(0.12 / 0.3)
        v = self.measure(rows("bigant_stairs", "base", "mujoco", 0.2, 0.08, 0.01, gamma, 30.0)
                         + rows("bigant_stairs", "base", "ours_coulomb", 0.25, 0.1, 0.0, gamma,
                                30.0))
        self.assertTrue(v["mujoco_available"])
        self.assertAlmostEqual(v["mujoco_base_peer_progress_per_cycle_m"], 0.2, places=9)
        self.assertAlmostEqual(v["mujoco_base_peer_progress_per_cycle_min_m"], 0.2, places=9)
        self.assertAlmostEqual(v["mujoco_base_peer_height_gain_per_cycle_m"], 0.08, places=9)
        self.assertAlmostEqual(v["mujoco_base_coulomb_progress_per_cycle_m"], 0.25, places=9)
        self.assertAlmostEqual(v["mujoco_progress_ratio"], 0.8, places=9)
        self.assertAlmostEqual(v["mujoco_base_peer_pitch_minus_ground_deg"],
                               math.degrees(gamma) - 21.8, places=9)
        # The sine's slope 2π f amp = 0.0063 m/s is below the drift 0.02 m/s: it never slides back.
        self.assertEqual(v["mujoco_base_peer_max_backslide_m"], 0.0)
        self.assertTrue(v["mujoco_base_peer_climbs"])
        self.assertTrue(v["mujoco_pitch_follows_stairs"])
        self.assertTrue(v["mujoco_agrees_with_ours"])  # 0.2 within 30 % of 0.25

    def test_a_slide_back_larger_than_the_limit_is_not_a_climb(self):
        # s = 0.02 t + A sin(2π t / 10): the slide back from a local maximum to the next minimum,
        # at cos = −v/(2π f A), is known in closed form.
        p, amp = 0.2, 0.1
        v = self.measure(rows("bigant_slope17", "base", "mujoco", p, 0.05, amp, 0.0, 0.0, 17.0)
                         + rows("bigant_slope17", "base", "ours_coulomb", p, 0.05, 0.0, 0.0, 0.0,
                                17.0), scene="bigant_slope17", stairs=False)
        w = 2 * math.pi * F
        c = -p * F / (w * amp)
        t_max = math.acos(c) / w            # first local maximum
        t_min = (2 * math.pi - math.acos(c)) / w  # the following minimum
        s = lambda t: p * F * t + amp * math.sin(w * t)  # noqa: E731
        self.assertAlmostEqual(v["mujoco_base_peer_max_backslide_m"], s(t_max) - s(t_min),
                               delta=2e-4)
        self.assertFalse(v["mujoco_base_peer_climbs"])
        self.assertFalse(v["mujoco_agrees_with_ours"])
        self.assertNotIn("mujoco_pitch_follows_stairs", v)

    def test_a_check_run_is_measured_under_its_label_and_a_missing_file_is_no_data(self):
        v = self.measure(rows("bigant_stairs", "base", "mujoco", -0.1, 0.0, 0.0, 0.0)
                         + rows("bigant_stairs", "base", "ours_coulomb", 0.2, 0.08, 0.0, 0.38)
                         + rows("bigant_stairs", "noslip", "mujoco", 0.1, 0.04, 0.0, 0.38))
        self.assertFalse(v["mujoco_base_peer_climbs"])
        self.assertAlmostEqual(v["mujoco_noslip_progress_ratio"], 0.5, places=9)
        self.assertAlmostEqual(v["mujoco_base_peer_progress_per_cycle_min_m"], -0.1, places=9)
        with tempfile.TemporaryDirectory() as d:
            self.assertIsNone(tp.load(Path(d)))
            v = tp.values(None, "bigant_stairs", stairs=True, prefix="mujoco_fine")
        # No data: every key the ledger may name is there, None, with the reason.
        self.assertEqual(v["mujoco_fine_available"], False)
        for key in ("mujoco_fine_agrees_with_ours", "mujoco_fine_pitch_follows_stairs",
                    "mujoco_fine_noslip_stiff_xy_peer_edge_share",
                    "mujoco_fine_slow_coulomb_progress_per_cycle_m"):
            self.assertIsNone(v[key])
            self.assertIn("referee.toml", v[key + "_reason"])


if __name__ == "__main__":
    unittest.main()
