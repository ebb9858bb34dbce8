#!/usr/bin/python3
"""Compare two builds' Google Benchmark binaries, or their timed studies, on a shared, noisy machine.

Runs binary A and binary B alternately, ROUNDS times each (A B A B ...), so that a change in the
machine's load falls on both, and prints per benchmark the smallest and the median CPU time of
each and their ratios B ÷ A. Other processes only add time, so the ratio of the smallest times is
the estimate to quote; the medians say how wide the spread was. A ratio below 1 means B is faster.

    scripts/bench_ab.py build-old/bin/bench_friction build/bin/bench_friction \\
        --filter 'BM_ModelViscous/(6|50)$' --rounds 8

With --sweep SPEC the binaries are two builds' `slipwalk`: each round runs `slipwalk sweep SPEC
--jobs 1` into a fresh data folder, and each row of the CSV it writes is a benchmark, named by the
--key columns and timed by the --time column (a timed study such as
studies/ch3_legged/cost_scaling.toml, whose time_ns is its median over repeats):

    scripts/bench_ab.py old/bin/slipwalk build/bin/slipwalk --rounds 15 \\
        --sweep studies/ch3_legged/cost_scaling.toml --key robot,sequence,N,method,tol

The times are thread CPU times as Google Benchmark reports them (cpu_time), or as the study
writes them. Only the standard library: no packages beyond python3.
"""
import argparse
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile


def fail(message, code=2):
    """Exit 2 for bad usage or input, 1 when a benchmark run itself failed."""
    print(f"bench_ab.py: error: {message}", file=sys.stderr)
    sys.exit(code)


def run_once(binary, pattern, min_time):
    """One run of `binary`: {benchmark name: cpu time in ns}."""
    command = [binary, f"--benchmark_filter={pattern}", f"--benchmark_min_time={min_time}",
               "--benchmark_format=json"]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        fail(f"{binary} exited with {done.returncode}: {done.stderr.strip()[-300:]}", code=1)
    if not done.stdout.strip():
        return {}  # no benchmark matched the filter
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError as e:
        fail(f"{binary}: its output is not Google Benchmark JSON ({e})", code=1)
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
    times = {}
    for b in report.get("benchmarks", []):
        if b.get("run_type", "iteration") != "iteration":
            continue  # aggregates of --benchmark_repetitions: the rounds here are the repeats
        times[b["name"]] = b["cpu_time"] * scale[b.get("time_unit", "ns")]
    return times


def run_sweep(binary, spec, key, column):
    """One `slipwalk sweep` of `spec` by `binary` on one thread: {row name: time in ns}."""
    data = tempfile.mkdtemp(prefix="bench_ab_")
    try:
        done = subprocess.run([binary, "sweep", spec, "--data", data, "--jobs", "1"],
                              capture_output=True, text=True, check=False)
        if done.returncode != 0:
            fail(f"{binary} sweep {spec} exited with {done.returncode}: "
                 f"{done.stderr.strip()[-300:]}", code=1)
        tables = [os.path.join(d, f) for d, _, files in os.walk(data) for f in files
                  if f.endswith(".csv")]
        if len(tables) != 1:
            fail(f"{binary} sweep {spec} wrote {len(tables)} CSV files, expected one", code=1)
        with open(tables[0], newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    finally:
        shutil.rmtree(data, ignore_errors=True)
    times = {}
    for row in rows:
        missing = [c for c in key + [column] if c not in row]
        if missing:
            fail(f"{spec}: the sweep's CSV has no column {', '.join(missing)} "
                 f"(it has {', '.join(row)})")
        name = "/".join(f"{c}={row[c]}" for c in key)
        if name in times:
            fail(f"{spec}: two rows are both {name}: add columns to --key")
        try:
            times[name] = float(row[column])
        except ValueError:
            fail(f"{spec}: row {name}: {column} is '{row[column]}', not a number", code=1)
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a", help="the reference benchmark binary, or slipwalk (A)")
    parser.add_argument("b", help="the binary to compare with it (B)")
    parser.add_argument("--filter", default=".", help="--benchmark_filter regex (default: all)")
    parser.add_argument("--rounds", type=int, default=6, help="runs of each binary (default 6)")
    parser.add_argument("--min-time", type=float, default=0.15,
                        help="--benchmark_min_time per benchmark and run, s (default 0.15)")
    parser.add_argument("--sweep", metavar="SPEC",
                        help="time the rows of `slipwalk sweep SPEC` instead of benchmarks")
    parser.add_argument("--key", default="id",
                        help="with --sweep: the CSV columns that name a row, comma-separated "
                             "(default id)")
    parser.add_argument("--time", default="time_ns",
                        help="with --sweep: the CSV column of a row's time in ns (default time_ns)")
    args = parser.parse_args()
    for name in (args.a, args.b):
        if not (os.path.isfile(name) and os.access(name, os.X_OK)):
            fail(f"{name}: not an executable file")
    if not 1 <= args.rounds <= 1000:
        fail(f"--rounds {args.rounds}: give 1 to 1000")
    if not 0.0 < args.min_time <= 60.0:
        fail(f"--min-time {args.min_time}: give a time in (0, 60] s")
    key = [c.strip() for c in args.key.split(",")]
    if args.sweep is not None:
        if not os.path.isfile(args.sweep):
            fail(f"--sweep {args.sweep}: not a file")
        if not all(key) or not args.time:
            fail(f"--key '{args.key}' / --time '{args.time}': give column names")

    def run(binary):
        if args.sweep is not None:
            return run_sweep(binary, args.sweep, key, args.time)
        return run_once(binary, args.filter, args.min_time)

    a_times, b_times = {}, {}
    for r in range(args.rounds):
        for binary, into in ((args.a, a_times), (args.b, b_times)):
            for name, t in run(binary).items():
                into.setdefault(name, []).append(t)
        print(f"round {r + 1}/{args.rounds}", file=sys.stderr)
    names = [n for n in a_times if n in b_times]
    if not names:
        what = f"row of {args.sweep}" if args.sweep else f"benchmark matching '{args.filter}'"
        fail(f"no {what} ran in both binaries")

    width = max(len(n) for n in names)
    print(f"{'benchmark':{width}}  {'A min':>9} {'A med':>9}  {'B min':>9} {'B med':>9}  "
          f"{'B/A min':>7} {'B/A med':>7}")
    for n in names:
        a_min, a_med = min(a_times[n]), statistics.median(a_times[n])
        b_min, b_med = min(b_times[n]), statistics.median(b_times[n])
        print(f"{n:{width}}  {a_min:9.1f} {a_med:9.1f}  {b_min:9.1f} {b_med:9.1f}  "
              f"{b_min / a_min:7.3f} {b_med / a_med:7.3f}")
    print(f"(ns of CPU time; {args.rounds} alternating runs of each binary)")


if __name__ == "__main__":
    main()
