"""MuJoCo's BigANT as the referee on §5.2's slope and stairs (Figs. 5.2, 5.3).

Input: DATA/ch5_terrain/referee.csv (kind peer_terrain, studies/ch5_terrain/referee.toml): per
point one terrain scene walked by our model under both laws (source ours_viscous, ours_coulomb)
and by MuJoCo (source mujoco), a row per sample: t, x, y (the plane's coordinates on a slope, the
world's on stairs), bx, by, bz (the body origin in the world), pitch (nose up, rad; relative to
the slope's plane, world on stairs), contacts; per point a label (base, or the check it runs).

overlay() draws MuJoCo's body path on a side-view panel; values() measures, for every label and
source, what the thesis' figures show: progress along the uphill (rising) direction per gait
cycle, height gained per cycle, the largest slide back, the mean pitch against the ground's slope,
the share of MuJoCo's steps with a foot on a tread's edge or a riser (ours has neither), and
whether the run climbs: progress and height gain in every whole cycle, a slide back of at most
BACKSLIDE_LIMIT of the run's own mean progress per cycle. Keys are prefixed `mujoco_`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

import common as c

STUDY = "ch5_terrain"
FILE = "referee.csv"
LABEL = "MuJoCo (dynamic, soft contact)"
STYLE = {"color": "tab:green", "ls": "--", "lw": 1.6}
# The check whose MuJoCo feet are ours' (no creep in stick, rigid sideways), drawn beside the base.
STRICT = "noslip_stiff_xy"
STRICT_LABEL = "MuJoCo, no-slip solver and stiff legs"
STRICT_STYLE = {"color": "tab:green", "ls": ":", "lw": 1.6}
SOURCES = {"mujoco": "peer", "ours_coulomb": "coulomb", "ours_viscous": "viscous"}
COLUMNS = ["scene", "label", "source", "heading_deg", "ground_slope_deg", "frequency", "t", "x",
           "y", "bx", "by", "bz", "pitch"]
BACKSLIDE_LIMIT = 0.1  # of the run's mean progress per cycle
PITCH_TOL_DEG = 5.0    # stairs: the body's mean pitch within this of the stairs' slope
AGREE_REL = 0.3        # MuJoCo's mean progress per cycle within this share of ours


def load(data: Path) -> c.Table | None:
    """The referee's table, or None when the study has not written it (the figures then show
    ours alone and record mujoco_available = false)."""
    path = Path(data) / STUDY / FILE
    if not path.is_file():
        return None
    t = c.Table(path, COLUMNS)
    return t if t.n else None


def run(table: c.Table, scene: str, label: str = "base", source: str = "mujoco") -> c.Table | None:
    """The rows of one run, in time order, without the NaN row of a build without MuJoCo."""
    on = ((table.str("scene") == scene) & (table.str("label") == label)
          & (table.str("source") == source) & np.isfinite(table["t"]))
    if np.count_nonzero(on) < 2:
        return None
    sub = table.subset(on)
    order = np.argsort(sub["t"], kind="stable")
    return sub.subset(order)


def overlay(ax, table: c.Table | None, scene: str, legend_loc: str = "upper left") -> bool:
    """MuJoCo's body path (bx, bz) of the base run and of the STRICT check on a side-view panel,
    the panel's legend (if it has one) drawn again to name them; False if there is no base run."""
    r = run(table, scene) if table is not None else None
    if r is None:
        return False
    # Keep the panel's frame (ours and the ground): a path that leaves it is cut at the frame's
    # edge and its end is written in the corner.
    ax.apply_aspect()
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    ends = []
    for path, label, style in ((r, LABEL, STYLE), (run(table, scene, STRICT), STRICT_LABEL,
                                                    STRICT_STYLE)):
        if path is None:
            continue
        ax.plot(path["bx"], path["bz"], label=label, **style)
        x, z = float(path["bx"][-1]), float(path["bz"][-1])
        if not (xlim[0] <= x <= xlim[1] and ylim[0] <= z <= ylim[1]):
            ends.append(f"{label}: ends at ({x:.2f}, {z:.2f}) m, outside the frame")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    if ends:
        ax.text(0.98, 0.02, "\n".join(ends), transform=ax.transAxes, ha="right", va="bottom",
                fontsize=8, color=STYLE["color"])
    if ax.get_legend() is not None:
        ax.legend(loc=legend_loc)
    return True


def measure(r: c.Table) -> dict:
    """What the thesis' figures show, measured on one run (see the module's head)."""
    psi = np.radians(float(r["heading_deg"][0]))
    period = 1.0 / float(r["frequency"][0])
    s = r["x"] * np.cos(psi) + r["y"] * np.sin(psi)
    t = r["t"]
    n = int(np.floor((t[-1] - t[0]) / period + 1e-9))
    out: dict = {"cycles": n}
    back = float(np.max(np.maximum.accumulate(s) - s))
    out["max_backslide_m"] = back
    out["mean_pitch_deg"] = float(np.degrees(np.mean(r["pitch"])))
    out["ground_slope_deg"] = float(r["ground_slope_deg"][0])
    out["pitch_minus_ground_deg"] = out["mean_pitch_deg"] - out["ground_slope_deg"]
    if "edge_share" in r.columns:  # MuJoCo: steps with a foot on a tread's edge or a riser
        out["edge_share"] = float(r["edge_share"][0])
    if n < 1:
        return out
    ends = t[0] + np.arange(n + 1) * period
    prog = np.diff(np.interp(ends, t, s))
    gain = np.diff(np.interp(ends, t, r["bz"]))
    out["progress_per_cycle_m"] = float(np.mean(prog))
    out["progress_per_cycle_min_m"] = float(np.min(prog))
    out["height_gain_per_cycle_m"] = float(np.mean(gain))
    out["height_gain_per_cycle_min_m"] = float(np.min(gain))
    out["max_backslide_rel_progress"] = (back / out["progress_per_cycle_m"]
                                         if out["progress_per_cycle_m"] > 0 else None)
    out["climbs"] = bool(np.min(prog) > 0 and np.min(gain) > 0
                         and back <= BACKSLIDE_LIMIT * out["progress_per_cycle_m"])
    return out


