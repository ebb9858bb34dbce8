#!/usr/bin/python3
"""Thesis Fig. 3.8: the metachronal gait's phases and its friction law (synthetic analog).

Input: DATA/ch3_robots/metachronal_{coulomb,viscous}.csv. Output: OUT/fig3_8.png,
OUT/values/fig3_8.json.

(A) each leg's motor shaft angle φ against the gait phase f·t mod 1 (thick: the foot is down;
four feet are down at any time, §3.5.1.5). (B) |F_xy|/F_z against the slip speed of the feet in
contact: with the Coulomb run generating the data this is the step of classical Coulomb friction
(μ for every slipping foot, anything up to μ for a sticking one); the viscous-Coulomb run gives
the line |F_xy|/F_z = μ|u| of its ansatz (eq. 3.19). The thesis' panel B is F/T data; ours shows
what each law would put there. Also the slip-velocity percentiles the thesis quotes (5 %, 95 %
of v_x of the feet in contact).

MuJoCo's BigANT driven by the same feet stands in, labelled so, for the thesis' measured robot
(DATA/ch3_peer/fig3_14.csv, metachronal base run, §3.5.4): red in (B) are its feet in contact
carrying at least 2 % of Mg (|F_xy|/F_z of the floor's force from its contacts against the foot
centre's speed over the floor), and its slip percentiles and feet down go to the values. Without
that file (a build without MuJoCo) the red points are skipped and the title says so. MuJoCo shows
no step: its feet creep at a speed that grows with the planar force, well inside the cone (the
values' mujoco_fit); its own sensitivity blocks show the soft contact causes it (mujoco_creep:
a softer solref creeps faster under less force, the time step changes nothing).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_8"
MJ_LABEL = "MuJoCo" + rb.STANDIN  # the version comes with the data: rb.mujoco_label
MOVING = 1e-6  # m/s: a foot in contact slower than this sticks


def contact_slip(run: rb.Run):
    down, sx, sy, ratio = [], [], [], []
    for leg in run.legs:
        d = run.leg("contact", leg) > 0
        fz = run.leg("Fz", leg)[d]
        down.append(d)
        sx.append(run.leg("slip_x", leg)[d])
        sy.append(run.leg("slip_y", leg)[d])
        ratio.append(np.hypot(run.leg("Fx", leg)[d], run.leg("Fy", leg)[d]) / fz)
    return np.stack(down, axis=1), np.concatenate(sx), np.concatenate(sy), np.concatenate(ratio)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    k = rb.Run(args.data, "metachronal_coulomb")
    v = rb.Run(args.data, "metachronal_viscous")
    freq = float(k.meta.get("scene", {}).get("gait", {}).get("frequency", 0.1))
    values: dict = {"frequency_hz": freq}
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))

    # (A) shaft angle vs gait phase, stance drawn thick.
    a = axes[0]
    phase = np.mod(freq * k.time, 1.0)
    cols = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    down_k, sx, sy, ratio = contact_slip(k)
    for i, leg in enumerate(k.legs):
        if f"phase_{leg}" not in k.t.columns:
            c.fail(f"{k.t.path}: no phase_{leg} column (the gait defines no phases)")
        phi = k.leg("phase", leg).copy()
        # break the lines where the shaft angle or the gait phase wraps
        wrap = np.r_[False, (np.abs(np.diff(phi)) > 0.5) | (np.abs(np.diff(phase)) > 0.5)]
        phi[wrap] = np.nan
        d = down_k[:, i]
        a.plot(phase, phi, color=cols[i % len(cols)], lw=0.7, label=leg)
        a.plot(phase, np.where(d, phi, np.nan), color=cols[i % len(cols)], lw=3.0)
    feet_down = down_k.sum(axis=1)
    values["feet_down_min"] = int(feet_down.min())
    values["feet_down_max"] = int(feet_down.max())
    values["feet_down_mean"] = float(feet_down.mean())
    values["duty_per_leg"] = down_k.mean(axis=0)
    values["duty_mean"] = float(down_k.mean())
    a.set_xlabel("gait phase f·t mod 1")
    a.set_ylabel("shaft angle φ [turns]")
    a.set_title(f"(A) shaft angle per leg (thick: stance; {feet_down.min()}–{feet_down.max()} "
                "feet down)")
    a.legend(fontsize=7, ncol=2)

    # (B) Coulomb: the step.
    speed = np.hypot(sx, sy)
    a = axes[1]
    a.plot(1e3 * speed, ratio, ".", ms=2, color=c.COULOMB, alpha=0.5)
    a.axhline(1.0, color="0.4", lw=0.8, ls=":")
    a.set_xlabel("slip speed |u| [mm/s]")
    a.set_ylabel("|F_xy| / F_z")
    a.set_title("(B) Coulomb run generates the data: a step at μ = 1")
    slipping = speed > MOVING
    values["coulomb_slipping_fraction"] = float(np.mean(slipping))
    values["coulomb_ratio_slipping_max_dev"] = (float(np.max(np.abs(ratio[slipping] - 1.0)))
                                                if np.any(slipping) else None)
    values["coulomb_ratio_sticking_max"] = (float(np.max(ratio[~slipping]))
                                            if np.any(~slipping) else None)
    # the step: |F|/F_z = mu = 1 for every slipping foot, at most mu for a sticking one
    values["coulomb_is_step"] = bool(
        np.any(slipping) and values["coulomb_ratio_slipping_max_dev"] < 1e-6
        and (values["coulomb_ratio_sticking_max"] is None
             or values["coulomb_ratio_sticking_max"] <= 1.0 + 1e-6))
    # the thesis' statistic: 5 % and 95 % percentiles of v_x of the feet in contact, mm/s
    values["slip_x_p5_mm_s"], values["slip_x_p95_mm_s"] = (float(p) for p in
                                                           np.percentile(1e3 * sx, [5, 95]))
    values["slip_x_p2_5_mm_s"], values["slip_x_p97_5_mm_s"] = (
        float(p) for p in np.percentile(1e3 * sx, [2.5, 97.5]))
    values["slip_speed_median_mm_s"] = float(np.median(1e3 * speed))

    # MuJoCo as measured: its own contacts, forces and slip, over the part of our run it covers.
    mj = rb.mujoco_until(rb.mujoco_as_measured(args.data, "metachronal"), k.time[-1])
    feet = rb.mujoco_feet(mj, k.legs)
    values["mujoco_as_measured"] = feet is not None
    if feet is not None:
        mdown = np.stack([feet[leg]["contact"] > 0 for leg in k.legs], axis=1)
        mfz = np.stack([feet[leg]["Fz"] for leg in k.legs], axis=1)
        mw = np.sum(mfz, axis=1, keepdims=True)
        loaded = mdown & (mfz > 0.02 * mw)
        msx = np.stack([feet[leg]["slip_x"] for leg in k.legs], axis=1)[mdown]
        msp = np.hypot(np.stack([feet[leg]["slip_x"] for leg in k.legs], axis=1),
                       np.stack([feet[leg]["slip_y"] for leg in k.legs], axis=1))[loaded]
        mratio = np.hypot(np.stack([feet[leg]["Fx"] for leg in k.legs], axis=1),
                          np.stack([feet[leg]["Fy"] for leg in k.legs], axis=1))[loaded] \
            / mfz[loaded]
        a.plot(1e3 * msp, mratio, ".", ms=3, color=c.MUJOCO, alpha=0.6,
               label=MJ_LABEL)
        a.legend(fontsize=7, loc="lower right")
        a.set_title("(B) Coulomb run (blue): a step at μ = 1; red: MuJoCo")
        mfit = c.linfit(msp, mratio)
        values["mujoco_fit"] = mfit
        values["mujoco_slip_x_p5_mm_s"], values["mujoco_slip_x_p95_mm_s"] = (
            float(p) for p in np.percentile(1e3 * msx, [5, 95]))
        values["mujoco_feet_down_mean"] = float(mdown.sum(axis=1).mean())
        values["mujoco_duty_mean"] = float(mdown.mean())
        slipping_m = msp > 5e-3  # m/s: MuJoCo's soft contacts creep; 5 mm/s is a slip
        values["mujoco_ratio_slipping_median"] = (float(np.median(mratio[slipping_m]))
                                                  if np.any(slipping_m) else None)
        # Is the creep MuJoCo's soft contact? Its own sensitivity blocks (fig3_14.toml): softer
        # contact (a longer solref time constant) and a shorter time step, metachronal gait.
        creep = []
        for label in ("base", "solref_timeconst", "timestep"):
            for run in rb.mujoco_runs(args.data, "metachronal", label):
                f = rb.mujoco_feet(run, k.legs)
                if f is None:
                    continue
                dn = np.stack([f[leg]["contact"] > 0 for leg in k.legs], axis=1)
                z = np.stack([f[leg]["Fz"] for leg in k.legs], axis=1)
                ld = dn & (z > 0.02 * np.sum(z, axis=1, keepdims=True))
                sp = np.hypot(np.stack([f[leg]["slip_x"] for leg in k.legs], axis=1),
                              np.stack([f[leg]["slip_y"] for leg in k.legs], axis=1))
                fr = np.hypot(np.stack([f[leg]["Fx"] for leg in k.legs], axis=1),
                              np.stack([f[leg]["Fy"] for leg in k.legs], axis=1))
                creep.append({"solref_timeconst": run["solref_timeconst"],
                              "timestep": run["timestep"],
                              "slip_speed_median_mm_s": float(np.median(1e3 * sp[dn])),
                              "ratio_median": float(np.median(fr[ld] / z[ld]))})
        values["mujoco_creep"] = creep
        values["mujoco_slip_note"] = (
            f"{MJ_LABEL}: ({values['mujoco_slip_x_p5_mm_s']:.1f}, "
            f"{values['mujoco_slip_x_p95_mm_s']:.1f}) mm/s over {mj['t'][-1]:.0f} s.")
        values["mujoco_step_note"] = (
            f"{MJ_LABEL}: feet slipping faster than 5 mm/s have median |F_xy|/F_z = "
            + (f"{values['mujoco_ratio_slipping_median']:.3g}"
               if values["mujoco_ratio_slipping_median"] is not None else "— (none)")
            + " (μ = 1)"
            + (f"; a line fits its feet down, |F_xy|/F_z = {mfit['k']:.3g} s/m·|u| "
               f"{'+' if mfit['b'] >= 0 else '−'} {abs(mfit['b']):.2g} (R² = {mfit['r2']:.2f}): "
               "its feet creep well inside the cone, no step"
               if mfit["k"] is not None and mfit["r2"] is not None else "") + "."
            + ("" if not creep else " MuJoCo's own blocks (solref time constant [ms], time step "
               "[ms]: median creep [mm/s] at median |F_xy|/F_z): " + "; ".join(
                   f"{1e3 * r['solref_timeconst']:g}, {1e3 * r['timestep']:g}: "
                   f"{r['slip_speed_median_mm_s']:.3g} at {r['ratio_median']:.2g}"
                   for r in sorted(creep, key=lambda r: (r["solref_timeconst"], r["timestep"])))
               + " — softer contact creeps faster under less force, the time step changes "
               "nothing: MuJoCo's soft friction constraint, not its integration."))
        values["mujoco_duty_note"] = (
            f"{MJ_LABEL}: {values['mujoco_feet_down_mean']:.3g} feet down on average, "
            f"duty {values['mujoco_duty_mean']:.3g}.")
    else:
        for key in ("mujoco_slip_note", "mujoco_step_note", "mujoco_duty_note"):
            values[key] = rb.MUJOCO_MISSING + "."

    # (B') viscous-Coulomb: a line of slope mu in its own units.
    _, vx_, vy_, vratio = contact_slip(v)
    vspeed = np.hypot(vx_, vy_)
    a = axes[2]
    a.plot(1e3 * vspeed, vratio, ".", ms=2, color=c.VISCOUS, alpha=0.5)
    fit = c.linfit(vspeed, vratio)
    values["viscous_fit"] = fit
    values["viscous_fit_slope"] = fit["k"]
    if fit["k"] is not None:
        xs = np.linspace(0, vspeed.max(), 2)
        a.plot(1e3 * xs, fit["k"] * xs + fit["b"], color="0.2", lw=0.9,
               label=f"fit: {fit['k']:.3g}·|u| + {fit['b']:.2g} (R² = {fit['r2']:.6f})")
        a.legend(fontsize=7)
    a.set_xlabel("slip speed |u| [mm/s]")
    a.set_ylabel("|F_xy| / F_z  (the ansatz' units: μ|u| in s/m · m/s)")
    a.set_title("(B) viscous-Coulomb run: the line of eq. 3.19")
    values["viscous_slip_x_p5_mm_s"], values["viscous_slip_x_p95_mm_s"] = (
        float(p) for p in np.percentile(1e3 * vx_, [5, 95]))
    fig.suptitle("BigANT, metachronal gait, synthetic; slip v_x of feet down, 5–95 %: "
                 f"({values['slip_x_p5_mm_s']:.1f}, {values['slip_x_p95_mm_s']:.1f}) mm/s "
                 "(Coulomb run)" + (
                     f", ({values['mujoco_slip_x_p5_mm_s']:.1f}, "
                     f"{values['mujoco_slip_x_p95_mm_s']:.1f}) mm/s (MuJoCo as measured, driven "
                     "by the same feet)" if feet is not None else "; " + rb.MUJOCO_MISSING),
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
