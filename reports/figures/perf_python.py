#!/usr/bin/python3
"""Alg. 1 in the thesis' language: our NumPy/SciPy port, timed per frame (thesis §3.5.3, §3.6.1).

The thesis timed a Python (NumPy/SciPy) implementation; ours is compiled C++. This script times
reports/peers/thesis_python.py (our port of Alg. 1, checked against slipwalk's C++ by
tests/reports/test_thesis_python.py) on this machine, to test whether Python's fixed cost per
call accounts for the thesis' flat growth with the number of legs and its compressed ratios:
 (a) the whole model (spring support + local connection A + viscous-Coulomb velocity) on disk
     robots with N = 3 … 50 legs (0.3 m rim, jittered feet, some lifted, random foot velocities:
     the cost study's generator, sweeps/points/legged_cost.cpp), growth N = 50 ÷ N = 3;
 (b) on BigANT-like hexapod frames, the viscous-Coulomb balance alone, one ε = 1e-5 solve by
     scipy.optimize.root(method='lm') and the thesis' continuation (ε = 1e-5, 1e-6, … until
     consecutive solutions change by < 1e-3), both started from the frame's viscous-Coulomb
     balance, timed with it.
Timing: time.thread_time_ns (CPU time of this thread), every frame built and its support solved
before the clock. Each repeat times a loop over all frames of every robot (a) and of every
hexapod method (b), in an order rotated from repeat to repeat, so every ratio is measured within
one repeat; reported are the medians over the repeats of the mean time per frame, and growth and
ratios as the medians of the per-repeat ratios.

Optional input: DATA/ch3_legged/cost_scaling.csv (the per-frame cost study of our C++; rows
robot = disk, method = model, and the hexapod's viscous, epsilon_1e-05 and coulomb_1e-09), drawn
beside the port where present.
Outputs: OUT/perf_python.png, OUT/values/perf_python.json; the check values (python_growth_within_3,
python_growth_within_2, python_ratio_*_within_50pct) hold the port's number where it meets the
thesis' value by the ledger entry's own rule and are null otherwise (with a *_reason).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "peers"))
import common as c  # noqa: E402
import thesis_python as tp  # noqa: E402

NAME = "perf_python"
STUDY = "ch3_legged"
CSV = "cost_scaling.csv"
DISK_N = [3, 4, 6, 8, 12, 16, 24, 32, 50]
# Sized so that the whole run costs a few seconds on a 2-core machine (frames, repeats).
DISK_FRAMES = 32
HEXAPOD_FRAMES = 64
REPEATS = 9
SEED = 20240501
EPSILON = 1e-5  # m/s, §3.5.1.3's first ε
HEXAPOD_METHODS = ("viscous", "epsilon", "coulomb", "support", "model")
PORT = c.CATEGORICAL[0]  # the port: no thesis colour of its own
OURS = c.VISCOUS         # our C++ model


def disk_cases(rng) -> dict[int, tuple]:
    cases = {}
    for n in DISK_N:
        robot, nominal = tp.disk_robot(n)
        cases[n] = (robot, [tp.random_frame(robot, nominal, rng) for _ in range(DISK_FRAMES)])
    return cases


def hexapod_case(rng) -> tuple:
    """The hexapod's frames with their supports solved (the friction methods start from F_z)."""
    robot, nominal = tp.hexapod_robot()
    frames = []
    for _ in range(HEXAPOD_FRAMES):
        q, qdot = tp.random_frame(robot, nominal, rng)
        frames.append((q, qdot, tp.friction_weights(robot, tp.spring_support(robot, q))))
    return robot, frames


def solve_hexapod(method: str, robot, q, qdot, c_k):
    if method == "model":
        return tp.model(robot, q, qdot)
    if method == "support":
        return tp.spring_support(robot, q)
    start = tp.viscous_balance(robot, q, qdot, c_k)
    if method == "viscous":
        return start
    if method == "epsilon":
        return tp.epsilon_balance(robot, q, qdot, c_k, EPSILON, start)
    return tp.coulomb_by_continuation(robot, q, qdot, c_k, start, eps_start=EPSILON)


def time_per_frame(run, frames) -> float:
    """Mean thread CPU time per frame of one loop over the frames, µs."""
    t0 = time.thread_time_ns()
    for f in frames:
        run(*f)
    return (time.thread_time_ns() - t0) * 1e-3 / len(frames)


