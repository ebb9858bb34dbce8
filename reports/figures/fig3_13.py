#!/usr/bin/python3
"""Thesis Fig. 3.13 / §3.5.3: cost growth with the number of legs against MuJoCo; parallel overhead.

Input: DATA/ch3_peer/fig3_13a.csv (kind peer_scaling: per random configuration of a disk robot
with N legs, the time of one evaluation of our model and of one MuJoCo mj_step on the same
configuration) and DATA/ch3_peer/fig3_13b.csv (kind parallel_overhead: per random hexapod
trajectory and thread count M, the time of the step increments on M threads and of the pose
products, sequential and parallel prefix), with their sidecars (machine: logical cores, load).
Output: OUT/fig3_13.png, OUT/values/fig3_13.json.

Panels: (a) time per step normalized by each simulator's median at N = 3, percentiles 2.5-97.5
(light), 25-75 (shaded), median (line), as the thesis' Fig. 3.13 a; (b) the absolute times per
step, both simulators warm-started (peer_speedup.py), and the median of ours with the spring
support started cold where time_ours_cold_ns was measured (dashed); (c) the ratio MuJoCo / ours per configuration; (d) the parallel overhead time x M / median
single-thread time over the trajectories, for the thesis' pipeline (steps in parallel, poses
composed sequentially) and with the parallel prefix product; M beyond the machine's cores is
marked oversubscribed; the CPU time of all threads over the single-thread CPU time shows the work
threading adds, whatever else the machine ran. In a build without MuJoCo the MuJoCo columns are NaN: the panels show our
side and say so.
"""
from __future__ import annotations

import sys

from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import peer_speedup as ps  # noqa: E402

NAME = "fig3_13"
STUDY = "ch3_peer"
PCT = (2.5, 25, 50, 75, 97.5)
# ours is the viscous-Coulomb model; MuJoCo its own colour (the palette of common.py)
OURS, PEER = c.VISCOUS, c.MUJOCO


def table(data: Path, name: str, required: list[str]) -> tuple[c.Table, dict]:
    path = c.study_file(data, f"{name}.csv", STUDY)
    t = c.Table(path, required)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    side = c.read_sidecar(path)
    if side is None:
        c.fail(f"{path.with_suffix('.json')}: sidecar missing")
    return t, side


def pct(x: np.ndarray) -> list[float]:
    x = x[np.isfinite(x)]
    return [float(np.percentile(x, p)) for p in PCT] if x.size else [float("nan")] * len(PCT)


def ribbon(ax, x, q, color, label):
    q = np.asarray(q)
    ax.fill_between(x, q[:, 0], q[:, 4], color=color, alpha=0.15, lw=0)
    ax.fill_between(x, q[:, 1], q[:, 3], color=color, alpha=0.35, lw=0)
    ax.plot(x, q[:, 2], ":", color=color, lw=1.8, marker="o", ms=3, label=label)


