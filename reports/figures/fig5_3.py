#!/usr/bin/python3
"""Thesis Fig. 5.3 / §5.2.2: BigANT's tripod up stairs (tread 0.3 m, riser 0.12 m).

Input: DATA/ch5_terrain/stairs_{viscous,coulomb}.csv (the scene
studies/ch5_terrain/scenes/bigant_stairs.toml under both laws, the legs carrying the stairs
linkage of robots/bigant.hpp: `slipwalk run` columns plus the world positions bx, by, bz of the
body and px_L, py_L, pz_L of each toe before compression), stairs_flat_{viscous,coulomb}.csv
(bigant_stairs_flat.toml: riser 0, the flat reference of the same legs),
stairs_standard_{viscous,coulomb}.csv (bigant_stairs_standard.toml: the standard leg, lift 42 mm,
on the same stairs: the diagnosis), stairs_fine_{viscous,coulomb}.csv (bigant_stairs_fine.toml:
the standard leg on the same slope in steps below its lift, a check) and
stairs_flat_standard_{viscous,coulomb}.csv (their flat reference).
Output: OUT/fig5_3.png, OUT/values/fig5_3.json.

Panels (a, b), as in the thesis, per law: the stairs (gray), the body centre (black; the thesis
draws it red, a colour the report keeps for measured data) and the toes of FL, ML, HL (blue,
orange, purple; stance: stars, swing: lines) seen from the side. (c) the body's forward position
against time on the stairs with the stairs leg and with the standard leg, and on flat ground;
(d) its height, with the frames where it jumps by more than a tenth of the riser.

What the thesis' figure shows (its caption: "a trajectory of simulated BigAnt robot moving up
stairs"; the body path rises with the stairs while the toes step from tread to tread) is read as
a climb at the walking stride: every gait cycle gains at least PROGRESS_MIN_REL of the flat
stride along the stairs (the stance stroke runs along the pitched body, so a whole stride would be
cos γ of the flat one, 0.93 here), the body never slides back by more than a tenth of the flat
stride nor falls back in height by more than a tenth of the riser (a monotone climb), its height
has no frame-to-frame jump over a tenth of the riser, it gains height at the stairs' rate
(the least-squares slope of its height against its forward position within GAIN_TOL_REL of
riser/tread) and its mean pitch follows the
stairs' slope γ = atan(riser/tread) within PITCH_TOL_DEG. The values also record what jumps and
slides coincide with: a loaded toe changing tread (the quasi-static model has no riser walls: a
returning toe still below the next tread when it passes the tread's edge stands on it), and a toe
in contact during its return (shaft angle outside the stance sweep), and among those the toes
that cross an edge onto the higher tread while in contact (they passed the edge below that
tread) apart from those that land by coming down onto a tread before their stance sweep begins
(on stairs a tread can lie above the body's stance line, so the toe lands while its shaft still
swings it forward).
"""
from __future__ import annotations

import sys
from pathlib import Path

import json

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402
import terrain_peer as tp  # noqa: E402

NAME = "fig5_3"
STUDY = "ch5_terrain"
LEGS = {"FL": "tab:blue", "ML": "tab:orange", "HL": "tab:purple"}  # the thesis' colours
ALL_LEGS = ("HL", "ML", "FL", "HR", "MR", "FR")
BODY = "black"
LAWS = {"viscous": ("viscous-Coulomb", c.VISCOUS), "coulomb": ("Coulomb", c.COULOMB)}
BACKSLIDE_LIMIT = 0.1   # of the flat progress per cycle
JUMP_LIMIT = 0.1        # of the riser of the thesis' stairs, per frame
FALLBACK_LIMIT = 0.1    # of the riser: the most the body's height may fall below its highest
PROGRESS_MIN_REL = 0.8  # of the flat stride, the least forward progress in any gait cycle
GAIN_TOL_REL = 0.15     # relative, height gained per forward metre against riser/tread
PITCH_TOL_DEG = 2.0     # deg, the body's mean pitch against the stairs' slope
# Each run and the flat reference of its legs.
KINDS = {"": "flat", "standard": "flat_standard", "fine": "flat_standard"}


