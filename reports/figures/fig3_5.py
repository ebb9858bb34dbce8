#!/usr/bin/python3
"""Thesis Fig. 3.5: BigANT's tripod-gait trajectory under both friction laws (synthetic analog).

Input: DATA/ch3_robots/tripod_viscous.csv and tripod_coulomb.csv (the same scene, Buehler-clock
tripod at 0.1 Hz, run with the viscous-Coulomb ansatz and with classical Coulomb friction).
Output: OUT/fig3_5.png, OUT/values/fig3_5.json.

Rows as in the thesis: the trajectory (body outline and origin at the start, half-way and end);
roll, pitch (from the spring support's plane, eq. 3.6, the same for both laws) and yaw; the body
velocity components; and in place of the residual against motion capture (which needs the
thesis' data) the difference Coulomb − viscous-Coulomb of each velocity component.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_5"
LENGTH, WIDTH = 0.73, 0.40  # m, BigANT's chassis outline drawn on the trajectory (73 cm long)


def outline(ax, x, y, th, color):
    corners = np.array([[1, 1], [1, -1], [-1, -1], [-1, 1], [1, 1]]) * [LENGTH / 2, WIDTH / 2]
    r = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    p = corners @ r.T + [x, y]
    ax.plot(p[:, 0], p[:, 1], color=color, lw=0.8, alpha=0.6)
    ax.plot([x], [y], "+", color=color, ms=8, mew=1.5)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    runs = {"viscous": rb.Run(args.data, "tripod_viscous"),
            "coulomb": rb.Run(args.data, "tripod_coulomb")}
    color = {"viscous": c.VISCOUS, "coulomb": c.COULOMB}
    label = {"viscous": "viscous-Coulomb", "coulomb": "Coulomb"}
    v, k = runs["viscous"], runs["coulomb"]
    if v.t.n != k.t.n or not np.allclose(v.time, k.time):
        c.fail("tripod_viscous and tripod_coulomb have different time grids")
    t = v.time

    mj = rb.mujoco_as_measured(args.data, "tripod")
    mj_label = mj["label"] + rb.STANDIN if mj is not None else None
    fig = plt.figure(figsize=(12, 12.5))
    gs = fig.add_gridspec(4, 3, height_ratios=[1.25, 1, 1, 1], hspace=0.55, wspace=0.3, top=0.9,
                          bottom=0.05, left=0.07, right=0.98)
    ax = fig.add_subplot(gs[0, :])
    for key, r in runs.items():
        ax.plot(r["x"], r["y"], color=color[key], lw=1.5, label=label[key])
        for i in (0, r.t.n // 2, r.t.n - 1):
            outline(ax, r["x"][i], r["y"][i], r["theta"][i], color[key])
    if mj is not None:
        ax.plot(mj["x"], mj["y"], color=c.MUJOCO, lw=1.5, label=mj_label)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("Robot trajectory: body outline and origin (+) at the start, half-way and end")

    roll, pitch = v.roll_pitch_deg()
    roll_k, pitch_k = k.roll_pitch_deg()
    for j, (name, yv, yk) in enumerate([("roll [deg]", roll, roll_k), ("pitch [deg]", pitch, pitch_k),
                                        ("yaw [deg]", np.degrees(v["theta"]),
                                         np.degrees(k["theta"]))]):
        a = fig.add_subplot(gs[1, j])
        if j < 2:  # the spring support is independent of the friction law
            a.plot(t, yv, color=c.SUPPORT, lw=1.2, label="spring support (both laws)")
        else:
            a.plot(t, yv, color=c.VISCOUS, lw=1.2)
            a.plot(t, yk, color=c.COULOMB, lw=1.2, ls="--")
            if mj is not None:
                a.plot(mj["t"], np.degrees(mj["theta"]), color=c.MUJOCO, lw=1.0)
        a.set_title(name)
        a.set_xlabel("t [s]")

    comps = [("vx", "heading velocity [m/s]", 1.0), ("vy", "side velocity [m/s]", 1.0),
             ("omega", "turning rate [deg/s]", 180 / np.pi)]
    values: dict = {"frames": v.t.n, "duration_s": float(t[-1]), "quick": v.quick()}
    for j, (col, title, scale) in enumerate(comps):
        a = fig.add_subplot(gs[2, j])
        a.plot(t, scale * v[col], color=c.VISCOUS, lw=1.0)
        a.plot(t, scale * k[col], color=c.COULOMB, lw=1.0, ls="--")
        if mj is not None:
            a.plot(mj["t"], scale * mj[col], color=c.MUJOCO, lw=0.9)
        a.set_title(title)
        a.set_xlabel("t [s]")
        d = fig.add_subplot(gs[3, j])
        # the difference in mm/s (velocities) or deg/s: small next to the signals above
        dscale, dunit = (1e3, "mm/s") if col != "omega" else (1.0, "deg/s")
        diff = dscale * scale * (k[col] - v[col])
        d.plot(t, diff, color=c.NEUTRAL, lw=0.9)
        if col == "vy":
            rb.flat_zero(a, scale * np.r_[v[col], k[col]], "m/s", "a straight tripod")
        d.set_title("Δ " + title.split(" velocity")[0].split(" rate")[0]
                    + f" [{dunit}], Coulomb − viscous")
        d.set_xlabel("t [s]")
        values[f"rms_{col}_viscous"] = rb.rms(v[col])
        values[f"rms_{col}_diff"] = rb.rms(k[col] - v[col])
        # relative only where there is something to be relative to (v_y is 0 to rounding)
        values[f"rel_rms_{col}_diff"] = (rb.rms(k[col] - v[col]) / rb.rms(v[col])
                                         if rb.rms(v[col]) > 1e-9 else None)

    # The trajectories: how far apart the two laws end, relative to the distance walked.
    end_v = np.array([v["x"][-1], v["y"][-1]])
    end_k = np.array([k["x"][-1], k["y"][-1]])
    path = float(np.sum(np.hypot(np.diff(v["x"]), np.diff(v["y"]))))
    values.update({
        "end_viscous": end_v, "end_coulomb": end_k,
        "end_distance_m": float(np.linalg.norm(end_k - end_v)),
        "path_length_m": path,
        "end_distance_rel": float(np.linalg.norm(end_k - end_v)) / max(path, 1e-300),
        "yaw_end_diff_deg": float(np.degrees(k["theta"][-1] - v["theta"][-1])),
        "mean_speed_viscous": float(np.linalg.norm(end_v) / t[-1]),
        "roll_range_deg": float(np.ptp(roll)), "pitch_range_deg": float(np.ptp(pitch)),
        "support_same_for_both_laws": bool(np.allclose(v["alpha"], k["alpha"])
                                           and np.allclose(v["beta"], k["beta"])),
    })
    values["mujoco_as_measured"] = mj is not None
    if mj is not None:
        end_m = np.array([mj["x"][-1], mj["y"][-1]])
        values["mujoco_end"] = end_m
        values["mujoco_end_distance_to_viscous_m"] = float(np.linalg.norm(end_m - end_v))
        values["mujoco_end_distance_to_coulomb_m"] = float(np.linalg.norm(end_m - end_k))
    # one legend for every panel, above them
    handles = [Line2D([], [], color=c.VISCOUS, lw=1.5, label="viscous-Coulomb"),
               Line2D([], [], color=c.COULOMB, lw=1.5, ls="--", label="Coulomb"),
               Line2D([], [], color=c.SUPPORT, lw=1.5, label="spring support (both laws)")]
    if mj is not None:
        handles.append(Line2D([], [], color=c.MUJOCO, lw=1.5, label=mj_label))
    handles.append(Line2D([], [], color=c.NEUTRAL, lw=1.5, label="Coulomb − viscous (row 4)"))
    fig.legend(handles=handles, loc="upper center", ncol=3, bbox_to_anchor=(0.5, 0.965),
               frameon=False)
    fig.suptitle("BigANT, tripod gait at 0.1 Hz, synthetic (no motion capture): the two laws "
                 f"end {values['end_distance_m']:.3g} m apart after {path:.3g} m", y=0.995)
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
