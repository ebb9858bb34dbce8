"""How much faster our model's evaluation is than one MuJoCo step, per number of legs N, on Fig.
3.13's disk robots (DATA/ch3_peer/fig3_13a.csv, kind peer_scaling): per N the median over the
warm-started configurations of time_mujoco_ns / time_ours_ns (each configuration timed on both
simulators, so the ratio is paired). Warm-started means both: MuJoCo's constraint solver from the
accelerations at that state, our spring support from the balance of that configuration (it is
timed back to back). time_ours_cold_ns, where present, times ours with the support's cold start
against the same warm MuJoCo step: the speed-up without our warm start, shown beside the target's.
One definition for fig3_13.py and perf_legged.py."""
from __future__ import annotations

import numpy as np

SPEEDUP_TARGET = 100.0  # our target: the whole model ≥ 100× faster than one MuJoCo 2.2.2 step
SPEEDUP_FROM_N = 8      # ... at every N ≥ 8


def speedup_by_n(t, ours: str = "time_ours_ns") -> dict[int, float]:
    """N -> median MuJoCo / ours (the column `ours`) over the warm-started configurations with both
    times finite; {} where the table has no such column."""
    if ours not in t.columns:
        return {}
    warm = t.str("warmstart") == "solution"
    n = t["N"].astype(int)
    ratio = t["time_mujoco_ns"] / t[ours]
    out = {}
    for k in np.unique(n[warm]):
        r = ratio[warm & (n == k) & np.isfinite(ratio)]
        if r.size:
            out[int(k)] = float(np.median(r))
    return out


def smallest_from_n8(by_n: dict[int, float]) -> tuple[float | None, int | None]:
    """The smallest median speed-up over N ≥ SPEEDUP_FROM_N and the N where it is (None, None
    where no such N was measured)."""
    over = {n: r for n, r in by_n.items() if n >= SPEEDUP_FROM_N}
    if not over:
        return None, None
    n_min = min(over, key=over.get)
    return over[n_min], n_min


def speedup_target(by_n: dict[int, float]) -> dict:
    """The target's values: the smallest median speed-up over N ≥ SPEEDUP_FROM_N, the N where it
    is, and whether it is met (None where no N ≥ SPEEDUP_FROM_N was measured)."""
    r, n = smallest_from_n8(by_n)
    return {"speedup_min_from_N8": r, "speedup_min_at_N": n,
            "target_speedup_met": None if r is None else r >= SPEEDUP_TARGET}


def cold_speedup(t) -> dict:
    """The smallest median speed-up over N ≥ SPEEDUP_FROM_N with our support started cold, and
    where it is (None without a table, t = None, or where time_ours_cold_ns was not measured)."""
    r, n = smallest_from_n8(speedup_by_n(t, "time_ours_cold_ns") if t is not None else {})
    return {"speedup_cold_min_from_N8": r, "speedup_cold_min_at_N": n}