class Run:
    """One scene run on stairs: the table, its stairs and gait, and what the criteria measure."""

    def __init__(self, data: Path, name: str):
        path = c.study_file(data, f"{name}.csv", STUDY)
        cols = ["t", "x", "y", "theta", "beta", "bx", "by", "bz"]
        for leg in ALL_LEGS:
            cols += [f"px_{leg}", f"py_{leg}", f"pz_{leg}", f"contact_{leg}", f"Fz_{leg}",
                     f"phase_{leg}"]
        self.t = c.Table(path, cols)
        if self.t.n < 2:
            c.fail(f"{path}: fewer than two rows")
        side = path.with_suffix(".json")
        self.meta = json.loads(side.read_text()) if side.is_file() else {}
        scene = self.meta.get("scene", {})
        self.terrain = scene.get("terrain")
        if not self.terrain or self.terrain.get("kind") != "stairs":
            c.fail(f"{side}: the sidecar names no stairs terrain")
        gait = scene.get("gait", {})
        if "frequency" not in gait or "sweep" not in gait:
            c.fail(f"{side}: the sidecar names no gait frequency and sweep")
        self.period = 1.0 / float(gait["frequency"])
        self.sweep = float(gait["sweep"])  # turns of the shaft in stance, centred on φ = 0
        self.tread = float(self.terrain["tread"])
        self.riser = float(self.terrain["riser"])
        psi = np.radians(float(self.terrain.get("heading_deg", 0.0)))
        self.u = np.array([np.cos(psi), np.sin(psi)])
        self.s = self.t["bx"] * self.u[0] + self.t["by"] * self.u[1]  # forward along the stairs
        self.linkage = str(gait.get("linkage", "standard"))
        # The body's nose-up pitch in the world: the stairs' slope seen along its heading
        # (terrain::stair_pitch) less the support's δβ (column beta, nose-down positive, eq. 3.6).
        slope = np.arctan(self.riser / self.tread * np.cos(self.t["theta"] - psi))
        self.pitch = slope - self.t["beta"]

    def height(self, px, py):
        """h(p): the tread under a world point (terrain.hpp: an edge belongs to the upper tread)."""
        return self.riser * np.floor((px * self.u[0] + py * self.u[1]) / self.tread)

    def cycle_progress(self) -> np.ndarray:
        """Forward progress of the body in each whole gait cycle."""
        t = self.t["t"]
        n = int(np.floor(t[-1] / self.period + 1e-9))
        ends = np.interp(np.arange(n + 1) * self.period, t, self.s)
        return np.diff(ends)

    def backslide(self) -> float:
        """The largest distance the body falls back behind the farthest point it reached."""
        return float(np.max(np.maximum.accumulate(self.s) - self.s))

    def cycle_height_gain(self) -> np.ndarray:
        """Height gained by the body in each whole gait cycle."""
        t = self.t["t"]
        n = int(np.floor(t[-1] / self.period + 1e-9))
        return np.diff(np.interp(np.arange(n + 1) * self.period, t, self.t["bz"]))

    def height_fallback(self) -> float:
        """The largest distance the body's height falls below the highest it reached."""
        return float(np.max(np.maximum.accumulate(self.t["bz"]) - self.t["bz"]))

    def jumps(self) -> np.ndarray:
        return np.abs(np.diff(self.t["bz"]))

    def tread_change(self) -> np.ndarray:
        """Per frame step: some toe in contact (before or after) changes tread."""
        out = np.zeros(self.t.n - 1, dtype=bool)
        for leg in ALL_LEGS:
            h = self.height(self.t[f"px_{leg}"], self.t[f"py_{leg}"])
            on = self.t[f"contact_{leg}"] > 0.5
            out |= (np.diff(h) != 0) & (on[1:] | on[:-1])
        return out

    def edge_contact(self) -> np.ndarray:
        """Per frame step: some returning toe (shaft outside the stance sweep) crosses a tread's
        edge onto the higher tread and is in contact after it: it passed the edge below that
        tread and stands on it. A toe that lands by coming down onto a tread is not counted."""
        out = np.zeros(self.t.n - 1, dtype=bool)
        for leg in ALL_LEGS:
            phi = (self.t[f"phase_{leg}"] + 0.5) % 1.0 - 0.5
            returning = np.abs(phi) > self.sweep / 2 + 1e-9
            h = self.height(self.t[f"px_{leg}"], self.t[f"py_{leg}"])
            on = self.t[f"contact_{leg}"] > 0.5
            out |= (np.diff(h) > 0) & on[1:] & returning[1:]
        return out

    def returning_load_share(self) -> np.ndarray:
        """Per frame: the share of the weight carried by toes in their return."""
        total = np.zeros(self.t.n)
        returning = np.zeros(self.t.n)
        for leg in ALL_LEGS:
            phi = (self.t[f"phase_{leg}"] + 0.5) % 1.0 - 0.5
            fz = self.t[f"Fz_{leg}"]
            total += fz
            returning += np.where(np.abs(phi) > self.sweep / 2 + 1e-9, fz, 0.0)
        return returning / np.maximum(total, 1e-12)

    def returning_contact(self) -> np.ndarray:
        """Per frame: some toe is in contact while its shaft is in the return (outside the
        stance sweep |φ| ≤ sweep/2, φ = 0 mid-stance; robots/bigant.hpp)."""
        out = np.zeros(self.t.n, dtype=bool)
        for leg in ALL_LEGS:
            phi = (self.t[f"phase_{leg}"] + 0.5) % 1.0 - 0.5
            out |= (self.t[f"contact_{leg}"] > 0.5) & (np.abs(phi) > self.sweep / 2 + 1e-9)
        return out


