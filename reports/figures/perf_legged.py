#!/usr/bin/python3
"""Performance of the multi-legged model: per-frame cost against the number of legs (thesis §3.6.1).

Input: DATA/ch3_legged/cost_scaling.csv (studies/ch3_legged/cost_scaling.toml, point kind
legged_cost): thread CPU time per frame (median over repeats of the mean over the frames, p25 and
p75) of the spring support alone, the local connection A, the viscous-Coulomb balance, the whole
model (connection::evaluate: support + A + balance) and the Coulomb balance to a relative duality
gap of 1e-9, on random frames of disk robots with N = 3 ... 50 legs and of a BigANT-like hexapod
(which also runs the thesis' single eps = 1e-5 approximation), all in one run.

A `sequence` column, where present, tells random independent frames ("independent") from the
frames of a walking trajectory ("trajectory", each solve warm from the previous frame); without
it every row is independent. The fits and the disk table use the independent rows; the Coulomb ÷
viscous ratio is shown for both, the trajectory one being the target's.

Optional inputs: DATA/ch3_legged/machine.csv (studies/ch3_legged/machine.toml, kind
machine_limits: this machine's clock and peak flops per cycle), for the physical limit of each
stage: the arithmetic it must do per leg (FLOPS below) against what the core can do per cycle;
without it the block says so and gives ns only. DATA/ch3_peer/fig3_13a.csv (kind peer_scaling),
for the speed-up over MuJoCo.

Outputs: OUT/perf_legged.png (cost vs N, absolute and relative to N = 3),
OUT/perf_legged_body.html (the block build_report.py puts into the performance page: the speed-up
over MuJoCo against our target; the whole model's cost per leg, per hexapod frame and Coulomb ÷
viscous as measurements, each beside its physical limit; the hexapod's numbers),
OUT/values/perf_legged.json (also the ledger's values for thesis §3.6.1 and the MuJoCo target). A data folder without
cost_scaling.csv gives a block that says so and no values.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html
import math

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import peer_speedup as ps  # noqa: E402

# The arithmetic each kernel does per foot, counted from the code it names (one table: recount it
# when a kernel changes). A +, − or × is 1 flop, an FMA 2 (there are none: the build has no -mfma
# and the support's AVX2 clone leaves FMA out), a divide 1 and a square root 1 (though each takes
# the time of many: machine.csv's latencies); negations (sign flips), comparisons, selects,
# min/max and abs are not counted. "per": the loop does the work for every foot ("foot") or skips
# the feet without friction ("contact": scaled by the fraction of feet down). "width": what the
# compiled loop runs on in this build: "scalar" (one double per instruction: the loops sum into
# scalars, which the compiler may not reassociate into vectors), "sse2" (Eigen's Array2d: two feet
# per instruction) or "avx2" (the support's four-wide vector code in its AVX2 clone; pairs of SSE2
# registers where the CPU has no AVX2).
FLOPS = {
    # lib/contact/support_newton.cpp, the level start (from 20 legs: the large-N end the slope b
    # measures), four feet at a time: rows_and_start's Σ K, Σ K q_z += (3) and q_x² + q_y² for the
    # lever scale (3); level_height's pass in z, one on the cost study's frames: h = q_z + z, w h,
    # two += (4); the start cell's pass at (0, 0, z), as add_feet below (25): 35. (The all-feet
    # start of fewer legs: the all-feet cell's sums in rows_and_start, 17, and the lever scale: 20.)
    "support_start_pass": {"flops": 35, "per": "foot", "width": "avx2"},
    # add_feet, each Newton step's pass: h = y v0 + x v1 + (q_z + v2) (2 × and 3 +: 5), the
    # sums as in the start pass (17), d = on − on_prev and changes += d d (3): 25.
    "support_newton_pass": {"flops": 25, "per": "foot", "width": "avx2"},
    # Once certified, four feet at a time: near_plane (h: 5, h h: 1) and the outputs (h: 5,
    # F_z = −K h: 1): 12.
    "support_certify": {"flops": 12, "per": "foot", "width": "avx2"},
    # lib/friction/balance.cpp viscous_balance_rows (isotropic robots, G = I), every foot, four at
    # a time, branch-free: c = μ F_z (1), c q_x, c q_y (2), L² = q_x² + q_y² (3), Σc, Σc q_x,
    # Σc q_y += (3), Σ c (q_x² + q_y²) += c q_x q_x + c q_y q_y (4), Σ c q̇_x, Σ c q̇_y += (2 each:
    # 4), Σ c (q_x q̇_y − q_y q̇_x) += (4), the active count += (1): 22. (The general loop for
    # anisotropic feet, viscous_balance_general, needs 40: c (1 + w²) and c w0 w1 per foot and the
    # products with them.)
    "system_assembly": {"flops": 22, "per": "foot", "width": "avx2"},
    # balance.cpp viscous_forces_rows (isotropic), every foot, four at a time: u0 = v0 − ω q_y +
    # q̇_x and u1 = v1 + ω q_x + q̇_y (3 each), F0, F1 = −c u (1 each), fx, fy += (2), mz += q_x F1
    # − q_y F0 (4), dissipation −= F·u (4), scale += c (|q̇0| + |q̇1| + |u0| + |u1|) (5): 23.
    # (viscous_forces, the general loop for anisotropic feet: 35, with G u = u + w (w·u).)
    "viscous_forces": {"flops": 23, "per": "foot", "width": "avx2"},
    # lib/connection/local_connection.cpp columns_from_rows (isotropic robots, from the viscous
    # rows), every foot, four at a time (transposed in registers to A's layout): c (S q) = (−q_y c,
    # q_x c) (2), six entries −(p c + p' s) (3 each: 18): 20. (columns<kAniso>, for anisotropic
    # feet: 36, with c G and (S q)ᵀ c G per foot.)
    "connection_columns": {"flops": 20, "per": "foot", "width": "avx2"},
    # lib/friction/coulomb_solver.hpp assemble<kAll, false> (coulomb.cpp's pass: one per Newton
    # step plus one), every foot: r0, r1 (six multiply-adds: 12), r·r (3), ρ = √(r·r + δ² + 1 − m)
    # (3 and a root: 4), ir = m / ρ (a divide: 1), f += m ρ (2), the r2_min term (2), g0, g1, g2
    # += (b r) ir (5 each: 15), v = B r⊥ (3 each: 9), w = ir³ (2), w v0, w v1 (2), h00 … h12 +=
    # (2 each: 10), h22 += w v2 v2 (3): 65. (The header of coulomb.cpp counts r's six
    # multiply-adds, the root and the divide, 14; the gradient and Hessian sums are the rest.)
    "coulomb_pass": {"flops": 65, "per": "foot", "width": "sse2"},
    # coulomb.cpp finish_pass<false> (once per solve: the certificate's forces), every foot: r
    # (12), r·r (3), ‖r‖ (1), primal += (2), the stepped s = r + B p (12) and m ‖s‖ summed (6),
    # 1 / (‖r‖ + 1 − m) (3), n = r / ‖r‖ (2), t = Bᵀ n⊥ (9), w = m_s c / c² (2), w t0, w t1 (2),
    # q00 … q12 += (10), q22 += (3), t·p / ‖r‖ (6), λ = n ∓ n⊥ t·p (4), λ −= B μ, masked (7
    # each: 14), ‖λ‖² (3), value += λ·d (4), F = −B λ (3 each: 6), fx, fy += (2), mz += (4): 110,
    # two roots and one divide among them.
    "coulomb_finish": {"flops": 110, "per": "foot", "width": "sse2"},
}
# Each stage as the passes of those kernels per frame: a count, or "steps" (the support's Newton
# steps per frame) or "iterations+1" (the Coulomb solver's Newton steps plus one). The Coulomb
# solve's setup (B_k, d_k per foot) and its viscous start are left out: its count is a floor.
STAGES = {
    "support": [("support_start_pass", 1), ("support_newton_pass", "steps"),
                ("support_certify", 1)],
    "connection": [("system_assembly", 1), ("connection_columns", 1)],
    "viscous": [("system_assembly", 1), ("viscous_forces", 1)],
    "model": [("support_start_pass", 1), ("support_newton_pass", "steps"),
              ("support_certify", 1), ("system_assembly", 1), ("connection_columns", 1),
              ("viscous_forces", 1)],
    "coulomb_1e-09": [("coulomb_pass", "iterations+1"), ("coulomb_finish", 1)],
}
# The support's Newton steps per frame: the CSV's newton_steps_mean at the disk robot with the most
# legs, the large-N end that the slope b measures; where the CSV has no such column, those
# lib/contact/support_newton.cpp's header quotes from bench_friction for 50 legs (2.5).
SUPPORT_STEPS_ASSUMED = 2.5
WIDTH_COLUMN = {"scalar": "flops_per_cycle_scalar", "sse2": "flops_per_cycle_sse2",
                "avx2": "flops_per_cycle_avx2", "avx2_fma": "flops_per_cycle_avx2_fma"}
WIDTH_LABEL = {"scalar": "scalar", "sse2": "2-wide SSE2", "avx2": "4-wide AVX2",
               "avx2_fma": "4-wide AVX2 + FMA"}
MACHINE_CSV = "machine.csv"

# Coulomb's and the ε-family's rows also time the viscous-Coulomb balance in the same repeats,
# alternately (legged_cost.cpp): ratio_viscous is the median of the per-repeat ratios, robust to
# the load of a shared machine drifting between two rows; a CSV without it gives the ratio of the
# two rows' medians.
PAIRED_COLUMNS = ("ratio_viscous", "viscous_time_ns")

NAME = "perf_legged"
STUDY = "ch3_legged"
CSV = "cost_scaling.csv"
COLUMNS = ["robot", "N", "method", "eps", "tol", "frames", "repeats", "time_ns", "time_ns_p25",
           "time_ns_p75", "contacts_mean", "iterations_mean", "unconverged"]
# (key, label, colour, marker), in the order of the legend; the chapter's colours (common.py):
# spring support purple, viscous-Coulomb orange, Coulomb blue
METHODS = [("support", "spring support (Newton route, Alg. 1 fallback)", c.SUPPORT, "s"),
           ("connection", "local connection A (eq. 3.20)", c.CATEGORICAL[2], "D"),
           ("viscous", "viscous-Coulomb balance", c.VISCOUS, "o"),
           ("model", "whole model (support + A + viscous)", c.REFERENCE, "v"),
           ("coulomb_1e-09", "Coulomb balance, certificate ≤ 1e-9", c.COULOMB, "^"),
           ("support_batch", "spring support, four frames per call (batched)", c.SUPPORT, "P"),
           ("model_batch", "whole model, four frames per call (batched)", c.REFERENCE, "X")]
LABEL = {k: lab for k, lab, _, _ in METHODS}
LABEL.update({"coulomb_1e-10": "Coulomb balance, certificate ≤ 1e-10",
              "epsilon_1e-05": "ε-family, single ε = 1e-5 m/s (thesis §3.5.1.3)"})
FRAME_S = 0.01  # the thesis' frames: 100 Hz (§3.5.1.1)
# Our one target here (the thesis sets none): the whole model ≥ 100× faster than a MuJoCo step
# at every N ≥ 8 (peer_speedup.py), a ratio measured in one run. The cost per leg, per hexapod
# frame and Coulomb ÷ viscous are shown as measurements beside their physical limits, with no
# verdict: absolute times move with the machine. The growth target (≤ ×2 from 3 to 50 legs) is
# retired too: a flat growth curve rewards a large fixed cost per call, and the thesis' ×3 is an
# interpreter's overhead.


def key_of(method: str, eps: float, tol: float) -> str:
    if method == "coulomb":
        return f"coulomb_{tol:.0e}"
    if method == "epsilon":
        return f"epsilon_{eps:.0e}"
    return method


def us(ns) -> str:
    return "—" if ns is None else f"{c.fmt(ns / 1000.0, 3)} µs"


def rows_of(t: c.Table) -> tuple[dict, dict]:
    """(robot, N, key) -> dict of the row's numbers, for the independent frames and for the
    trajectory frames (empty without a `sequence` column)."""
    seq = t.str("sequence") if "sequence" in t.columns else ["independent"] * t.n
    extra = [name for name in PAIRED_COLUMNS + ("newton_steps_mean",) if name in t.columns]
    out: dict = {"independent": {}, "trajectory": {}}
    for i in range(t.n):
        if seq[i] not in out:
            c.fail(f"{t.path}:{i + 2}: sequence '{seq[i]}' is neither 'independent' nor "
                   "'trajectory'")
        k = key_of(str(t["method"][i]), float(t["eps"][i]), float(t["tol"][i]))
        out[seq[i]][(str(t["robot"][i]), int(t["N"][i]), k)] = {
            name: float(t[name][i]) for name in COLUMNS + extra
            if name not in ("robot", "method")}
    return out["independent"], out["trajectory"]


def measure(rows: dict) -> dict:
    v: dict = {}
    disk_n = sorted({n for (robot, n, _) in rows if robot == "disk"})
    v["disk_N"] = disk_n
    for key, *_ in METHODS:
        for n in disk_n:
            r = rows.get(("disk", n, key))
            if r:
                v[f"disk_{key}_N{n}_ns"] = r["time_ns"]
        lo, hi = rows.get(("disk", min(disk_n), key)), rows.get(("disk", max(disk_n), key))
        v[f"growth_{key}"] = hi["time_ns"] / lo["time_ns"] if lo and hi else None
        v[f"growth_{key}_from"] = min(disk_n)
        v[f"growth_{key}_to"] = max(disk_n)
    # time = a + b N by least squares over the disk robots: the growth N0 -> N1 is
    # (a + b N1) / (a + b N0), at most ×2 iff a ≥ (N1 − 2 N0) b (44 b for 3 -> 50 legs).
    for key, *_ in METHODS:
        ns = [n for n in disk_n if ("disk", n, key) in rows]
        if len(ns) >= 2:
            b, a = np.polyfit(ns, [rows[("disk", n, key)]["time_ns"] for n in ns], 1)
            v[f"fit_{key}_a_ns"] = float(a)
            v[f"fit_{key}_b_ns"] = float(b)
    v["growth_needs_a_over_b"] = float(max(disk_n) - 2 * min(disk_n)) if disk_n else None
    # §3.6.2: viscous-Coulomb "scales better with the number of contacts" than Coulomb friction:
    # the growth of the two balances, the cost of one more leg (b), the fixed part in legs (a / b).
    for key in ("viscous", "coulomb_1e-09"):
        a, b = v.get(f"fit_{key}_a_ns"), v.get(f"fit_{key}_b_ns")
        v[f"fit_{key}_a_over_b"] = a / b if a is not None and b else None
        v[f"fit_growth_{key}"] = ((a + b * max(disk_n)) / (a + b * min(disk_n))
                                  if a is not None and b is not None else None)
    gv, gc = v.get("growth_viscous"), v.get("growth_coulomb_1e-09")
    v["growth_viscous_over_coulomb"] = gv / gc if gv and gc else None
    bv, bc = v.get("fit_viscous_b_ns"), v.get("fit_coulomb_1e-09_b_ns")
    v["per_leg_viscous_over_coulomb"] = bv / bc if bv is not None and bc else None
    v["ratio_coulomb_viscous_disk_min"] = min(
        (rows[("disk", n, "coulomb_1e-09")]["time_ns"] / rows[("disk", n, "viscous")]["time_ns"]
         for n in disk_n if ("disk", n, "coulomb_1e-09") in rows and ("disk", n, "viscous") in rows),
        default=None)
    v["disk_contacts_mean"] = [rows[("disk", n, "viscous")]["contacts_mean"]
                               for n in disk_n if ("disk", n, "viscous") in rows]
    v["disk_down_fraction"] = (float(np.mean([rows[("disk", n, "viscous")]["contacts_mean"] / n
                                              for n in disk_n if ("disk", n, "viscous") in rows]))
                               if v["disk_contacts_mean"] else None)
    for (robot, n, key), r in rows.items():
        if robot != "hexapod":
            continue
        v[f"hexapod_{key}_ns"] = r["time_ns"]
        v[f"hexapod_{key}_ms"] = r["time_ns"] * 1e-6
        v[f"hexapod_{key}_p25_ns"] = r["time_ns_p25"]
        v[f"hexapod_{key}_p75_ns"] = r["time_ns_p75"]
        v[f"hexapod_{key}_iterations"] = r["iterations_mean"]
        if is_paired(r):
            v[f"hexapod_{key}_ratio_viscous"] = r["ratio_viscous"]
        v[f"hexapod_{key}_unconverged"] = int(r["unconverged"])
        v["hexapod_contacts_mean"] = r["contacts_mean"]
    visc = v.get("hexapod_viscous_ns")
    coul = v.get("hexapod_coulomb_1e-09_ns")
    eps = v.get("hexapod_epsilon_1e-05_ns")
    model = v.get("hexapod_model_ns")

    def ratio(a, b):
        return a / b if a is not None and b else None

    v["ratio_coulomb_viscous_hexapod"] = paired_ratio(rows.get(("hexapod", 6, "coulomb_1e-09")),
                                                      ratio(coul, visc))
    v["ratio_epsilon_viscous_hexapod"] = paired_ratio(rows.get(("hexapod", 6, "epsilon_1e-05")),
                                                      ratio(eps, visc))
    v["ratio_viscous_paired"] = is_paired(rows.get(("hexapod", 6, "coulomb_1e-09")))
    v["ratio_coulomb_epsilon_hexapod"] = ratio(coul, eps)
    v["ratio_model_viscous_hexapod"] = ratio(model, visc)
    v["realtime_factor_model_hexapod"] = ratio(FRAME_S * 1e9, model)
    v["realtime_factor_coulomb_hexapod"] = ratio(FRAME_S * 1e9, coul)
    # The same frames four per call (connection::evaluate_batch: frame i of a group in lane i),
    # for frames that do not wait for each other; a trajectory's frames do, and take one per call.
    v["ratio_model_batch_hexapod"] = ratio(v.get("hexapod_model_batch_ns"), model)
    thesis_solvers(v, rows, visc, coul, eps)
    return v


def thesis_solvers(v: dict, rows: dict, visc, coul, eps) -> None:
    """The thesis' own solvers in this build (§3.5.1.3: MINPACK's Levenberg–Marquardt, one ε or
    the sequence of ε), their ratios as the thesis states its own, and the checks of the
    entries that compare those ratios: set when the thesis' algorithm, timed here, lands within
    the entry's own tolerance of the thesis' ratio."""
    ct, et = v.get("hexapod_coulomb_thesis_ns"), v.get("hexapod_epsilon_thesis_ns")

    def ratio(a, b):
        return a / b if a is not None and b else None

    v["ratio_coulomb_thesis_viscous_hexapod"] = paired_ratio(
        rows.get(("hexapod", 6, "coulomb_thesis")), ratio(ct, visc))
    v["ratio_epsilon_thesis_viscous_hexapod"] = paired_ratio(
        rows.get(("hexapod", 6, "epsilon_thesis")), ratio(et, visc))
    v["ratio_coulomb_thesis_epsilon_thesis_hexapod"] = ratio(ct, et)
    v["ratio_coulomb_thesis_over_ours_hexapod"] = ratio(ct, coul)
    v["ratio_epsilon_thesis_over_ours_hexapod"] = ratio(et, eps)
    ledger = {cl["id"]: cl for cl in c.load_ledger().get("claim", [])}
    for entry, key in (("3.6.1-coulomb-over-viscous", "ratio_coulomb_thesis_viscous_hexapod"),
                       ("3.6.1-epsilon-over-viscous", "ratio_epsilon_thesis_viscous_hexapod"),
                       ("3.6.1-coulomb-over-epsilon",
                        "ratio_coulomb_thesis_epsilon_thesis_hexapod")):
        cl, got = ledger.get(entry), v.get(key)
        name = f"thesis_algorithm_reproduces_{key.removeprefix('ratio_').removesuffix('_hexapod')}"
        if cl is None or got is None:
            v[name], v[name + "_reason"] = None, "not measured"
            continue
        thesis, tol = float(cl["thesis"]), float(cl["tol"])
        ok = abs(got / thesis - 1.0) <= tol
        v[name] = got if ok else None
        v[name + "_reason"] = None if ok else (
            f"the thesis' algorithm gives ×{got:.3g} here against the thesis' ×{thesis:g} "
            f"(beyond ±{tol:.0%})")


def is_paired(row: dict | None) -> bool:
    """Whether a row timed the viscous-Coulomb balance alternately with its own method."""
    return row is not None and math.isfinite(row.get("ratio_viscous", math.nan))


def paired_ratio(row: dict | None, unpaired: float | None) -> float | None:
    """A row's time ÷ the viscous-Coulomb balance's: the paired ratio where the row has one,
    else `unpaired` (two rows' medians)."""
    return row["ratio_viscous"] if is_paired(row) else unpaired


def trajectory_ratio(v: dict, traj: dict) -> None:
    """Coulomb to 1e-9 ÷ viscous-Coulomb on the hexapod's trajectory frames, where measured; the
    ratio the block states is that one, else the independent frames' (and the values say which)."""
    tv, tc = traj.get(("hexapod", 6, "viscous")), traj.get(("hexapod", 6, "coulomb_1e-09"))
    r = paired_ratio(tc, tc["time_ns"] / tv["time_ns"] if tv and tc and tv["time_ns"] else None)
    v["ratio_viscous_paired"] = is_paired(tc) if tc else v.get("ratio_viscous_paired", False)
    v["ratio_coulomb_viscous_hexapod_trajectory"] = r
    v["hexapod_trajectory_viscous_ns"] = tv["time_ns"] if tv else None
    v["hexapod_trajectory_coulomb_1e-09_ns"] = tc["time_ns"] if tc else None
    # The support and the whole model along the walk, the support warm-started from the frame
    # before (SupportOptions::warm_start), where measured.
    for key in ("support", "model"):
        row = traj.get(("hexapod", 6, key))
        v[f"hexapod_trajectory_{key}_ns"] = row["time_ns"] if row else None
        v[f"hexapod_trajectory_{key}_newton_steps"] = row.get("newton_steps_mean") if row else None
    v["ratio_stated_sequence"] = "trajectory" if r is not None else "independent"
    v["ratio_coulomb_viscous_stated"] = r if r is not None else v.get("ratio_coulomb_viscous_hexapod")


def speedup(v: dict, data: Path) -> None:
    """The whole model against one MuJoCo step (Fig. 3.13's disk robots), where measured."""
    path = data / "ch3_peer" / "fig3_13a.csv"
    v.update(ps.speedup_target({}))
    v.update(ps.cold_speedup(None))
    v["speedup_N"] = v["speedup_median"] = None
    v["speedup_missing"] = None
    if not path.is_file():
        v["speedup_missing"] = f"{c.shown_path(path)} is missing (run slipwalk reproduce ch3_peer)"
        return
    t = c.Table(path, ["N", "warmstart", "time_ours_ns", "time_mujoco_ns"])
    by_n = ps.speedup_by_n(t) if t.n else {}
    if not by_n:
        v["speedup_missing"] = (f"{c.shown_path(path)}: no configuration timed on both "
                                "simulators (MuJoCo not in that build, or a --no-timing run)")
        return
    v["speedup_N"] = sorted(by_n)
    v["speedup_median"] = [by_n[n] for n in sorted(by_n)]
    v.update(ps.speedup_target(by_n))
    v.update(ps.cold_speedup(t))


def read_machine(data: Path) -> tuple[dict | None, str | None]:
    """machine.csv's single row as numbers, or None and why."""
    path = data / STUDY / MACHINE_CSV
    if not path.is_file():
        return None, (f"{c.shown_path(path)} is missing (run slipwalk reproduce ch3_legged, "
                      "or slipwalk sweep studies/ch3_legged/machine.toml)")
    t = c.Table(path, ["ghz", *WIDTH_COLUMN.values(), "latency_add_cycles",
                       "latency_mul_cycles", "latency_div_cycles", "latency_sqrt_cycles",
                       "message"])
    if t.n == 0:
        return None, f"{c.shown_path(path)} has no rows"
    m = {name: float(col[0]) for name, col in t.columns.items() if col.dtype != object}
    m["message"] = str(t["message"][0])
    if not (np.isfinite(m["ghz"]) and m["ghz"] > 0):
        return None, (f"{c.shown_path(path)}: no clock measured ("
                      f"{m['message'] or 'a --no-timing run'})")
    # A virtual CPU's add chain need not run at its clock: cycles counted from it would be wrong.
    if "clock_plausible" in t.columns and m.get("clock_plausible", 1.0) == 0.0:
        return None, f"{c.shown_path(path)}: {m['message']}"
    return m, None


def limits(v: dict, rows: dict, machine: dict | None) -> None:
    """Per stage: the flops per leg per frame (FLOPS × passes), and, with machine.csv, the cycles
    per leg the slope b measures, the flops per cycle that achieves, and the fraction of the peak
    at the widths the stage's loops use (the cycles the arithmetic needs at that peak ÷ the
    cycles measured), and of the machine's peak (4-wide with FMA)."""
    disk_n = v["disk_N"]
    down = v.get("disk_down_fraction") or 0.0
    support = [(n, rows[("disk", n, "support")]) for n in disk_n if ("disk", n, "support") in rows]
    steps = [(n, r["newton_steps_mean"]) for n, r in support if "newton_steps_mean" in r]
    v["support_steps"] = max(steps)[1] if steps else SUPPORT_STEPS_ASSUMED
    v["support_steps_source"] = (f"the CSV's newton_steps_mean at N = {max(steps)[0]}"
                                 if steps else "assumed (support_newton.cpp's header, 50 legs)")
    coul = [rows[("disk", n, "coulomb_1e-09")]["iterations_mean"] for n in disk_n
            if ("disk", n, "coulomb_1e-09") in rows]
    v["coulomb_iterations"] = float(np.mean(coul)) if coul else None
    v["machine_available"] = machine is not None
    # every key, None where machine.csv is missing (the ledger's texts quote them)
    v["machine_ghz"] = machine["ghz"] if machine else None
    for w, col in WIDTH_COLUMN.items():
        v[f"machine_peak_{w}"] = machine[col] if machine else None
    for op in ("add", "mul", "div", "sqrt"):
        v[f"machine_latency_{op}"] = machine[f"latency_{op}_cycles"] if machine else None
    for stage, parts in STAGES.items():
        flops = 0.0
        cycles_at_peak = 0.0
        widths = []
        for kernel, count in parts:
            k = FLOPS[kernel]
            if count == "steps":
                count = v["support_steps"]
            elif count == "iterations+1":
                it = v["coulomb_iterations"]
                count = it + 1.0 if it is not None else None
            if count is None:
                flops = None
                break
            f = count * k["flops"] * (down if k["per"] == "contact" else 1.0)
            flops += f
            widths.append(k["width"])
            if machine is not None:
                w = k["width"]
                peak = machine[WIDTH_COLUMN[w]]
                if not np.isfinite(peak):  # no AVX2: the default clone's pairs of SSE2 registers
                    peak = machine[WIDTH_COLUMN["sse2"]]
                cycles_at_peak += f / peak
        v[f"limit_{stage}_flops_per_leg"] = flops
        v[f"limit_{stage}_widths"] = sorted(set(widths), key=list(WIDTH_COLUMN).index)
        for what in ("cycles_per_leg", "flops_per_cycle", "peak_cycles_per_leg",
                     "fraction_of_peak", "fraction_of_machine_peak"):
            v[f"limit_{stage}_{what}"] = None
        b = v.get(f"fit_{stage}_b_ns")
        if machine is None or flops is None or b is None or b <= 0:
            continue
        cycles = b * machine["ghz"]
        v[f"limit_{stage}_cycles_per_leg"] = cycles
        v[f"limit_{stage}_flops_per_cycle"] = flops / cycles
        v[f"limit_{stage}_peak_cycles_per_leg"] = cycles_at_peak
        v[f"limit_{stage}_fraction_of_peak"] = cycles_at_peak / cycles
        fma = machine[WIDTH_COLUMN["avx2_fma"]]
        v[f"limit_{stage}_fraction_of_machine_peak"] = (flops / fma / cycles
                                                        if np.isfinite(fma) else None)
    # The targets' limits: the whole model's per-leg arithmetic at the peak of its widths (ns per
    # leg, and for the hexapod's six legs: its fixed part — the 3 × 3 solves — left out), and the
    # Coulomb ÷ viscous ratio of the arithmetic alone on the hexapod (its feet down and Coulomb
    # steps): what the time ratio would be if both ran equally close to the peak.
    peak = v.get("limit_model_peak_cycles_per_leg")
    ghz = v.get("machine_ghz")
    v["limit_model_per_leg_ns"] = peak / ghz if peak is not None and ghz else None
    v["limit_hexapod_model_ns"] = 6 * peak / ghz if peak is not None and ghz else None
    fma = v.get("machine_peak_avx2_fma")
    flops = v.get("limit_model_flops_per_leg")
    v["limit_model_per_leg_machine_ns"] = (flops / fma / ghz if flops is not None and ghz and fma
                                           and np.isfinite(fma) else None)
    it = v.get("hexapod_coulomb_1e-09_iterations")
    hx_down = (v.get("hexapod_contacts_mean") or 0.0) / 6.0
    if it is not None:
        coulomb = (it + 1.0) * FLOPS["coulomb_pass"]["flops"] + FLOPS["coulomb_finish"]["flops"]
        viscous = (FLOPS["system_assembly"]["flops"] * hx_down
                   + FLOPS["viscous_forces"]["flops"])
        v["flops_ratio_coulomb_viscous_hexapod"] = coulomb / viscous
    else:
        v["flops_ratio_coulomb_viscous_hexapod"] = None


def figure(plt, rows: dict, v: dict, out) -> None:
    # narrow enough to read at the page's narrow width too: the panels one above the other
    fig, axs = plt.subplots(2, 1, figsize=(7.5, 11), sharex=True)
    disk_n = v["disk_N"]
    for key, label, color, marker in METHODS:
        ns = [n for n in disk_n if ("disk", n, key) in rows]
        if not ns:
            continue
        t = np.array([rows[("disk", n, key)]["time_ns"] for n in ns]) / 1000.0
        lo = np.array([rows[("disk", n, key)]["time_ns_p25"] for n in ns]) / 1000.0
        hi = np.array([rows[("disk", n, key)]["time_ns_p75"] for n in ns]) / 1000.0
        axs[0].errorbar(ns, t, yerr=[np.maximum(t - lo, 0), np.maximum(hi - t, 0)], color=color,
                        marker=marker, ms=5, lw=1.4, capsize=2, label=label)
        axs[1].plot(ns, t / t[0], color=color, marker=marker, ms=5, lw=1.4)
        hx = rows.get(("hexapod", 6, key))
        if hx:
            axs[0].plot([6], [hx["time_ns"] / 1000.0], marker="*", ms=13, color=color, mec="k",
                        mew=0.6, ls="none")
    axs[0].plot([], [], marker="*", ms=12, color="w", mec="k", ls="none",
                label="hexapod (BigANT-like), at N = 6")
    n_ref = np.array([disk_n[0], disk_n[-1]], float)
    axs[1].plot(n_ref, n_ref / n_ref[0], color="0.6", ls=":", lw=1.2, label="∝ N")
    down = v.get("disk_down_fraction")
    for ax in axs:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(disk_n)
        ax.set_xticklabels([str(n) for n in disk_n])
        ax.minorticks_off()
    axs[1].set_xlabel("legs N (disk robot, 0.3 m rim" +
                      (f"; {down:.0%} of the feet down)" if down else ")"))
    axs[0].set_ylabel("CPU time per frame [µs]")
    axs[0].set_title("a) cost per frame (median; bars: p25–p75 of repeats)")
    axs[1].set_ylabel(f"cost per frame ÷ cost at N = {disk_n[0]}")
    axs[1].set_title(f"b) growth relative to N = {disk_n[0]}")
    # one legend for the methods (below panel a's curves), one for panel b's references
    axs[0].legend(loc="upper left", bbox_to_anchor=(0.0, -0.02), ncol=1, frameon=False)
    axs[1].legend(loc="upper left")
    fig.tight_layout(h_pad=0.5)
    fig.subplots_adjust(hspace=0.66)
    c.save_figure(fig, out, NAME)


def pct(x) -> str:
    return "—" if x is None else f"{x:.0%}"


def times(x) -> str:
    return "—" if x is None else f"{x:,.0f}"


def met(ok: bool) -> str:
    return "<span class='v ok'>met</span>" if ok else "<span class='v bad'>not met</span>"


def verdict(ok: bool | None) -> str:
    return "<span class='v'>not measured</span>" if ok is None else met(ok)


def ns(x, digits: int = 3) -> str:
    return "—" if x is None else f"{c.fmt(x, digits)} ns"


def limits_block(v: dict, machine_missing: str | None) -> str:
    """The physical limit of each stage: flops per leg against what the core does per cycle."""
    stages = [k for k, *_ in METHODS if f"limit_{k}_flops_per_leg" in v]
    if machine_missing is not None:
        rows = "".join(
            f"<tr><td>{html.escape(LABEL[k])}</td><td>{ns(v.get(f'fit_{k}_b_ns'))}</td>"
            f"<td>{c.fmt(v.get(f'limit_{k}_flops_per_leg'), 3)}</td></tr>" for k in stages)
        return (f"<p class='bad small'>Machine limits not measured: "
                f"{html.escape(machine_missing)}; time per leg in ns only.</p>"
                "<table class='data'><thead><tr><th>stage</th><th>ns per leg (b)</th>"
                f"<th>flops per leg</th></tr></thead><tbody>{rows}</tbody></table>")
    rows = "".join(
        f"<tr><td>{html.escape(LABEL[k])}</td><td>{ns(v.get(f'fit_{k}_b_ns'))}</td>"
        f"<td>{c.fmt(v.get(f'limit_{k}_cycles_per_leg'), 3)}</td>"
        f"<td>{c.fmt(v.get(f'limit_{k}_flops_per_leg'), 3)}</td>"
        f"<td>{c.fmt(v.get(f'limit_{k}_flops_per_cycle'), 3)}</td>"
        f"<td>{', '.join(WIDTH_LABEL[w] for w in v.get(f'limit_{k}_widths', []))}</td>"
        f"<td>{c.fmt(v.get(f'limit_{k}_peak_cycles_per_leg'), 3)}</td>"
        f"<td>{pct(v.get(f'limit_{k}_fraction_of_peak'))}</td>"
        f"<td>{pct(v.get(f'limit_{k}_fraction_of_machine_peak'))}</td></tr>" for k in stages)
    peaks = ", ".join(f"{WIDTH_LABEL[w]} {c.fmt(v.get(f'machine_peak_{w}'), 3)}"
                      for w in WIDTH_COLUMN)
    lat = ", ".join(f"{op} {c.fmt(v.get(f'machine_latency_{op}'), 3)}"
                    for op in ("add", "mul", "div", "sqrt"))
    return f"""<p class="small"><b>How far from the limit.</b> This machine, measured
(<code>studies/ch3_legged/machine.toml</code>): {c.fmt(v.get('machine_ghz'), 3)} GHz while the
thread ran; peak double-precision flops per cycle: {peaks}; latency in cycles: {lat}. Per stage,
from the disk robots' slope b: the cycles one more leg costs, the arithmetic it needs (flops per
leg per frame: the kernels' counts in <code>perf_legged.py</code>'s FLOPS table, an FMA 2 flops,
a divide or a square root 1, times the passes per frame — the support's Newton steps
{c.fmt(v.get('support_steps'), 3)}, {html.escape(v.get('support_steps_source', ''))}; the Coulomb
solver's {c.fmt(v.get('coulomb_iterations'), 3)} steps + 1 passes and its final pass, its setup
left out; the system assembly scaled by the {pct(v.get('disk_down_fraction'))} of the feet down),
the flops per cycle that achieves, and the fraction of the peak: the cycles that arithmetic needs
at the peak of the widths the stage's loops run at, over the cycles measured; last, against the
machine's peak (4-wide with FMA).</p>
<table class='data'><thead><tr><th>stage</th><th>ns per leg (b)</th><th>cycles per leg</th>
<th>flops per leg</th><th>flops per cycle</th><th>widths used</th><th>cycles at their peak</th>
<th>fraction of that peak</th><th>of the machine's peak</th></tr></thead><tbody>{rows}</tbody>
</table>"""


def body(v: dict, rows: dict, machine_missing: str | None) -> str:
    n0, n1 = v["disk_N"][0], v["disk_N"][-1]
    g = {k: v.get(f"growth_{k}") for k, *_ in METHODS}
    sp = v.get("speedup_min_from_N8")
    sp_text = (f"×{c.fmt(sp, 3)} (smallest, at N = {v.get('speedup_min_at_N')})" if sp is not None
               else html.escape(v.get("speedup_missing") or "no N ≥ 8 measured"))
    traj = v.get("ratio_coulomb_viscous_hexapod_trajectory")
    seq = v.get("ratio_stated_sequence")
    target_row = (f"<tr><td>Whole model ≥ {ps.SPEEDUP_TARGET:g}× faster than one MuJoCo 2.2.2 "
                  f"step, every N ≥ {ps.SPEEDUP_FROM_N} (Fig. 3.13's disk robots, median per N)"
                  f"</td><td>≥ {ps.SPEEDUP_TARGET:g}×</td><td>{sp_text}</td>"
                  f"<td>{verdict(v.get('target_speedup_met'))}</td></tr>")
    # Measurements, no verdicts: absolute times move with the machine.
    measured = [
        ("Whole model: marginal cost per leg (b of time = a + b N, disk robots)",
         f"{ns(v.get('limit_model_per_leg_ns'))} (its arithmetic at the peak of its widths; "
         f"{ns(v.get('limit_model_per_leg_machine_ns'))} at 4-wide FMA)",
         f"{ns(v.get('fit_model_b_ns'))} (a = {ns(v.get('fit_model_a_ns'))})"),
        ("Hexapod: whole model per frame (support + A + viscous-Coulomb)",
         f"{ns(v.get('limit_hexapod_model_ns'))} (6 legs' arithmetic at peak, fixed part "
         "left out)", us(v.get("hexapod_model_ns"))),
        ("Hexapod: whole model per frame, four independent frames per call "
         "(evaluate_batch; not a trajectory, whose frames wait for each other)",
         f"{ns(v.get('limit_hexapod_model_ns'))} (as above)", us(v.get("hexapod_model_batch_ns"))),
        ("Hexapod: Coulomb to 1e-9 ÷ viscous-Coulomb, "
         + ("timed alternately in the same repeats" if v.get("ratio_viscous_paired")
            else "same run") + f" ({seq} frames)",
         f"×{c.fmt(v.get('flops_ratio_coulomb_viscous_hexapod'), 3)} (ratio of their "
         "arithmetic)", f"{c.fmt(v.get('ratio_coulomb_viscous_stated'), 3)}×"),
        ("Hexapod: the thesis' own Coulomb solver (§3.5.1.3: Levenberg–Marquardt over "
         "ε = 1e-5, 1e-6, …; friction/thesis_coulomb.hpp) ÷ ours to 1e-9, same frames",
         "—", f"{c.fmt(v.get('ratio_coulomb_thesis_over_ours_hexapod'), 3)}× "
         f"({us(v.get('hexapod_coulomb_thesis_ns'))} against "
         f"{us(v.get('hexapod_coulomb_1e-09_ns'))})"),
    ]
    measured_rows = "".join(f"<tr><td>{html.escape(a)}</td><td>{lim}</td><td>{ours}</td></tr>"
                            for a, lim, ours in measured)
    independent = c.fmt(v.get("ratio_coulomb_viscous_hexapod"), 3)
    paired = (" (each Coulomb repeat timed back to back with one of the viscous-Coulomb balance on "
              "the same frames, before or after it in turn; the median of the per-repeat ratios, "
              "which a load drifting between two rows of the run does not move)"
              if v.get("ratio_viscous_paired") else "")
    ratios = (f"Coulomb ÷ viscous-Coulomb on the hexapod{paired}: ×{independent} on independent "
              "random frames" +
              (f", ×{c.fmt(traj, 3)} along a trajectory (each solve warm from the last frame: the "
               "target's)" if traj is not None else
               "; no trajectory rows in this run (no <code>sequence</code> column, or none "
               "'trajectory'), so the target reads the independent frames"))
    hx_keys = ["support", "connection", "viscous", "model", "support_batch", "model_batch",
               "epsilon_1e-05", "coulomb_1e-09", "coulomb_1e-10"]
    visc = v.get("hexapod_viscous_ns")

    def over_viscous(k: str) -> float | None:
        unpaired = v[f"hexapod_{k}_ns"] / visc if visc else None
        return v.get(f"hexapod_{k}_ratio_viscous", unpaired)

    hx_rows = "".join(
        f"<tr><td>{html.escape(LABEL[k])}</td><td>{us(v.get(f'hexapod_{k}_ns'))}</td>"
        f"<td>{us(v.get(f'hexapod_{k}_p25_ns'))} – {us(v.get(f'hexapod_{k}_p75_ns'))}</td>"
        f"<td>{c.fmt(over_viscous(k), 3)}×</td>"
        f"<td>{c.fmt(v.get(f'hexapod_{k}_iterations'), 3)}</td></tr>"
        for k in hx_keys if f"hexapod_{k}_ns" in v)
    head = "".join(f"<th>{html.escape(LABEL[k])}</th>" for k, *_ in METHODS)
    disk_rows = []
    for i, n in enumerate(v["disk_N"]):
        cells = "".join(f"<td>{us(v.get(f'disk_{k}_N{n}_ns'))}</td>" for k, *_ in METHODS)
        cm = v["disk_contacts_mean"][i] if i < len(v["disk_contacts_mean"]) else None
        disk_rows.append(f"<tr><td>{n}</td><td>{c.fmt(cm, 3)}</td>{cells}</tr>")
    fit_rows = "".join(
        f"<tr><td>{html.escape(LABEL[k])}</td><td>{c.fmt(v.get(f'fit_{k}_a_ns'), 3)}</td>"
        f"<td>{c.fmt(v.get(f'fit_{k}_b_ns'), 3)}</td>"
        f"<td>{c.fmt(v[f'fit_{k}_a_ns'] / v[f'fit_{k}_b_ns'], 3) if v.get(f'fit_{k}_b_ns') else '—'}"
        f"</td></tr>" for k, *_ in METHODS if f"fit_{k}_a_ns" in v)
    support_share = (v["hexapod_support_ns"] / v["hexapod_model_ns"]
                     if v.get("hexapod_support_ns") and v.get("hexapod_model_ns") else None)
    machine = (f"{html.escape(str(v.get('machine_cpu')))}, {v.get('machine_logical_cores')} "
               f"logical cores (1-minute load average {v.get('machine_load_average')} at the "
               f"start), {html.escape(str(v.get('compiler')))}; run {v.get('date')}")
    return f"""
<div class="fig wide" id="perf-legged"><img src="{NAME}.png" alt="per-frame cost vs legs">
<div class="text"><h3>The multi-legged model: cost per frame (thesis §3.6.1)</h3>
<p>Thread CPU time per frame on {int(v.get('frames', 0))} random frames per robot (the spring
support decides which feet are down; hexapod: {c.fmt(v.get('hexapod_contacts_mean'), 3)} feet on
average), the median of {int(v.get('repeats', 0))} repeats of a loop over all frames, every row
from the same run (<code>studies/ch3_legged/cost_scaling.toml</code>). Per hexapod frame the
whole model costs {us(v.get('hexapod_model_ns'))}, {pct(support_share)} of it the spring-support
search, and {us(v.get('hexapod_model_batch_ns'))} when independent frames go four per call
(<code>connection::evaluate_batch</code>: frame i of a group in lane i of a vector, where one frame
puts four feet there, so no sums across lanes and one vector division for four 3 × 3 solves;
the same contact sets, every output to rounding); at the thesis' 100 Hz frames that is {times(v.get('realtime_factor_model_hexapod'))} times
faster than real time (with Coulomb friction to 1e-9 instead of the viscous ansatz:
{times(v.get('realtime_factor_coulomb_hexapod'))} times). Every stage reads every
foot, so the cost grows with N; from {n0} to {n1} legs the viscous-Coulomb balance grows
×{c.fmt(g['viscous'], 3)}, the Coulomb balance ×{c.fmt(g['coulomb_1e-09'], 3)} (its Newton steps do
not grow with N) and the whole model ×{c.fmt(g['model'], 3)}. We set no target on that growth
any more: a flat growth curve rewards a large fixed cost per call, and the thesis' ×3 (§3.5.3)
is an interpreter's overhead; the cost of one more leg is measured instead.
<b>Machine:</b> {machine}.</p>
<table class='data'><thead><tr><th>our target</th><th>target</th><th>ours</th><th></th></tr>
</thead><tbody>{target_row}</tbody></table>
<p class="small">Measured, beside the physical limit of each (no verdicts: absolute times move
with the machine, and a ratio against a peer in one run is what a target can stand on):</p>
<table class='data'><thead><tr><th>measured</th><th>physical limit</th><th>ours</th></tr></thead>
<tbody>{measured_rows}</tbody></table>
<p class="small">{ratios}.</p>
{limits_block(v, machine_missing)}
<p class="small">Fits time = a + b·N over the disk robots (ns): b is the cost of one more leg, a
the fixed cost per call. The spring support runs an active-set Newton method on its convex
potential (a few vectorized passes over the feet, the Newton route) and falls back to Alg. 1's
path where that does not certify. From 20 legs it starts near the level body's balance, and its
Newton steps per frame stay about flat in N (below 20, from the all-feet plane, they grow
slowly; the level start has fewer instructions from 12 legs but saves time only from about 20).</p>
<table class='data'><thead><tr><th>stage</th><th>a (ns)</th><th>b (ns per leg)</th><th>a / b</th>
</tr></thead><tbody>{fit_rows}</tbody></table>
<p class="small">The hexapod, per frame (median; p25–p75 over repeats; ÷ the viscous-Coulomb
balance of the same run, for Coulomb and the ε-family timed alternately with it in the same
repeats; mean solver iterations, or spring-support contact changes):</p>
<table class='data'><thead><tr><th>stage</th><th>CPU time</th><th>p25 – p75</th>
<th>÷ viscous</th><th>iterations</th></tr></thead><tbody>{hx_rows}</tbody></table>
<details><summary>Disk robots: every N</summary><table class='data'><thead><tr><th>N</th>
<th>feet down (mean)</th>{head}</tr></thead><tbody>{''.join(disk_rows)}</tbody></table>
</details>
<p class="small">From <code>DATA/{STUDY}/{CSV}</code>, <code>DATA/{STUDY}/{MACHINE_CSV}</code> and
<code>DATA/ch3_peer/fig3_13a.csv</code> by <code>reports/figures/{NAME}.py</code>; numbers in
<code>values/{NAME}.json</code>. What each friction solver's accuracy costs: the
<a href="cost_of_accuracy.html#coa-legged">cost of accuracy</a> page.</p>
</div></div>
"""


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    path = args.data / STUDY / CSV
    if not path.is_file():
        c.atomic_write_text(args.out / f"{NAME}_body.html",
                            "<p class='bad' id='perf-legged'>Multi-legged cost per frame not "
                            f"built: <code>{html.escape(c.shown_path(path))}</code> is missing (run "
                            "<code>slipwalk reproduce ch3_legged</code>).</p>\n")
        print(f"{NAME}.py: warning: {path}: missing, block not built")
        return
    plt = c.setup_matplotlib()
    t = c.Table(path, COLUMNS)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    rows, traj = rows_of(t)
    for need in [("hexapod", 6, "viscous"), ("hexapod", 6, "coulomb_1e-09"),
                 ("hexapod", 6, "model")]:
        if need not in rows:
            c.fail(f"{path}: no row for {need[0]} {need[2]}")
    if not any(r == "disk" for r, _, _ in rows):
        c.fail(f"{path}: no disk rows")
    v = measure(rows)
    trajectory_ratio(v, traj)
    speedup(v, args.data)
    machine, machine_missing = read_machine(args.data)
    v["machine_missing"] = machine_missing
    limits(v, rows, machine)
    side = c.read_sidecar(path) or {}
    prov = side.get("provenance", {}) if isinstance(side, dict) else {}
    machine = prov.get("machine", {}) if isinstance(prov, dict) else {}
    v.update({
        "machine_cpu": machine.get("cpu"), "machine_logical_cores": machine.get("logical_cores"),
        "machine_load_average": machine.get("load_average_1min"), "threads": side.get("threads"),
        "compiler": prov.get("compiler"), "date": side.get("date"), "timing": side.get("timing"),
        "frames": int(np.max(t["frames"])), "repeats": int(np.max(t["repeats"])),
    })
    figure(plt, rows, v, args.out)
    c.atomic_write_text(args.out / f"{NAME}_body.html", body(v, rows, machine_missing))
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
