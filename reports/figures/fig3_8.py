#!/usr/bin/python3
"""Thesis Fig. 3.8: the metachronal gait's phases, its friction and its slip (synthetic analog).

Input: DATA/ch3_robots/metachronal_{coulomb,viscous}.csv, tripod_coulomb.csv, and for MuJoCo
DATA/ch3_peer/fig3_14.csv. Output: OUT/fig3_8.png, OUT/values/fig3_8.json.

(A) each leg's motor shaft angle φ against the gait phase f·t mod 1 (thick: the foot is down;
four feet are down at any time, §3.5.1.5). (B) the thesis' panel B, |F_xy|/F_z against the slip
speed of the feet in contact, from which it reads classical Coulomb friction in its F/T data. We
have no F/T data: MuJoCo's BigANT driven by the same feet stands in for the robot (labelled so,
in its own colour; DATA/ch3_peer/fig3_14.csv, metachronal base run, §3.5.4), its feet in contact
carrying at least 2 % of Mg against the Coulomb law's step. Our own runs would only plot their
input laws back (the step; the line μ|u| of eq. 3.19 in the ansatz' units), so they are checked
in the values instead (coulomb_is_step, viscous_fit). MuJoCo shows no step: its feet creep at a
speed that grows with the planar force, well inside the cone (mujoco_fit); its own sensitivity
blocks show the soft contact causes it (mujoco_creep: a softer solref creeps faster under less
force, the time step changes nothing). Without MuJoCo's data the panel says so. (C) what the
thesis quotes from the same data, the slip velocity v_x of the feet in contact (body frame), as
cumulative distributions: 5 % and 95 % percentiles where the curves cross the dotted lines, for
both laws, MuJoCo and, for contrast, the tripod; the thesis' percentiles as stars when the claims
ledger holds them.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_8"
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


def ledger_thesis(claim_id: str):
    """The thesis' value of a ledger entry, None where the ledger does not hold it."""
    return next((cl.get("thesis") for cl in c.load_ledger().get("claim", [])
                 if cl.get("id") == claim_id), None)


