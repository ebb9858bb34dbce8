#!/usr/bin/python3
"""Thesis Table 4.1 / §4.4.1: the estimated transducer offsets and leg weights, per leg.

Input: DATA/ch4_calibration/parameters.csv (calib_parameters, one calibration of the synthetic
BigANT, seed 1). Output: OUT/table4_1_table.html, OUT/values/table4_1.json.

The synthetic transducers' true offsets and leg weights ARE Table 4.1's printed values
(lib/calibration/synthetic.cpp), so the table shows each estimate ± its standard error with the
truth beside it, and the measure is z = (estimate − truth) / SE, never estimate against thesis.
Below Table 4.1's rows the same for the mounting errors of the full model (rotation vector of R̃_k,
identifiable displacement u_k), which the thesis does not tabulate.

The study runs the default noise and the noiseless robot; the table shows the default, and the
noiseless one gives zero_noise_<block>_error_max.

Values: per block (force offsets, torque offsets, weights, rotations, displacements) the largest
|z| and whether it is ≤ Z_TABLE; the fraction of all parameters within 3 SE; the largest
difference between the file's truth and the ledger's Table 4.1 (0 when the study's truth is the
table); per leg and parameter the estimate, SE and z.
"""
from __future__ import annotations

import html
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import calibration as cal  # noqa: E402
import common as c  # noqa: E402

NAME = "table4_1"
# Threshold of the ledger, fixed before the study's data existed: the largest |z| of a block of
# 6 to 18 estimates; for correct standard errors P(max |z| > 4) ≈ 18 × 6.3e-5 ≈ 0.1 %.
Z_TABLE = 4.0
BLOCKS = {"force_offset": cal.OFFSET_FORCE, "torque_offset": cal.OFFSET_TORQUE,
          "weight": ("weight",), "rotation": cal.ROTATION, "displacement": cal.DISPLACEMENT}
ROW_LABEL = {"offset_fx": "f_offset x [N]", "offset_fy": "f_offset y [N]",
             "offset_fz": "f_offset z [N]", "offset_tx": "τ_offset x [N·m]",
             "offset_ty": "τ_offset y [N·m]", "offset_tz": "τ_offset z [N·m]",
             "weight": "m g [N]", "rotation_x": "R̃ rotation x [mrad]",
             "rotation_y": "R̃ rotation y [mrad]", "rotation_z": "R̃ rotation z [mrad]",
             "displacement_x": "u x [mm]", "displacement_y": "u y [mm]",
             "displacement_z": "u z [mm]"}
SCALE = {"rotation": 1e3, "displacement": 1e3}  # shown in mrad, mm
THESIS_ROWS = {"force_offset": "table4.1-force-offsets", "torque_offset": "table4.1-torque-offsets",
               "weight": "table4.1-leg-gravity"}


