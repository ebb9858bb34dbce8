"""Shared helpers of the walking-robot figures (thesis §3.5, Figs. 3.5-3.12).

Their data live in DATA/ch3_robots/<run>.csv (`slipwalk reproduce ch3_robots`: one scene run
each, the columns of `slipwalk run`, scene/run_writer.hpp) with a sidecar naming the scene,
walker and legs. Every run is synthetic: the thesis' motion capture and F/T data are not ours.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

import common as c

STUDY = "ch3_robots"


class Run:
    """One scene run: its table, sidecar and leg names."""

    def __init__(self, data: Path, name: str):
        path = data / STUDY / f"{name}.csv"
        if not path.is_file():
            c.fail(f"{path}: input file missing (run `slipwalk reproduce {STUDY}` to produce it)")
        self.name = name
        self.t = c.Table(path, ["t", "x", "y", "theta", "vx", "vy", "omega", "alpha", "beta"])
        if self.t.n < 2:
            c.fail(f"{path}: fewer than two rows")
        side = path.with_suffix(".json")
        try:
            self.meta = json.loads(side.read_text()) if side.is_file() else {}
        except json.JSONDecodeError as e:
            c.fail(f"{side}: not valid JSON: {e}")
        self.legs = list(self.meta.get("legs") or [])
        if not self.legs:
            self.legs = [col[len("contact_"):] for col in self.t.columns
                         if col.startswith("contact_")]
        self.time = self.t["t"]
        self.dt = float(self.time[1] - self.time[0])

    def __getitem__(self, col: str) -> np.ndarray:
        return self.t[col]

    def leg(self, what: str, leg: str) -> np.ndarray:
        return self.t[f"{what}_{leg}"]

    def roll_pitch_deg(self) -> tuple[np.ndarray, np.ndarray]:
        """Roll and pitch of the body over the support plane of eq. 3.6, in degrees: a foot's
        height is -beta q_x + alpha q_y + q_z + z, so the ground tilts by atan(alpha) about x and
        atan(beta) about y in the body frame."""
        return np.degrees(np.arctan(self["alpha"])), np.degrees(np.arctan(self["beta"]))

    def quick(self) -> bool:
        return bool(self.meta.get("quick", False))


# MuJoCo's BigANT driven by our feet stands in for the robot where the thesis drew motion capture
# and F/T data (§3.5.4): the base runs of studies/ch3_peer/fig3_14.toml (same gait, K, μ as these
# scenes), drawn in common.MUJOCO (not the thesis' red: it is not a measurement).
STANDIN = " (stand-in for the measured robot)"


def mujoco_label(peer: str | None) -> str:
    """The peer's name and version as the data name it ("mujoco 2.2.2" -> "MuJoCo 2.2.2")."""
    peer = str(peer or "mujoco").strip()
    return "MuJoCo" + peer[len("mujoco"):] if peer.lower().startswith("mujoco") else peer


LEG_COLUMNS = ("contact", "Fz", "Fx", "Fy", "slip_x", "slip_y")
MUJOCO_MISSING = ("no MuJoCo data (a build without MuJoCo, `slipwalk reproduce ch3_peer` not run, "
                  "or a fig3_14.csv without per-leg columns): the MuJoCo overlay is skipped")
MUJOCO_MISSING_TITLE = "no MuJoCo data (see the values): its lines are left out"


