#!/usr/bin/python3
"""Sweeps beyond one process: parallel efficiency over MPI ranks, shards and threads, and how
many ranks one coordinator can feed.

Inputs (studies/scaling_out/):
- DATA/scaling_out/efficiency.csv (point kind scale_out): one CPU-bound sweep run as a
  subprocess in four modes, `repeats` rounds in rotated order: serial, R threads (--jobs R), R MPI
  ranks of one thread, R shard processes at once then merged. wall_s is the sweep's own run time
  (shards: the longest shard), process_wall_s the whole command with launch (and merge);
  same_bytes = 1 when the mode's CSV equals the serial one byte for byte (--no-timing).
- DATA/scaling_out/coordinator.csv (point kind coordinator_throughput): mpirun of a no-op sweep
  with --coordinator-jobs 0; points_per_cpu_s = remote points per CPU second of rank 0's main
  thread, the rate one coordinator sustains where it is the bottleneck.
- every sidecar DATA/<study>/*.json that has point_seconds (the other studies' sweeps): the mean
  time t of a point of the study, Σ sum / Σ count over its sweeps. Sidecars without
  point_seconds are skipped and counted; a shard's sidecar is skipped where the merged one is
  there (it carries the shards' times).

Parallel efficiency of a mode in a round: wall_s(serial) / (workers × wall_s(mode)); per mode the
median over the rounds (the smallest per-workload median if there are several workloads).
Saturation: ranks of J threads each ask for a point every t / J seconds, so one coordinator
saturates at R_sat = points_per_cpu_s × t / J ranks; J = 1 (the worst case), points_per_cpu_s the
median over repeats (the smallest per-configuration median if there are several).

Outputs: OUT/scaling_out.png ((a) wall time per mode and round, the median efficiencies in the
legend; (b) R_sat per study against the 1,000-rank goal, the multi-legged studies marked),
OUT/scaling_out_table.html, OUT/values/scaling_out.json (also the ledger's values).
"""
from __future__ import annotations

import html
import json
import math
import re
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "scaling_out"
STUDY = "scaling_out"
EFFICIENCY_CSV = "efficiency.csv"
COORDINATOR_CSV = "coordinator.csv"
EFFICIENCY_COLUMNS = ["id", "workload", "mode", "workers", "repeat", "points", "wall_s",
                      "process_wall_s", "same_bytes", "exit_code", "message"]
COORDINATOR_COLUMNS = ["id", "points", "ranks", "jobs", "repeat", "wall_s", "coordinator_cpu_s",
                       "messages", "remote_points", "points_per_s", "points_per_cpu_s",
                       "points_per_message", "exit_code", "message"]
MODES = ("serial", "threads", "mpi", "shards")
PARALLEL = MODES[1:]
MODE_COLOUR = {"serial": c.CATEGORICAL[4], "threads": c.CATEGORICAL[0],
               "mpi": c.CATEGORICAL[2], "shards": c.CATEGORICAL[1]}
# The studies whose points run the multi-legged model: the coordinator must feed 1,000 ranks
# of them (the goal); the others are shown for what they are.
MULTILEGGED = ("ch3_legged", "ch3_robots", "ch3_peer", "ch4_calibration", "ch5_planning",
               "ch5_residual", "ch5_terrain")
RSAT_GOAL = 1000.0
EFFICIENCY_GOAL = 0.9  # MPI at 2 ranks
THREADS_PER_RANK = 1   # J of R_sat: every rank computes on one thread (the worst case)
SHARD_SIDECAR = re.compile(r"^(?P<name>.+)\.shard-\d+-of-\d+\.json$")


def mode_label(mode: str, workers: int) -> str:
    return {"serial": "serial", "threads": f"{workers} threads", "mpi": f"{workers} MPI ranks",
            "shards": f"{workers} shards + merge"}[mode]


def key_part(text: str) -> str:
    """A workload or study name as part of a value key."""
    return re.sub(r"[^a-z0-9_]+", "_", text.lower()).strip("_") or "x"


