"""Shared helpers of the §5.3 report scripts (the residual term B, studies/ch5_residual).

The study's files (columns fixed by the sweep kinds of sweeps/points/residual.cpp):
  transfer.csv  residual_transfer: a row per test snapshot (interior samples after the dropped
                first cycle) of one (training set, test trial) point: v_true (MuJoCo's Multipod,
                the "measured" robot), v_model = A(q) q̇ (the template), v_fit = (A(q) + B) q̇
  errors.csv    residual_errors: one row per point: RMSEs on the training and test snapshots,
                means over the test snapshots, rank and condition of the q̇ matrix
  training.csv  residual_training: validation RMSEs against the number of training trials k
Velocities: forward v_x and side v_y in m/s (body frame), yaw rate ω in rad/s.
"""
from __future__ import annotations

import math

import numpy as np

import common as c

STUDY = "ch5_residual"
FREQUENCIES = (0.3, 0.6, 1.2, 2.4)  # Hz, the four the thesis lists (§5.3.2)
TRAIN_DPHI = (0.65, 0.9, 1.1, 1.35)  # ×π, the training trials of Fig. 5.5
TEST_DPHI = 1.0  # ×π, the test trial of Fig. 5.5 (not on the 26-grid)
BASE_FREQUENCY = 0.3  # Hz, the training frequency of Fig. 5.6's left halves
COMPONENTS = ("x", "y", "w")
COMPONENT_NAME = {"x": "forward velocity", "y": "side velocity", "w": "yaw rate"}
COMPONENT_UNIT = {"x": "m/s", "y": "m/s", "w": "rad/s"}

# Colours of §5.3 (the thesis' captions): the robot's measured motion red (here MuJoCo's
# Multipod stands in for the motion capture), the template model blue, model + B orange,
# model + B trained at the test trial's own frequency purple (Fig. 5.6, right halves).
TRUE = c.MEASURED
MODEL = c.ESTIMATE
FIT = "tab:orange"
OWN = "tab:purple"

TRANSFER_COLUMNS = ["id", "train_frequency", "test_frequency", "test_dphi_pi", "estimator",
                    "asymmetry", "t"] + [f"v_{w}_{k}" for w in ("true", "model", "fit")
                                         for k in COMPONENTS]
ERRORS_COLUMNS = (["id", "train_frequency", "train_dphi_pi", "test_frequency", "test_dphi_pi",
                   "estimator", "asymmetry", "lambda", "rank", "condition", "snapshots"]
                  + [f"{s}_rmse_{w}_{k}" for s in ("train", "test") for w in ("model", "fit")
                     for k in COMPONENTS]
                  + [f"test_mean_{w}_{k}" for w in ("true", "model", "fit") for k in COMPONENTS]
                  + ["b_norm"])
TRAINING_COLUMNS = (["id", "frequency", "train_trials", "draw", "train_dphi_pi"]
                    + [f"validation_rmse_{w}_{k}" for w in ("model", "fit") for k in COMPONENTS])


def tag(f: float) -> str:
    """A frequency as a value-key part: 0.3 Hz -> 'f0p3'."""
    return "f" + f"{f:g}".replace(".", "p")


def dphi_list(text) -> tuple[float, ...]:
    """A train_dphi_pi cell ('0.65 0.9 1.1 1.35', or a lone number) as a sorted tuple."""
    return tuple(sorted(float(v) for v in str(text).split()))


def load(data, name: str, columns: list[str]) -> c.Table:
    """DATA/ch5_residual/<name> with its required columns; exit 2 when it has no rows. B is
    trained at the test's frequency unless a point names train_frequency: an empty cell there
    reads as the test frequency."""
    t = c.Table(c.study_file(data, name, STUDY), columns)
    if t.n == 0:
        c.fail(f"{t.path}: no data rows")
    if "train_frequency" in t.columns and "test_frequency" in t.columns:
        train = t["train_frequency"].astype(float)
        t.columns["train_frequency"] = np.where(np.isnan(train), t["test_frequency"], train)
    return t


def rows(t: c.Table, **match) -> c.Table:
    """The rows whose numeric columns equal (np.isclose) and text columns equal the given values;
    train_dphi_pi is matched as a set of offsets."""
    mask = np.ones(t.n, bool)
    for name, want in match.items():
        if name == "train_dphi_pi":
            mask &= np.array([dphi_list(v) == tuple(sorted(want)) for v in t.str(name)])
        elif isinstance(want, str):
            mask &= t.str(name) == want
        else:
            mask &= np.isclose(t[name].astype(float), want)
    return t.subset(mask)


def frequencies(t: c.Table, column: str) -> list[float]:
    """The thesis' frequencies present in a column, in order."""
    have = t[column].astype(float)
    return [f for f in FREQUENCIES if np.any(np.isclose(have, f))]


def ratio(a: float, b: float) -> float:
    """a / b for two errors (≥ 0): +∞ when only b is 0, 1 when both are (equal errors)."""
    if b == 0.0:
        return 1.0 if a == 0.0 else math.inf
    return a / b


def rel_diff(a: float, b: float) -> float:
    """|a − b| / max(|a|, |b|), 0 when both are 0."""
    m = max(abs(a), abs(b))
    return abs(a - b) / m if m > 0 else 0.0


def rmse(a: np.ndarray) -> float:
    a = np.asarray(a, float)
    return float(np.sqrt(np.mean(a * a))) if a.size else float("nan")


def test_trial(transfer: c.Table, train_f: float, test_f: float, dphi: float = TEST_DPHI,
               estimator: str = "pinv", asymmetry: float = 1.0) -> c.Table:
    """The snapshots of one transfer point, in time order; exit 2 when the study has none."""
    r = rows(transfer, train_frequency=train_f, test_frequency=test_f, test_dphi_pi=dphi,
             estimator=estimator, asymmetry=asymmetry)
    if r.n == 0:
        c.fail(f"{transfer.path}: no snapshots for B trained at {train_f:g} Hz, tested at "
               f"{test_f:g} Hz, Δφ = {dphi:g}π ({estimator}, asymmetry {asymmetry:g})")
    # B trained at 0.3 Hz and tested at 0.3 Hz is both Fig. 5.5's and Fig. 5.6's point; a study
    # may list it twice (the same inputs give the same rows): the first point is taken.
    ids = r.str("id")
    r = r.subset(ids == ids[0])
    return r.subset(np.argsort(r["t"], kind="stable"))


def error_point(errors: c.Table, train_f: float, test_f: float, dphi: float = TEST_DPHI,
                estimator: str = "pinv", asymmetry: float = 1.0) -> dict:
    """The row of errors.csv for B trained on the Fig. 5.5 offsets at train_f, tested on one
    trial, as a dict of floats."""
    r = rows(errors, train_frequency=train_f, train_dphi_pi=TRAIN_DPHI, test_frequency=test_f,
             test_dphi_pi=dphi, estimator=estimator, asymmetry=asymmetry)
    if r.n == 0:
        c.fail(f"{errors.path}: no row for B trained at {train_f:g} Hz, tested at {test_f:g} Hz, "
               f"Δφ = {dphi:g}π ({estimator}, asymmetry {asymmetry:g})")
    # as in test_trial: a point listed twice has the same row twice; the first is taken
    return {k: (float(v[0]) if v.dtype != object else v[0]) for k, v in r.columns.items()}