def digits(se: float) -> int:
    """Decimals that show the SE to two significant digits (at most 6)."""
    if not np.isfinite(se) or se <= 0:
        return 4
    return int(min(6, max(0, 1 - np.floor(np.log10(se)))))


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    everything = cal.load(args.data, "parameters.csv", cal.PARAMETER_COLUMNS)
    t = cal.at_noise(everything)
    legs = cal.legs_in(t)
    v: dict = {"z_bound": Z_TABLE, "legs": legs}
    # the noiseless robot, where the study ran it: every error should be round-off
    if "noise_scale" in everything.columns and np.any(everything["noise_scale"] == 0.0):
        zero = cal.at_noise(everything, 0.0)
        for block, names in BLOCKS.items():
            errs = [abs(cal.parameter(zero, leg, n)["error"]) for leg in legs for n in names]
            v[f"zero_noise_{block}_error_max"] = float(max(errs))
    p = {(leg, name): cal.parameter(t, leg, name) for leg in legs for name in cal.PARAMETERS}
    for (leg, name), r in p.items():
        v[f"{leg}_{name}_estimate"] = r["estimate"]
        v[f"{leg}_{name}_se"] = r["se"]
        v[f"{leg}_{name}_z"] = r["z"]
    zs_all = []
    for block, names in BLOCKS.items():
        zs = np.array([p[leg, n]["z"] for leg in legs for n in names])
        errs = np.array([abs(p[leg, n]["error"]) for leg in legs for n in names])
        ses = np.array([p[leg, n]["se"] for leg in legs for n in names])
        zs_all.append(zs)
        v[f"{block}_error_max"] = float(errs.max())
        v[f"{block}_se_min"] = float(ses.min())
        v[f"{block}_se_max"] = float(ses.max())
        if np.all(np.isfinite(zs)):
            v[f"{block}_z_abs_max"] = float(np.abs(zs).max())
            v[f"{block}_within_bound"] = bool(np.abs(zs).max() <= Z_TABLE)
        else:
            for key in (f"{block}_z_abs_max", f"{block}_within_bound"):
                v[key] = None
                v[key + "_reason"] = "a standard error is zero (noiseless data): z undefined"
    zs = np.concatenate(zs_all)
    v["parameters"] = int(zs.size)
    v["within_3se_fraction"] = float(np.mean(np.abs(zs) <= cal.Z_BOUND)) if np.all(
        np.isfinite(zs)) else None
    if v["within_3se_fraction"] is None:
        v["within_3se_fraction_reason"] = "a standard error is zero (noiseless data): z undefined"
    # the study's truth against the ledger's Table 4.1 (the synthetic robot is built from it)
    diffs = []
    for block, claim in THESIS_ROWS.items():
        table = cal.thesis_table(claim)
        for j, leg in enumerate(cal.LEGS):
            if leg not in legs:
                continue
            for i, name in enumerate(BLOCKS[block]):
                diffs.append(abs(p[leg, name]["truth"] - table[i, j]))
    v["truth_table_max_abs_diff"] = float(max(diffs))
    v["truth_is_table"] = bool(max(diffs) <= 1e-9)

    # ---- the table: estimate ± SE, the truth beside it; |z| > 3 marked
    head = "".join(f"<th>{leg}</th>" for leg in legs)
    body = []
    for block, names in BLOCKS.items():
        if block == "rotation":
            body.append(f"<tr><th colspan='{len(legs) + 1}'>beyond Table 4.1: the mounting "
                        "errors of the full model (§4.3.2)</th></tr>")
        scale = SCALE.get(block, 1.0)
        for name in names:
            cells = []
            for leg in legs:
                r = p[leg, name]
                d = digits(r["se"] * scale)
                bad = np.isfinite(r["z"]) and abs(r["z"]) > cal.Z_BOUND
                cells.append(f"<td class='{'bad' if bad else ''}'>{r['estimate'] * scale:.{d}f}"
                             f" ± {r['se'] * scale:.{d}f}<br><small>truth "
                             f"{r['truth'] * scale:.{d}f}, z = {c.fmt(r['z'], 2)}</small></td>")
            body.append(f"<tr><th>{html.escape(ROW_LABEL[name])}</th>{''.join(cells)}</tr>")
    out = ("<table class='data'><thead><tr><th></th>" + head + "</tr></thead><tbody>\n"
           + "\n".join(body) + "\n</tbody></table>\n"
           f"<p>Estimate ± standard error; below it the synthetic truth (Table 4.1's printed "
           f"values for the offsets and weights; largest difference from the ledger's table "
           f"{c.fmt(v['truth_table_max_abs_diff'], 2)}) and z = (estimate − truth)/SE, "
           f"marked where |z| &gt; 3. Data: "
           f"<code>{html.escape(c.shown_path(t.path))}</code>.</p>\n")
    c.atomic_write_text(args.out / f"{NAME}_table.html", out)
    c.write_values(args.out, NAME, v)


if __name__ == "__main__":
    main()
