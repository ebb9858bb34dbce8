"""Shared helpers of the chapter-4 report scripts (the F/T calibration, studies/ch4_calibration).

The study's files (columns fixed by the sweep kinds of sweeps/points/calibration.cpp; a sweep may
add its own parameter columns, e.g. seed, in front):
  parameters.csv         calib_parameters: a row per estimated number of one calibration of the
                         synthetic BigANT: leg, parameter, estimate, se, truth, error, z
                         (= error / se); N, N·m, rad (rotation vector of R̃_k), m
  seeds.csv              the same over seeds 1..20 (a `seed` column tells the calibrations apart)
  com.csv                calib_com: per leg × axis × phase bin: the median, quartiles and 2.5/97.5 %
                         quantiles of the smoothed CoM samples in the bin over all cycles, the
                         periodic fit and the truth at the bin centre (m, in the transducer frame)
  hanging_residuals.csv  calib_hanging_residuals: reading − predict_hanging per leg, hanging
                         orientation, component, model (exact | no_misalignment), sample
  pose_residuals.csv     calib_pose_residuals: the total wrench residual per standing pose and
                         method (naive | no_mounting | full | literal), W frame, N and N·m
  models.csv             calib_models: Table 4.2's statistics per transformation-error model
  starts.csv             calib_starts: the multistart of §4.4.2 per start and solver
  accuracy.csv           calib_accuracy: errors against truth over noise_scale × poses × seed
Everything is synthetic: the truth is known, and Table 4.1's printed values ARE the truth of the
synthetic transducers' offsets and leg weights (lib/calibration/synthetic.cpp), so an estimate is
compared with the truth within its standard error, never with the thesis.
"""
from __future__ import annotations

import math

import numpy as np

import common as c

STUDY = "ch4_calibration"
LEGS = ("HL", "ML", "FL", "HR", "MR", "FR")  # Table 4.1's column order
AXES = ("x", "y", "z")
FORCES = ("fx", "fy", "fz")
TORQUES = ("tx", "ty", "tz")
COMPONENTS = FORCES + TORQUES
COMPONENT_LABEL = {"fx": "F_x", "fy": "F_y", "fz": "F_z", "tx": "T_x", "ty": "T_y", "tz": "T_z"}
COMPONENT_UNIT = {k: ("N" if k in FORCES else "N·m") for k in COMPONENTS}
ORIENTATIONS = ("+x", "-x", "+z", "-z")
HANGING_MODELS = ("exact", "no_misalignment")
POSE_METHODS = ("naive", "no_mounting", "full", "literal")
# Table 4.2's models in the thesis' row order
MODELS = ("full", "shared_translation", "translations_only", "com_only")
MODEL_LABEL = {"full": "Full (six rotations + six translations)",
               "shared_translation": "Six rotations + single translation",
               "translations_only": "Six translations only",
               "com_only": "Single translation"}
OFFSET_FORCE = ("offset_fx", "offset_fy", "offset_fz")
OFFSET_TORQUE = ("offset_tx", "offset_ty", "offset_tz")
ROTATION = ("rotation_x", "rotation_y", "rotation_z")
DISPLACEMENT = ("displacement_x", "displacement_y", "displacement_z")
PARAMETERS = OFFSET_FORCE + OFFSET_TORQUE + ("weight",) + ROTATION + DISPLACEMENT

PARAMETER_COLUMNS = ["leg", "parameter", "estimate", "se", "truth", "error", "z"]
COM_COLUMNS = ["leg", "axis", "phase", "median", "q25", "q75", "q025", "q975", "fit", "truth"]
HANGING_COLUMNS = ["leg", "orientation", "component", "model", "sample", "residual"]
POSE_COLUMNS = ["pose", "method"] + list(COMPONENTS)
MODEL_COLUMNS = ["model", "dof", "rss", "cv_mse", "bic", "selected"]
START_COLUMNS = ["start", "solver", "cost", "iterations", "converged", "seconds",
                 "rotation_error_deg", "displacement_error_mm"]
ACCURACY_COLUMNS = ["noise_scale", "poses", "seed", "weight_err_max", "offset_force_err_max",
                    "offset_torque_err_max", "com_err_rms", "rotation_err_max_deg",
                    "displacement_err_max_mm", "z_abs_max", "z_rms", "within_3se",
                    "seconds_hanging", "seconds_standing", "rss"]

# Colours: the thesis' own where its captions state them. Fig. 4.4: x blue, y orange, z green;
# Fig. 4.5: with ŝ orange, without blue; Fig. 4.6: naive light blue, without the transformation
# error orange, full green (ours adds the literal eq. 4.8 target in purple).
AXIS_COLOR = {"x": "tab:blue", "y": "tab:orange", "z": "tab:green"}
HANGING_COLOR = {"exact": "tab:orange", "no_misalignment": "tab:blue"}
METHOD_COLOR = {"naive": "lightskyblue", "no_mounting": "tab:orange", "full": "tab:green",
                "literal": "tab:purple"}
METHOD_LABEL = {"naive": "naive taring", "no_mounting": "no transformation error",
                "full": "full calibration", "literal": "full, literal eq. 4.8"}

Z_BOUND = 3.0  # "within three standard errors"


