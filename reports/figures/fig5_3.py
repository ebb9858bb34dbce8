#!/usr/bin/python3
"""Thesis Fig. 5.3 / §5.2.2: BigANT's tripod up stairs (tread 0.3 m, riser 0.12 m).

Input: DATA/ch5_terrain/stairs_viscous.csv and stairs_coulomb.csv (the scene
studies/ch5_terrain/scenes/bigant_stairs.toml under both laws: `slipwalk run` columns plus the
world positions bx, by, bz of the body and px_L, py_L, pz_L of each toe before compression),
stairs_fine_{viscous,coulomb}.csv (bigant_stairs_fine.toml: the same stairs' slope in steps a
quarter the size, the check) and stairs_flat_{viscous,coulomb}.csv (bigant_stairs_flat.toml:
riser 0, the flat reference).
Output: OUT/fig5_3.png, OUT/values/fig5_3.json.

Panels (a, b), as in the thesis, per law: the stairs (gray), the body centre (black; the thesis
draws it red, a colour the report keeps for measured data) and the toes of FL, ML, HL (blue,
orange, purple; stance: stars, swing: lines) seen from the side. (c) the body's forward position
against time on the stairs, on the fine stairs and on flat ground; (d) its height, with the
frames where it jumps by more than a tenth of the riser.

What the thesis' figure shows (its caption: "a trajectory of simulated BigAnt robot moving up
stairs") is read here as a climb: forward progress in every gait cycle, no slide back by more
than a tenth of the flat stride, and a body height that follows the treads without jumping by
more than a tenth of the riser from one frame to the next. The values also record what the
jumps and slides coincide with: a loaded toe changing tread (the quasi-static model has no riser
walls: a returning toe still below the next tread when it passes the tread's edge stands on it),
and a toe in contact during its return (shaft angle outside the stance sweep), which pushes the
body back as it keeps moving forward.
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
BACKSLIDE_LIMIT = 0.1  # of the flat progress per cycle
JUMP_LIMIT = 0.1       # of the riser of the thesis' stairs, per frame


class Run:
    """One scene run on stairs: the table, its stairs and gait, and what the criteria measure."""

    def __init__(self, data: Path, name: str):
        path = c.study_file(data, f"{name}.csv", STUDY)
        cols = ["t", "x", "y", "theta", "bx", "by", "bz"]
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


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    runs = {(kind, law): Run(args.data, f"stairs_{kind + '_' if kind else ''}{law}")
            for kind in ("", "fine", "flat") for law in LAWS}
    stairs = runs[("", "coulomb")]
    jump_limit = JUMP_LIMIT * stairs.riser

    fig = plt.figure(figsize=(13, 9.5))
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1], hspace=0.25, wspace=0.2,
                          left=0.06, right=0.98, top=0.93, bottom=0.06)
    values: dict = {"riser_m": stairs.riser, "tread_m": stairs.tread,
                    "fine_riser_m": runs[("fine", "coulomb")].riser,
                    "fine_tread_m": runs[("fine", "coulomb")].tread,
                    "riser_over_tread": stairs.riser / stairs.tread,
                    "stair_slope_deg": float(np.degrees(np.arctan(stairs.riser / stairs.tread))),
                    "fine_stair_slope_deg": float(np.degrees(np.arctan(
                        runs[("fine", "coulomb")].riser / runs[("fine", "coulomb")].tread))),
                    "jump_limit_m": jump_limit, "backslide_limit_rel_stride": BACKSLIDE_LIMIT}
    cycles = int(np.floor(stairs.t["t"][-1] / stairs.period + 1e-9))
    peer = tp.load(args.data)  # MuJoCo's BigANT on the same stairs (referee.toml), if run
    for i, law in enumerate(LAWS):
        ax = fig.add_subplot(gs[0, i])
        side_view(ax, runs[("", law)],
                  f"({'ab'[i]}) {LAWS[law][0]}: {cycles} cycles at {1 / stairs.period:g} Hz",
                  legend=i == 0)
        tp.overlay(ax, peer, "bigant_stairs")

    # The flat reference: stride per cycle, and how high a returning toe rises above the ground.
    clearance = []
    for law in LAWS:
        flat = runs[("flat", law)]
        values[f"flat_{law}_progress_per_cycle_m"] = float(np.mean(flat.cycle_progress()))
        clearance += [float(np.max(flat.t[f"pz_{leg}"])) for leg in ALL_LEGS]
    values["flat_max_toe_clearance_m"] = max(clearance)
    values["riser_over_toe_clearance"] = stairs.riser / values["flat_max_toe_clearance_m"]

    for kind in ("", "fine"):
        for law in LAWS:
            run = runs[(kind, law)]
            key = f"{kind + '_' if kind else ''}{law}"
            stride = values[f"flat_{law}_progress_per_cycle_m"]
            prog = run.cycle_progress()
            jumps = run.jumps()
            big = jumps > jump_limit
            # The velocity of frame n moves the body over [t_n, t_n+1) (trajectory_kernel.hpp).
            back = np.diff(run.s) < -1e-12
            returning = run.returning_contact()[:-1]
            values[f"{key}_cycle_progress_m"] = [float(p) for p in prog]
            values[f"{key}_cycle_progress_min_m"] = float(np.min(prog))
            values[f"{key}_cycle_progress_min_rel_flat"] = float(np.min(prog) / stride)
            values[f"{key}_max_backslide_m"] = run.backslide()
            values[f"{key}_max_backslide_rel_stride"] = run.backslide() / stride
            values[f"{key}_max_height_jump_m"] = float(np.max(jumps))
            values[f"{key}_jumps_over_limit"] = int(np.count_nonzero(big))
            values[f"{key}_jumps_at_tread_change"] = int(np.count_nonzero(big & run.tread_change()))
            values[f"{key}_backward_frames"] = int(np.count_nonzero(back))
            values[f"{key}_backward_frames_returning_toe"] = int(
                np.count_nonzero(back & returning))
            values[f"{key}_progress_m"] = float(run.s[-1] - run.s[0])
            values[f"{key}_height_gain_m"] = float(run.t["bz"][-1] - run.t["bz"][0])
            values[f"{key}_height_gain_per_progress"] = (values[f"{key}_height_gain_m"]
                                                         / values[f"{key}_progress_m"])
            values[f"{key}_climbs_like_thesis"] = bool(
                np.min(prog) > 0 and run.backslide() <= BACKSLIDE_LIMIT * stride
                and np.max(jumps) <= jump_limit)
            summary = run.meta.get("summary", {})
            values[f"{key}_not_converged_frames"] = int(summary.get("not_converged_frames", 0))
            values[f"{key}_unsupported_frames"] = int(summary.get("unsupported_frames", 0))
            if big.any():
                values[f"{key}_jumps_at_tread_change_frac"] = (
                    values[f"{key}_jumps_at_tread_change"] / values[f"{key}_jumps_over_limit"])
            if back.any():
                values[f"{key}_backward_frames_returning_toe_frac"] = (
                    values[f"{key}_backward_frames_returning_toe"]
                    / values[f"{key}_backward_frames"])
        # Stance toes on their treads: a toe in contact lies below the tread under it by its
        # spring's compression (F_z/K) and never above it.
        if not kind:
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

    # (c) forward position, (d) height against time; thesis stairs solid, fine dashed, flat dotted.
    ax_s, ax_z = fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])
    fine = runs[("fine", "coulomb")]
    styles = {"": ("-", f"stairs {stairs.tread:g} × {stairs.riser:g} m"),
              "fine": ("--", f"fine {fine.tread:g} × {fine.riser:g} m"), "flat": (":", "flat")}
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
    ax_s.set_title(f"(c) progress: slides back on the {stairs.riser:g} m risers")
    ax_s.legend(loc="upper left", ncol=1)
    ax_z.set_ylabel("height gain of the body [m]")
    ax_z.set_title("(d) height: jumps when a loaded toe changes tread")
    ax_z.legend(loc="upper left")

    values.update(tp.values(peer, "bigant_stairs", stairs=True))
    values.update(tp.values(peer, "bigant_stairs_fine", stairs=True, prefix="mujoco_fine"))
    fig.suptitle("Fig. 5.3 analog: BigANT's alternating tripod up stairs (synthetic)")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