def body_velocity(t, x, y, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """vx, vy (body frame) and omega by central differences of sampled poses."""
    dx, dy = np.gradient(x, t), np.gradient(y, t)
    cth, sth = np.cos(theta), np.sin(theta)
    return cth * dx + sth * dy, -sth * dx + cth * dy, np.gradient(theta, t)


def mujoco_runs(data: Path, gait: str, label: str) -> list[dict]:
    """Every MuJoCo point of `gait` in block `label` of DATA/ch3_peer/fig3_14.csv, one dict per
    point id as mujoco_as_measured's plus its solref_timeconst, timestep and mu; [] when absent."""
    path = data / "ch3_peer" / "fig3_14.csv"
    if not path.is_file():
        return []
    t = c.Table(path, ["id", "gait", "source", "label", "t", "peer"])
    on = ((t.str("gait") == gait) & (t.str("source") == "mujoco") & (t.str("label") == label)
          & np.isfinite(t["t"]))
    runs = []
    for point in sorted(set(t.str("id")[on])):
        m = _mujoco_run(t, on & (t.str("id") == point))
        if m is not None:
            m.update({k: float(t[k][on & (t.str("id") == point)][0])
                      for k in ("solref_timeconst", "timestep", "mu")})
            runs.append(m)
    return runs


def _mujoco_run(t: c.Table, on: np.ndarray) -> dict | None:
    if np.count_nonzero(on) < 3:
        return None
    order = np.argsort(t["t"][on])
    m = {k: t[k][on][order] for k in ("t", "x", "y", "theta")}
    m["vx"], m["vy"], m["omega"] = body_velocity(m["t"], m["x"], m["y"], m["theta"])
    m["label"] = mujoco_label(t.str("peer")[on][0])
    names = [col[len("Fz_"):] for col in t.columns if col.startswith("Fz_")]
    names = [leg for leg in names if all(f"{w}_{leg}" in t.columns for w in LEG_COLUMNS)]
    if names:
        m["legs"] = {leg: {w: t[f"{w}_{leg}"][on][order] for w in LEG_COLUMNS} for leg in names}
    return m


def mujoco_as_measured(data: Path, gait: str) -> dict | None:
    """MuJoCo's base run of `gait` from DATA/ch3_peer/fig3_14.csv: t, x, y, theta and the body
    velocity (vx, vy in the body frame, omega) by central differences of the sampled poses, and
    "label", the peer's name and version as the data give it ("MuJoCo 2.2.2"); with per-leg
    columns (sweeps/points/peer_bigant.cpp) also "legs": {leg: {contact, Fz, Fx, Fy, slip_x,
    slip_y}} (forces of the floor on the foot, N, and the foot's velocity over the floor,
    m/s, body frame, as our runs' columns). None when the file or its MuJoCo rows are missing (a
    build without MuJoCo, or ch3_peer not run)."""
    path = data / "ch3_peer" / "fig3_14.csv"
    if not path.is_file():
        return None
    t = c.Table(path, ["gait", "source", "label", "t", "x", "y", "theta", "peer"])
    on = ((t.str("gait") == gait) & (t.str("source") == "mujoco") & (t.str("label") == "base")
          & np.isfinite(t["t"]))
    return _mujoco_run(t, on)


def mujoco_feet(mj: dict | None, legs: list[str]) -> dict | None:
    """MuJoCo's per-leg columns for our leg names, None when absent (an older fig3_14.csv)."""
    if mj is None or "legs" not in mj or any(leg not in mj["legs"] for leg in legs):
        return None
    return mj["legs"]


def mujoco_until(mj: dict | None, t_end: float) -> dict | None:
    """MuJoCo's samples up to t_end (our run's last frame), None when fewer than three remain."""
    if mj is None:
        return None
    on = mj["t"] <= t_end + 1e-9
    if np.count_nonzero(on) < 3:
        return None
    out = {k: v[on] for k, v in mj.items() if k not in ("legs", "label")}
    out["label"] = mj["label"]
    if "legs" in mj:
        out["legs"] = {leg: {w: a[on] for w, a in cols.items()} for leg, cols in mj["legs"].items()}
    return out


def nearest(run: Run, col: str, times: np.ndarray) -> np.ndarray:
    """Our run's column at the sample nearest each time (our frames include MuJoCo's sample
    times: both step from t = 0 on grids that divide 0.1 s)."""
    i = np.clip(np.round(np.interp(times, run.time, np.arange(run.t.n))).astype(int), 0,
                run.t.n - 1)
    return run[col][i]


def velocity_at(run: Run, times: np.ndarray) -> dict:
    """Our body velocity at MuJoCo's sample times, by the same central differences of the poses
    at those times as MuJoCo's (so both are smoothed alike)."""
    x, y, th = (nearest(run, k, times) for k in ("x", "y", "theta"))
    vx, vy, om = body_velocity(times, x, y, th)
    return {"vx": vx, "vy": vy, "omega": om}


def rms(x: np.ndarray) -> float:
    x = np.asarray(x, float)
    return float(np.sqrt(np.mean(x * x))) if x.size else float("nan")


def mg(run: Run) -> np.ndarray:
    """Mg per frame: the normal loads sum to the weight (eq. 3.7)."""
    return np.sum([run.leg("Fz", leg) for leg in run.legs], axis=0)


def planar(run: Run) -> tuple[np.ndarray, np.ndarray]:
    """(frames x legs) F_x and F_y of every leg."""
    fx = np.stack([run.leg("Fx", leg) for leg in run.legs], axis=1)
    fy = np.stack([run.leg("Fy", leg) for leg in run.legs], axis=1)
    return fx, fy


def sigma(pred_x, pred_y, ref_x, ref_y) -> np.ndarray:
    """The thesis' per-frame scale (§3.5.1.4): sigma = argmin_c sum_k (c|F^_k| - |F_k|)^2 =
    sum |F^||F| / sum |F^|^2, because the model defines the forces up to a positive factor.
    Here the reference is the Coulomb run (the thesis': the F/T measurements)."""
    a = np.hypot(pred_x, pred_y)
    b = np.hypot(ref_x, ref_y)
    den = np.sum(a * a, axis=1)
    return np.where(den > 0, np.sum(a * b, axis=1) / np.where(den > 0, den, 1.0), 0.0)


def flat_zero(ax, y, unit: str, what: str = "mirror-symmetric gait") -> None:
    """A signal that is zero to rounding: say so rather than plot 1e-17 noise at full scale."""
    lim = float(np.max(np.abs(y))) if np.size(y) else 0.0
    if lim < 1e-9:
        ax.set_ylim(-1.0, 1.0)
        ax.text(0.5, 0.75, f"≡ 0 to rounding ({lim:.0e} {unit}): {what}",
                transform=ax.transAxes, ha="center", color="0.3")
