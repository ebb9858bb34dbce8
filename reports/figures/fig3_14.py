#!/usr/bin/python3
"""Thesis Fig. 3.14 / §3.5.4: BigANT sim to sim, our model against MuJoCo driven by the same feet.

Input: DATA/ch3_peer/fig3_14.csv (kind peer_bigant: per gait and source -- ours_viscous,
ours_coulomb, mujoco -- the pose x, y, theta every sample time from the start; MuJoCo rows carry
the feet's tracking RMSE per axis; label names the MuJoCo variant: base, or the one parameter a
sensitivity block changed) and its sidecar.
Output: OUT/fig3_14.png, OUT/fig3_14_table.html (MuJoCo's sensitivity), OUT/values/fig3_14.json.

Panels per gait (rows: tripod, metachronal): x, y, theta against time for ours (viscous-Coulomb,
Coulomb) and MuJoCo (base thick; the sensitivity variants thin), and the path in the plane. The
thesis' red motion-capture line has no counterpart: we have no BigANT recordings, and MuJoCo is
the stand-in for the robot. Without MuJoCo in the build only our lines are drawn and the panels
say so.
"""
from __future__ import annotations

import sys

import html
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "fig3_14"
STUDY = "ch3_peer"
GAITS = ("tripod", "metachronal")
# The chapter's colours (common.py): the thesis drew its model blue and MuJoCo orange here, which
# in Figs. 3.5-3.10 are Coulomb and viscous-Coulomb; MuJoCo gets its own colour.
OURS_V, OURS_C, PEER = c.VISCOUS, c.COULOMB, c.MUJOCO
# The column each sensitivity label varies; "base" is MuJoCo as §3.5.4 sets it.
VARIED = {"mu": "mu", "solref_timeconst": "solref_timeconst",
          "solref_dampratio": "solref_dampratio", "timestep": "timestep", "kp_xy": "kp_xy",
          "lead": "lead", "thesis": "kp_z"}
# MuJoCo's own numerical and contact parameters (the spread of its answer); kp_xy and the lead
# change the actuators, i.e. the robot, and are listed but not counted in the spread.
SPREAD_LABELS = ("base", "mu", "solref_timeconst", "solref_dampratio", "timestep")


def series(t: c.Table, mask: np.ndarray) -> dict:
    order = np.argsort(t["t"][mask])
    return {k: t[k][mask][order] for k in ("t", "x", "y", "theta")}


def final(s: dict) -> np.ndarray:
    return np.array([s["x"][-1], s["y"][-1], s["theta"][-1]])