def scaling(t: c.Table, values: dict, axes) -> None:
    ax_norm, ax_abs, ax_ratio = axes
    warm = t.str("warmstart") == "solution"
    N = t["N"].astype(int)
    ours, peer = t["time_ours_ns"] * 1e-3, t["time_mujoco_ns"] * 1e-3  # µs
    has_peer = bool(np.isfinite(peer[warm]).any())
    values["peer_available"] = has_peer
    values["peer"] = str(t.str("peer")[0])
    Ns = np.unique(N[warm])
    values["N"] = Ns.tolist()
    values["configs_per_N"] = int(np.sum(warm & (N == Ns[0])))
    q_ours = [pct(ours[warm & (N == n)]) for n in Ns]
    q_peer = [pct(peer[warm & (N == n)]) for n in Ns]
    base_ours, base_peer = q_ours[0][2], q_peer[0][2]
    values["ours_us_median"] = [q[2] for q in q_ours]
    values["mujoco_us_median"] = [q[2] for q in q_peer] if has_peer else None
    values["ours_us_3"], values["ours_us_50"] = q_ours[0][2], q_ours[-1][2]
    values["ours_growth_50"] = q_ours[-1][2] / base_ours
    values["ours_growth_p97_5_50"] = q_ours[-1][4] / base_ours
    contacts = t["contacts"]
    values["contacts_mean_50"] = float(np.mean(contacts[warm & (N == Ns[-1])]))
    ribbon(ax_norm, Ns, np.array(q_ours) / base_ours, OURS, "ours (viscous-Coulomb model)")
    ribbon(ax_abs, Ns, q_ours, OURS, "ours")
    values["ours_cold_us_median"] = None
    if "time_ours_cold_ns" in t.columns:  # the spring support started cold (peer_speedup.py)
        cold_ours = t["time_ours_cold_ns"] * 1e-3
        values["ours_cold_us_median"] = [float(np.median(cold_ours[warm & (N == n)])) for n in Ns]
        ax_abs.plot(Ns, values["ours_cold_us_median"], "--", color=OURS, lw=1.2,
                    label="ours, its support started cold (median)")
    if has_peer:
        values["mujoco_us_3"], values["mujoco_us_50"] = q_peer[0][2], q_peer[-1][2]
        values["mujoco_growth_50"] = q_peer[-1][2] / base_peer
        ratio = peer / ours
        q_ratio = [pct(ratio[warm & (N == n)]) for n in Ns]
        values["ratio_median"] = [q[2] for q in q_ratio]
        values["ratio_median_min"] = min(q[2] for q in q_ratio)
        values["ratio_min"] = float(np.nanmin(ratio[warm]))
        values["mujoco_faster_fraction"] = float(np.mean(ratio[np.isfinite(ratio)] < 1.0))
        same = t["mujoco_contacts"] == contacts
        values["same_contacts_fraction"] = float(np.mean(same[warm]))
        values["mujoco_iter_mean"] = float(np.nanmean(t["mujoco_iter"][warm]))
        values["rewind_fraction_max"] = float(np.nanmax(t["time_rewind_ns"] / t["time_mujoco_ns"]))
        cold = ~warm
        if cold.any():
            cN = np.unique(N[cold])
            med = [float(np.median(peer[cold & (N == n)])) for n in cN]
            values["cold_N"] = cN.tolist()
            values["mujoco_cold_us_median"] = med
            values["mujoco_cold_growth"] = med[-1] / med[0]
            values["mujoco_cold_iter_mean"] = float(np.nanmean(t["mujoco_iter"][cold]))
        peer_label = values["peer"].replace("mujoco", "MuJoCo") + " mj_step"
        ribbon(ax_norm, Ns, np.array(q_peer) / base_peer, PEER, peer_label)
        ribbon(ax_abs, Ns, q_peer, PEER, peer_label)
        ribbon(ax_ratio, Ns, q_ratio, c.REFERENCE, "MuJoCo / ours, per configuration")
        ax_ratio.axhline(1.0, color="0.4", lw=0.8)
        # Our target: the whole model ≥ 100× faster than one MuJoCo step at every N ≥ 8 (the
        # median per N; peer_speedup.py, which perf_legged.py's target table also reads).
        by_n = ps.speedup_by_n(t)
        values["speedup_N"] = sorted(by_n)
        values["speedup_median"] = [by_n[n] for n in sorted(by_n)]
        values.update(ps.speedup_target(by_n))
        values.update(ps.cold_speedup(t))
        met = values["target_speedup_met"]
        ax_ratio.axhline(ps.SPEEDUP_TARGET, color="k", ls="--", lw=0.9,
                         label=f"our target: ≥ {ps.SPEEDUP_TARGET:g}× at every N ≥ "
                               f"{ps.SPEEDUP_FROM_N}" +
                               ("" if met is None else
                                f"\n({'met' if met else 'not met'}: smallest median "
                                f"×{values['speedup_min_from_N8']:.3g} at N = "
                                f"{values['speedup_min_at_N']})"))
        ax_ratio.set_ylim(bottom=0)
    else:
        for ax in (ax_norm, ax_ratio):
            ax.text(0.5, 0.5, "MuJoCo not in this build\n(SLIPWALK_MUJOCO=OFF or "
                    "libmujoco-dev missing)", transform=ax.transAxes, ha="center", color="0.4")
    growth = c.thesis("3.5.3-mujoco-growth")
    ax_norm.set_title(f"(a) time per step / median at N = 3\n(thesis: ours < ×3, MuJoCo "
                      f"×{growth:g})")
    ax_norm.set_xlabel("legs N")
    ax_norm.set_ylabel("normalized time per step")
    ax_norm.legend(loc="upper left")
    ax_abs.set_xscale("log")
    ax_abs.set_yscale("log")
    ax_abs.set_xlabel("legs N")
    ax_abs.set_ylabel("time per step [µs]")
    ax_abs.set_title("(b) time per step,\nsame machine and configurations")
    ax_abs.legend(loc="upper left")
    ax_ratio.set_xlabel("legs N")
    ax_ratio.set_ylabel("MuJoCo time / our time")
    ax_ratio.set_title("(c) how much slower MuJoCo's step is\nthan our evaluation")
    if has_peer:
        ax_ratio.legend(loc="lower right")
    else:
        values.update(ps.speedup_target({}), speedup_N=None, speedup_median=None)
        values.update(ps.cold_speedup(None))


