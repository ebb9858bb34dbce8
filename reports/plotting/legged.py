"""Shared helpers of the chapter 3 report scripts (the multi-legged model).

Their data live in DATA/ch3_legged/ (`slipwalk reproduce ch3_legged`); the rest of the
conventions (values JSON, atomic PNGs, the ledger) are those of common.py.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

import common as c

STUDY = "ch3_legged"


def table(data: Path, name: str, required: list[str]) -> c.Table:
    """DATA/ch3_legged/<name>.csv with the required columns and at least one row."""
    path = data / STUDY / f"{name}.csv"
    if not path.is_file():
        c.fail(f"{path}: input file missing (run `slipwalk reproduce {STUDY}` to produce it)")
    t = c.Table(path, required)
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    return t


def sidecar(data: Path, name: str) -> dict:
    """The sweep's provenance sidecar (its expanded points are the inputs of each id)."""
    path = data / STUDY / f"{name}.json"
    if not path.is_file():
        c.fail(f"{path}: sidecar missing (run `slipwalk reproduce {STUDY}` to produce it)")
    try:
        return json.loads(path.read_text())
    except json.JSONDecodeError as e:
        c.fail(f"{path}: not valid JSON: {e}")


def point_inputs(meta: dict) -> dict[int, dict]:
    """id -> the point's input values."""
    return {int(p["id"]): p for p in meta.get("points", [])}


def quantiles(x: np.ndarray, qs=(10, 50, 90)) -> list[float | None]:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return [None for _ in qs]
    return [float(np.percentile(x, q)) for q in qs]