def load(data, name: str, columns: list[str]) -> c.Table:
    """DATA/ch4_calibration/<name> with its required columns; exit 2 when it has no rows."""
    t = c.Table(c.study_file(data, name, STUDY), columns)
    if t.n == 0:
        c.fail(f"{t.path}: no data rows")
    return t


def rows(t: c.Table, **match) -> c.Table:
    """The rows whose text columns equal, and numeric columns are close to, the given values."""
    mask = np.ones(t.n, bool)
    # text columns compared as fixed-width strings, converted once per table (object arrays
    # compare element by element in Python: slow on the hanging residuals' ~10⁵ rows)
    text = t.__dict__.setdefault("_text", {})
    for name, want in match.items():
        if isinstance(want, str):
            if name not in text:
                text[name] = t.str(name).astype(str)
            mask &= text[name] == want
        else:
            mask &= np.isclose(t[name].astype(float), want)
    return t.subset(mask)


DEFAULT_NOISE = 1.0  # the study's default noise scale (1 = the generator's σ's)


def at_noise(t: c.Table, noise: float = DEFAULT_NOISE) -> c.Table:
    """The rows of one noise scale, where a sweep ran several (parameters.toml and models.toml
    run the default robot and the noiseless one); a table without the column, or with one noise
    scale only, is returned whole. Exit 2 when the file has other noise scales but not this."""
    if "noise_scale" not in t.columns:
        return t
    have = t["noise_scale"].astype(float)
    if np.all(have == have[0]) and noise == DEFAULT_NOISE:
        return t
    r = t.subset(np.isclose(have, noise))
    if r.n == 0:
        c.fail(f"{t.path}: no rows with noise_scale {noise:g} (have "
               f"{', '.join(f'{x:g}' for x in sorted(set(have)))})")
    return r


def flag(col: np.ndarray) -> np.ndarray:
    """A yes/no column (1/0 or true/false) as booleans."""
    if col.dtype == object:
        return np.array([str(v).strip().lower() in ("1", "true", "yes") for v in col])
    return np.asarray(col, float) != 0.0


def legs_in(t: c.Table) -> list[str]:
    """The legs of a table in Table 4.1's order; exit 2 on an unknown leg name."""
    have = set(t.str("leg"))
    unknown = sorted(have - set(LEGS))
    if unknown:
        c.fail(f"{t.path}: unknown leg(s) {', '.join(unknown)} (expected {', '.join(LEGS)})")
    return [k for k in LEGS if k in have]


def parameter(t: c.Table, leg: str, name: str) -> dict:
    """The one row of a parameters table for (leg, parameter) as a dict of floats."""
    r = rows(t, leg=leg, parameter=name)
    if r.n != 1:
        c.fail(f"{t.path}: {r.n} rows for leg {leg}, parameter {name} (expected 1)")
    return {k: float(r[k][0]) for k in ("estimate", "se", "truth", "error", "z")}


def rmse(a) -> float:
    a = np.asarray(a, float)
    return float(np.sqrt(np.mean(a * a))) if a.size else math.nan


def rel_reduction(before: float, after: float) -> float:
    """1 − after / before (the share of an RMSE a calibration removes); nan when before is 0."""
    return 1.0 - after / before if before > 0 else math.nan


def robot_weight() -> float:
    """The robot's weight G_robot [N]: §4.1.1's mass (the ledger) × g, the synthetic BigANT's."""
    return float(c.thesis("4.1.1-robot-mass")) * c.G


def thesis_table(claim_id: str) -> np.ndarray:
    """A Table 4.1 ledger entry (rows x, y, z as printed, columns LEGS) as a 3 × 6 array, or a
    single row of 6 (the leg weights)."""
    vals = np.asarray(c.thesis(claim_id), float)
    return vals.reshape(-1, len(LEGS))


def violins(ax, data: list[np.ndarray], pos, color: str, side: str | None, width: float = 0.7,
            alpha: float = 0.5) -> None:
    """Violins (100-point kernel density, as §4.4 draws them) with a median tick; side 'left' or
    'right' keeps one half, for a split violin of two series."""
    keep = [(p, d) for p, d in zip(pos, data) if np.asarray(d).size > 1 and np.ptp(d) > 0]
    if keep:
        parts = ax.violinplot([d for _, d in keep], positions=[p for p, _ in keep], widths=width,
                              showextrema=False, showmedians=False, points=100)
        for body in parts["bodies"]:
            if side is not None:
                verts = body.get_paths()[0].vertices
                mid = np.mean(verts[:, 0])
                verts[:, 0] = (np.clip(verts[:, 0], -np.inf, mid) if side == "left"
                               else np.clip(verts[:, 0], mid, np.inf))
            body.set_facecolor(color)
            body.set_edgecolor(color)
            body.set_alpha(alpha)
    half = width / 2
    for p, d in zip(pos, data):
        d = np.asarray(d, float)
        if d.size == 0:
            continue
        lo, hi = ((p - half * 0.6, p + half * 0.6) if side is None
                  else (p - half, p) if side == "left" else (p, p + half))
        ax.plot([lo, hi], [np.median(d)] * 2, color=color, lw=1.6)
