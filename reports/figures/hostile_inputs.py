#!/usr/bin/python3
"""Stability: the hostile-input campaign, class by class.

Input: DATA/stability/hostile_inputs.csv (studies/stability/hostile_inputs.toml, point kind
hostile_inputs): per point, cases of one class generated from a seed, each run by the slipwalk
binary in a fresh temporary folder and judged against the command-line contract, with the counts
of each breach and the first bad case as a shell line that replays it.

Outputs: OUT/hostile_inputs_table.html (per class: what was generated, cases tried, crashes,
hangs, wrong exit codes, messages without a place, false successes, changed inputs, leftovers,
the first bad case) and OUT/values/hostile_inputs.json (the same counts, per class and in all).
"""
from __future__ import annotations

import csv
import html
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "hostile_inputs"
STUDY = "stability"
COUNTS = ["tried", "ok", "crashes", "hangs", "wrong_exit", "no_place", "false_success",
          "clobbered", "leftovers"]
BREACHES = COUNTS[2:]
HEAD = {"crashes": "crashes", "hangs": "hangs", "wrong_exit": "wrong exit codes",
        "no_place": "messages without a place", "false_success": "false successes",
        "clobbered": "changed inputs", "leftovers": "leftovers"}


def read_rows(path: Path) -> list[dict]:
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        c.fail(f"{path}: no data rows")
    missing = [k for k in ["class", "title", "what", "first", "first_failure", *COUNTS]
               if k not in rows[0]]
    if missing:
        c.fail(f"{path}: columns missing: {', '.join(missing)}")
    return rows


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    path = c.study_file(args.data, "hostile_inputs.csv", STUDY)
    rows = read_rows(path)
    classes: dict[str, dict] = {}
    for r in sorted(rows, key=lambda r: int(float(r["first"]))):
        k = classes.setdefault(r["class"], {"title": r["title"], "what": r["what"],
                                            "first_failure": "", **{n: 0 for n in COUNTS}})
        for n in COUNTS:
            k[n] += int(float(r[n]))
        if not k["first_failure"] and r["first_failure"]:
            k["first_failure"] = r["first_failure"]
    order = [r["class"] for r in rows]
    ids = sorted(classes, key=order.index)
    total = {n: sum(classes[i][n] for i in ids) for n in COUNTS}
    values: dict = {"classes": ids, "total": total, "all_clean": total["ok"] == total["tried"]}
    for i in ids:
        for n in COUNTS:
            values[f"{i}_{n}"] = classes[i][n]
    for n in COUNTS:
        values[n] = total[n]

    body = []
    for i in ids:
        k = classes[i]
        bad = k["tried"] - k["ok"]
        cells = "".join(f"<td class='{'bad' if k[n] else ''}'>{k[n]}</td>" for n in BREACHES)
        fail = (f"<code>{html.escape(k['first_failure'][:600])}</code>" if k["first_failure"]
                else "—")
        body.append(f"<tr class='{'bad' if bad else ''}'><td><b>{html.escape(i)}</b>: "
                    f"{html.escape(k['title'])}</td><td>{html.escape(k['what'])}</td>"
                    f"<td>{k['tried']}</td>{cells}<td>{fail}</td></tr>")
    cells = "".join(f"<td>{total[n]}</td>" for n in BREACHES)
    body.append(f"<tr><td><b>all</b></td><td></td><td>{total['tried']}</td>{cells}<td></td></tr>")
    head = "".join(f"<th>{HEAD[n]}</th>" for n in BREACHES)
    out = ("<table class='data'><thead><tr><th>class</th><th>what was generated</th>"
           f"<th>tried</th>{head}<th>first bad case (replay)</th></tr></thead><tbody>\n"
           + "\n".join(body) + "\n</tbody></table>\n"
           f"<p>Data: <code>{html.escape(c.shown_path(path))}</code>.</p>\n")
    c.atomic_write_text(args.out / f"{NAME}_table.html", out)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