# How far the wall-clock overhead at M threads on fewer cores may sit from what time-sharing
# alone predicts, and how much more work than one thread's the threads may do, for the excess to
# count as the machine's (threads waiting for a core) rather than the algorithm's.
OVERSUBSCRIBED_REL_TOL = 0.2
OVERSUBSCRIBED_MAX_WORK = 1.2


def oversubscription(values: dict, cores: int, Ms, m: int) -> None:
    """At m threads on fewer cores, time-sharing alone predicts overhead_at_cores × m / cores;
    it explains the measured overhead only when the two agree to OVERSUBSCRIBED_REL_TOL and the
    threads did no more work (CPU time) than one thread by OVERSUBSCRIBED_MAX_WORK."""
    key = f"oversubscription_explains_{m}"
    values.update({f"overhead_seq_{m}_predicted": None, f"cpu_overhead_{m}_median": None,
                   f"overhead_seq_{m}_rel_to_predicted": None, key: None,
                   "oversubscribed_rel_tol": OVERSUBSCRIBED_REL_TOL,
                   "oversubscribed_max_work": OVERSUBSCRIBED_MAX_WORK})
    if m not in set(Ms.tolist()) or not cores or cores >= m:
        values[key + "_reason"] = f"not oversubscribed: {cores} cores, {m} threads"
        return
    predicted = values["overhead_at_cores"] * m / cores
    work = values["cpu_overhead_median"][list(Ms).index(m)]
    measured = values[f"overhead_seq_{m}_median"]
    values[f"overhead_seq_{m}_predicted"] = predicted
    values[f"cpu_overhead_{m}_median"] = work
    rel = abs(measured / predicted - 1.0)
    values[f"overhead_seq_{m}_rel_to_predicted"] = rel
    ok = rel <= OVERSUBSCRIBED_REL_TOL and work <= OVERSUBSCRIBED_MAX_WORK
    values[key] = predicted if ok else None
    values[key + "_reason"] = None if ok else (
        f"measured {measured:.3g} against {predicted:.3g} predicted by time-sharing "
        f"(off by {rel:.0%}, allowed {OVERSUBSCRIBED_REL_TOL:.0%}), work ×{work:.3g} "
        f"(allowed {OVERSUBSCRIBED_MAX_WORK})")


