#!/usr/bin/python3
"""Thesis Fig. 5.3 / §5.2.2: BigANT's tripod up stairs (tread 0.3 m, riser 0.12 m).

Input: DATA/ch5_terrain/stairs_viscous.csv and stairs_coulomb.csv (the scene
studies/ch5_terrain/scenes/bigant_stairs.toml under both laws: `slipwalk run` columns plus the
world positions bx, by, bz of the body and px_L, py_L, pz_L of each toe before compression).
Output: OUT/fig5_3.png, OUT/values/fig5_3.json.

Panels per law, as in the thesis: the stairs (gray), the body centre (red) and the toes of FL,
ML, HL (blue, orange, purple; stance: stars, swing: lines) seen from the side. The stance toes
must stand on their treads: a toe in contact lies below the tread under it by its spring's
compression (F_z/K) and never above it, which the values check.
"""
from __future__ import annotations

import sys
from pathlib import Path

import json

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig5_3"
STUDY = "ch5_terrain"
LEGS = {"FL": "tab:blue", "ML": "tab:orange", "HL": "tab:purple"}
ALL_LEGS = ("HL", "ML", "FL", "HR", "MR", "FR")
BODY = "tab:red"


def load_run(data, name):
    path = data / STUDY / f"{name}.csv"
    if not path.is_file():
        c.fail(f"{path}: input file missing (run `slipwalk reproduce {STUDY}` to produce it)")
    cols = ["t", "x", "y", "theta", "bx", "by", "bz"]
    for leg in ALL_LEGS:
        cols += [f"px_{leg}", f"py_{leg}", f"pz_{leg}", f"contact_{leg}", f"Fz_{leg}"]
    t = c.Table(path, cols)
    if t.n < 2:
        c.fail(f"{path}: fewer than two rows")
    side = path.with_suffix(".json")
    meta = json.loads(side.read_text()) if side.is_file() else {}
    return t, meta


def step_height(terrain: dict, px, py):
    psi = np.radians(float(terrain.get("heading_deg", 0.0)))
    s = px * np.cos(psi) + py * np.sin(psi)
    return float(terrain["riser"]) * np.floor(s / float(terrain["tread"]))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    values: dict = {}
    for ax, law in zip(axes, ("viscous", "coulomb")):
        t, meta = load_run(args.data, f"stairs_{law}")
        terrain = meta.get("scene", {}).get("terrain")
        if not terrain or terrain.get("kind") != "stairs":
            c.fail(f"stairs_{law}.json: the sidecar names no stairs terrain")
        tread, riser = float(terrain["tread"]), float(terrain["riser"])
        lo = min(np.min(t[f"px_{leg}"]) for leg in ALL_LEGS) - 0.2
        hi = max(np.max(t[f"px_{leg}"]) for leg in ALL_LEGS) + 0.2
        xs = np.linspace(lo, hi, 2000)
        ax.fill_between(xs, step_height(terrain, xs, 0 * xs), lo * riser / tread - 0.2,
                        step="post", color="0.85", label=f"stairs {tread} m × {riser} m")
        ax.plot(t["bx"], t["bz"], color=BODY, lw=1.5, label="body centre")
        for leg, col in LEGS.items():
            px, pz, on = t[f"px_{leg}"], t[f"pz_{leg}"], t[f"contact_{leg}"] > 0.5
            ax.plot(px, np.where(on, np.nan, pz), color=col, lw=0.8)
            idx = np.flatnonzero(on)[::25]
            ax.plot(px[idx], pz[idx], "*", color=col, ms=4, label=f"{leg} (stance *, swing —)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("horizontal distance along the stairs [m]")
        ax.set_ylabel("height [m]")
        ax.set_title(f"{'viscous-Coulomb' if law == 'viscous' else 'Coulomb'}: three cycles at "
                     "0.1 Hz")
        ax.legend(fontsize=6.5, loc="upper left")
        # Stance toes on their treads: height above the tread under them, in contact.
        above = []
        for leg in ALL_LEGS:
            on = t[f"contact_{leg}"] > 0.5
            h = step_height(terrain, t[f"px_{leg}"][on], t[f"py_{leg}"][on])
            above.append(t[f"pz_{leg}"][on] - h)
        above = np.concatenate(above)
        values[f"{law}_stance_max_above_tread_m"] = float(np.max(above))
        values[f"{law}_stance_max_compression_m"] = float(-np.min(above))
        values[f"{law}_height_gain_m"] = float(t["bz"][-1] - t["bz"][0])
        values[f"{law}_progress_m"] = float(t["bx"][-1] - t["bx"][0])
        values[f"{law}_treads_climbed"] = float((t["bz"][-1] - t["bz"][0]) / riser)
        summary = meta.get("summary", {})
        values[f"{law}_not_converged_frames"] = int(summary.get("not_converged_frames", 0))
        values[f"{law}_unsupported_frames"] = int(summary.get("unsupported_frames", 0))
        values["stair_slope_deg"] = float(np.degrees(np.arctan(riser / tread)))
    values["climbs_both"] = bool(values["viscous_height_gain_m"] > 0.12
                                 and values["coulomb_height_gain_m"] > 0.12)
    fig.suptitle("Fig. 5.3 analog: BigANT's alternating tripod up stairs (synthetic)")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