def is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def messages(t: c.Table, mask: np.ndarray) -> str:
    """The distinct messages of the rows in mask, for a reason."""
    found = [m for m in dict.fromkeys(t.str("message")[mask]) if m]
    return "; ".join(found) if found else "no message"


# ---------------------------------------------------------------------------------------------
# Parallel efficiency


def efficiency(data: Path) -> tuple[dict, dict]:
    """The values of efficiency.csv, and what the figure and table draw."""
    t = c.Table(c.study_file(data, EFFICIENCY_CSV, STUDY), EFFICIENCY_COLUMNS)
    if t.n == 0:
        c.fail(f"{t.path}: no data rows")
    mode = t.str("mode")
    workload = t.str("workload")
    unknown = sorted(set(mode) - set(MODES))
    if unknown:
        c.fail(f"{t.path}: unknown mode(s) {', '.join(unknown)} (known: {', '.join(MODES)})")
    for col in ("workers", "repeat", "exit_code", "same_bytes"):
        if not np.all(np.isfinite(t[col])):
            c.fail(f"{t.path}: column '{col}' must be a number in every row")
    ok = (t["exit_code"] == 0) & np.isfinite(t["wall_s"]) & (t["wall_s"] > 0)
    if not np.any(ok & (mode == "serial")):
        c.fail(f"{t.path}: no successful serial run, so no efficiency can be computed "
               f"({messages(t, mode == 'serial')})")
    workloads = list(dict.fromkeys(workload))
    v: dict = {"rounds": int(len(set(t["repeat"]))), "workloads": workloads,
               "efficiency_goal": EFFICIENCY_GOAL}
    draw: dict = {"rounds": sorted(set(int(r) for r in t["repeat"])), "rows": {}, "workers": {}}

    # Per workload and round: the serial wall time, against which each mode's efficiency.
    effs: dict = {m: {w: [] for w in workloads} for m in PARALLEL}
    for i in range(t.n):
        if not ok[i]:
            continue
        draw["rows"].setdefault((workload[i], mode[i]), []).append(
            (int(t["repeat"][i]), float(t["wall_s"][i]), float(t["process_wall_s"][i])))
    for i in range(t.n):
        if mode[i] == "serial" or not ok[i]:
            continue
        serial = (ok & (mode == "serial") & (workload == workload[i])
                  & (t["repeat"] == t["repeat"][i]))
        if not np.any(serial):
            continue
        s = float(np.median(t["wall_s"][serial]))
        effs[mode[i]][workload[i]].append(s / (t["workers"][i] * t["wall_s"][i]))

    same_all = True
    reasons = []
    for m in MODES:
        rows = mode == m
        ran = rows & ok
        failed = rows & (t["exit_code"] > 0)
        skipped = rows & (t["exit_code"] < 0)
        workers = sorted(set(int(w) for w in t["workers"][rows]))
        draw["workers"][m] = workers[0] if workers else (1 if m == "serial" else 2)
        v[f"runs_{m}"] = int(np.count_nonzero(ran))
        v[f"runs_failed_{m}"] = int(np.count_nonzero(failed))
        v[f"runs_not_run_{m}"] = int(np.count_nonzero(skipped))
        v[f"workers_{m}"] = draw["workers"][m]
        v[f"wall_s_{m}"] = float(np.median(t["wall_s"][ran])) if np.any(ran) else None
        v[f"process_wall_s_{m}"] = (float(np.nanmedian(t["process_wall_s"][ran]))
                                    if np.any(ran) and np.any(np.isfinite(t["process_wall_s"][ran]))
                                    else None)
        if m == "serial":
            continue
        if not np.any(ran):
            why = (f"{m} did not run: {messages(t, rows)}" if np.any(rows)
                   else f"no {m} rows in {EFFICIENCY_CSV}")
            v[f"efficiency_{m}"] = None
            v[f"efficiency_{m}_reason"] = why
            v[f"same_bytes_{m}"] = None
            v[f"same_bytes_{m}_reason"] = why
            same_all = None if same_all is not False else False
            reasons.append(why)
            continue
        # A run that failed wrote no CSV to compare: it counts as not the same bytes.
        same = bool(np.all(t["same_bytes"][ran] == 1)) and not np.any(failed)
        v[f"same_bytes_{m}"] = same
        if not same:
            same_all = False
        medians = {w: float(np.median(e)) for w, e in effs[m].items() if e}
        if not medians:
            v[f"efficiency_{m}"] = None
            v[f"efficiency_{m}_reason"] = f"no round with both a serial and a {m} run"
            continue
        v[f"efficiency_{m}"] = min(medians.values())
        v[f"efficiency_{m}_rounds"] = sum(len(e) for e in effs[m].values())
        v[f"speedup_{m}"] = v[f"efficiency_{m}"] * draw["workers"][m]
        if len(medians) > 1:
            for w, e in medians.items():
                v[f"efficiency_{m}_{key_part(w)}"] = e
    v["same_bytes_all"] = same_all
    if same_all is None:
        v["same_bytes_all_reason"] = "; ".join(reasons)
    v["efficiency_mpi_goal_met"] = (None if v.get("efficiency_mpi") is None
                                    else bool(v["efficiency_mpi"] >= EFFICIENCY_GOAL))
    v["points_per_run"] = float(np.max(t["points"]))
    # The machine the modes shared: what a wall time and an efficiency are read against.
    side = c.read_sidecar(t.path)
    machine = ((side or {}).get("provenance") or {}).get("machine") or {}
    v["logical_cores"] = machine.get("logical_cores")
    v["load_average_1min"] = machine.get("load_average_1min")
    return v, draw


