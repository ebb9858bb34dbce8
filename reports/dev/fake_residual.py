#!/usr/bin/python3
"""Development tool: stand-in inputs for the §5.3 report scripts (fig5_5, fig5_6,
residual_training) in the columns of studies/ch5_residual.

    /usr/bin/python3 reports/dev/fake_residual.py --out /tmp/fake [--quick]

It writes OUT/ch5_residual/{transfer,errors,training}.csv (not trials.csv, which no report script
reads). The "robot" is made up: eight feet whose planar velocities q̇ are first and second
harmonics of the undulation phase 2πft + iΔφ (module i), a "template" v_model = A₀ q̇ plus a
forward speed, and a "measured" v_true = v_model + B_true(f) q̇ (the leg-to-leg differences,
scaled by the asymmetry; B_true drifts slowly with f, so B from 0.3 Hz transfers imperfectly)
+ a constant side drift (no constant B can remove it: q̇ of a periodic gait has zero mean over
whole cycles) + a fourth harmonic growing with f² (dynamics no B captures) + noise. B is
fitted here by least squares exactly as §5.3.1 (pseudo-inverse; ridge with a fixed λ). It
exists to develop the report without the C++ build or MuJoCo; the numbers mean nothing. Never
point it at data/: this script refuses to write there.
"""
from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))
import common as c  # noqa: E402
import residual as rs  # noqa: E402

LEGS = 8
MODULES = LEGS // 2
RATE = 125.0  # Hz, the motion capture of §5.3.2
CYCLES = 8
GRID = np.round(np.linspace(0.2, 1.8, 26), 6)
VALIDATE = (0.2, 0.52, 0.84, 1.16, 1.48, 1.8)
rng = np.random.default_rng(17)
LEG_COEF = rng.normal(size=(LEGS, 4)) * [0.03, 0.01, 0.02, 0.008]  # m: harmonic amplitudes
LEG_SHIFT = rng.uniform(0, 2 * np.pi, size=(LEGS, 2))
A0 = rng.normal(size=(3, 2 * LEGS)) * [[0.05], [0.05], [0.3]]
B0 = rng.normal(size=(3, 2 * LEGS)) * [[0.03], [0.12], [0.5]]
B_SYM = rng.normal(size=(3, 2 * LEGS)) * [[0.02], [0.02], [0.1]]


def trial(f: float, dphi: float, asym: float, seed: int) -> dict:
    """One made-up trial: the snapshots after the first cycle (t ≥ 1/f)."""
    noise = np.random.default_rng(seed)
    t = np.arange(0.0, CYCLES / f, 1.0 / RATE)
    t = t[t >= 1.0 / f]
    w = 2 * np.pi * f
    qdot = np.empty((t.size, 2 * LEGS))
    for k in range(LEGS):
        side = 1.0 if k < MODULES else -1.0
        ph = w * t + (k % MODULES) * dphi * np.pi
        a, b, cc, d = LEG_COEF[k]
        qdot[:, 2 * k] = w * (-a * np.sin(ph) + b * np.sin(2 * ph + LEG_SHIFT[k, 0]))
        qdot[:, 2 * k + 1] = side * w * (cc * np.cos(ph) + d * np.cos(2 * ph + LEG_SHIFT[k, 1]))
    qdot += noise.normal(scale=1e-3, size=qdot.shape)
    v_model = qdot @ A0.T
    v_model[:, 0] += 0.12 * f * (1 + 0.3 * np.cos(2 * w * t))
    b_true = asym * B0 * (1 + 0.12 * (f - 0.3)) + B_SYM
    v_true = v_model + qdot @ b_true.T
    v_true[:, 1] += -asym * 0.003 * np.sqrt(f / 0.3)  # the side drift
    v_true += 0.004 * f**2 * np.sin(4 * w * t)[:, None] * [1.0, 1.5, 8.0]  # dynamics
    v_true += noise.normal(scale=[0.002, 0.002, 0.01], size=v_true.shape)
    return {"t": t, "qdot": qdot, "v_true": v_true, "v_model": v_model}


_CACHE: dict = {}


def get(f: float, dphi: float, asym: float = 1.0) -> dict:
    key = (f, round(dphi, 6), asym)
    if key not in _CACHE:
        _CACHE[key] = trial(f, dphi, asym, seed=len(_CACHE) + 1)
    return _CACHE[key]


