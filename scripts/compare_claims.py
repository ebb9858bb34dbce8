#!/usr/bin/python3
"""Compare the claims ledger's verdicts of two report builds.

    scripts/compare_claims.py OLD/reports/out/values/claims.json NEW/reports/out/values/claims.json

Each file is a report build's values/claims.json (reports/site/build_report.py writes it: per
ledger entry its id, verdict, our value and the rest). Prints every entry whose verdict differs,
every entry only one of them has, and a count per verdict for each; with --values also every entry
whose value moved by more than --rtol (relative). Exit 0 when every verdict is the same and no
entry is missing from either side, 1 otherwise, 2 for bad input. A timing entry (a verdict that
depends on the machine) can differ between two runs on a shared machine: the report says which,
by its id, so that a reader can judge.

Only the standard library.
"""
import argparse
import collections
import json
import math
import sys


def fail(message):
    print(f"compare_claims.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            entries = json.load(f)
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    except json.JSONDecodeError as e:
        fail(f"{path}:{e.lineno}:{e.colno}: not JSON: {e.msg}")
    if not isinstance(entries, list) or not all(isinstance(e, dict) and "id" in e
                                                 for e in entries):
        fail(f"{path}: expected a list of ledger entries with an id each")
    by_id = {}
    for e in entries:
        if e["id"] in by_id:
            fail(f"{path}: entry {e['id']} appears twice")
        by_id[e["id"]] = e
    return by_id


def moved(a, b, rtol):
    if not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in (a, b)):
        return a != b
    if math.isnan(a) and math.isnan(b):
        return False
    return abs(a - b) > rtol * max(abs(a), abs(b), 1e-300)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old", help="the earlier build's values/claims.json")
    p.add_argument("new", help="the later build's values/claims.json")
    p.add_argument("--values", action="store_true", help="also list values that moved")
    p.add_argument("--rtol", type=float, default=1e-6, help="relative change that counts (1e-6)")
    args = p.parse_args()
    old, new = load(args.old), load(args.new)

    changed = [i for i in old if i in new and old[i].get("verdict") != new[i].get("verdict")]
    only_old = sorted(set(old) - set(new))
    only_new = sorted(set(new) - set(old))
    for i in changed:
        print(f"verdict  {i}: {old[i].get('verdict')} -> {new[i].get('verdict')} "
              f"(ours {old[i].get('ours')} -> {new[i].get('ours')})")
    for i in only_old:
        print(f"gone     {i} ({old[i].get('verdict')})")
    for i in only_new:
        print(f"new      {i} ({new[i].get('verdict')})")
    if args.values:
        for i in sorted(set(old) & set(new)):
            if moved(old[i].get("ours"), new[i].get("ours"), args.rtol):
                print(f"value    {i}: {old[i].get('ours')} -> {new[i].get('ours')}")
    for name, side in (("old", old), ("new", new)):
        counts = collections.Counter(e.get("verdict") for e in side.values())
        print(f"{name}: {len(side)} entries; " +
              ", ".join(f"{v}: {n}" for v, n in sorted(counts.items(), key=str)))
    same = not changed and not only_old and not only_new
    print("same verdicts" if same else
          f"{len(changed)} verdicts differ, {len(only_old)} gone, {len(only_new)} new")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