def side_view(ax, run: Run, title: str, legend: bool):
    t = run.t
    lo = min(np.min(t[f"px_{leg}"]) for leg in ALL_LEGS) - 0.2
    hi = max(np.max(t[f"px_{leg}"]) for leg in ALL_LEGS) + 0.2
    xs = np.linspace(lo, hi, 2000)
    ax.fill_between(xs, run.height(xs, 0 * xs), run.height(lo, 0.0) - 0.1,
                    step="post", color="0.85", label=f"stairs {run.tread:g} m × {run.riser:g} m")
    ax.plot(t["bx"], t["bz"], color=BODY, lw=1.5, label="body centre")
    for leg, col in LEGS.items():
        px, pz, on = t[f"px_{leg}"], t[f"pz_{leg}"], t[f"contact_{leg}"] > 0.5
        ax.plot(px, np.where(on, np.nan, pz), color=col, lw=0.8)
        idx = np.flatnonzero(on)[::25]
        ax.plot(px[idx], pz[idx], "*", color=col, ms=5, label=f"{leg} toe (stance *, swing —)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("horizontal distance along the stairs [m]")
    ax.set_ylabel("height [m]")
    ax.set_title(title)
    if legend:
        ax.legend(loc="upper left")


def measure(run: Run, stride: float, key: str, values: dict, jump_limit: float,
            fallback_limit: float):
    """The criteria's values of one run against the flat stride of its legs; the height limits
    are those of the thesis' stairs (a tenth of their riser) for every run."""
    prog = run.cycle_progress()
    gain = run.cycle_height_gain()
    jumps = run.jumps()
    big = jumps > jump_limit
    # The velocity of frame n moves the body over [t_n, t_n+1) (trajectory_kernel.hpp).
    back = np.diff(run.s) < -1e-12
    returning = run.returning_contact()
    edge = run.edge_contact()
    slope_deg = float(np.degrees(np.arctan(run.riser / run.tread)))
    v = {"linkage": run.linkage, "flat_stride_m": stride,
         "cycle_progress_m": [float(p) for p in prog],
         "cycle_progress_min_m": float(np.min(prog)),
         "cycle_progress_min_rel_flat": float(np.min(prog) / stride),
         "cycle_progress_mean_rel_flat": float(np.mean(prog) / stride),
         "cycle_height_gain_m": [float(g) for g in gain],
         "cycle_height_gain_mean_m": float(np.mean(gain)),
         "max_backslide_m": run.backslide(), "max_backslide_rel_stride": run.backslide() / stride,
         "max_height_fallback_m": run.height_fallback(),
         "max_height_fallback_rel_riser": run.height_fallback() / run.riser,
         "max_height_jump_m": float(np.max(jumps)),
         "jumps_over_limit": int(np.count_nonzero(big)),
         "jumps_at_tread_change": int(np.count_nonzero(big & run.tread_change())),
         "backward_frames": int(np.count_nonzero(back)),
         "backward_frames_returning_toe": int(np.count_nonzero(back & returning[:-1])),
         "returning_contact_frames": int(np.count_nonzero(returning)),
         "edge_contact_frames": int(np.count_nonzero(edge)),
         "jumps_at_edge_contact": int(np.count_nonzero(big & edge)),
         "progress_m": float(run.s[-1] - run.s[0]),
         "height_gain_m": float(run.t["bz"][-1] - run.t["bz"][0]),
         "mean_pitch_deg": float(np.degrees(np.mean(run.pitch))),
         "stairs_slope_deg": slope_deg}
    v["height_gain_per_progress"] = v["height_gain_m"] / v["progress_m"]
    # The rate of the climb without the treads' quantization of the end points: the slope of
    # the least-squares line of the body's height against its forward position.
    v["height_per_forward_fit"] = float(np.polyfit(run.s, run.t["bz"], 1)[0])
    v["height_rate_rel_slope"] = v["height_per_forward_fit"] / (run.riser / run.tread)
    v["mean_pitch_minus_slope_deg"] = v["mean_pitch_deg"] - slope_deg
    checks = {"progress": bool(np.min(prog) >= PROGRESS_MIN_REL * stride),
              "no_backslide": bool(run.backslide() <= BACKSLIDE_LIMIT * stride),
              "monotone_height": bool(run.height_fallback() <= fallback_limit),
              "no_jump": bool(np.max(jumps) <= jump_limit),
              "height_rate": bool(abs(v["height_rate_rel_slope"] - 1.0) <= GAIN_TOL_REL),
              "pitch": bool(abs(v["mean_pitch_minus_slope_deg"]) <= PITCH_TOL_DEG)}
    for name, ok in checks.items():
        v[f"meets_{name}"] = ok
    v["climbs_like_thesis"] = all(checks.values())
    v["criteria_failed"] = ", ".join(n for n, ok in checks.items() if not ok) or "none"
    summary = run.meta.get("summary", {})
    v["not_converged_frames"] = int(summary.get("not_converged_frames", 0))
    v["unsupported_frames"] = int(summary.get("unsupported_frames", 0))
    if big.any():
        v["jumps_at_tread_change_frac"] = v["jumps_at_tread_change"] / v["jumps_over_limit"]
    if back.any():
        v["backward_frames_returning_toe_frac"] = (v["backward_frames_returning_toe"]
                                                   / v["backward_frames"])
        # How much of the weight the returning toes carry while the body moves back.
        v["backward_frames_returning_load_mean"] = float(
            np.mean(run.returning_load_share()[:-1][back]))
    for name, value in v.items():
        values[f"{key}_{name}"] = value


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    kinds = ("", "fine", "flat", "standard", "flat_standard")
    runs = {(kind, law): Run(args.data, f"stairs_{kind + '_' if kind else ''}{law}")
            for kind in kinds for law in LAWS}
    stairs = runs[("", "coulomb")]
    fine = runs[("fine", "coulomb")]
    jump_limit = JUMP_LIMIT * stairs.riser

    fig = plt.figure(figsize=(13, 9.5))
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1], hspace=0.25, wspace=0.2,
                          left=0.06, right=0.98, top=0.93, bottom=0.06)
    values: dict = {"riser_m": stairs.riser, "tread_m": stairs.tread,
                    "fine_riser_m": fine.riser, "fine_tread_m": fine.tread,
                    "riser_over_tread": stairs.riser / stairs.tread,
                    "stair_slope_deg": float(np.degrees(np.arctan(stairs.riser / stairs.tread))),
                    "fine_stair_slope_deg": float(np.degrees(np.arctan(fine.riser / fine.tread))),
                    "jump_limit_m": jump_limit, "backslide_limit_rel_stride": BACKSLIDE_LIMIT,
                    "fallback_limit_m": FALLBACK_LIMIT * stairs.riser,
                    "progress_min_rel_flat": PROGRESS_MIN_REL, "gain_tol_rel": GAIN_TOL_REL,
                    "pitch_tol_deg": PITCH_TOL_DEG, "linkage": stairs.linkage}
    cycles = int(np.floor(stairs.t["t"][-1] / stairs.period + 1e-9))
    peer = tp.load(args.data)  # MuJoCo's BigANT on the same stairs (referee.toml), if run
    for i, law in enumerate(LAWS):
        ax = fig.add_subplot(gs[0, i])
        side_view(ax, runs[("", law)],
                  f"({'ab'[i]}) {LAWS[law][0]}, {stairs.linkage} leg: {cycles} cycles at "
                  f"{1 / stairs.period:g} Hz", legend=i == 0)
        tp.overlay(ax, peer, "bigant_stairs")

    # The flat references: stride per cycle, and how high a returning toe rises above the ground.
    for flat_kind in ("flat", "flat_standard"):
        clearance = []
        for law in LAWS:
            flat = runs[(flat_kind, law)]
            values[f"{flat_kind}_{law}_progress_per_cycle_m"] = float(
                np.mean(flat.cycle_progress()))
            clearance += [float(np.max(flat.t[f"pz_{leg}"])) for leg in ALL_LEGS]
        values[f"{flat_kind}_max_toe_clearance_m"] = max(clearance)
    values["riser_over_toe_clearance"] = stairs.riser / values["flat_standard_max_toe_clearance_m"]
    values["riser_over_stairs_leg_clearance"] = stairs.riser / values["flat_max_toe_clearance_m"]

    for kind, flat_kind in KINDS.items():
        for law in LAWS:
            key = f"{kind + '_' if kind else ''}{law}"
            measure(runs[(kind, law)], values[f"{flat_kind}_{law}_progress_per_cycle_m"], key,
                    values, jump_limit, values["fallback_limit_m"])
            # Returning toes on the ground against flat ground with the same legs (the round
            # corners of the path touch there too).
            flat_returning = np.count_nonzero(runs[(flat_kind, law)].returning_contact())
            values[f"{key}_touchdown_frames_rel_flat"] = (
                values[f"{key}_returning_contact_frames"] / max(flat_returning, 1))
    # Stance toes on their treads: a toe in contact lies below the tread under it by its spring's
    # compression (F_z/K) and never above it.
    for law in LAWS:
        run = runs[("", law)]
        above = []
        for leg in ALL_LEGS:
            on = run.t[f"contact_{leg}"] > 0.5
            h = run.height(run.t[f"px_{leg}"][on], run.t[f"py_{leg}"][on])
            above.append(run.t[f"pz_{leg}"][on] - h)
        above = np.concatenate(above)
        values[f"{law}_stance_max_above_tread_m"] = float(np.max(above))
        values[f"{law}_stance_max_compression_m"] = float(-np.min(above))

    # (c) forward position, (d) height against time; stairs leg solid, standard leg dashed, fine
    # stairs (standard leg) dash-dotted, flat dotted.
    ax_s, ax_z = fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])
    styles = {"": ("-", f"{stairs.linkage} leg, stairs {stairs.tread:g} × {stairs.riser:g} m"),
              "standard": ("--", f"standard leg, stairs {stairs.tread:g} × {stairs.riser:g} m"),
              "fine": ("-.", f"standard leg, fine {fine.tread:g} × {fine.riser:g} m"),
              "flat": (":", f"{stairs.linkage} leg, flat")}
    for law, (label, col) in LAWS.items():
        for kind, (ls, what) in styles.items():
            run = runs[(kind, law)]
            ax_s.plot(run.t["t"], run.s - run.s[0], ls, color=col, lw=1.3,
                      label=f"{label}, {what}")
            if kind == "flat":
                continue
            ax_z.plot(run.t["t"], run.t["bz"] - run.t["bz"][0], ls, color=col, lw=1.3,
                      label=f"{label}, {what}")
            big = np.flatnonzero(run.jumps() > jump_limit)
            ax_z.plot(run.t["t"][big + 1], run.t["bz"][big + 1] - run.t["bz"][0], "o",
                      mfc="none", color=col, ms=7)
    ax_z.plot([], [], "o", mfc="none", color="0.3", ms=7,
              label=f"jump > {jump_limit * 100:.1f} cm in one frame")
    for ax in (ax_s, ax_z):
        for k in range(1, cycles):
            ax.axvline(k * stairs.period, color="0.6", lw=0.8, ls="-.")
        ax.set_xlabel("time [s] (dash-dotted: gait cycles)")
    ax_s.set_ylabel("forward position of the body [m]")
    ax_s.set_title(f"(c) progress: the standard leg slides back on the {stairs.riser:g} m risers")
    ax_s.legend(loc="upper left", ncol=1, fontsize="small")
    ax_z.set_ylabel("height gain of the body [m]")
    ax_z.set_title("(d) height: jumps when a loaded toe changes tread")
    ax_z.legend(loc="upper left", fontsize="small")

    values.update(tp.values(peer, "bigant_stairs", stairs=True))
    values.update(tp.values(peer, "bigant_stairs_fine", stairs=True, prefix="mujoco_fine"))
    values.update(tp.values(peer, "bigant_stairs_standard", stairs=True,
                            prefix="mujoco_standard"))
    fig.suptitle("Fig. 5.3 analog: BigANT's alternating tripod up stairs (synthetic)")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
