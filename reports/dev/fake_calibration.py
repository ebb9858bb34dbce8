#!/usr/bin/python3
"""Development tool: stand-in inputs for the chapter-4 report scripts (table4_1, fig4_4, fig4_5,
fig4_6, table4_2, calib_accuracy) in the columns of studies/ch4_calibration.

    /usr/bin/python3 reports/dev/fake_calibration.py --out /tmp/fake [--quick]

It writes OUT/ch4_calibration/{parameters,seeds,com,hanging_residuals,pose_residuals,models,
starts,accuracy}.csv. The "calibration" is made up: a truth (Table 4.1's offsets and weights from
the ledger, small mounting errors, a leg CoM that is a first and second harmonic of the phase),
estimates = truth + standard error × a normal draw, CoM samples scattered about the truth,
hanging residuals that are normal with ŝ and shifted per orientation without it, pose residuals
whose spread shrinks from naive taring to the full calibration, Table 4.2's BIC computed from
made-up RSS by its formula, and errors that fall as noise / √poses. No calibration runs here;
it exists to develop the report without the C++ build; the numbers mean nothing. Never point it
at data/: this script refuses to write there.
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))
import calibration as cal  # noqa: E402
import common as c  # noqa: E402

rng = np.random.default_rng(4)
ROT_TRUE = rng.normal(scale=math.radians(2.0), size=(6, 3))  # rad
DISP_TRUE = rng.normal(scale=0.01, size=(6, 3)) + [-0.045, 0.037, -0.02]  # m
SE = {"offset_f": 0.01, "offset_t": 0.0005, "weight": 0.02, "rotation": 0.002,
      "displacement": 0.001}
COM_A = rng.uniform(0.02, 0.035, size=(6, 2))  # m: x, z amplitudes
COM_C = rng.uniform(0, 2 * np.pi, size=(6, 2))
COM_D = np.column_stack([rng.normal(scale=0.01, size=6), np.full(6, 0.06), np.full(6, -0.08)])


def truth() -> dict:
    f = cal.thesis_table("table4.1-force-offsets")
    t = cal.thesis_table("table4.1-torque-offsets")
    w = cal.thesis_table("table4.1-leg-gravity")[0]
    out = {}
    for j, leg in enumerate(cal.LEGS):
        for i, a in enumerate(cal.AXES):
            out[leg, f"offset_f{a}"] = (f[i, j], SE["offset_f"])
            out[leg, f"offset_t{a}"] = (t[i, j], SE["offset_t"])
            out[leg, f"rotation_{a}"] = (ROT_TRUE[j, i], SE["rotation"])
            out[leg, f"displacement_{a}"] = (DISP_TRUE[j, i], SE["displacement"])
        out[leg, "weight"] = (w[j], SE["weight"])
    return out


def parameter_rows(seed: int, noise: float = 1.0) -> list[list]:
    draw = np.random.default_rng([7, seed])
    rows = []
    for (leg, name), (true, se) in truth().items():
        err = noise * se * draw.normal() if noise > 0 else 1e-13 * draw.normal()
        rows.append([leg, name, f"{true + err:.10g}", f"{noise * se:.6g}", f"{true:.10g}",
                     f"{err:.6g}", f"{err / (noise * se):.6g}" if noise > 0 else "nan"])
    return rows


def com_truth(j: int, axis: str, phi: np.ndarray) -> np.ndarray:
    if axis == "y":
        return COM_D[j, 1] + 0 * phi
    i = 0 if axis == "x" else 1
    base = COM_D[j, 0] if axis == "x" else COM_D[j, 2]
    return (base + COM_A[j, i] * np.sin(2 * np.pi * phi + COM_C[j, i])
            + 0.15 * COM_A[j, i] * np.sin(4 * np.pi * phi + COM_C[j, i]))


def com_rows(bins: int, cycles: int = 10) -> list[list]:
    draw = np.random.default_rng(11)
    rows = []
    for j, leg in enumerate(cal.LEGS):
        for axis in cal.AXES:
            for b in range(bins):
                centre = (b + 0.5) / bins - 0.5
                phi = centre + (draw.uniform(-0.5, 0.5, size=cycles * 25)) / bins
                samples = com_truth(j, axis, phi) + draw.normal(scale=0.003, size=phi.size)
                q = np.quantile(samples, [0.5, 0.25, 0.75, 0.025, 0.975])
                true = float(com_truth(j, axis, np.array([centre]))[0])
                fit = true + 0.0005 * math.sin(3 * centre + j)
                rows.append([leg, axis, f"{centre:.6g}"] + [f"{x:.6g}" for x in q]
                            + [f"{fit:.6g}", f"{true:.6g}"])
    return rows


def hanging_rows(samples: int) -> list[list]:
    draw = np.random.default_rng(12)
    rows = []
    for j, leg in enumerate(cal.LEGS):
        tilt = draw.normal(scale=math.radians(2.0), size=(4, 3))  # per orientation
        for o, orient in enumerate(cal.ORIENTATIONS):
            for k, comp in enumerate(cal.COMPONENTS):
                sd = 0.05 if comp in cal.FORCES else 0.003
                lever = 1.0 if comp in cal.FORCES else 0.06
                shift = 6.2 * lever * tilt[o, k % 3]
                base = draw.normal(scale=sd, size=samples)
                for model in cal.HANGING_MODELS:
                    res = base + (shift if model == "no_misalignment" else 0.0)
                    rows += [[leg, orient, comp, model, i, f"{r:.6g}"] for i, r in enumerate(res)]
    return rows


def pose_rows(poses: int) -> list[list]:
    draw = np.random.default_rng(13)
    spread = {"naive": [4, 3, 5, 0.8, 1.0, 0.3], "no_mounting": [1.5, 1.2, 0.8, 0.3, 0.4, 0.1],
              "full": [0.3, 0.3, 0.4, 0.02, 0.02, 0.01],
              "literal": [0.3, 0.3, 0.4, 0.02, 0.02, 0.01]}
    bias = {"naive": [6, -4, 8, 1.5, -2.0, 0.2], "no_mounting": [0.5, 0.3, 0, 0.1, 0.1, 0],
            "full": [0] * 6, "literal": [0, 0, 0, 0.4, -0.3, 0]}
    rows = []
    for p in range(poses):
        for m in cal.POSE_METHODS:
            w = np.array(bias[m]) + np.array(spread[m]) * draw.normal(size=6)
            rows.append([p, m] + [f"{x:.6g}" for x in w])
    return rows


def model_rows(poses: int) -> list[list]:
    mse = {"full": 0.5, "shared_translation": 0.7, "translations_only": 2.6, "com_only": 4.4}
    dof = {"full": 36, "shared_translation": 21, "translations_only": 18, "com_only": 3}
    rows, bic = [], {}
    for m in cal.MODELS:
        rss = mse[m] * poses * 6
        bic[m] = poses * math.log(rss / poses) + dof[m] * math.log(poses)
        rows.append([m, dof[m], f"{rss:.8g}", f"{mse[m] * (1 + dof[m] / poses):.6g}",
                     f"{bic[m]:.8g}"])
    best = min(bic, key=bic.get)
    return [r + [int(r[0] == best)] for r in rows]


def start_rows(starts: int) -> list[list]:
    draw = np.random.default_rng(14)
    rows = []
    for s in range(starts):
        for solver in ("alternating", "ceres_so3"):
            cost = 1629.0 * (1 + 1e-4 * abs(draw.normal()))
            rows.append([s, solver, f"{cost:.10g}", int(draw.integers(8, 40)), 1,
                         f"{abs(draw.normal(0.2, 0.05)):.4g}", f"{abs(draw.normal(0.3, 0.05)):.4g}",
                         f"{abs(draw.normal(1.0, 0.2)):.4g}"])
    return rows


def accuracy_rows(quick: bool) -> list[list]:
    draw = np.random.default_rng(15)
    noises = (0.0, 1.0) if quick else (0.0, 0.25, 0.5, 1.0, 2.0, 4.0)
    poses = (25, 100) if quick else (25, 50, 100, 200, 543)
    seeds = (1, 2) if quick else (1, 2, 3, 4, 5)
    rows = []
    for s_ in noises:
        for p in poses:
            for seed in seeds:
                e = lambda base: (s_ * base * abs(draw.normal(1, 0.3)) if s_ > 0  # noqa: E731
                                  else 1e-13 * abs(draw.normal()))
                std = lambda base: e(base) * math.sqrt(543 / p)  # noqa: E731
                z = draw.normal(size=78)
                zs = (f"{np.max(np.abs(z)):.4g}", f"{math.sqrt(np.mean(z * z)):.4g}",
                      f"{np.mean(np.abs(z) <= 3):.4g}") if s_ > 0 else ("nan", "nan", "nan")
                rows.append([s_, p, seed, f"{e(0.03):.4g}", f"{e(0.02):.4g}", f"{e(0.001):.4g}",
                             f"{e(0.0005):.4g}", f"{std(0.1):.4g}", f"{std(1.0):.4g}", *zs,
                             f"{0.2 + 0.001 * p:.4g}", f"{0.01 * p:.4g}",
                             f"{(s_ ** 2) * p * 6 * 0.1:.6g}"])
    return rows


def write(path: Path, header: list[str], rows: list[list]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    if (c.REPO / "data").resolve() in [args.out.resolve(), *args.out.resolve().parents]:
        c.fail(f"{args.out}: refusing to write stand-in data under data/")
    folder = args.out / cal.STUDY
    poses = 60 if args.quick else 543
    # as the study: parameters.toml and models.toml run the default robot and the noiseless one
    write(folder / "parameters.csv", ["seed", "noise_scale"] + cal.PARAMETER_COLUMNS,
          [[1, s_] + r for s_ in (1.0, 0.0) for r in parameter_rows(1, s_)])
    write(folder / "seeds.csv", ["seed"] + cal.PARAMETER_COLUMNS,
          [[s] + r for s in range(1, 21) for r in parameter_rows(s)])
    write(folder / "com.csv", cal.COM_COLUMNS, com_rows(12 if args.quick else 36))
    write(folder / "hanging_residuals.csv", cal.HANGING_COLUMNS,
          hanging_rows(20 if args.quick else 90))
    write(folder / "pose_residuals.csv", cal.POSE_COLUMNS, pose_rows(poses))
    write(folder / "models.csv", ["noise_scale", "poses"] + cal.MODEL_COLUMNS,
          [[1.0, poses] + r for r in model_rows(poses)]
          + [[0.0, poses] + r[:2] + [1e-20, 1e-24, -1e4, int(r[0] == "full")]
             for r in model_rows(poses)])
    write(folder / "starts.csv", cal.START_COLUMNS, start_rows(5 if args.quick else 20))
    write(folder / "accuracy.csv", cal.ACCURACY_COLUMNS, accuracy_rows(args.quick))
    print(f"wrote {folder}/*.csv")


if __name__ == "__main__":
    main()
