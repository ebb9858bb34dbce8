#!/usr/bin/python3
"""Thesis Figs. 3.3 and 3.4 / §3.3: the spring-support search path of a 2-D and a 3-D robot.

Input: DATA/ch3_legged/fig3_3_4.csv (kind legged_support_path: per robot its feet, the visited
states (α, β, z) with the contact set after each, the balance of each state's contact set — the
"target" the search heads for — and the result). Output: OUT/fig3_3_4.png,
OUT/values/fig3_3_4.json.

A foot's height is h_j = −β q_x,j + α q_y,j + q_z,j + z (eq. 3.6); its contact plane h_j = 0 is a
line in (β, z) for the 2-D robot (all q_y = 0) and a plane in (α, β, z) for the 3-D one. Checks
computed here: the potential U = Σ ½K min(h, 0)² + Mg z never rises along the path; the end is
the balance of its own contact set; tilt steps with one or two contacts follow eqs. 3.11 and 3.12.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import legged as lg  # noqa: E402

NAME = "fig3_3_4"
COLORS = c.CATEGORICAL  # the legs have no thesis meaning: none of the laws' colours, no red


class Robot:
    def __init__(self, t: c.Table, pid: int):
        m = t["id"] == pid
        row = t.str("row")
        f = m & (row == "foot")
        o = np.argsort(t["foot"][f])
        self.name = str(t.str("robot")[f][0])
        self.q = np.column_stack([t["qx"][f][o], t["qy"][f][o], t["qz"][f][o]])
        self.K = t["K"][f][o]
        self.Fz = t["Fz"][f][o]
        s = m & (row == "step")
        o = np.argsort(t["step"][s])
        self.s = np.column_stack([t["alpha"][s][o], t["beta"][s][o], t["z"][s][o]])
        self.target = np.column_stack([t["target_alpha"][s][o], t["target_beta"][s][o],
                                       t["target_z"][s][o]])
        self.mask = [str(x) for x in t.str("mask")[s][o]]
        self.changed = t["changed"][s][o].astype(int)
        r = np.flatnonzero(m & (row == "result"))
        if r.size != 1 or self.s.shape[0] == 0:
            c.fail(f"{t.path}: robot id {pid}: needs step rows and one result row")
        r = r[0]
        self.status = str(t.str("status")[r])
        self.iterations = int(t["iterations"][r])
        self.residual = float(t["residual"][r])
        self.final = np.array([t["alpha"][r], t["beta"][r], t["z"][r]])
        self.final_mask = str(t.str("mask")[r])
        self.planar = bool(np.all(self.q[:, 1] == 0))
        self.Mg = float(self.Fz.sum()) if self.status in ("balanced", "line", "point") else None

    def heights(self, s) -> np.ndarray:
        a, b, z = s
        return -b * self.q[:, 0] + a * self.q[:, 1] + self.q[:, 2] + z

    def potential(self, s, Mg: float) -> float:
        h = np.minimum(self.heights(s), 0.0)
        return float(0.5 * np.sum(self.K * h * h) + Mg * s[2])


def cosine(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(a @ b / (np.linalg.norm(a) * np.linalg.norm(b)))


def check(r: Robot, values: dict, key: str) -> None:
    Mg = r.Mg if r.Mg else 1.0
    U = np.array([r.potential(s, Mg) for s in r.s])
    values[f"{key}_robot"] = r.name
    values[f"{key}_states"] = int(r.s.shape[0])
    values[f"{key}_contact_changes"] = r.iterations
    values[f"{key}_status"] = r.status
    values[f"{key}_residual"] = r.residual
    values[f"{key}_final_state"] = r.final.tolist()
    values[f"{key}_final_contacts"] = r.final_mask
    values[f"{key}_loads"] = r.Fz.tolist()
    values[f"{key}_potential"] = U.tolist()
    values[f"{key}_potential_max_rise"] = float(np.max(np.diff(U))) if U.size > 1 else 0.0
    values[f"{key}_potential_decreases"] = bool(U.size < 2 or np.max(np.diff(U)) <= 1e-12 * abs(U).max())
    last = r.target[-1]
    values[f"{key}_end_is_own_balance"] = bool(np.all(np.isfinite(last)) and
                                              np.max(np.abs(last - r.final)) <= 1e-9)
    values[f"{key}_balanced"] = bool(r.status in ("balanced", "line") and r.residual <= 1e-9)
    # tilt steps (no target: the contacts cannot balance the moment) with one or two contacts
    for i in range(r.s.shape[0] - 1):
        if np.all(np.isfinite(r.target[i])):
            continue
        feet = [j for j, ch in enumerate(r.mask[i]) if ch == "C"]
        step = r.s[i + 1] - r.s[i]
        if np.linalg.norm(step) == 0:
            continue
        if len(feet) == 1:
            qx, qy = r.q[feet[0], 0], r.q[feet[0], 1]
            printed = np.array([qy, -qx, -qy * qy - qx * qx])  # eq. 3.11, [δα, δβ, δz]
            values[f"{key}_eq3_11_cos"] = cosine(step, printed)
        elif len(feet) == 2:
            (x1, y1), (x2, y2) = r.q[feet[0], :2], r.q[feet[1], :2]
            dx, dy, cc = x1 - x2, y1 - y2, y1 * x2 - y2 * x1
            printed = -np.array([dy, dx, cc]) * cc / abs(cc)  # eq. 3.12 as printed, [δα, δβ, δz]
            swapped = -np.array([dx, dy, cc]) * cc / abs(cc)  # its entries read as [δβ, δα, δz]
            values[f"{key}_eq3_12_cos_printed"] = cosine(step, printed)
            values[f"{key}_eq3_12_cos_swapped"] = cosine(step, swapped)


def zigzag(x0, y0, y1, n=6, w=0.018):
    """A spring from (x0, y0) down to (x0, y1)."""
    ys = np.linspace(y0, y1, 2 * n + 3)
    xs = np.full_like(ys, x0)
    xs[2:-2:2] += w
    xs[3:-2:2] -= w
    return xs, ys


def plot_2d(fig, gs_top, gs_bottom, r: Robot):
    ax = fig.add_subplot(gs_top)
    b_all, z_all = r.s[:, 1], r.s[:, 2]  # the view frames the path; counterfactuals run off it
    bspan = max(np.ptp(b_all), 0.05)
    bs = np.linspace(b_all.min() - 0.35 * bspan, b_all.max() + 0.35 * bspan, 50)
    for j in range(r.q.shape[0]):
        ax.plot(bs, bs * r.q[j, 0] - r.q[j, 2], color=COLORS[j], lw=2,
                label=f"leg {j}: z = β q_x − q_z")
    for i in range(r.s.shape[0]):
        b, z = r.s[i, 1], r.s[i, 2]
        if i + 1 < r.s.shape[0]:
            ax.plot(r.s[i:i + 2, 1], r.s[i:i + 2, 2], "k-", lw=1.6)
            tg = r.target[i]
            if np.all(np.isfinite(tg)) and np.linalg.norm(tg - r.s[i + 1]) > 1e-9:
                ax.plot([r.s[i + 1, 1], tg[1]], [r.s[i + 1, 2], tg[2]], "k--", lw=0.9)
        last = i == r.s.shape[0] - 1
        ax.plot(b, z, "*" if last else "o", color="k", ms=13 if last else 5)
        if i > 0 and r.changed[i] >= 0:
            ax.plot(b, z, "o", ms=11, mfc="none", mec=COLORS[r.changed[i]], mew=1.5)
        if not (last and np.allclose(r.s[i], r.s[i - 1])):
            ax.annotate(str(i), (b, z), textcoords="offset points",
                        xytext=(-14 if i % 2 else 7, -14 if i % 2 else 6), fontsize=12,
                        fontweight="bold")
    ax.set_xlim(bs[0], bs[-1])
    zspan = max(np.ptp(z_all), 0.02)
    ax.set_ylim(z_all.min() - 0.4 * zspan, z_all.max() + 0.4 * zspan)
    ax.set_xlabel("pitch slope β")
    ax.set_ylabel("body height z [m]")
    ax.set_title("Fig. 3.3 (a): 2-D robot, search in (β, z); above a leg's line\nthat leg is in "
                 "the air (black: path; dashed: the counterfactual\nrest of a segment; star: "
                 "balance)")
    ax.legend(loc="best", title="leg touches the ground on")
    # poses
    n = r.s.shape[0]
    sub = gs_bottom.subgridspec(1, n)
    xmin, xmax = r.q[:, 0].min() - 0.08, r.q[:, 0].max() + 0.08
    for i in range(n):
        axp = fig.add_subplot(sub[0, i])
        a, b, z = r.s[i]
        h = r.heights(r.s[i])
        axp.axhline(0, color="0.4", lw=1.2)
        xb = np.array([xmin, xmax])
        axp.plot(xb, -b * xb + z, color="k", lw=3)
        for j in range(r.q.shape[0]):
            hip = -b * r.q[j, 0] + z
            foot = max(h[j], 0.0)
            xs, ys = zigzag(r.q[j, 0], hip, foot)
            axp.plot(xs, ys, color=COLORS[j], lw=1.3)
            if r.mask[i][j] == "C":
                axp.plot(r.q[j, 0], 0, "^", color=COLORS[j], ms=6)
            if i > 0 and r.changed[i] == j:
                axp.plot(r.q[j, 0], foot, "o", ms=13, mfc="none", mec="k", mew=1.2)
        axp.set_xlim(xmin - 0.02, xmax + 0.02)
        axp.set_ylim(-0.03, 0.32)
        axp.set_title(f"{i}: {r.mask[i]}\nβ = {b:.3f}\nz = {z:.3f}")
        axp.set_xticks([])
        if i:
            axp.set_yticks([])
        else:
            axp.set_ylabel("height [m]")
        axp.grid(False)


def plot_3d(fig, gs_top, gs_bottom, r: Robot):
    ax = fig.add_subplot(gs_top, projection="3d")
    A, B = r.s[:, 0], r.s[:, 1]
    aspan, bspan = max(np.ptp(A), 0.05), max(np.ptp(B), 0.05)
    ag = np.linspace(A.min() - 0.3 * aspan, A.max() + 0.3 * aspan, 12)
    bg = np.linspace(B.min() - 0.3 * bspan, B.max() + 0.3 * bspan, 12)
    AA, BB = np.meshgrid(ag, bg)
    zlo, zhi = r.s[:, 2].min() - 0.03, r.s[:, 2].max() + 0.03
    for j in range(r.q.shape[0]):
        ZZ = BB * r.q[j, 0] - AA * r.q[j, 1] - r.q[j, 2]
        ZZ = np.where((ZZ >= zlo) & (ZZ <= zhi), ZZ, np.nan)
        ax.plot_surface(AA, BB, ZZ, color=COLORS[j], alpha=0.25, linewidth=0, shade=False)
        ax.plot([], [], color=COLORS[j], lw=6, alpha=0.5, label=f"leg {j}'s contact plane h = 0")
    ax.plot(A, B, r.s[:, 2], "k-o", ms=4, lw=1.8)
    for i in range(r.s.shape[0] - 1):
        tg = r.target[i]
        if np.all(np.isfinite(tg)) and np.linalg.norm(tg - r.s[i + 1]) > 1e-9:
            ax.plot([r.s[i + 1, 0], tg[0]], [r.s[i + 1, 1], tg[1]], [r.s[i + 1, 2], tg[2]], "k--")
    ax.plot([A[-1]], [B[-1]], [r.s[-1, 2]], "*", color="k", ms=14)
    for i in range(r.s.shape[0]):
        if i == r.s.shape[0] - 1 and np.allclose(r.s[i], r.s[i - 1]):
            continue
        ax.text(A[i], B[i], r.s[i, 2] + 0.004, str(i), fontsize=12, fontweight="bold")
    ax.set_xlabel("roll slope α")
    ax.set_ylabel("pitch slope β")
    ax.set_zlabel("height z [m]")
    ax.set_zlim(zlo, zhi)
    ax.view_init(elev=22, azim=-60)
    ax.set_title("Fig. 3.4 (left): 3-D robot, search in (α, β, z)")
    ax.legend(loc="upper left", bbox_to_anchor=(-0.05, 1.0))
    n = r.s.shape[0]
    cols = (n + 1) // 2
    sub = gs_bottom.subgridspec(2, cols, hspace=0.3, wspace=0.0)
    qx, qy = r.q[:, 0], r.q[:, 1]
    corners = np.array([[qx.min(), qy.min()], [qx.max(), qy.min()], [qx.max(), qy.max()],
                        [qx.min(), qy.max()], [qx.min(), qy.min()]])
    for i in range(n):
        axp = fig.add_subplot(sub[i // cols, i % cols], projection="3d")
        a, b, z = r.s[i]
        h = r.heights(r.s[i])
        gx = np.array([qx.min() - 0.15, qx.max() + 0.15])
        gy = np.array([qy.min() - 0.15, qy.max() + 0.15])
        GX, GY = np.meshgrid(gx, gy)
        axp.plot_surface(GX, GY, np.zeros_like(GX), color="0.85", alpha=0.4, linewidth=0)
        cz = -b * corners[:, 0] + a * corners[:, 1] + z
        axp.plot(corners[:, 0], corners[:, 1], cz, color="k", lw=2.5)
        for j in range(r.q.shape[0]):
            hip = -b * qx[j] + a * qy[j] + z
            foot = max(h[j], 0.0)
            axp.plot([qx[j], qx[j]], [qy[j], qy[j]], [hip, foot], color=COLORS[j], lw=2)
            if r.mask[i][j] == "C":
                axp.plot([qx[j]], [qy[j]], [0], "^", color=COLORS[j], ms=6)
            if i > 0 and r.changed[i] == j:
                axp.plot([qx[j]], [qy[j]], [foot], "o", ms=12, mfc="none", mec="k")
        axp.set_zlim(0, 0.3)
        axp.set_box_aspect(None, zoom=1.45)
        axp.set_xticks([])
        axp.set_yticks([])
        axp.set_zticks([])
        axp.view_init(elev=18, azim=-60)
        axp.set_title(f"{i}: {r.mask[i]}\nα = {a:.3f}, β = {b:.3f}, z = {z:.3f}", pad=0)


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = lg.table(args.data, NAME, ["id", "robot", "row", "step", "foot", "alpha", "beta", "z",
                                   "contacts", "changed", "mask", "target_alpha", "target_beta",
                                   "target_z", "qx", "qy", "qz", "K", "Fz", "status",
                                   "iterations", "residual"])
    robots = [Robot(t, int(pid)) for pid in sorted(set(t["id"].astype(int).tolist()))]
    planar = [r for r in robots if r.planar]
    spatial = [r for r in robots if not r.planar]
    if not planar or not spatial:
        c.fail(f"{t.path}: needs a 2-D robot (all q_y = 0) and a 3-D robot")
    r2, r3 = planar[0], spatial[0]
    values: dict = {}
    check(r2, values, "robot2d")
    check(r3, values, "robot3d")
    values["all_potential_decrease"] = bool(values["robot2d_potential_decreases"] and
                                            values["robot3d_potential_decreases"])
    values["all_end_balanced"] = bool(values["robot2d_balanced"] and values["robot3d_balanced"]
                                      and values["robot2d_end_is_own_balance"]
                                      and values["robot3d_end_is_own_balance"])
    values["eq3_11_one_minus_cos"] = (1.0 - values["robot3d_eq3_11_cos"]
                                      if "robot3d_eq3_11_cos" in values else None)
    values["eq3_12_printed_cos"] = values.get("robot3d_eq3_12_cos_printed")
    values["eq3_12_swapped_cos"] = values.get("robot3d_eq3_12_cos_swapped")

    fig = plt.figure(figsize=(14, 13.5))
    outer = fig.add_gridspec(2, 2, height_ratios=[1.2, 1.0], hspace=0.28, wspace=0.14,
                             left=0.07, right=0.97, top=0.88, bottom=0.03)
    plot_2d(fig, outer[0, 0], outer[1, 0], r2)
    plot_3d(fig, outer[0, 1], outer[1, 1], r3)
    fig.suptitle("Figs. 3.3, 3.4: the spring-support search (§3.3). Bottom: the robot at each "
                 "state with its contact set\n(C: in contact, -: in the air, one letter per leg "
                 "0…3), legs as springs, ▲ feet in the contact set, ○ the leg that just changed")
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