def cdf(ax, x_mm_s, color, label, ls="-"):
    x = np.sort(np.asarray(x_mm_s, float))
    ax.plot(x, (np.arange(x.size) + 0.5) / x.size, color=color, ls=ls, lw=1.8, label=label)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    k = rb.Run(args.data, "metachronal_coulomb")
    v = rb.Run(args.data, "metachronal_viscous")
    tri = rb.Run(args.data, "tripod_coulomb")
    freq = float(k.meta.get("scene", {}).get("gait", {}).get("frequency", 0.1))
    values: dict = {"frequency_hz": freq}
    fig, axes = plt.subplots(1, 3, figsize=(14, 5.4), width_ratios=[1.1, 1, 1])

    # (A) shaft angle vs gait phase, stance drawn thick.
    a = axes[0]
    phase = np.mod(freq * k.time, 1.0)
    down_k, sx, sy, ratio = contact_slip(k)
    for i, leg in enumerate(k.legs):
        if f"phase_{leg}" not in k.t.columns:
            c.fail(f"{k.t.path}: no phase_{leg} column (the gait defines no phases)")
        phi = k.leg("phase", leg).copy()
        # break the lines where the shaft angle or the gait phase wraps
        wrap = np.r_[False, (np.abs(np.diff(phi)) > 0.5) | (np.abs(np.diff(phase)) > 0.5)]
        phi[wrap] = np.nan
        d = down_k[:, i]
        col = c.CATEGORICAL[i % len(c.CATEGORICAL)]
        a.plot(phase, phi, color=col, lw=0.8, label=leg)
        a.plot(phase, np.where(d, phi, np.nan), color=col, lw=3.5)
    feet_down = down_k.sum(axis=1)
    values["feet_down_min"] = int(feet_down.min())
    values["feet_down_max"] = int(feet_down.max())
    values["feet_down_mean"] = float(feet_down.mean())
    values["duty_per_leg"] = down_k.mean(axis=0)
    values["duty_mean"] = float(down_k.mean())
    a.set_xlabel("gait phase f·t mod 1")
    a.set_ylabel("motor shaft angle φ [turns]")
    a.set_title(f"(A) shaft angle per leg; thick: stance\n({feet_down.min()}–{feet_down.max()} "
                f"feet down, mean {feet_down.mean():.2f})")
    a.legend(ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False,
             handlelength=1.5, columnspacing=1.0)

    # The Coulomb run: every slipping foot on the step |F_xy|/F_z = μ (the law, checked here;
    # plotting it back would show the input law, so panel B shows the stand-in robot instead).
    speed = np.hypot(sx, sy)
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
    mu = float(np.median(ratio[slipping])) if np.any(slipping) else 1.0  # the run's μ
    # the thesis' statistic: 5 % and 95 % percentiles of v_x of the feet in contact, mm/s
    values["slip_x_p5_mm_s"], values["slip_x_p95_mm_s"] = (float(p) for p in
                                                           np.percentile(1e3 * sx, [5, 95]))
    values["slip_x_p2_5_mm_s"], values["slip_x_p97_5_mm_s"] = (
        float(p) for p in np.percentile(1e3 * sx, [2.5, 97.5]))
    values["slip_speed_median_mm_s"] = float(np.median(1e3 * speed))
    # the tripod for contrast (§3.5.1.5: "much more slipping than the tripod gait")
    _, tsx, _, _ = contact_slip(tri)
    values["tripod_slip_x_p5_mm_s"], values["tripod_slip_x_p95_mm_s"] = (
        float(p) for p in np.percentile(1e3 * tsx, [5, 95]))

    # The viscous-Coulomb run: |F_xy|/F_z = μ|u| in the ansatz' own units (eq. 3.19).
    _, vx_, vy_, vratio = contact_slip(v)
    vspeed = np.hypot(vx_, vy_)
    fit = c.linfit(vspeed, vratio)
    values["viscous_fit"] = fit
    values["viscous_fit_slope"] = fit["k"]
    values["viscous_slip_x_p5_mm_s"], values["viscous_slip_x_p95_mm_s"] = (
        float(p) for p in np.percentile(1e3 * vx_, [5, 95]))

    # MuJoCo standing in for the measured robot: its own contacts, forces and slip, over the
    # part of our run it covers.
    mj = rb.mujoco_until(rb.mujoco_as_measured(args.data, "metachronal"), k.time[-1])
    feet = rb.mujoco_feet(mj, k.legs)
    values["mujoco_as_measured"] = feet is not None
    a = axes[1]
    if feet is not None:
        label = mj["label"] + rb.STANDIN
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
        # (B) the thesis' panel with the stand-in's feet, against what each law would give
        a.plot(1e3 * msp, mratio, ".", ms=4, color=c.MUJOCO, alpha=0.5,
               label=f"{mj['label']}: feet down, > 2 % of Mg")
        top = 1e3 * max(float(np.max(msp)), 1e-3)
        a.plot([0, 0, top], [0, mu, mu], color=c.COULOMB, lw=1.8,
               label=f"Coulomb law: the step at μ = {mu:.3g}")
        mfit = c.linfit(msp, mratio)
        if mfit["k"] is not None:
            xs = np.linspace(0, top / 1e3, 2)
            a.plot(1e3 * xs, mfit["k"] * xs + mfit["b"], color=c.REFERENCE, ls="--", lw=1.3,
                   label=f"line fit: R² = {mfit['r2']:.2f}")
        a.set_ylim(-0.03, 1.15 * mu)
        a.legend(loc="center right")
        a.set_title(f"(B) |F_xy| / F_z against slip speed:\n{label}")
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
        for block in ("base", "solref_timeconst", "timestep"):
            for run in rb.mujoco_runs(args.data, "metachronal", block):
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
            f"{label}: ({values['mujoco_slip_x_p5_mm_s']:.1f}, "
            f"{values['mujoco_slip_x_p95_mm_s']:.1f}) mm/s over {mj['t'][-1]:.0f} s.")
        values["mujoco_step_note"] = (
            f"{label}: feet slipping faster than 5 mm/s have median |F_xy|/F_z = "
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
            f"{label}: {values['mujoco_feet_down_mean']:.3g} feet down on average, "
            f"duty {values['mujoco_duty_mean']:.3g}.")
    else:
        for key in ("mujoco_slip_note", "mujoco_step_note", "mujoco_duty_note"):
            values[key] = rb.MUJOCO_MISSING + "."
        a.text(0.5, 0.5, "needs force and slip data of a robot:\nthe thesis' F/T data, or "
               "MuJoCo's\nBigANT as a stand-in (no MuJoCo\ndata here: see the values)",
               transform=a.transAxes, ha="center", va="center", color="0.3")
        a.set_xticks([])
        a.set_yticks([])
        a.set_title("(B) |F_xy| / F_z against slip speed")
    a.set_xlabel("slip speed |u| of the foot [mm/s]")
    a.set_ylabel("|F_xy| / F_z")

    # (C) the slip velocities the thesis quotes, as cumulative distributions: its 5 % and 95 %
    # percentiles read off where the curves cross 0.05 and 0.95.
    a = axes[2]
    cdf(a, 1e3 * sx, c.COULOMB, "ours, Coulomb")
    cdf(a, 1e3 * vx_, c.VISCOUS, "ours, viscous-Coulomb")
    if feet is not None:
        cdf(a, 1e3 * msx, c.MUJOCO, mj["label"])
    cdf(a, 1e3 * tsx, c.NEUTRAL, "tripod, ours, Coulomb", ls="--")
    for q in (0.05, 0.95):
        a.axhline(q, color="0.5", lw=0.8, ls=":")
    quoted = ledger_thesis("3.5.1.5-slip-percentiles")
    if quoted is not None:
        # the thesis' measured percentiles: red, the colour the thesis gives its measurements
        a.plot(quoted, [0.05, 0.95], "*", color=c.MEASURED, ms=13,
               label=f"thesis, BigANT measured: ({quoted[0]:g}, {quoted[1]:g})")
    a.set_xlabel("slip velocity v_x of feet down [mm/s]")
    a.set_ylabel("fraction of foot frames ≤ v_x")
    a.set_title("(C) slip velocity of feet in contact,\nmetachronal gait (5 %, 95 %: dotted)")
    a.legend(loc="lower right")
    fig.suptitle("BigANT, metachronal gait, synthetic; slip v_x of feet down, 5–95 %: "
                 f"({values['slip_x_p5_mm_s']:.1f}, {values['slip_x_p95_mm_s']:.1f}) mm/s "
                 "(ours, Coulomb)" + (
                     f", ({values['mujoco_slip_x_p5_mm_s']:.1f}, "
                     f"{values['mujoco_slip_x_p95_mm_s']:.1f}) mm/s ({mj['label']})"
                     if feet is not None else ""))
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