def parallel(t: c.Table, side: dict, values: dict, ax) -> None:
    cores = int(side.get("provenance", {}).get("machine", {}).get("logical_cores", 0) or 0)
    load = side.get("provenance", {}).get("machine", {}).get("load_average_1min")
    values["logical_cores"], values["load_average_1min"] = cores, load
    M = t["threads"].astype(int)
    Ms = np.unique(M)
    inc, seq, scan = t["time_increments_ns"], t["time_sequential_ns"], t["time_scan_ns"]
    one = M == 1
    if not one.any():
        c.fail(f"{t.path}: no single-thread rows (threads = 1) to normalize by")
    base_seq = float(np.median(inc[one] + seq[one]))
    base_scan = float(np.median(inc[one] + scan[one]))
    q_seq = [pct((inc[M == m] + seq[M == m]) * m / base_seq) for m in Ms]
    q_scan = [pct((inc[M == m] + scan[M == m]) * m / base_seq) for m in Ms]
    values["threads"] = Ms.tolist()
    values["trajectories"] = int(one.sum())
    values["steps"] = int(t["steps"][0])
    values["overhead_seq_median"] = [q[2] for q in q_seq]
    values["overhead_scan_median"] = [q[2] for q in q_scan]
    for m, qs, qc in zip(Ms, q_seq, q_scan):
        values[f"overhead_seq_{m}_median"] = qs[2]
        values[f"overhead_scan_{m}_median"] = qc[2]
    at = min(cores, int(Ms.max())) if cores else int(Ms.max())
    values["overhead_at_cores"] = values[f"overhead_seq_{at}_median"]
    values["overhead_scan_at_cores"] = values[f"overhead_scan_{at}_median"]
    values["single_thread_ms"] = base_seq * 1e-6
    values["single_thread_scan_ms"] = base_scan * 1e-6
    seq1 = float(np.median(seq[one]))
    values["product_seq_us"] = seq1 * 1e-3
    values["product_scan_us"] = [float(np.median(scan[M == m])) * 1e-3 for m in Ms]
    values["product_gain"] = [seq1 / float(np.median(scan[M == m])) for m in Ms]
    values["product_gain_at_cores"] = values["product_gain"][at - 1]
    values["product_share_single"] = seq1 / base_seq
    values["scan_max_diff"] = float(np.max(t["scan_max_diff"]))
    values["deterministic"] = bool(np.all(t["same_as_one_thread"] == 1))
    values["unsupported_frames"] = int(np.sum(t["unsupported"][one]))
    # The work done: CPU time of all threads / median single-thread CPU time (1 = no extra work;
    # unlike wall time it does not depend on whether the machine had M free cores).
    cpu = t["time_cpu_increments_ns"] + seq
    base_cpu = float(np.median(cpu[one]))
    q_cpu = [pct(cpu[M == m] / base_cpu) for m in Ms]
    values["cpu_overhead_median"] = [q[2] for q in q_cpu]
    values["cpu_overhead_at_cores"] = q_cpu[at - 1][2]
    # The parallel half of entry 3.6.1-scales-and-parallelizes on its own: the overhead where it
    # holds its bound, None where it does not (the entry's check when only its growth fails).
    bound = float(c.target("3.6.1-scales-and-parallelizes")[1])
    values["cpu_overhead_within_bound"] = (values["cpu_overhead_at_cores"]
                                           if values["cpu_overhead_at_cores"] <= bound else None)
    oversubscription(values, cores, Ms, 4)
    values["prefix_product_ok"] = bool(values["scan_max_diff"] <= 1e-12 and values["deterministic"]
                                       and values["product_gain_at_cores"] > 1.0)
    values["prefix_product_exact"] = bool(values["scan_max_diff"] <= 1e-12 and values["deterministic"])
    # The product takes ~0.1 ms, so a thread waiting for a core swamps its gain: other processes
    # only add time, so the gain is taken between lower deciles over the trajectories, less the
    # sequential product's own timing spread (interquartile range at one thread, which a few
    # disturbed trajectories do not move), and only where the machine had a core free for the
    # second thread (1-minute load below its cores).
    spread = float(np.percentile(seq[one], 75) - np.percentile(seq[one], 25)) / seq1
    gain_low = (float(np.percentile(seq[M == at], 10) / np.percentile(scan[M == at], 10))
                if cores and load is not None and load < cores else None)
    values.update(product_seq_spread=spread, product_gain_low_at_cores=gain_low,
                  product_gain_low_less_spread=None if gain_low is None else gain_low - spread,
                  product_gain_low_less_spread_reason=None if gain_low is not None else
                  f"1-minute load {load} on {cores} cores: no core free for the second thread")
    ribbon(ax, Ms - 0.06, q_seq, c.REFERENCE, "poses composed sequentially (thesis)")
    ribbon(ax, Ms + 0.06, q_scan, c.CATEGORICAL[0], "poses by a parallel prefix product")
    ribbon(ax, Ms + 0.18, q_cpu, c.NEUTRAL, "CPU time of all threads / 1 thread's")
    ax.plot(Ms, Ms, color="0.5", lw=0.8, ls="--", label="no parallelism (overhead = M)")
    ax.axhline(1.0, color="0.3", lw=0.8)
    if cores and Ms.max() > cores:
        ax.axvspan(cores + 0.5, Ms.max() + 0.5, color="0.85", alpha=0.6, lw=0,
                   label=f"oversubscribed ({cores} cores)")
    ax.set_xticks(Ms)
    ax.set_xlim(0.5, Ms.max() + 0.5)
    ax.set_xlabel("threads M")
    ax.set_ylabel("time × M / median single-thread time")
    ax.set_title(f"(d) parallel overhead, steps on M threads: hexapod,\n"
                 f"{values['trajectories']} trajectories × {values['steps']} steps (load {load})")
    ax.legend(loc="upper left")


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    ta, _ = table(args.data, "fig3_13a", ["N", "warmstart", "peer", "contacts", "mujoco_contacts",
                                          "mujoco_iter", "time_ours_ns", "time_mujoco_ns",
                                          "time_rewind_ns"])
    tb, side_b = table(args.data, "fig3_13b", ["trajectory", "steps", "threads", "unsupported",
                                               "scan_max_diff", "same_as_one_thread",
                                               "time_increments_ns", "time_sequential_ns",
                                               "time_scan_ns", "time_cpu_increments_ns"])
    if np.all(ta["time_ours_ns"] == 0) or np.all(tb["time_increments_ns"] == 0):
        c.fail(f"{args.data / STUDY}: timings are all 0 (a --no-timing run): nothing to plot")
    values: dict = {}
    fig, ax = plt.subplots(2, 2, figsize=(13, 10))
    scaling(ta, values, (ax[0, 0], ax[0, 1], ax[1, 0]))
    parallel(tb, side_b, values, ax[1, 1])
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
