#!/usr/bin/python3
"""The smallest text of each figure as the report page would show it, from OUT/layout/*.json.

    /usr/bin/python3 reports/dev/text_sizes.py OUT [--wide-px 1300] [--narrow-px 700]

A development aid for figure scripts, before the page check in Chromium
(reports/site/check_pages.py) measures the widths the page really gives: a figure registered
`wide` (data/thesis/figures.toml) is assumed shown --wide-px CSS pixels wide, any other
--narrow-px, never wider than its PNG. Displayed pt = font pt x shown px / (96 x width_in).
Figures below 8 pt are listed first.
"""
from __future__ import annotations

import argparse
import json
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--wide-px", type=float, default=1300)
    ap.add_argument("--narrow-px", type=float, default=700)
    args = ap.parse_args()
    registry = tomllib.loads((REPO / "data" / "thesis" / "figures.toml").read_text())
    # a script's images: <script>.png, or the `images` it declares (Path(...).stem per PNG)
    wide = {Path(img).stem for f in registry["figure"] if f.get("wide")
            for img in f.get("images", [f"{f['script']}.png"])}
    rows = []
    for p in sorted((args.out / "layout").glob("*.json")):
        lay = json.loads(p.read_text())
        if lay["text_min_pt"] is None:
            continue
        png_px = lay["width_in"] * lay["dpi"]
        shown = min(png_px, args.wide_px if p.stem in wide else args.narrow_px)
        pt = lay["text_min_pt"] * shown / (96 * lay["width_in"])
        smallest = ", ".join(f"{s['text']!r} {s['pt']:g}" for s in lay["smallest"][:3])
        rows.append((pt, p.stem, lay["width_in"], smallest))
    for pt, name, width, smallest in sorted(rows):
        print(f"{'TOO SMALL' if pt < 8 else 'ok':9s} {pt:5.1f} pt  {name:20s} {width:5.1f} in  {smallest}")
    return 1 if any(r[0] < 8 for r in rows) else 0


if __name__ == "__main__":
    raise SystemExit(main())