# ---------------------------------------------------------------------------------------------
# The coordinator's throughput


def coordinator(data: Path) -> tuple[dict, list[dict]]:
    t = c.Table(c.study_file(data, COORDINATOR_CSV, STUDY), COORDINATOR_COLUMNS)
    if t.n == 0:
        c.fail(f"{t.path}: no data rows")
    for col in ("points", "ranks", "jobs", "exit_code"):
        if not np.all(np.isfinite(t[col])):
            c.fail(f"{t.path}: column '{col}' must be a number in every row")
    rate = t["points_per_cpu_s"]
    usable = (t["exit_code"] == 0) & np.isfinite(rate) & (rate > 0)
    v: dict = {"coordinator_runs": int(t.n),
               "coordinator_runs_usable": int(np.count_nonzero(usable))}
    groups = []
    for key in dict.fromkeys(zip(t["points"], t["ranks"], t["jobs"])):
        rows = usable & (t["points"] == key[0]) & (t["ranks"] == key[1]) & (t["jobs"] == key[2])
        if not np.any(rows):
            continue
        med = {col: float(np.nanmedian(t[col][rows])) if np.any(np.isfinite(t[col][rows])) else None
               for col in ("wall_s", "coordinator_cpu_s", "messages", "remote_points",
                           "points_per_s", "points_per_cpu_s", "points_per_message")}
        groups.append({"points": int(key[0]), "ranks": int(key[1]), "jobs": int(key[2]),
                       "repeats": int(np.count_nonzero(rows)), **med})
    keys = ("points_per_cpu_s", "points_per_s", "points_per_message", "ranks", "points",
            "repeats", "wall_s", "cpu_s")
    if not groups:
        why = (f"no successful coordinator run with a CPU time above zero "
               f"({messages(t, ~usable)})")
        for k in keys + ("us_per_point", "messages_per_cpu_s"):
            v[f"coordinator_{k}"] = None
        v["coordinator_points_per_cpu_s_reason"] = why
        return v, groups
    # Points slower than the coordinator come back one to a message (nothing to batch). Every
    # message of a run cost at most cpu_s / messages, its points included, so the largest
    # messages per CPU second of any run bounds the rate of one-point messages from below.
    per_message = t["messages"][usable] / t["coordinator_cpu_s"][usable]
    v["coordinator_messages_per_cpu_s"] = float(np.max(per_message))
    # The bound on the ranks one coordinator feeds: its slowest configuration.
    worst = min(groups, key=lambda g: g["points_per_cpu_s"])
    for k in keys:
        v[f"coordinator_{k}"] = worst["coordinator_cpu_s" if k == "cpu_s" else k]
    v["coordinator_us_per_point"] = 1e6 / worst["points_per_cpu_s"]
    return v, groups