CHECKS = ("noslip", "stiff_xy", "noslip_stiff_xy", "slow", "light")
# The runs referee.toml makes per scene (label: sources), and what measure() returns for each:
# every one of these keys is written, None with a <key>_reason where it could not be measured.
RUNS = {"base": ("peer", "coulomb", "viscous"), "slow": ("peer", "coulomb", "viscous"),
        **{label: ("peer",) for label in CHECKS if label != "slow"}}
MEASURES = ("cycles", "max_backslide_m", "mean_pitch_deg", "ground_slope_deg",
            "pitch_minus_ground_deg", "edge_share", "progress_per_cycle_m",
            "progress_per_cycle_min_m", "height_gain_per_cycle_m", "height_gain_per_cycle_min_m",
            "max_backslide_rel_progress", "climbs")
NO_RUN = ("no referee run with a whole gait cycle (studies/ch5_terrain/referee.toml): not run, a "
          "quick run, or a build without MuJoCo")


def values(table: c.Table | None, scene: str, stairs: bool = False, prefix: str = "mujoco") -> dict:
    """<prefix>_<label>_<peer|coulomb|viscous>_<measure> for every run of the scene, and the
    comparisons of each MuJoCo run with ours (Coulomb: the law that climbs in Figs. 5.2-5.3):
    <prefix>_agrees_with_ours for the base, <prefix>_<label>_agrees for the checks. Every key is
    written; one that could not be measured is None and has a <key>_reason (the ledger's rule)."""
    out = _values(table, scene, stairs)
    expected = [f"mujoco_{label}_{short}_{m}" for label, shorts in RUNS.items()
                for short in shorts for m in MEASURES]
    expected += ["mujoco_progress_ratio", "mujoco_agrees_with_ours"]
    expected += ["mujoco_pitch_follows_stairs"] if stairs else []
    expected += [f"mujoco_{label}_{k}" for label in CHECKS for k in ("progress_ratio", "agrees")]
    for key in expected:
        if out.get(key) is None:
            out[key] = None
            out[key + "_reason"] = NO_RUN
    return {k.replace("mujoco", prefix, 1): v for k, v in out.items()}


def _agrees(out: dict, label: str, stairs: bool) -> bool | None:
    peer = out.get(f"mujoco_{label}_peer_progress_per_cycle_m")
    ours = out.get(f"mujoco_{label}_coulomb_progress_per_cycle_m",
                   out.get("mujoco_base_coulomb_progress_per_cycle_m"))
    if peer is None or ours is None:
        return None
    ok = out[f"mujoco_{label}_peer_climbs"] and abs(peer - ours) <= AGREE_REL * abs(ours)
    if stairs:
        ok = ok and abs(out[f"mujoco_{label}_peer_pitch_minus_ground_deg"]) <= PITCH_TOL_DEG
    return bool(ok)


def _values(table: c.Table | None, scene: str, stairs: bool) -> dict:
    out: dict = {"mujoco_available": False, "mujoco_backslide_limit_rel": BACKSLIDE_LIMIT,
                 "mujoco_pitch_tol_deg": PITCH_TOL_DEG, "mujoco_agree_rel": AGREE_REL}
    if table is None:
        return out
    on = table.str("scene") == scene
    for label in sorted(set(table.str("label")[on])):
        for source, short in SOURCES.items():
            r = run(table, scene, label, source)
            if r is None:
                continue
            for key, v in measure(r).items():
                out[f"mujoco_{label}_{short}_{key}"] = v
    peer = out.get("mujoco_base_peer_progress_per_cycle_m")
    ours = out.get("mujoco_base_coulomb_progress_per_cycle_m")
    if peer is None or ours is None:
        return out
    out["mujoco_available"] = True
    out["mujoco_progress_ratio"] = peer / ours if ours else None
    if stairs:
        dev = out["mujoco_base_peer_pitch_minus_ground_deg"]
        out["mujoco_pitch_follows_stairs"] = bool(abs(dev) <= PITCH_TOL_DEG)
    out["mujoco_agrees_with_ours"] = _agrees(out, "base", stairs)
    # Each check: MuJoCo's progress per cycle over ours (the slow run's over ours at its own
    # frequency), and whether it meets the base's criterion.
    for label in CHECKS:
        p = out.get(f"mujoco_{label}_peer_progress_per_cycle_m")
        o = out.get(f"mujoco_{label}_coulomb_progress_per_cycle_m", ours)
        if p is not None and o:
            out[f"mujoco_{label}_progress_ratio"] = p / o
            out[f"mujoco_{label}_agrees"] = _agrees(out, label, stairs)
    return out