def measure(disks: dict, hexapod: tuple) -> tuple[dict, dict]:
    """Per repeat, every disk robot's whole model and every hexapod method, in a rotated order.
    Returns µs per frame per repeat: {N: [..]}, {method: [..]}."""
    jobs = [("disk", n) for n in DISK_N] + [("hexapod", m) for m in HEXAPOD_METHODS]
    robot6, frames6 = hexapod

    def job(kind, key) -> float:
        if kind == "disk":
            robot, frames = disks[key]
            return time_per_frame(lambda q, qd: tp.model(robot, q, qd), frames)
        return time_per_frame(lambda q, qd, ck: solve_hexapod(key, robot6, q, qd, ck), frames6)

    for kind, key in jobs:  # one untimed pass: first calls (imports, caches) are not counted
        job(kind, key)
    disk_us = {n: [] for n in DISK_N}
    hex_us = {m: [] for m in HEXAPOD_METHODS}
    for r in range(REPEATS):
        shift = r % len(jobs)
        for kind, key in jobs[shift:] + jobs[:shift]:
            (disk_us if kind == "disk" else hex_us)[key].append(job(kind, key))
    return disk_us, hex_us


def per_repeat_ratio(a: list[float], b: list[float]) -> float:
    return float(np.median(np.asarray(a) / np.asarray(b)))


def ledger_entry(claim_id: str) -> dict:
    for entry in c.load_ledger().get("claim", []):
        if entry.get("id") == claim_id:
            return entry
    c.fail(f"{c.LEDGER}: no claim with id '{claim_id}'")


def checks(v: dict) -> None:
    """The check values: the port's number where it meets the thesis' by the entry's own rule."""
    growth = v["python_growth_50"]
    below = float(ledger_entry("3.5.3-ours-growth")["thesis"])  # "less than a factor of 3"
    doubles = float(ledger_entry("1.2.2-only-doubles")["thesis"])  # "only doubles"
    v["python_growth_within_3"] = growth if growth < below else None
    v["python_growth_within_3_reason"] = (None if growth < below else
                                          f"the port grows ×{growth:.3g}, not below ×{below:g}")
    v["python_growth_within_2"] = growth if growth <= doubles else None
    v["python_growth_within_2_reason"] = (None if growth <= doubles else
                                          f"the port grows ×{growth:.3g}, above ×{doubles:g}")
    for entry, key in (("3.6.1-coulomb-over-viscous", "python_ratio_coulomb_viscous"),
                       ("3.6.1-epsilon-over-viscous", "python_ratio_epsilon_viscous")):
        cl = ledger_entry(entry)
        thesis, tol, got = float(cl["thesis"]), float(cl["tol"]), v[key]
        ok = abs(got - thesis) <= tol * abs(thesis)
        v[f"{key}_within_50pct"] = got if ok else None
        v[f"{key}_within_50pct_reason"] = None if ok else (
            f"the port gives ×{got:.3g} against the thesis' ×{thesis:g} (beyond ±{tol:.0%})")


def values_of(disk_us: dict, hex_us: dict, disks: dict, hexapod: tuple) -> dict:
    v = {"disk_N": DISK_N, "disk_frames": DISK_FRAMES, "hexapod_frames": HEXAPOD_FRAMES,
         "repeats": REPEATS, "seed": SEED, "clock": "time.thread_time_ns (thread CPU time)",
         "epsilon": EPSILON}
    v["python_model_us_by_N"] = [float(np.median(disk_us[n])) for n in DISK_N]
    v["python_model_us_p25_by_N"] = [float(np.percentile(disk_us[n], 25)) for n in DISK_N]
    v["python_model_us_p75_by_N"] = [float(np.percentile(disk_us[n], 75)) for n in DISK_N]
    v["python_growth_50"] = per_repeat_ratio(disk_us[DISK_N[-1]], disk_us[DISK_N[0]])
    v["python_growth_from"], v["python_growth_to"] = DISK_N[0], DISK_N[-1]
    fit = c.linfit(np.array(DISK_N, float), np.array(v["python_model_us_by_N"]))
    v["python_fit_a_us"], v["python_fit_b_us"] = fit["b"], fit["k"]
    v["python_fit_a_over_b"] = fit["b"] / fit["k"] if fit["k"] else None
    v["python_model_us_3"] = v["python_model_us_by_N"][0]
    v["python_model_us_50"] = v["python_model_us_by_N"][-1]
    v["python_disk_contacts_mean"] = [
        float(np.mean([tp.spring_support(r, q).contact.sum() for q, _ in fr]))
        for r, fr in (disks[n] for n in DISK_N)]
    v["python_disk_support_changes_mean"] = [
        float(np.mean([tp.spring_support(r, q).changes for q, _ in fr]))
        for r, fr in (disks[n] for n in DISK_N)]
    for m in HEXAPOD_METHODS:
        v[f"python_hexapod_{m}_us"] = float(np.median(hex_us[m]))
        v[f"python_hexapod_{m}_us_p25"] = float(np.percentile(hex_us[m], 25))
        v[f"python_hexapod_{m}_us_p75"] = float(np.percentile(hex_us[m], 75))
    v["python_ratio_epsilon_viscous"] = per_repeat_ratio(hex_us["epsilon"], hex_us["viscous"])
    v["python_ratio_coulomb_viscous"] = per_repeat_ratio(hex_us["coulomb"], hex_us["viscous"])
    v["python_ratio_coulomb_epsilon"] = per_repeat_ratio(hex_us["coulomb"], hex_us["epsilon"])
    # Read as whole frames instead (the thesis does not say whether its "run time for
    # viscous-Coulomb friction" includes the spring support): support + friction solve ÷ the
    # whole model, per repeat.
    support = np.asarray(hex_us["support"])
    v["python_ratio_coulomb_viscous_whole_frame"] = per_repeat_ratio(
        support + np.asarray(hex_us["coulomb"]), hex_us["model"])
    v["python_ratio_epsilon_viscous_whole_frame"] = per_repeat_ratio(
        support + np.asarray(hex_us["epsilon"]), hex_us["model"])
    robot6, frames6 = hexapod
    runs = [solve_hexapod("coulomb", robot6, *f) for f in frames6]
    singles = [solve_hexapod("epsilon", robot6, *f) for f in frames6]
    v["python_coulomb_eps_steps_mean"] = float(np.mean([s.eps_steps for s in runs]))
    v["python_coulomb_evaluations_mean"] = float(np.mean([s.evaluations for s in runs]))
    v["python_coulomb_unsettled"] = int(sum(not s.converged for s in runs))
    v["python_epsilon_evaluations_mean"] = float(np.mean([s.evaluations for s in singles]))
    v["python_hexapod_contacts_mean"] = float(np.mean([np.count_nonzero(f[2]) for f in frames6]))
    checks(v)
    return v


