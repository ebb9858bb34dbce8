#!/usr/bin/python3
"""Development tool: writes stand-in inputs for the report scripts into a scratch folder.

    /usr/bin/python3 reports/dev/fake_data.py --out /tmp/fake [--quick]

It writes OUT/ch2_inchworm/*.csv (+ JSON sidecars) in the formats `slipwalk reproduce` writes,
computed in Python: the exact v_ss by the closed form, the "analytic" method by iterating the
exact stroke map (two phases of constant acceleration per stroke) from rest, the other
integrators as the analytic result with made-up noise and costs. It exists to develop and test
the report without the C++ build. Never point it at data/: the real data come from the C++ code,
and this script refuses to write there.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))
import common as c  # noqa: E402

SWEEP_COLUMNS = ["id", "mu", "mu_s", "F", "f_tilde", "F_frac", "method", "rtol", "stop",
                 "estimator", "v_ss", "period", "c0", "regime", "est_error", "last_difference",
                 "contraction", "strokes", "converged", "steps", "rhs_evals", "wall_s", "message"]


# ---------------------------------------------------------------------------------------------
# The stroke map of the instant-swap model (μ_s = μ), as lib/inchworm/closed_form.cpp


def stroke(F, mu, c0):
    a_x = (F - mu * c.m * c.G) / c.m
    b = (F + mu * c.M * c.G) / c.M
    r1 = F / c.m + F / c.M
    kappa = F / (F + mu * c.M * c.G)
    if F <= mu * c.M * c.G:
        r2, a2, slid = a_x, (F - mu * c.m * c.G) / (c.m + c.M), False
    else:
        r2, a2, slid = a_x + (F - mu * c.M * c.G) / c.M, mu * c.G * c.RHO, True
    t1 = c0 / b
    l1 = 0.5 * r1 * t1 * t1
    if l1 >= c.DL:
        T = math.sqrt(2 * c.DL / r1)
        return c0 - mu * c.G * T, T, c0 * T - 0.5 * mu * c.G * T * T, False
    R = c.DL - l1
    rate = r1 * t1
    t2 = 2 * R / (rate + math.sqrt(rate * rate + 2 * r2 * R))
    c1 = kappa * c0
    return c1 + a2 * t2, t1 + t2, 0.5 * (c0 + c1) * t1 + c1 * t2 + 0.5 * a2 * t2 * t2, slid


def remaining_error(v):
    j = len(v) - 1
    s = max(1, j // 4)
    d1 = v[j - s] - v[j - 2 * s]
    d2 = v[j] - v[j - s]
    rho = d2 / d1 if d1 != 0 else math.nan
    if 0 < rho < 1:
        return abs(d2) * rho / (1 - rho), rho ** (1 / s)
    return abs(d1) + abs(d2), math.nan


def simulate(F, mu, target=1e-10, stop="estimate", estimator="cycle", max_strokes=400000,
             min_cycles=4, record=False):
    """Mirrors steady_state_by_simulation (lib/inchworm/simulate.hpp) on the exact stroke map."""
    cvel = 0.0
    avgs, running = [], []
    tot_d = tot_t = 0.0
    prev = math.nan
    out = {"converged": 0, "message": "", "strokes": 0, "est_error": math.nan,
           "last_difference": math.nan, "contraction": math.nan}
    for cycle in range(max_strokes // 2):
        c_start = cvel
        cvel, Ta, Da, _ = stroke(F, mu, cvel)
        Da += c.RHO * c.L_MAX
        cvel, Tb, Db, slid = stroke(F, mu, cvel)
        Db -= c.RHO * c.L_MIN
        out["strokes"] += 2
        avg = (Da + Db) / (Ta + Tb)
        avgs.append(avg)
        tot_d += Da + Db
        tot_t += Ta + Tb
        running.append(tot_d / tot_t)
        rep = running[-1] if estimator == "running" else avg
        out.update(v_ss=rep, period=0.5 * (Ta + Tb), c0=c_start, regime=2 if slid else 1)
        j = len(avgs) - 1
        if j >= 1:
            out["last_difference"] = abs(rep - prev) / abs(rep)
        prev = rep
        if j >= 2:
            err, lam = remaining_error(avgs)
            out["est_error"] = err / abs(avg)
            out["contraction"] = lam
            crit = out["est_error"] if stop == "estimate" else out["last_difference"]
            if cycle + 1 >= min_cycles and crit <= target:
                out["converged"] = 1
                out["message"] = "converged"
                break
    if not out["converged"]:
        out["message"] = f"no convergence within {max_strokes} strokes"
    if record:
        out["cycle_averages"] = avgs
        out["running"] = running
    return out


# ---------------------------------------------------------------------------------------------
# Trace (Fig. 2.2)


def trace_rows(F, mu, cycles=6, dt=1e-3):
    m, M, g = c.m, c.M, c.G
    x = M * c.L_MIN / (m + M)
    y = -m * c.L_MIN / (m + M)
    xd = yd = 0.0
    t = 0.0
    side = 1
    rows = []
    slide_M_rest = -1 if F > mu * M * g else 0

    def row(t, x, y, xd, yd, sm, sM, side, ev):
        rows.append([t, x, y, (m * x + M * y) / (m + M), xd, yd, (m * xd + M * yd) / (m + M),
                     sm, sM, side, ev])

    sM = slide_M_rest
    row(t, x, y, xd, yd, 1, sM, side, "start")
    next_sample = dt
    for _ in range(2 * cycles):
        # phases: (acc_m, acc_M, duration, event at end)
        ax = (F - mu * m * g) / m
        goal = c.L_MAX if side > 0 else -c.L_MIN
        phases = []
        if yd > 0:
            sM = 1
            ay = (-F - mu * M * g) / M
            t1 = yd / -ay
            # does the length limit come first?
            d0, dd0 = x - y, xd - yd
            r1 = ax - ay
            tl = (-dd0 + math.sqrt(dd0 * dd0 + 2 * r1 * (goal - d0))) / r1
            if tl <= t1:
                phases.append((ax, ay, tl, "collision", 1))
            else:
                phases.append((ax, ay, t1, "M_stops", 1))
        # run the phases; the second (M stuck or sliding back) follows when M stops first
        done = False
        while not done:
            if phases:
                ax_, ay_, dur, ev, sMp = phases.pop(0)
            else:
                sMp = slide_M_rest
                ay_ = (-F + mu * M * g) / M if sMp < 0 else 0.0
                ax_ = ax
                d0, dd0 = x - y, xd - yd
                r = ax_ - ay_
                dur = (-dd0 + math.sqrt(dd0 * dd0 + 2 * r * (goal - d0))) / r
                ev = "collision"
            t_end = t + dur
            while next_sample < t_end - 1e-12:
                s = next_sample - t
                row(next_sample, x + xd * s + 0.5 * ax_ * s * s, y + yd * s + 0.5 * ay_ * s * s,
                    xd + ax_ * s, yd + ay_ * s, 1, sMp, side, "")
                next_sample += dt
            x, y = x + xd * dur + 0.5 * ax_ * dur * dur, y + yd * dur + 0.5 * ay_ * dur * dur
            xd, yd = xd + ax_ * dur, yd + ay_ * dur
            t = t_end
            if ev == "M_stops":
                yd = 0.0
                row(t, x, y, xd, yd, 1, sMp, side, "M_stops")
                continue
            row(t, x, y, xd, yd, 1, sMp, side, "collision_before")
            v = (m * xd + M * yd) / (m + M)
            x, y = y, x
            xd = yd = v
            side = -side
            row(t, x, y, xd, yd, 1, 1, side, "collision_after")
            done = True
    return rows


# ---------------------------------------------------------------------------------------------


def sweep_row(pid, F, mu, method, rtol=1e-10, stop="estimate", estimator="cycle", mu_s=None,
              rng=None, **sim):
    row = {"id": pid, "mu": mu, "mu_s": mu if mu_s is None else mu_s, "F": F,
           "f_tilde": F / (mu * c.M * c.G), "F_frac": (F - mu * c.m * c.G) /
           (5 * c.M * c.G - mu * c.m * c.G), "method": method, "rtol": rtol, "stop": stop,
           "estimator": estimator}
    if method in ("exact", "rootfind"):
        cf = c.closed_form(F, mu)
        row.update(v_ss=cf["v_ss"], period=cf["period"], c0=cf["c0"], regime=cf["regime"],
                   est_error=0, last_difference=0, contraction=math.nan, strokes=0,
                   converged=1, steps=0, rhs_evals=0 if method == "exact" else 40,
                   wall_s=2e-7 if method == "exact" else 5e-6, message="closed form")
        return row
    if method == "gsl" and rng is not None and sim.get("not_built"):
        row.update(v_ss=math.nan, period=math.nan, c0=math.nan, regime=0, est_error=math.nan,
                   last_difference=math.nan, contraction=math.nan, strokes=0, converged=0,
                   steps=0, rhs_evals=0, wall_s=1e-6, message="method gsl is not built")
        return row
    s = simulate(F, mu, target=rtol, stop=stop, estimator=estimator)
    v = s["v_ss"]
    steps = s["strokes"] * 4
    rhs = steps
    wall = s["strokes"] * 3e-7
    if method != "analytic":
        # made-up integrator error ~ rtol and costs growing like rtol^(-1/5)
        v *= 1 + rng.normal() * rtol * 30
        steps = int(s["strokes"] * 8 * rtol ** -0.2)
        rhs = steps * {"cvode": 1.6, "odeint": 6, "gsl": 7}[method]
        wall = rhs * {"cvode": 9e-8, "odeint": 3e-8, "gsl": 4e-8}[method]
    row.update(v_ss=v, period=s["period"], c0=s["c0"], regime=s["regime"],
               est_error=s["est_error"], last_difference=s["last_difference"],
               contraction=s["contraction"], strokes=s["strokes"], converged=s["converged"],
               steps=steps, rhs_evals=rhs, wall_s=wall, message=s["message"])
    return row


def write_csv(path: Path, columns, rows, spec):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(columns)
        for r in rows:
            if isinstance(r, dict):
                r = [r[k] for k in columns]
            w.writerow(["nan" if isinstance(v, float) and math.isnan(v) else
                        (f"{v:.17g}" if isinstance(v, float) else v) for v in r])
    side = {"spec": spec, "provenance": {"git_commit": "fake-data", "compiler": "none (python)",
                                         "libraries": {"numpy": np.__version__}},
            "threads": 1, "wall_s": 0.0, "generator": "reports/dev/fake_data.py"}
    path.with_suffix(".json").write_text(json.dumps(side, indent=1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    repo = Path(__file__).resolve().parents[2]
    if (repo / "data").resolve() in [args.out.resolve(), *args.out.resolve().parents]:
        sys.exit("fake_data.py: refusing to write fake data under data/")
    d = args.out / c.STUDY
    d.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(1)
    q = args.quick
    G, Mg = c.G, c.M * c.G

    tr = trace_rows(45.0, 1.0)
    write_csv(d / "fig2_2_trace.csv", ["t", "x", "y", "com", "xdot", "ydot", "comdot", "slide_m",
                                       "slide_M", "side", "event"], tr,
              {"F": 45, "mu": 1, "cycles": 6, "sample_dt": 1e-3})

    rows, pid = [], 0
    for mu in (1.0, 0.2):
        lo = mu * c.m * G
        for F in np.linspace(lo, 5 * Mg, 21 if q else 81)[1:]:
            for meth in ("exact", "analytic"):
                rows.append(sweep_row(pid, float(F), mu, meth)); pid += 1
    write_csv(d / "fig2_3.csv", SWEEP_COLUMNS, rows, {"name": "fig2_3"})

    rows, pid = [], 0
    for mu in np.linspace(0.05, 1, 6 if q else 20):
        for F in np.linspace(mu * Mg, 5 * Mg, 10 if q else 40):
            rows.append(sweep_row(pid, float(F), float(mu), "exact")); pid += 1
    write_csv(d / "regression.csv", SWEEP_COLUMNS, rows, {"name": "regression"})

    rows, pid = [], 0
    for mu in np.linspace(0.05, 1, 10 if q else 40):
        for F in np.linspace(mu * Mg, 5 * Mg, 12 if q else 60):
            rows.append(sweep_row(pid, float(F), float(mu), "exact")); pid += 1
    write_csv(d / "eq2_6_map.csv", SWEEP_COLUMNS, rows, {"name": "eq2_6_map"})

    rows, pid = [], 0
    for mu in (1.0, 0.2):
        for F in np.linspace(mu * c.m * G, 5 * Mg, 9 if q else 31)[1:]:
            F = float(F)
            rows.append(sweep_row(pid, F, mu, "exact")); pid += 1
            for est in ("running", "cycle"):
                for tol in (1e-4, 1e-5, 1e-6):
                    rows.append(sweep_row(pid, F, mu, "analytic", rtol=tol, stop="difference",
                                          estimator=est)); pid += 1
            for tol in (1e-4, 1e-5, 1e-6):
                rows.append(sweep_row(pid, F, mu, "analytic", rtol=tol)); pid += 1
    write_csv(d / "separation.csv", SWEEP_COLUMNS, rows, {"name": "separation"})

    rows, pid = [], 0
    hard = [(9.81000000981, 1.0, None), (14.715000014715, 1.0, None),
            (14.714999985285, 1.0, None), (73.575, 0.05, None), (735.75, 0.05, None),
            (20.0, 1.0, 1.3)]
    for F, mu, mus in hard:
        for meth in ("exact", "rootfind", "analytic", "cvode", "odeint", "gsl"):
            rows.append(sweep_row(pid, F, mu, meth, mu_s=mus, rng=rng, not_built=True)); pid += 1
    write_csv(d / "hard_cases.csv", SWEEP_COLUMNS, rows, {"name": "hard_cases"})

    rows, pid = [], 0
    for F, mu in ((45.0, 1.0), (73.575, 0.05)):
        for meth in ("exact", "rootfind"):
            rows.append(sweep_row(pid, F, mu, meth)); pid += 1
        for meth in ("analytic", "cvode", "odeint", "gsl"):
            for tol in (1e-6, 1e-8, 1e-10, 1e-12) if q else (1e-6, 1e-7, 1e-8, 1e-9, 1e-10,
                                                              1e-11, 1e-12):
                rows.append(sweep_row(pid, F, mu, meth, rtol=tol, rng=rng)); pid += 1
    write_csv(d / "cost.csv", SWEEP_COLUMNS, rows, {"name": "cost"})

    rows, pid = [], 0
    for F, mu in ((45.0, 1.0), (73.575, 0.05)):
        ex = c.closed_form(F, mu)["v_ss"]
        s = simulate(F, mu, target=-1, max_strokes=100 if q else 800, record=True)
        for k, (a, r) in enumerate(zip(s["cycle_averages"], s["running"])):
            rows.append([pid, mu, F, "analytic", k + 1, a, r, ex, abs(a - ex) / ex,
                         abs(r - ex) / ex])
            pid += 1
    write_csv(d / "convergence.csv", ["id", "mu", "F", "method", "cycle", "cycle_average",
                                      "running_mean", "exact", "err_cycle", "err_running"], rows,
              {"name": "convergence"})
    print(f"fake data written to {d}")


if __name__ == "__main__":
    main()
