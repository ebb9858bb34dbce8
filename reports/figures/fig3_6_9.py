#!/usr/bin/python3
"""Thesis Figs. 3.6 and 3.9: per-leg forces of BigANT, tripod and metachronal gait (synthetic).

Input: DATA/ch3_robots/{tripod,metachronal}_{viscous,coulomb}.csv. Output: OUT/fig3_6.png
(tripod, Fig. 3.6), OUT/fig3_9.png (metachronal, Fig. 3.9), OUT/values/fig3_6_9.json.
One gait cycle is shown (the second: the runs repeat it); the values cover the whole runs.

Per leg (rows HL … FR), as in the thesis: F_x/Mg and F_y/Mg of both laws and F_z/Mg of the
spring support. The viscous-Coulomb forces carry the ansatz' own units, so — as the thesis does
against its F/T measurements — they are scaled per frame by the σ that best matches the Coulomb
forces' magnitudes (§3.5.1.4). The thesis' measured forces (red) need its F/T data; in their
place, labelled as a stand-in and in MuJoCo's own colour, is MuJoCo's BigANT driven by the same
feet (DATA/ch3_peer/fig3_14.csv, base runs, §3.5.4): the floor's forces on each foot from its
contacts, over MuJoCo's own ΣF_z. Without that file (a build without MuJoCo) its lines are
skipped and the title says so. MuJoCo's F_z shares follow our spring support closely; its planar
forces stay small, because its feet hang on x/y position actuators of kp = 100 N/m (§3.5.4),
which push no harder than kp times the tracking error (~0.01 Mg per cm), where our feet follow
the gait exactly and press against each other.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import robots as rb  # noqa: E402

NAME = "fig3_6_9"
# gait, the PNG it goes to (named after the thesis figure), its title
GAITS = (("tripod", "fig3_6", "Fig. 3.6, tripod"),
         ("metachronal", "fig3_9", "Fig. 3.9, metachronal"))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    runs = {g: (rb.Run(args.data, f"{g}_viscous"), rb.Run(args.data, f"{g}_coulomb"))
            for g, _, _ in GAITS}
    values: dict = {}
    for gait, png, title in GAITS:
        v, k = runs[gait]
        legs = v.legs
        fig, axes = plt.subplots(len(legs), 3, figsize=(12, 1.9 * len(legs) + 1.6), sharex=True)
        # one gait cycle, the second (the first starts from the clock's rest phase): readable
        freq = float(v.meta.get("scene", {}).get("gait", {}).get("frequency", 0.1))
        t0 = 1.0 / freq if v.time[-1] >= 2.0 / freq else 0.0
        cyc = (v.time >= t0) & (v.time <= t0 + 1.0 / freq)
        t = v.time
        w = rb.mg(k)
        vx, vy = rb.planar(v)
        kx, ky = rb.planar(k)
        s = rb.sigma(vx, vy, kx, ky)
        values[f"{gait}_sigma_median"] = float(np.median(s[s > 0])) if np.any(s > 0) else None
        values[f"{gait}_mg_spread"] = float(np.ptp(w) / np.mean(w))
        mj = rb.mujoco_until(rb.mujoco_as_measured(args.data, gait), t[-1])
        feet = rb.mujoco_feet(mj, legs)
        if feet is not None:
            mt = mj["t"]
            mcyc = (mt >= t0) & (mt <= t0 + 1.0 / freq)
            mw = np.sum([feet[leg]["Fz"] for leg in legs], axis=0)
            mw = np.where(mw > 0, mw, np.nan)
        fz_diff, fx_diff = [], []
        for i, leg in enumerate(legs):
            for j, (pv, pk) in enumerate(((vx[:, i], kx[:, i]), (vy[:, i], ky[:, i]))):
                a = axes[i, j]
                a.plot(t[cyc], (s * pv / w)[cyc], color=c.VISCOUS, lw=1.2)
                a.plot(t[cyc], (pk / w)[cyc], color=c.COULOMB, lw=1.0, ls="--")
                if feet is not None:
                    a.plot(mt[mcyc], (feet[leg][("Fx", "Fy")[j]] / mw)[mcyc], color=c.MUJOCO,
                           lw=1.1)
            a = axes[i, 2]
            a.plot(t[cyc], (v.leg("Fz", leg) / rb.mg(v))[cyc], color=c.SUPPORT, lw=1.2)
            if feet is not None:
                a.plot(mt[mcyc], (feet[leg]["Fz"] / mw)[mcyc], color=c.MUJOCO, lw=1.1)
                # whole runs: ours at MuJoCo's sample times against MuJoCo's
                fz_diff.append(rb.nearest(v, f"Fz_{leg}", mt) / np.interp(mt, t, rb.mg(v))
                               - feet[leg]["Fz"] / mw)
                fx_diff.append(rb.nearest(k, f"Fx_{leg}", mt) / np.interp(mt, t, w)
                               - feet[leg]["Fx"] / mw)
            a.set_ylim(-0.05, 0.65)
            axes[i, 0].set_ylabel(leg, fontsize=12, fontweight="bold", rotation=0, ha="right",
                                  va="center", labelpad=12)
            values[f"{gait}_fz_max_{leg}"] = float(np.max(v.leg("Fz", leg) / rb.mg(v)))
        values[f"{gait}_mujoco_as_measured"] = feet is not None
        if feet is not None:
            # MuJoCo's contacts start a step late or early against our spring support's: the
            # rms over the whole run is dominated by the handovers
            values[f"{gait}_mujoco_fz_rms_diff"] = rb.rms(np.concatenate(fz_diff))
            values[f"{gait}_mujoco_fx_coulomb_rms_diff"] = rb.rms(np.concatenate(fx_diff))
            values[f"{gait}_mujoco_fz_max"] = float(np.nanmax([feet[leg]["Fz"] / mw
                                                               for leg in legs]))
        for j, lab in enumerate(("F_x / Mg", "F_y / Mg", "F_z / Mg")):
            axes[0, j].set_title(lab)
            axes[-1, j].set_xlabel("t [s]")
        handles = [Line2D([], [], color=c.VISCOUS, lw=1.5, label="viscous-Coulomb (σ-scaled)"),
                   Line2D([], [], color=c.COULOMB, lw=1.5, ls="--", label="Coulomb"),
                   Line2D([], [], color=c.SUPPORT, lw=1.5, label="spring support (F_z)")]
        if feet is not None:
            handles.append(Line2D([], [], color=c.MUJOCO, lw=1.5,
                                  label=mj["label"] + rb.STANDIN))
        fig.legend(handles=handles, loc="upper center", ncol=len(handles) if feet is None else 2,
                   bbox_to_anchor=(0.5, 0.965), frameon=False)
        fig.suptitle(f"{title}: BigANT's per-leg forces over one cycle, t = {t0:g}…"
                     f"{t0 + 1 / freq:g} s (synthetic; the thesis' red is F/T data)"
                     + ("" if feet is not None else "\n" + rb.MUJOCO_MISSING_TITLE), y=0.995)
        fig.tight_layout(rect=(0.02, 0, 1, 0.93))
        c.save_figure(fig, args.out, png)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