def ours_from_study(data: Path, v: dict) -> dict | None:
    """Our C++ from the cost study, where present (µs per frame): the whole model by N, and on
    the hexapod our own solvers and the thesis' algorithm in C++ (MINPACK's LM)."""
    path = data / STUDY / CSV
    if not path.is_file():
        v["ours_missing"] = f"{c.shown_path(path)} is missing"
        return None
    t = c.Table(path, ["robot", "N", "method", "eps", "tol", "time_ns"])
    independent = (np.array([s == "independent" for s in t["sequence"]])
                   if "sequence" in t.columns else np.ones(t.n, bool))

    def pick(robot: str, method: str, eps=None, tol=None) -> dict[int, float]:
        keep = independent & (t["robot"] == robot) & (t["method"] == method)
        if eps is not None:
            keep &= np.isclose(t["eps"], eps, rtol=1e-9, atol=0.0)
        if tol is not None:
            keep &= np.isclose(t["tol"], tol, rtol=1e-9, atol=0.0)
        return {int(n): float(x) * 1e-3 for n, x in zip(t["N"][keep], t["time_ns"][keep])}

    model = pick("disk", "model")
    ours = {"N": sorted(model), "model_us": [model[n] for n in sorted(model)],
            "viscous": pick("hexapod", "viscous").get(6),
            "epsilon": pick("hexapod", "epsilon", eps=EPSILON).get(6),
            "coulomb": pick("hexapod", "coulomb", tol=1e-9).get(6),
            "epsilon_thesis": pick("hexapod", "epsilon_thesis", eps=EPSILON).get(6),
            "coulomb_thesis": pick("hexapod", "coulomb_thesis").get(6)}
    v["ours_N"], v["ours_model_us_by_N"] = ours["N"], ours["model_us"]
    for key in ("viscous", "epsilon", "coulomb", "epsilon_thesis", "coulomb_thesis"):
        v[f"ours_hexapod_{key}_us"] = ours[key]
    # The same algorithm in Python over C++: the interpreter's cost against the work
    v["python_over_cpp_viscous"] = (v["python_hexapod_viscous_us"] / ours["viscous"]
                                    if ours["viscous"] else None)
    v["python_over_cpp_coulomb_thesis"] = (v["python_hexapod_coulomb_us"] / ours["coulomb_thesis"]
                                           if ours["coulomb_thesis"] else None)
    v["python_over_cpp_epsilon_thesis"] = (v["python_hexapod_epsilon_us"] / ours["epsilon_thesis"]
                                           if ours["epsilon_thesis"] else None)
    v["ours_missing"] = None
    return ours