# ---------------------------------------------------------------------------------------------
# Mean point time per study, from the sidecars


def point_times(data: Path) -> list[dict]:
    """Per study folder of DATA (this study's own apart): the timed points, the mean point time
    and the sidecars with and without point_seconds."""
    studies = []
    for folder in sorted(p for p in data.iterdir() if p.is_dir() and p.name != STUDY):
        total, count, used, skipped = 0.0, 0, 0, 0
        for side in sorted(folder.glob("*.json")):
            shard = SHARD_SIDECAR.match(side.name)
            if shard and (folder / f"{shard['name']}.json").is_file():
                continue  # the merged sidecar carries this shard's points
            try:
                doc = json.loads(side.read_text())
            except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
                c.fail(f"{side}: not a readable JSON sidecar: {e}")
            ps = doc.get("point_seconds") if isinstance(doc, dict) else None
            if ps is None:
                skipped += 1
                continue
            n, s = (ps.get("count"), ps.get("sum")) if isinstance(ps, dict) else (None, None)
            if not (is_number(n) and is_number(s) and n >= 0 and s >= 0):
                c.fail(f"{side}: point_seconds must hold a count and a sum of seconds "
                       f"(got {json.dumps(ps)[:80]})")
            total += float(s)
            count += int(n)
            used += 1
        if used == 0 and skipped == 0:
            continue
        studies.append({"study": folder.name, "sidecars": used, "sidecars_skipped": skipped,
                        "points": count, "seconds": total,
                        "mean_s": total / count if count > 0 else None,
                        "multilegged": folder.name in MULTILEGGED})
    return studies


# ---------------------------------------------------------------------------------------------
# Output


def table_html(v: dict, groups: list[dict], studies: list[dict]) -> str:
    modes = []
    for m in MODES:
        w = v[f"workers_{m}"]
        eff = "—" if m == "serial" else c.fmt(v.get(f"efficiency_{m}"), 3)
        same = "reference" if m == "serial" else c.fmt(v.get(f"same_bytes_{m}"))
        note = v.get(f"efficiency_{m}_reason", "")
        if v[f"runs_failed_{m}"]:
            note = (note + "; " if note else "") + f"{v[f'runs_failed_{m}']} run(s) failed"
        modes.append(f"<tr><td>{html.escape(mode_label(m, w))}</td><td>{v[f'runs_{m}']}</td>"
                     f"<td>{c.fmt(v[f'wall_s_{m}'], 4)}</td>"
                     f"<td>{c.fmt(v[f'process_wall_s_{m}'], 4)}</td><td>{eff}</td>"
                     f"<td>{same}</td><td>{html.escape(note)}</td></tr>")
    coord = "".join(
        f"<tr><td>{g['points']}</td><td>{g['ranks']}</td><td>{g['jobs']}</td><td>{g['repeats']}</td>"
        f"<td>{c.fmt(g['points_per_s'], 3)}</td><td>{c.fmt(g['points_per_cpu_s'], 3)}</td>"
        f"<td>{c.fmt(g['points_per_message'], 3)}</td></tr>" for g in groups) or (
        "<tr><td colspan='7'>no successful run: "
        f"{html.escape(str(v.get('coordinator_points_per_cpu_s_reason', '')))}</td></tr>")
    cores = (f"a machine of {v['logical_cores']} logical cores" if v.get("logical_cores")
             else "a machine whose cores the sidecar does not give")
    per_study = []
    for s in studies:
        name = html.escape(s["study"]) + (" (multi-legged)" if s["multilegged"] else "")
        rsat = s.get("rsat")
        cls = " class='bad'" if s["multilegged"] and rsat is not None and rsat < RSAT_GOAL else ""
        per_study.append(f"<tr><td>{name}</td><td>{s['sidecars']}</td>"
                         f"<td>{s['sidecars_skipped']}</td><td>{s['points']}</td>"
                         f"<td>{c.fmt(s['mean_s'], 3)}</td><td{cls}>{c.fmt(rsat, 3)}</td></tr>")
    return f"""<table class='data'><thead><tr><th>mode</th><th>rounds run</th><th>median wall_s [s]</th>
<th>median whole command [s]</th><th>median efficiency</th><th>CSV = serial bytes</th><th>note</th>
</tr></thead><tbody>{''.join(modes)}</tbody></table>
<table class='data'><thead><tr><th>points</th><th>ranks</th><th>jobs</th><th>repeats</th>
<th>points / s (measured)</th><th>points / coordinator CPU s</th><th>points / message</th>
</tr></thead><tbody>{coord}</tbody></table>
<table class='data'><thead><tr><th>study</th><th>sidecars timed</th><th>sidecars without times</th>
<th>points timed</th><th>mean point [s]</th><th>R_sat [ranks of 1 thread]</th></tr></thead>
<tbody>{''.join(per_study)}</tbody></table>
<p class="small">Medians over the rounds, on {cores}. points / s is limited on this machine by
the worker ranks sharing its cores with the coordinator; points / coordinator CPU s is the
coordinator's own bound, from which R_sat = points / CPU s × mean point time (ranks of one
thread). Sidecars without point_seconds (written before sweeps timed their points, or not by a
sweep) are not counted; a shard's sidecar is not counted beside its merged one.</p>
"""


