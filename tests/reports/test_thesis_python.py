"""The NumPy/SciPy port of the thesis' Algorithm 1 (reports/peers/thesis_python.py) against its
oracle, slipwalk's C++ (`slipwalk model`, CSV batch mode and one JSON frame), on random frames of
disk robots with 3 to 50 legs (some feet lifted), of the BigANT-like hexapod and of an
anisotropic hexapod with mixed stiffnesses and friction: the same contact sets and statuses, the
height, tilt, loads and viscous-Coulomb body velocity to rounding (1e-9 relative), the local
connection A to rounding, and the Coulomb velocity of the ε-continuation within the
continuation's own tolerance of slipwalk's certified Coulomb solve. Besides, the port's own
answers balance force and moment. Nothing is timed. The oracle tests need the binary
(SLIPWALK_BINARY, which ctest sets); without it they are skipped and the balance tests still run.
"""
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

REPO = Path(os.environ.get("SLIPWALK_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(REPO / "reports" / "peers"))
import thesis_python as tp  # noqa: E402

BINARY = os.environ.get("SLIPWALK_BINARY")
ROUNDING = 1e-9  # relative agreement of the support and the viscous-Coulomb balance
# The continuation stops once two consecutive ε solutions differ by Δ ≤ 1e-3 ‖v‖. Where the
# ε-solution's error shrinks by a factor r per step (ε ×0.1: r = 0.1 where it is linear in ε, as
# for sliding feet, and r = √0.1 where it goes as √ε, as for a foot at rest, whose force rises
# over slip speeds of order √ε), the last error is at most r/(1 − r) Δ < Δ for r < ½: the
# velocity is within 1e-3 ‖v‖ of Coulomb's.
CONTINUATION_TOL = 1e-3
FRAMES = 12
STATUS = {0: "balanced", 1: "line", 2: "point", 3: "unsupported"}  # SupportSummary::Status


def anisotropic_hexapod() -> tuple[tp.Robot, np.ndarray]:
    robot, nominal = tp.hexapod_robot()
    rng = np.random.default_rng(7)
    robot.K = robot.K * rng.uniform(0.3, 3.0, 6)
    robot.mu = rng.uniform(0.3, 1.2, 6)
    robot.w = rng.uniform(-0.8, 0.8, (6, 2))
    return robot, nominal


def robots() -> dict[str, tuple[tp.Robot, np.ndarray]]:
    out = {f"disk{n}": tp.disk_robot(n) for n in (3, 4, 6, 12, 50)}
    out["hexapod"] = tp.hexapod_robot()
    out["anisotropic hexapod"] = anisotropic_hexapod()
    return out


def frames_of(robot: tp.Robot, nominal: np.ndarray, seed: int):
    rng = np.random.default_rng(seed)
    return [tp.random_frame(robot, nominal, rng) for _ in range(FRAMES)]


def robot_json(robot: tp.Robot) -> dict:
    return {"K": robot.K.tolist(), "mu": robot.mu.tolist(), "w": robot.w.tolist(),
            "Mg": robot.Mg}


def slipwalk_batch(robot: tp.Robot, frames, law: str, tmp: Path) -> np.ndarray:
    """`slipwalk model --robot ... --in frames.csv --friction law`, its output as a record array."""
    (tmp / "robot.json").write_text(json.dumps(robot_json(robot)))
    n = robot.legs
    header = ["theta"] + [f"{p}{j}{a}" for j in range(n) for p in ("q", "qd") for a in "xyz"]
    rows = [",".join(header)]
    for q, qdot in frames:
        cells = [0.0] + [x for j in range(n) for x in (*q[j], *qdot[j])]
        rows.append(",".join(repr(float(x)) for x in cells))
    (tmp / "frames.csv").write_text("\n".join(rows) + "\n")
    p = subprocess.run([BINARY, "model", "--robot", str(tmp / "robot.json"), "--in",
                        str(tmp / "frames.csv"), "--friction", law],
                       capture_output=True, text=True, check=True)
    return np.atleast_1d(np.genfromtxt(io.StringIO(p.stdout), delimiter=",", names=True))


def per_leg(row, quantity: str, n: int) -> np.ndarray:
    return np.array([row[f"{quantity}{j}"] for j in range(n)])


def relative(a, b) -> float:
    a, b = np.atleast_1d(a), np.atleast_1d(b)
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


@unittest.skipUnless(BINARY, "SLIPWALK_BINARY is not set: no oracle to compare with")
class ThePortAgreesWithSlipwalk(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cases = {}
        with tempfile.TemporaryDirectory() as tmp:
            for seed, (name, (robot, nominal)) in enumerate(robots().items()):
                frames = frames_of(robot, nominal, seed)
                cls.cases[name] = (robot, frames, slipwalk_batch(robot, frames, "viscous",
                                                                 Path(tmp)))
            for name in ("hexapod", "anisotropic hexapod"):
                robot, frames, _ = cls.cases[name]
                cls.cases[name + " coulomb"] = (robot, frames,
                                                slipwalk_batch(robot, frames, "coulomb",
                                                               Path(tmp)))

    def test_contact_sets_heights_tilts_and_loads_equal_slipwalks(self):
        tilted = 0
        for name, (robot, frames, rows) in self.cases.items():
            if name.endswith("coulomb"):
                continue
            for i, ((q, _), row) in enumerate(zip(frames, rows)):
                with self.subTest(robot=name, frame=i):
                    s = tp.spring_support(robot, q)
                    tilted += s.tilts > 0
                    self.assertEqual(s.status, STATUS[int(row["support"])])
                    np.testing.assert_array_equal(s.contact,
                                                  per_leg(row, "contact", robot.legs) == 1)
                    self.assertLess(relative(s.z, row["z"]), ROUNDING)
                    # the tilt relative to the body's size: α, β are slopes (m/m)
                    tilt = max(abs(row["alpha"]), abs(row["beta"]), 1e-3)
                    self.assertLess(abs(s.alpha - row["alpha"]) / tilt, ROUNDING)
                    self.assertLess(abs(s.beta - row["beta"]) / tilt, ROUNDING)
                    self.assertLess(relative(s.Fz, per_leg(row, "Fz", robot.legs)), ROUNDING)
        # §3.3.3's tilt steps (fewer than three feet down at z*) were on the path somewhere
        self.assertGreater(tilted, 0)

    def test_the_viscous_coulomb_body_velocity_and_forces_equal_slipwalks(self):
        for name, (robot, frames, rows) in self.cases.items():
            if name.endswith("coulomb"):
                continue
            for i, ((q, qdot), row) in enumerate(zip(frames, rows)):
                with self.subTest(robot=name, frame=i):
                    r = tp.model(robot, q, qdot)
                    self.assertLess(relative(r.v, [row["vx"], row["vy"], row["wz"]]), ROUNDING)
                    c = tp.friction_weights(robot, r.support)
                    F = tp.foot_forces(robot, q, qdot, c, r.v)
                    ours = np.column_stack([per_leg(row, "Fx", robot.legs),
                                            per_leg(row, "Fy", robot.legs)])
                    self.assertLess(relative(F, ours), ROUNDING)

    def test_the_local_connection_of_a_json_frame_equals_slipwalks(self):
        robot, nominal = anisotropic_hexapod()
        q, qdot = frames_of(robot, nominal, 99)[0]
        frame = {"q": q.tolist(), "qdot": qdot.tolist(), **robot_json(robot)}
        p = subprocess.run([BINARY, "model", "--friction", "viscous"], input=json.dumps(frame),
                           capture_output=True, text=True, check=True)
        A = np.array(json.loads(p.stdout)["A"])
        self.assertLess(relative(tp.model(robot, q, qdot).A, A), ROUNDING)

    def test_coulomb_by_epsilon_continuation_is_within_its_tolerance_of_slipwalks(self):
        for name in ("hexapod coulomb", "anisotropic hexapod coulomb"):
            robot, frames, rows = self.cases[name]
            for i, ((q, qdot), row) in enumerate(zip(frames, rows)):
                with self.subTest(robot=name, frame=i):
                    self.assertEqual(row["friction_converged"], 1)  # certified
                    c = tp.friction_weights(robot, tp.spring_support(robot, q))
                    start = tp.viscous_balance(robot, q, qdot, c)
                    r = tp.coulomb_by_continuation(robot, q, qdot, c, start)
                    self.assertTrue(r.converged)
                    certified = np.array([row["vx"], row["vy"], row["wz"]])
                    self.assertLess(np.linalg.norm(r.v - certified),
                                    CONTINUATION_TOL * np.linalg.norm(certified))


class ThePortsOwnAnswersBalance(unittest.TestCase):
    def setUp(self):
        self.cases = [(robot, frames_of(robot, nominal, 11 + k))
                      for k, (robot, nominal) in enumerate(robots().values())]

    def test_the_loads_carry_the_weight_and_hold_no_moment(self):
        for robot, frames in self.cases:
            for q, _ in frames:
                s = tp.spring_support(robot, q)
                size = np.max(np.linalg.norm(q[:, :2], axis=1))
                self.assertLess(abs(s.Fz.sum() - robot.Mg) / robot.Mg, 1e-12)
                self.assertLess(abs(np.dot(q[:, 0], s.Fz)) / (robot.Mg * size), 1e-12)
                self.assertLess(abs(np.dot(q[:, 1], s.Fz)) / (robot.Mg * size), 1e-12)
                self.assertTrue(np.all(s.Fz[~s.contact] == 0.0) and np.all(s.Fz[s.contact] > 0))

    def test_the_viscous_forces_balance_and_the_connection_gives_the_same_velocity(self):
        for robot, frames in self.cases:
            for q, qdot in frames:
                r = tp.model(robot, q, qdot)
                c = tp.friction_weights(robot, r.support)
                scale = np.sum(np.abs(tp.foot_forces(robot, q, qdot, c, np.zeros(3))))
                residual = tp.planar_balance(robot, q, qdot, c, r.v)
                self.assertLess(np.max(np.abs(residual[:2])) / scale, 1e-12)
                self.assertLess(abs(residual[2]) / (scale * 0.4), 1e-12)
                self.assertLess(relative(r.v, tp.viscous_balance(robot, q, qdot, c)), 1e-12)

    def test_an_epsilon_solution_balances_its_own_law(self):
        robot, frames = self.cases[-1]  # the anisotropic hexapod
        for q, qdot in frames:
            c = tp.friction_weights(robot, tp.spring_support(robot, q))
            start = tp.viscous_balance(robot, q, qdot, c)
            r = tp.epsilon_balance(robot, q, qdot, c, 1e-5, start)
            self.assertTrue(r.converged)
            scale = np.sum(c)  # each foot's ε-force is at most about c_k
            self.assertLess(np.max(np.abs(tp.planar_balance(robot, q, qdot, c, r.v, 1e-5)))
                            / scale, 1e-6)

    def test_a_foot_alone_under_the_com_tilts_and_a_com_outside_the_feet_tips(self):
        robot = tp.uniform_robot(3, 1000.0, 1.0, 10.0)
        # one low foot touches first at z*; the body then tilts onto the others (§3.3.3)
        q = np.array([[0.2, 0.0, -0.12], [-0.1, 0.15, -0.1], [-0.1, -0.15, -0.1]])
        s = tp.spring_support(robot, q)
        self.assertEqual(s.status, "balanced")
        self.assertGreater(s.tilts, 0)
        self.assertTrue(np.all(s.contact))
        # every foot on one side of the CoM: no balance, the robot tips
        q[:, 0] = [0.2, 0.1, 0.1]
        self.assertEqual(tp.spring_support(robot, q).status, "unsupported")


if __name__ == "__main__":
    unittest.main()
