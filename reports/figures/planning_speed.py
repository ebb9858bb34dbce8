#!/usr/bin/python3
"""Speed of the brute-force planner (thesis §5.5.1.1, §5.6): one planning step, on CPU threads.

Input: DATA/ch5_planning/cost.csv (studies/ch5_planning/cost.toml, point kind planning_cost):
wall time per planning step of BigANT-like robots (6–12 legs, M = 2–5 speed choices) in four
modes: `full` (all M^N options per step, the thesis' step, at the tripod start), `dedup` (the
planner as it runs, each distinct motion once, every step of a 300-step straight plan),
`kernel` and `reference` (the inner loop alone, fast route and reference loop, CPU time per
option-substep, from which the full step of M^N options is extrapolated: the only way to cost
4^10 and 4^12 options per step); medians over repeats, all in one run.

Outputs: OUT/planning_speed.png ((a) ms per step against legs, full enumeration measured and
extrapolated, and the planner's deduplicated step, against the thesis' GPU 6.9 ms per step;
(b) the same against M at 6 legs; (c) the time per option-substep of the fast route and the
reference loop), OUT/values/planning_speed.json (also the ledger's values for §5.4.3, §5.5.1.1
and §5.6). The thesis' numbers come from the claims ledger.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "planning_speed"
STUDY = "ch5_planning"
CSV = "cost.csv"
COLUMNS = ["legs", "M", "mode", "threads", "steps", "repeats", "options_per_step",
           "infeasible_per_step", "time_ms", "time_ms_p25", "time_ms_p75", "time_ms_mean",
           "cpu_ms_mean", "ns_per_evaluation", "options_per_second"]
SUBSTEPS = 20       # T_s (planning/planner.hpp): option-substeps per option
THESIS_STEPS = 150  # §5.5.1.1: "150 time steps" in the GPU's 1.03 s


def main() -> None:
    args = c.parse_args(__doc__.splitlines()[0])
    t = c.Table(c.study_file(args.data, CSV, STUDY), COLUMNS)
    if t.n == 0:
        c.fail(f"{t.path}: no data rows")
    rows = []
    for i in range(t.n):
        r = {k: float(t[k][i]) for k in COLUMNS if k != "mode"}
        r["mode"] = str(t["mode"][i])
        rows.append(r)

    def get(mode, legs=6, m=4, threads=1, steps=None):
        """The first row that matches: the spec lists the dedicated blocks (more repeats, the
        whole plan) first."""
        for r in rows:
            if (r["mode"] == mode and r["legs"] == legs and r["M"] == m and r["threads"] == threads
                    and (steps is None or r["steps"] == steps)):
                return r
        return None

    gpu_s = float(c.thesis("5.5.1.1-gpu-time"))          # 150 steps, s
    cpu_step_s = float(c.thesis("5.5.1.1-cpu-time"))     # one step, s
    gpu_step_ms = 1e3 * gpu_s / THESIS_STEPS
    v: dict = {"thesis_gpu_step_ms": gpu_step_ms, "thesis_cpu_step_s": cpu_step_s,
               "thesis_gpu_steps_per_second": THESIS_STEPS / gpu_s,
               "thesis_cpu_ns_per_evaluation": 1e9 * cpu_step_s / (4096 * SUBSTEPS),
               "thesis_gpu_ns_per_evaluation": 1e6 * gpu_step_ms / (4096 * SUBSTEPS)}

    # ---- the thesis' step: BigANT, M = 4, all 4096 options --------------------------------
    for threads in (1, 2):
        full = get("full", threads=threads)
        dedup = get("dedup", threads=threads)
        if full:
            v[f"full_ms_t{threads}"] = full["time_ms"]
            v[f"full_ms_t{threads}_p25"] = full["time_ms_p25"]
            v[f"full_ms_t{threads}_p75"] = full["time_ms_p75"]
            v[f"full_options_per_second_t{threads}"] = full["options_per_second"]
            v[f"full_ns_per_evaluation_core_t{threads}"] = full["ns_per_evaluation"]
            v[f"full_ms_mean_t{threads}"] = full["time_ms_mean"]
            v[f"full_cpu_ms_mean_t{threads}"] = full["cpu_ms_mean"]
            v["full_options"] = full["options_per_step"]
        if dedup:
            v[f"dedup_ms_t{threads}"] = dedup["time_ms"]
            v[f"dedup_ms_t{threads}_p25"] = dedup["time_ms_p25"]
            v[f"dedup_ms_t{threads}_p75"] = dedup["time_ms_p75"]
            v[f"dedup_ms_mean_t{threads}"] = dedup["time_ms_mean"]
            v[f"dedup_cpu_ms_mean_t{threads}"] = dedup["cpu_ms_mean"]
            v[f"dedup_options_t{threads}"] = dedup["options_per_step"]
            v[f"dedup_steps_t{threads}"] = int(dedup["steps"])
            v[f"dedup_options_per_second_t{threads}"] = dedup["options_per_second"]
    kern = get("kernel")
    ref = get("reference")
    if kern:
        v["kernel_ns_per_evaluation"] = kern["ns_per_evaluation"]
    if ref:
        v["reference_ns_per_evaluation"] = ref["ns_per_evaluation"]
    if kern and ref:
        v["kernel_speedup"] = ref["ns_per_evaluation"] / kern["ns_per_evaluation"]
    if "kernel_ns_per_evaluation" in v:
        v["thesis_cpu_over_ours_per_evaluation"] = (v["thesis_cpu_ns_per_evaluation"]
                                                    / v["kernel_ns_per_evaluation"])
    if "reference_ns_per_evaluation" in v:
        v["thesis_cpu_over_reference_per_evaluation"] = (v["thesis_cpu_ns_per_evaluation"]
                                                         / v["reference_ns_per_evaluation"])
    if "full_ms_t2" in v:
        v["full_150_steps_s_t2"] = THESIS_STEPS * v["full_ms_t2"] * 1e-3
        v["full_steps_per_second_t2"] = 1e3 / v["full_ms_t2"]
        v["full_t2_over_thesis_gpu"] = v["full_ms_t2"] / gpu_step_ms
    if "full_ms_t1" in v:
        v["full_s_t1"] = v["full_ms_t1"] * 1e-3
        v["thesis_gpu_over_our_cpu_t1"] = v["full_ms_t1"] / gpu_step_ms  # < 1: ours is faster
        v["our_cpu_t1_over_thesis_cpu"] = cpu_step_s / v["full_s_t1"]
    if "dedup_ms_t2" in v:
        v["dedup_steps_per_second_t2"] = 1e3 / v["dedup_ms_t2"]
        v["dedup_150_steps_s_t2"] = THESIS_STEPS * v["dedup_ms_t2"] * 1e-3

    # ---- growth with legs and M (2 threads where measured, else 1) -----------------------------
    legs_all = sorted({int(r["legs"]) for r in rows})
    ms_all = sorted({int(r["M"]) for r in rows})
    # The deduplicated step against N: plans of the same length for every N (the spec's legs
    # block), since the options per step grow as more legs come down along a plan.
    legs_steps = [int(r["steps"]) for r in rows if r["mode"] == "dedup" and r["legs"] > 6]
    v["dedup_legs_steps"] = min(legs_steps) if legs_steps else None
    growth: dict = {}
    for mode in ("full", "dedup", "kernel", "reference"):
        for legs in legs_all:
            for m in ms_all:
                steps = v["dedup_legs_steps"] if mode == "dedup" and m == 4 else None
                r = get(mode, legs, m, 2, steps) or get(mode, legs, m, 1, steps)
                if r:
                    growth[(mode, legs, m)] = r
                    v[f"{mode}_ms_legs{legs}_M{m}"] = r["time_ms"]
                    v[f"{mode}_options_legs{legs}_M{m}"] = r["options_per_step"]
                    if mode in ("kernel", "reference"):
                        v[f"{mode}_ns_legs{legs}_M{m}"] = r["ns_per_evaluation"]
    # The extrapolated full step on 2 threads: kernel time per evaluation × M^N × T_s / 2.
    # Against M at 6 legs: the whole plan's steps (the first matching rows).
    by_m: dict = {}
    for mode in ("full", "dedup"):
        for m in ms_all:
            r = get(mode, 6, m, 2) or get(mode, 6, m, 1)
            if r:
                by_m[(mode, m)] = r
                v[f"{mode}_ms_M{m}"] = r["time_ms"]
                v[f"{mode}_options_M{m}"] = r["options_per_step"]
    for legs in legs_all:
        r = growth.get(("kernel", legs, 4))
        if r:
            v[f"full_extrapolated_ms_t2_legs{legs}"] = (
                r["ns_per_evaluation"] * 4 ** legs * SUBSTEPS * 1e-6 / 2)
    if "full_extrapolated_ms_t2_legs6" in v:
        v["full_extrapolated_150_steps_s_t2"] = THESIS_STEPS * v["full_extrapolated_ms_t2_legs6"] * 1e-3

    # ---- the figure -----------------------------------------------------------------------------
    plt = c.setup_matplotlib()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    ax = axes[0]
    dedup_label = (f"as planned (distinct motions), median step of {v['dedup_legs_steps']}"
                   if v["dedup_legs_steps"] else "as planned (distinct motions), median step")
    for mode, label, col, mk in (("full", "full enumeration, measured", c.VISCOUS, "o"),
                                 ("dedup", dedup_label, c.REFERENCE, "s")):
        pts = sorted((legs, r["time_ms"]) for (md, legs, m), r in growth.items()
                     if md == mode and m == 4)
        if pts:
            x, y = zip(*pts)
            ax.plot(x, y, mk + "-", color=col, label=label, ms=6)
    ext = sorted((legs, v[f"full_extrapolated_ms_t2_legs{legs}"]) for legs in legs_all
                 if f"full_extrapolated_ms_t2_legs{legs}" in v)
    if ext:
        x, y = zip(*ext)
        ax.plot(x, y, "o--", mfc="none", color=c.VISCOUS,
                label="full enumeration, from the inner loop's time")
    ax.axhline(gpu_step_ms, color=c.COULOMB, ls=":", label=f"thesis GPU {gpu_step_ms:.1f} ms")
    ax.set_yscale("log")
    ax.set_xlabel("legs N (M = 4 speeds, 2 threads)")
    ax.set_ylabel("wall time per planning step [ms]")
    ax.set_title("(a) a planning step against N")
    ax.legend(loc="upper left", fontsize=9)

    ax = axes[1]
    for mode, label, col, mk in (("full", "full enumeration", c.VISCOUS, "o"),
                                 ("dedup", "as planned, median step", c.REFERENCE, "s")):
        pts = sorted((m, r["time_ms"]) for (md, m), r in by_m.items() if md == mode)
        if pts:
            x, y = zip(*pts)
            ax.plot(x, y, mk + "-", color=col, label=label)
    ax.axhline(gpu_step_ms, color=c.COULOMB, ls=":", label="thesis GPU (M = 4)")
    ax.set_yscale("log")
    ax.set_xlabel("speed choices M (6 legs, 2 threads)")
    ax.set_ylabel("wall time per planning step [ms]")
    ax.set_title("(b) a planning step against M")
    ax.legend(loc="upper left", fontsize=9)

    ax = axes[2]
    for mode, label, col, mk in (("kernel", "fast route", c.VISCOUS, "o"),
                                 ("reference", "reference loop (support + balance)",
                                  c.SUPPORT, "s")):
        pts = sorted((legs, r["ns_per_evaluation"]) for (md, legs, m), r in growth.items()
                     if md == mode and m == 4)
        if pts:
            x, y = zip(*pts)
            ax.plot(x, y, mk + "-", color=col, label=label)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("legs N")
    ax.set_ylabel("CPU time per option-substep [ns], one thread")
    ax.set_title("(c) the inner loop")
    ax.legend(loc="center right", fontsize=9)
    from matplotlib.ticker import MaxNLocator

    for ax in axes:
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    fig.suptitle("Planning speed on CPU threads (thesis §5.5.1.1: GPU 1.03 s per 150 steps, "
                 "CPU 31 s per step)")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