def figure(v: dict, draw: dict, studies: list[dict], out: Path) -> None:
    plt = c.setup_matplotlib()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(14, 5.2), gridspec_kw={"width_ratios": [1, 1.1]})

    # (a) wall time per round and mode; the whole command as an open marker above each bar
    rounds = draw["rounds"]
    workloads = list(dict.fromkeys(w for w, _ in draw["rows"]))
    slots = [(w, r) for w in workloads for r in rounds]
    width = 0.8 / len(MODES)
    for j, m in enumerate(MODES):
        xs, ys, ps = [], [], []
        for k, (w, r) in enumerate(slots):
            for rr, wall, proc in draw["rows"].get((w, m), []):
                if rr == r:
                    xs.append(k + (j - 1.5) * width)
                    ys.append(wall)
                    ps.append(proc)
        label = mode_label(m, draw["workers"][m])
        if m != "serial":
            e = v.get(f"efficiency_{m}")
            label += f": {e:.2f}" if e is not None else ": not run"
        ax.bar(xs, ys, width, color=MODE_COLOUR[m], label=label)
        ax.plot(xs, ps, "o", mfc="none", color=MODE_COLOUR[m], ms=5)
    ax.plot([], [], "o", mfc="none", color="0.3", label="whole command, with launch and merge")
    ax.set_xticks(range(len(slots)))
    ax.set_xticklabels([f"round {r}" if len(workloads) == 1 else f"{w}\nround {r}"
                        for w, r in slots])
    tallest = max((max(w, p if np.isfinite(p) else 0.0) for rows in draw["rows"].values()
                   for _, w, p in rows), default=1.0)
    ax.set_ylim(0, 1.55 * tallest)  # room for the legend above the bars
    ax.set_ylabel("wall time of the sweep [s]")
    cores = f" on {v['logical_cores']} cores" if v["logical_cores"] else ""
    ax.set_title(f"(a) one sweep of {v['points_per_run']:.0f} points{cores}, "
                 f"serial and over {draw['workers']['mpi']} workers")
    ax.legend(loc="upper center", ncol=2, fontsize=9, title_fontsize=9, framealpha=0.9,
              title="median parallel efficiency (serial time ÷ workers × time)")

    # (b) R_sat per study
    shown = [s for s in studies if s.get("rsat")]
    if shown:
        y = np.arange(len(shown))
        bx.barh(y, [s["rsat"] for s in shown], color=[c.CATEGORICAL[0] if s["multilegged"]
                                                      else c.CATEGORICAL[5] for s in shown])
        bx.set_yticks(y)
        bx.set_yticklabels([s["study"] + (" *" if s["multilegged"] else "") for s in shown])
        bx.invert_yaxis()
        bx.set_xscale("log")
        for yi, s in zip(y, shown):
            label = f"{s['rsat']:,.0f}" if s["rsat"] >= 10 else f"{s['rsat']:.2g}"
            bx.text(s["rsat"] * 1.1, yi, label,
                    va="center", fontsize=9, bbox={"fc": "white", "ec": "none", "pad": 0.5})
        lo = min(min(s["rsat"] for s in shown), RSAT_GOAL) / 3
        hi = max(max(s["rsat"] for s in shown), RSAT_GOAL) * 6
        bx.set_xlim(lo, hi)
    else:
        bx.text(0.5, 0.5, "no sidecar with point_seconds, or no coordinator rate",
                ha="center", va="center", transform=bx.transAxes)
        bx.set_xscale("log")
        bx.set_xlim(1, 1e5)
    from matplotlib.patches import Patch

    goal = bx.axvline(RSAT_GOAL, color=c.REFERENCE, ls="--", label=f"goal: {RSAT_GOAL:,.0f} ranks")
    bx.set_xlabel("R_sat: ranks of one thread one coordinator can feed (log)")
    rate = v.get("coordinator_points_per_cpu_s")
    bx.set_title("(b) R_sat = coordinator's points / CPU s"
                 + (f" ({rate:,.0f})" if rate else "") + " × a study's mean point time")
    bx.legend(handles=[goal, Patch(color=c.CATEGORICAL[0], label="multi-legged study (*)"),
                       Patch(color=c.CATEGORICAL[5], label="other study")],
              loc="lower right", fontsize=9, framealpha=0.9)
    bx.grid(axis="y", visible=False)
    fig.tight_layout()
    c.save_figure(fig, out, NAME)