def gap(a: dict, b: dict) -> dict:
    """RMS over a's times of the difference in position (m) and heading (rad), and at the end."""
    bx, by, bth = (np.interp(a["t"], b["t"], b[k]) for k in ("x", "y", "theta"))
    dp = np.hypot(a["x"] - bx, a["y"] - by)
    dth = a["theta"] - bth
    return {"pos_rms": float(np.sqrt(np.mean(dp**2))), "theta_rms": float(np.sqrt(np.mean(dth**2))),
            "pos_end": float(dp[-1]), "theta_end": float(abs(dth[-1]))}


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    path = c.study_file(args.data, f"{NAME}.csv", STUDY)
    t = c.Table(path, ["gait", "source", "label", "t", "x", "y", "theta", "mu", "timestep",
                       "solref_timeconst", "solref_dampratio", "kp_xy", "kp_z", "K", "lead",
                       "rmse_x", "rmse_y", "rmse_z", "rmse_z_swing", "rmse_xy_foot_max",
                       "mean_contacts", "peer", "message"])
    if t.n == 0:
        c.fail(f"{path}: no data rows")
    gait, source, label = t.str("gait"), t.str("source"), t.str("label")
    mj_rows = (source == "mujoco") & np.isfinite(t["t"])
    has_peer = bool(mj_rows.any())
    values: dict = {"peer_available": has_peer,
                    "peer": str(t.str("peer")[mj_rows][0]) if has_peer else "none",
                    "K_ours": float(t["K"][0]), "kp_z": float(t["kp_z"][0])}
    fig, ax = plt.subplots(2, 4, figsize=(14, 8.4))
    rows_html = []
    spreads, gaps, tracking = [], [], []
    for i, g in enumerate(GAITS):
        on = gait == g
        if not on.any():
            c.fail(f"{path}: no rows for gait {g}")
        base = on & (label == "base")
        ov = series(t, base & (source == "ours_viscous"))
        oc = series(t, base & (source == "ours_coulomb"))
        if ov["t"].size == 0 or oc["t"].size == 0:
            c.fail(f"{path}: gait {g}: our rows (ours_viscous, ours_coulomb) missing")
        values[f"{g}_duration_s"] = float(ov["t"][-1])
        values[f"{g}_ours_viscous_end"] = final(ov).tolist()
        values[f"{g}_ours_coulomb_end"] = final(oc).tolist()
        values[f"{g}_laws_gap"] = gap(ov, oc)
        curves = [(ov, OURS_V, "-", 1.8, "ours, viscous-Coulomb"),
                  (oc, OURS_C, "--", 1.4, "ours, Coulomb")]
        if has_peer:
            mb = base & (source == "mujoco")
            mj = series(t, mb)
            values[f"{g}_mujoco_end"] = final(mj).tolist()
            gv, gc = gap(ov, mj), gap(oc, mj)
            values[f"{g}_viscous_vs_mujoco"] = gv
            values[f"{g}_coulomb_vs_mujoco"] = gc
            first = np.flatnonzero(mb)[0]
            trk = {k: float(t[k][first]) for k in ("rmse_x", "rmse_y", "rmse_z", "rmse_z_swing",
                                                  "rmse_xy_foot_max", "mean_contacts")}
            values[f"{g}_tracking"] = trk
            tracking.append(trk)
            # MuJoCo's variants: final pose of each.
            finals = {("base", "—"): final(mj)}
            gait_rows = []
            for lab in VARIED:
                lm = on & (source == "mujoco") & (label == lab)
                for v in np.unique(t[VARIED[lab]][lm]):
                    s = series(t, lm & (t[VARIED[lab]] == v))
                    finals[(lab, f"{v:g}")] = final(s)
                    ax[i, 0].plot(s["t"], s["x"], color=PEER, lw=0.6, alpha=0.45)
                    ax[i, 1].plot(s["t"], s["y"], color=PEER, lw=0.6, alpha=0.45)
                    ax[i, 2].plot(s["t"], np.degrees(s["theta"]), color=PEER, lw=0.6, alpha=0.45)
                    ax[i, 3].plot(s["x"], s["y"], color=PEER, lw=0.6, alpha=0.45)
                    first = np.flatnonzero(lm & (t[VARIED[lab]] == v))[0]
                    gait_rows.append((g, lab, f"{v:g}", finals[(lab, f"{v:g}")],
                                      float(t["rmse_xy_foot_max"][first])))
            pts = np.array([p for (lab, _), p in finals.items() if lab in SPREAD_LABELS])
            d = np.hypot(pts[:, None, 0] - pts[None, :, 0], pts[:, None, 1] - pts[None, :, 1])
            spread = {"pos": float(d.max()), "theta": float(np.ptp(pts[:, 2])),
                      "x": float(np.ptp(pts[:, 0])), "y": float(np.ptp(pts[:, 1])),
                      "runs": int(len(pts))}
            values[f"{g}_mujoco_spread"] = spread
            values[f"{g}_mujoco_final_x"] = {f"{lab} {v}": float(p[0])
                                             for (lab, v), p in finals.items()}
            ts = [p[:2] for (lab, _), p in finals.items() if lab in ("base", "timestep")]
            ts = np.array(ts)
            values[f"{g}_timestep_spread_mm"] = 1000 * float(
                np.max(np.hypot(ts[:, None, 0] - ts[None, :, 0], ts[:, None, 1] - ts[None, :, 1])))
            zb = t["z"][mb]
            values[f"{g}_mujoco_height_m"] = float(np.mean(zb))
            values[f"{g}_ours_height_m"] = float(np.mean(t["z"][base & (source == "ours_viscous")]))
            values[f"{g}_ours_mean_contacts"] = float(
                np.mean(t["contacts"][base & (source == "ours_viscous")]))
            values[f"{g}_mujoco_mean_contacts"] = trk["mean_contacts"]
            soft = on & (source == "mujoco") & (label == "solref_timeconst")
            if soft.any():
                tc = t["solref_timeconst"][soft].max()
                values[f"{g}_default_contact_extra_sink_cm"] = 100 * float(
                    np.mean(zb) - np.mean(t["z"][soft & (t["solref_timeconst"] == tc)]))
            thesis_x = [float(p[0]) for (lab, _), p in finals.items() if lab == "thesis"]
            values[f"{g}_thesis_variant_x"] = thesis_x[0] if thesis_x else None
            kp = on & (source == "mujoco") & (label == "kp_xy")
            values[f"{g}_kp_xy_variant_x"] = (float(np.nanmax(t["x"][kp & (t["t"] == t["t"][kp].max())]))
                                              if kp.any() else None)
            values[f"{g}_kp_xy_variant_tracking_cm"] = (
                100 * float(np.nanmax(t["rmse_xy_foot_max"][kp])) if kp.any() else None)
            spreads.append(spread)
            values[f"{g}_gap_over_spread"] = gv["pos_end"] / spread["pos"] if spread["pos"] else None
            # Flat numbers for the ledger's texts.
            values[f"{g}_tracking_xy_foot_max_cm"] = 100 * trk["rmse_xy_foot_max"]
            values[f"{g}_gap_end_cm"] = 100 * gv["pos_end"]
            values[f"{g}_coulomb_gap_end_cm"] = 100 * gc["pos_end"]
            values[f"{g}_spread_cm"] = 100 * spread["pos"]
            values[f"{g}_mujoco_x"] = float(mj["x"][-1])
            values[f"{g}_ours_viscous_x"] = float(ov["x"][-1])
            values[f"{g}_ours_coulomb_x"] = float(oc["x"][-1])
            values[f"{g}_viscous_over_mujoco_x"] = float(ov["x"][-1] / mj["x"][-1])
            values[f"{g}_coulomb_over_mujoco_x"] = float(oc["x"][-1] / mj["x"][-1])
            values[f"{g}_mujoco_theta_end_deg"] = float(np.degrees(mj["theta"][-1]))
            gaps.append(gv)
            rows_html += [(g, "base", "—", final(mj), trk["rmse_xy_foot_max"])] + gait_rows
            curves.append((mj, PEER, "-", 2.0, f"{values['peer'].replace('mujoco', 'MuJoCo')} "
                           "(stand-in for the measured robot)"))
        for s, col, ls, lw, lab in curves:
            ax[i, 0].plot(s["t"], s["x"], color=col, ls=ls, lw=lw, label=lab)
            ax[i, 1].plot(s["t"], s["y"], color=col, ls=ls, lw=lw)
            ax[i, 2].plot(s["t"], np.degrees(s["theta"]), color=col, ls=ls, lw=lw)
            ax[i, 3].plot(s["x"], s["y"], color=col, ls=ls, lw=lw)
        for j, yl in enumerate(("x [m]", "y [m]", "θ [deg]")):
            ax[i, j].set_xlabel("t [s]")
            ax[i, j].set_ylabel(yl)
            ax[i, j].set_title(f"{g}: {yl.split()[0]}")
        ax[i, 3].set_xlabel("x [m]")
        ax[i, 3].set_ylabel("y [m]")
        ax[i, 3].set_title(f"{g}: path")
        if not has_peer:
            ax[i, 3].text(0.5, 0.5, "MuJoCo not in this build\n(SLIPWALK_MUJOCO=OFF or "
                          "libmujoco-dev missing)", transform=ax[i, 3].transAxes, ha="center",
                          color="0.4")

    if has_peer:
        values["tracking_xy_foot_max_cm"] = 100 * max(tr["rmse_xy_foot_max"] for tr in tracking)
        values["tracking_rmse_x_cm"] = 100 * max(tr["rmse_x"] for tr in tracking)
        values["tracking_rmse_y_cm"] = 100 * max(tr["rmse_y"] for tr in tracking)
        values["tracking_rmse_z_cm"] = 100 * max(tr["rmse_z"] for tr in tracking)
        values["tracking_rmse_z_swing_cm"] = 100 * max(tr["rmse_z_swing"] for tr in tracking)
        values["stance_deflection_cm"] = 100 * 8.18 * 9.81 / 3 / values["kp_z"]
        ratios = [values[f"{g}_gap_over_spread"] for g in GAITS]
        values["gap_over_spread_max"] = max(r for r in ratios if r is not None)
        values["mujoco_spread_pos_cm"] = [100 * s["pos"] for s in spreads]
        values["mujoco_spread_theta_deg"] = [float(np.degrees(s["theta"])) for s in spreads]
        values["viscous_gap_end_cm"] = [100 * gp["pos_end"] for gp in gaps]
        values["viscous_gap_theta_end_deg"] = [float(np.degrees(gp["theta_end"])) for gp in gaps]
        values["laws_gap_end_cm"] = [100 * values[f"{g}_laws_gap"]["pos_end"] for g in GAITS]
        values["ours_closer_to_mujoco_than_its_spread"] = bool(values["gap_over_spread_max"] <= 1)
        kpv = [values[f"{g}_kp_xy_variant_tracking_cm"] for g in GAITS]
        values["kp_xy_variant_tracking_cm"] = max(kpv) if None not in kpv else None
        values["kp_xy_variant"] = float(np.nanmax(t["kp_xy"][label == "kp_xy"])) if (
            label == "kp_xy").any() else None
    cells = ["<table class='data'><thead><tr><th>gait</th><th>MuJoCo variant</th><th>value</th>"
             "<th>final x [m]</th><th>final y [m]</th><th>final θ [deg]</th>"
             "<th>worst foot xy tracking RMSE [mm]</th></tr></thead><tbody>"]
    for g, lab, v, p, rm in rows_html:
        cells.append(f"<tr><td>{g}</td><td>{html.escape(lab)}</td><td>{v}</td>"
                     f"<td>{p[0]:.3f}</td><td>{p[1]:.3f}</td><td>{np.degrees(p[2]):.2f}</td>"
                     f"<td>{1000 * rm:.1f}</td></tr>")
    for g in GAITS:
        for law in ("viscous", "coulomb"):
            p = values[f"{g}_ours_{law}_end"]
            cells.append(f"<tr><td>{g}</td><td><b>ours, {law}</b></td><td>K = "
                         f"{values['K_ours']:g} N/m</td><td>{p[0]:.3f}</td><td>{p[1]:.3f}</td>"
                         f"<td>{np.degrees(p[2]):.2f}</td><td>—</td></tr>")
    cells.append("</tbody></table>")
    if has_peer:
        cells.append("<p>MuJoCo's spread of the final position over its friction, solref and time "
                     "step (base and one change at a time): "
                     + ", ".join(f"{g} {100 * s['pos']:.1f} cm / {np.degrees(s['theta']):.2f}°"
                                 for g, s in zip(GAITS, spreads))
                     + "; our viscous-Coulomb model's final distance from MuJoCo's base run: "
                     + ", ".join(f"{g} {100 * gp['pos_end']:.1f} cm / "
                                 f"{np.degrees(gp['theta_end']):.2f}°"
                                 for g, gp in zip(GAITS, gaps)) + ".</p>")
    else:
        cells.append("<p>MuJoCo not in this build: no sensitivity table.</p>")
    c.atomic_write_text(args.out / f"{NAME}_table.html", "\n".join(cells) + "\n")
    handles, labels = ax[0, 0].get_legend_handles_labels()
    if has_peer:
        handles.append(Line2D([], [], color=PEER, lw=0.8, alpha=0.6))
        labels.append("MuJoCo with one parameter changed (table)")
    fig.legend(handles, labels, loc="upper center", ncol=2, frameon=False,
               bbox_to_anchor=(0.5, 1.0))
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