def fit(trials: list[dict], estimator: str) -> dict:
    q = np.vstack([tr["qdot"] for tr in trials])
    r = np.vstack([tr["v_true"] - tr["v_model"] for tr in trials])
    s = np.linalg.svd(q, compute_uv=False)
    rank = int(np.sum(s > max(q.shape) * np.finfo(float).eps * s[0]))
    lam = 0.0
    if estimator == "ridge":
        lam = 1e-3 * s[0] ** 2
        b = np.linalg.solve(q.T @ q + lam * np.eye(q.shape[1]), q.T @ r).T
    else:
        b = (np.linalg.pinv(q) @ r).T
    return {"B": b, "rank": rank, "condition": s[0] / s[rank - 1], "lambda": lam,
            "snapshots": q.shape[0]}


def velocities(tr: dict, b: np.ndarray) -> dict:
    return {"true": tr["v_true"], "model": tr["v_model"],
            "fit": tr["v_model"] + tr["qdot"] @ b.T}


def rmses(trials: list[dict], b: np.ndarray, which: str) -> np.ndarray:
    err = np.vstack([velocities(tr, b)[which] - tr["v_true"] for tr in trials])
    return np.sqrt(np.mean(err**2, axis=0))


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
    freqs = (0.3, 1.2) if args.quick else rs.FREQUENCIES
    folder = args.out / rs.STUDY
    train_text = " ".join(f"{d:g}" for d in rs.TRAIN_DPHI)

    points = []  # (train f, test f, test Δφ, estimator, asymmetry)
    for est in ("pinv", "ridge"):
        for asym in (1.0, 0.0):
            for f in freqs:
                for train_f in sorted({f, rs.BASE_FREQUENCY}):
                    points.append((train_f, f, rs.TEST_DPHI, est, asym))
                points += [(f, f, d, est, asym) for d in rs.TRAIN_DPHI]
    transfer, errors = [], []
    for pid, (train_f, f, dphi, est, asym) in enumerate(points):
        train = [get(train_f, d, asym) for d in rs.TRAIN_DPHI]
        test = get(f, dphi, asym)
        b = fit(train, est)
        v = velocities(test, b["B"])
        if est == "pinv" and asym == 1.0:
            for i, t in enumerate(test["t"]):
                transfer.append([pid, train_f, f, dphi, est, asym, f"{t:.6f}"]
                                + [f"{v[w][i, j]:.6g}" for w in ("true", "model", "fit")
                                   for j in range(3)])
        errors.append([pid, train_f, train_text, f, dphi, est, asym, b["lambda"], b["rank"],
                       f"{b['condition']:.6g}", b["snapshots"]]
                      + [f"{x:.6g}" for s in (train, [test]) for w in ("model", "fit")
                         for x in rmses(s, b["B"], w)]
                      + [f"{x:.6g}" for w in ("true", "model", "fit") for x in v[w].mean(axis=0)]
                      + [f"{np.linalg.norm(b['B']):.6g}", "0.01"])
    write(folder / "transfer.csv", rs.TRANSFER_COLUMNS, transfer)
    write(folder / "errors.csv", rs.ERRORS_COLUMNS + ["wall_s"], errors)

    training = []
    pool = [d for d in GRID if not np.any(np.isclose(d, VALIDATE))]
    draws = 5 if args.quick else 20
    pid = 0
    for f in freqs:
        validate = [get(f, d) for d in VALIDATE]
        for k in range(1, (4 if args.quick else 8) + 1):
            for draw in range(draws):
                pick = np.random.default_rng([pid, draw]).choice(len(pool), k, replace=False)
                train = [get(f, pool[i]) for i in sorted(pick)]
                b = fit(train, "pinv")
                training.append([pid, f, k, draw, " ".join(f"{pool[i]:g}" for i in sorted(pick))]
                                + [f"{x:.6g}" for w in ("model", "fit")
                                   for x in rmses(validate, b["B"], w)])
            pid += 1
    write(folder / "training.csv", rs.TRAINING_COLUMNS, training)
    print(f"wrote {folder}/transfer.csv ({len(transfer)} rows), errors.csv ({len(errors)}), "
          f"training.csv ({len(training)})")


if __name__ == "__main__":
    main()
