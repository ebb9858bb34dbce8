"""The claims ledger: values measured by the figure scripts, and the verdict of each claim.

A claim compares `ours` (value keys `script.name`) with the thesis' number by a rule; the verdict
is computed, never typed (data/thesis/claims.toml, its header states the rules). A failed claim is
"differs — explained" only when its `check` names values that hold the result of the check behind
the explanation; otherwise its cause is unknown and the explanation is shown as a hypothesis.
A claim no study of ours covers yet is "not covered yet" (compare = "not_covered"): its note says
which study will cover it.
"""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))
import common as c  # noqa: E402

EXPLAINED = "differs — explained"
CAUSE_UNKNOWN = "differs — cause unknown"
NEEDS_DATA = "needs data we do not have"
NOT_COVERED = "not covered yet"
VERDICT_CLASS = {
    "reproduced": "ok",
    EXPLAINED: "explained",
    CAUSE_UNKNOWN: "unknown",
    NEEDS_DATA: "nodata",
    NOT_COVERED: "notcovered",
    "not measured": "bad",
}
# The thesis value of a check of our own (an invariant or cross-check the thesis states no number
# or statement for); the page lists those apart.
NOT_GIVEN = "not given"


class Values:
    def __init__(self, folder: Path):
        self.by_script: dict[str, dict] = {}
        for p in sorted(folder.glob("*.json")):
            self.by_script[p.stem] = json.loads(p.read_text())
        self.missing: list[str] = []

    def has(self, key: str) -> bool:
        script, _, name = key.partition(".")
        return name in self.by_script.get(script, {})

    def get(self, key: str):
        script, _, name = key.partition(".")
        if script not in self.by_script or name not in self.by_script[script]:
            self.missing.append(key)
            return None
        return self.by_script[script][name]


def fmt_value(v, spec: str | None = None) -> str:
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, list):
        return "[" + ", ".join(fmt_value(x, spec) for x in v) + "]"
    if isinstance(v, (int, float)):
        if spec:
            try:
                return format(v, spec)
            except (ValueError, TypeError):
                pass
        return c.fmt(v, 4)
    return str(v)


TEMPLATE = re.compile(r"\{([a-z0-9_]+)\.([^{}:]+)(?::([^{}]*))?\}")


def render(text: str, values: Values) -> str:
    def sub(mt):
        key = f"{mt.group(1)}.{mt.group(2)}"
        if not values.has(key):
            values.missing.append(key)
            return f"[missing {key}]"
        return fmt_value(values.get(key), mt.group(3))

    return TEMPLATE.sub(sub, text or "")


def compare(rule: str, ours: float, target: float, tol: float) -> bool:
    if rule == "at_least":
        return ours >= target - tol
    if rule == "at_most":
        return ours <= target + tol
    if rule == "abs_tol":
        return abs(ours - target) <= tol
    if rule == "rel_tol":
        return abs(ours - target) <= tol * abs(target)
    raise ValueError(f"unknown compare rule '{rule}'")


def is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def evaluate(claim: dict, values: Values) -> dict:
    """The verdict of one ledger entry, computed from the values."""
    cid = claim.get("id", "?")
    rule = claim.get("compare")
    keys = claim.get("ours")
    res = {"id": cid, "ours": None, "reason": ""}
    if isinstance(keys, list):
        got = [values.get(k) for k in keys]
        agg = claim.get("aggregate")
        if agg in ("min", "max"):
            nums = [g for g in got if is_number(g)]
            res["ours"] = (min(nums) if agg == "min" else max(nums)) if nums else None
        elif agg is None:
            res["ours"] = got
        else:
            raise ValueError(f"claim {cid}: unknown aggregate '{agg}'")
    elif isinstance(keys, str):
        res["ours"] = values.get(keys)
    elif keys is not None:
        raise ValueError(f"claim {cid}: 'ours' must be a key or a list of keys")

    if rule == "needs_data":
        res["verdict"] = NEEDS_DATA
        return res
    if rule == "not_covered":
        # No study of ours covers the claim yet; the note must say which one will.
        if not claim.get("note"):
            raise ValueError(f"claim {cid}: compare = 'not_covered' needs a note naming the study "
                             "that will cover it")
        res["verdict"] = NOT_COVERED
        return res
    if keys is None:
        raise ValueError(f"claim {cid}: 'ours' is required with compare = '{rule}'")
    ours = res["ours"]
    missing = [k for k in (keys if isinstance(keys, list) else [keys]) if not values.has(k)]
    if missing:
        res["verdict"] = "not measured"
        res["reason"] = "no value " + ", ".join(missing)
        return res
    if ours is None or (isinstance(ours, list) and any(o is None for o in ours)):
        reasons = [values.get(k + "_reason") for k in (keys if isinstance(keys, list) else [keys])
                   if values.has(k + "_reason")]
        res["verdict"] = "not measured"
        res["reason"] = "; ".join(str(r) for r in reasons) or "the script could not measure it"
        return res

    if rule == "is_true":
        ok = ours is True
    else:
        target = claim.get("target", claim.get("thesis"))
        tol = float(claim.get("tol", 0.0))
        if isinstance(ours, list):
            if not isinstance(target, list) or len(target) != len(ours):
                raise ValueError(f"claim {cid}: a list in 'ours' needs a list target of equal "
                                 "length (or an aggregate)")
            ok = all(compare(rule, float(o), float(tg), tol) for o, tg in zip(ours, target))
        else:
            if not is_number(target):
                raise ValueError(f"claim {cid}: compare '{rule}' needs a numeric target")
            if not is_number(ours):
                raise ValueError(f"claim {cid}: value {keys} is not a number: {ours!r}")
            ok = compare(rule, float(ours), float(target), tol)
    res["verdict"] = "reproduced" if ok else differs_verdict(claim, values, res)
    return res


def check_keys(claim: dict) -> list[str]:
    """The value keys a claim's `check` names (the result of the check behind its explanation)."""
    check = claim.get("check")
    if check is None:
        return []
    keys = [check] if isinstance(check, str) else check
    if not isinstance(keys, list) or not keys or not all(isinstance(k, str) for k in keys):
        raise ValueError(f"claim {claim.get('id')}: 'check' must be a value key or a list of them")
    if not claim.get("explanation"):
        raise ValueError(f"claim {claim.get('id')}: a 'check' needs the 'explanation' it supports")
    return keys


def differs_verdict(claim: dict, values: Values, res: dict) -> str:
    """A failed comparison is explained only when the explanation names a check that was run and
    whose result is in the values; otherwise its cause is unknown (the explanation, if any, is a
    hypothesis)."""
    keys = check_keys(claim)
    res["check"] = keys
    if not keys:
        return CAUSE_UNKNOWN
    missing = [k for k in keys if not values.has(k) or values.get(k) is None]
    if missing:
        res["reason"] = "the check's value is missing: " + ", ".join(missing)
        return CAUSE_UNKNOWN
    return EXPLAINED