def figure(plt, v: dict, ours: dict | None, out: Path) -> None:
    fig, axs = plt.subplots(1, 3, figsize=(14, 4.4), gridspec_kw={"width_ratios": [1, 1, 1.3]})
    n = np.array(DISK_N)
    port = np.array(v["python_model_us_by_N"])
    ax = axs[0]
    ax.fill_between(n, v["python_model_us_p25_by_N"], v["python_model_us_p75_by_N"], color=PORT,
                    alpha=0.3, lw=0)
    ax.plot(n, port, "o-", color=PORT, ms=4, label="the thesis' algorithm, NumPy/SciPy (port)")
    if ours and ours["N"]:
        ax.plot(ours["N"], ours["model_us"], "s-", color=OURS, ms=4, label="ours, C++")
    ax.set_yscale("log")
    ax.set_xlabel("legs N")
    ax.set_ylabel("thread CPU time per frame (µs)")
    ax.set_title("(a) whole model per frame: support + A + viscous balance")
    ax.legend(loc="center right")
    ax = axs[1]
    ax.plot(n, port / port[0], "o-", color=PORT, ms=4, label=f"port: ×{v['python_growth_50']:.3g}"
            f" at N = {DISK_N[-1]}")
    if ours and ours["N"] and ours["N"][0] == DISK_N[0]:
        base = ours["model_us"][0]
        ax.plot(ours["N"], np.array(ours["model_us"]) / base, "s-", color=OURS, ms=4,
                label=f"ours, C++: ×{ours['model_us'][-1] / base:.3g} at N = {ours['N'][-1]}")
    for claim, style in (("3.5.3-ours-growth", "--"), ("1.2.2-only-doubles", ":")):
        limit = float(c.thesis(claim))
        ax.axhline(limit, color=c.REFERENCE, ls=style, lw=1,
                   label=f"thesis: ×{limit:g} ({'§3.5.3' if limit == 3 else '§1.2.2'})")
    ax.set_xlabel("legs N")
    ax.set_ylabel(f"time ÷ time at N = {DISK_N[0]}")
    ax.set_title("(b) growth with the number of legs")
    ax.legend(loc="upper left")
    ax = axs[2]
    keys = ["viscous", "epsilon", "coulomb"]
    thesis_ms = [float(x) for x in c.thesis("3.6.1-runtime-per-frame")]
    groups = [("thesis (its Python, its machine)", [x * 1e3 for x in thesis_ms], c.REFERENCE),
              ("port (NumPy/SciPy, here)", [v[f"python_hexapod_{k}_us"] for k in keys], PORT)]
    if ours and all(ours.get(k) for k in ("viscous", "epsilon_thesis", "coulomb_thesis")):
        groups.append(("the thesis' algorithm in C++ (MINPACK's LM, here)",
                       [ours["viscous"], ours["epsilon_thesis"], ours["coulomb_thesis"]],
                       c.NEUTRAL))
    if ours and all(ours.get(k) for k in keys):
        groups.append(("ours, C++ (own ε and Coulomb solvers, here)", [ours[k] for k in keys],
                       OURS))
    width = 0.8 / len(groups)
    for g, (label, ys, color) in enumerate(groups):
        x = np.arange(3) + (g - (len(groups) - 1) / 2) * width
        ax.bar(x, ys, width, color=color, label=label)
        # the port's ratios as measured (medians of per-repeat ratios); the others', of the bars
        paired = {"epsilon": v["python_ratio_epsilon_viscous"],
                  "coulomb": v["python_ratio_coulomb_viscous"]} if color == PORT else {}
        for xi, yi, k in zip(x, ys, keys):
            ratio = paired.get(k, yi / ys[0])
            if k != "viscous":
                ax.text(xi, yi * 1.3, f"×{ratio:.3g}", ha="center", va="bottom", fontsize=8.5,
                        rotation=90)
    port_x = (1 - (len(groups) - 1) / 2) * width  # the port's viscous bar
    ax.plot([port_x], [v["python_hexapod_model_us"]], marker="_", ms=16, mew=2.5, ls="none",
            color=PORT, label="port: whole model per frame (support + A + velocity)")
    ax.set_yscale("log")
    ax.set_xticks(range(3), ["viscous-Coulomb", "one ε = 1e-5", "Coulomb"])
    ax.set_ylabel("time per frame (µs)")
    ax.set_title("(c) hexapod: friction per frame (× = ÷ viscous)")
    ax.legend(loc="upper left", fontsize=8.5)
    top = max(max(ys) for _, ys, _ in groups)
    ax.set_ylim(ax.get_ylim()[0], top * 3e3)  # room for the ratios and the legend
    fig.tight_layout()
    c.save_figure(fig, out, NAME)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    start = time.perf_counter()
    rng = np.random.default_rng(SEED)
    disks = disk_cases(rng)
    hexapod = hexapod_case(rng)
    disk_us, hex_us = measure(disks, hexapod)
    v = values_of(disk_us, hex_us, disks, hexapod)
    ours = ours_from_study(args.data, v)
    plt = c.setup_matplotlib()
    v["python_run_s"] = time.perf_counter() - start  # frames, timing and values; not the figure
    figure(plt, v, ours, args.out)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