def main() -> None:
    args = c.parse_args(__doc__.splitlines()[0])
    v, draw = efficiency(args.data)
    cv, groups = coordinator(args.data)
    v.update(cv)
    studies = point_times(args.data)
    rate = v["coordinator_points_per_cpu_s"]
    v["threads_per_rank"] = THREADS_PER_RANK
    v["rsat_goal"] = RSAT_GOAL
    v["studies"] = [s["study"] for s in studies]
    for s in studies:
        k = key_part(s["study"])
        s["rsat"] = (rate * s["mean_s"] / THREADS_PER_RANK
                     if rate is not None and s["mean_s"] is not None else None)
        v[f"points_{k}"] = s["points"]
        v[f"point_mean_s_{k}"] = s["mean_s"]
        v[f"sidecars_{k}"] = s["sidecars"]
        v[f"sidecars_skipped_{k}"] = s["sidecars_skipped"]
        v[f"rsat_{k}"] = s["rsat"]
    v["sidecars_skipped"] = sum(s["sidecars_skipped"] for s in studies)
    timed = {s["study"]: s for s in studies if s["rsat"] is not None}
    v["multilegged_timed"] = [st for st in MULTILEGGED if st in timed]
    v["multilegged_untimed"] = [st for st in MULTILEGGED if st not in timed]
    if v["multilegged_timed"]:
        low = min(v["multilegged_timed"], key=lambda st: timed[st]["rsat"])
        v["rsat_min_multilegged"] = timed[low]["rsat"]
        v["rsat_min_study"] = low
        v["rsat_goal_met"] = bool(timed[low]["rsat"] >= RSAT_GOAL)
    else:
        why = (v.get("coordinator_points_per_cpu_s_reason")
               or "no multi-legged study has a sidecar with point_seconds under the data folder")
        for k in ("rsat_min_multilegged", "rsat_min_study", "rsat_goal_met"):
            v[k] = None
            v[f"{k}_reason"] = why
    # The same with one point to a message (no batching): the conservative bound.
    one = v.get("coordinator_messages_per_cpu_s")
    v["rsat_min_multilegged_unbatched"] = (
        one * timed[v["rsat_min_study"]]["mean_s"] / THREADS_PER_RANK
        if one is not None and v.get("rsat_min_study") else None)
    low = min(timed, key=lambda st: timed[st]["rsat"]) if timed else None
    v["rsat_min_all"] = timed[low]["rsat"] if low else None
    v["rsat_min_all_study"] = low

    figure(v, draw, studies, args.out)
    c.atomic_write_text(args.out / f"{NAME}_table.html", table_html(v, groups, studies))
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
