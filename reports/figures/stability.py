#!/usr/bin/python3
"""Stability: the hard cases, each run by every method.

Input: DATA/ch2_inchworm/hard_cases.csv — specific hard (F, μ, μ_s) points (at the edges of the
regimes and of the parameter range) × methods exact, rootfind, analytic, cvode, odeint, gsl.
The reference is the exact closed form of the same case. Output: OUT/stability.png (relative
difference from exact per case and method), OUT/stability_table.html, OUT/values/stability.json.
"""
from __future__ import annotations

import sys
from pathlib import Path

import html

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402

NAME = "stability"
METHODS = ("exact", "rootfind", "analytic", "cvode", "odeint", "gsl")
AGREE = 1e-6  # a converged method "agrees" when within this relative difference of exact


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "hard_cases.csv", c.SWEEP_COLUMNS + ["strokes", "message"])
    mus = c.mu_static(t)
    msgs = t.str("message")
    meth = t["method"]
    methods = [m for m in METHODS if np.any(meth == m)] + sorted(
        {str(m) for m in meth} - set(METHODS))
    keys = []
    for F, mu, ms in zip(t["F"], t["mu"], mus):
        k = (round(float(F), 9), round(float(mu), 12), round(float(ms), 12))
        if k not in keys:
            keys.append(k)

    rel = np.full((len(keys), len(methods)), np.nan)
    status = np.full((len(keys), len(methods)), "", dtype=object)
    rows_html = []
    values: dict = {"n_cases": len(keys), "methods": methods, "agree_tol": AGREE}
    n_conv = {m: 0 for m in methods}
    n_agree = {m: 0 for m in methods}
    n_nb = {m: 0 for m in methods}
    n_run = {m: 0 for m in methods}
    for i, (F, mu, ms) in enumerate(keys):
        sc = np.isclose(t["F"], F) & np.isclose(t["mu"], mu) & np.isclose(mus, ms)
        se = sc & (meth == "exact") & (t["converged"] == 1)
        ref = float(t["v_ss"][se][0]) if np.any(se) else None
        regime = 1 if F <= ms * c.M * c.G else 2
        rows_html.append(
            f"<tr class='group'><td colspan='6'>case {i + 1}: F = {F:.12g} N, μ = {mu:g}, "
            f"μ_s = {ms:g} (F/(μ_s m g) = {F / (ms * c.m * c.G):.12g}, F/(μ_s M g) = "
            f"{F / (ms * c.M * c.G):.12g}; regime {'I' if regime == 1 else 'II'})</td></tr>")
        for j, m in enumerate(methods):
            sm = np.flatnonzero(sc & (meth == m))
            if sm.size == 0:
                status[i, j] = "not run"
                continue
            r = sm[0]
            n_run[m] += 1
            conv = t["converged"][r] == 1
            v = t["v_ss"][r]
            d = abs(v / ref - 1) if (ref is not None and conv and np.isfinite(v)) else None
            if conv:
                n_conv[m] += 1
                if d is not None and d <= AGREE:
                    n_agree[m] += 1
            nb = "not built" in str(msgs[r])
            n_nb[m] += nb
            status[i, j] = "not built" if nb else ("ok" if conv else "failed")
            if d is not None:
                rel[i, j] = d
            cls = "muted" if nb else ("" if conv and (d is None or d <= AGREE) else "bad")
            rows_html.append(
                f"<tr class='{cls}'><td>{html.escape(m)}</td><td>{c.fmt(v, 10)}</td>"
                f"<td>{c.fmt(d, 2)}</td><td>{'yes' if conv else 'no'}</td>"
                f"<td>{int(t['strokes'][r]) if np.isfinite(t['strokes'][r]) else '—'}</td>"
                f"<td>{html.escape(str(msgs[r]))}</td></tr>")
    for m in methods:
        col = rel[:, methods.index(m)]
        values[f"runs_{m}"] = n_run[m]
        values[f"converged_{m}"] = n_conv[m]
        values[f"agree_{m}"] = n_agree[m]
        values[f"not_built_{m}"] = n_nb[m]
        values[f"max_rel_diff_{m}"] = float(np.nanmax(col)) if np.any(np.isfinite(col)) else None
    built = [m for m in methods if n_run[m] > n_nb[m]]
    values["methods_built"] = built
    values["all_built_converged_and_agree"] = bool(all(
        n_agree[m] == n_run[m] - n_nb[m] for m in built))
    values["cases"] = [list(k) for k in keys]

    html_out = ("<table class='data'><thead><tr><th>method</th><th>v_ss [m/s]</th>"
                "<th>|v − exact| / exact</th><th>converged</th><th>strokes</th><th>message</th>"
                "</tr></thead><tbody>\n" + "\n".join(rows_html) + "\n</tbody></table>\n")
    c.atomic_write_text(args.out / "stability_table.html", html_out)

    # The closed form ("exact") is the reference of every row, so it gets no column of its own.
    cols = [j for j, m in enumerate(methods) if m != "exact"]
    fig, ax = plt.subplots(figsize=(8.4, 1.3 + 0.5 * len(keys)))
    shown = np.log10(np.maximum(rel[:, cols], 1e-17))
    im = ax.imshow(np.where(np.isfinite(rel[:, cols]), shown, np.nan), cmap="viridis", vmin=-17,
                   vmax=0, aspect="auto")
    for i in range(len(keys)):
        for jj, j in enumerate(cols):
            txt = (f"{rel[i, j]:.0e}" if np.isfinite(rel[i, j]) else status[i, j])
            if txt == "0e+00":
                txt = "0"
            ax.text(jj, i, txt, ha="center", va="center",
                    color="w" if np.isfinite(rel[i, j]) and shown[i, jj] < -8 else "k")
    ax.set_xticks(range(len(cols)))
    ax.set_xticklabels([methods[j] for j in cols])
    ax.set_yticks(range(len(keys)))
    ax.set_yticklabels([f"{i + 1}: F = {F:.4g} N, μ = {mu:g}, μ_s = {ms:g}"
                        for i, (F, mu, ms) in enumerate(keys)])
    ax.grid(False)
    fig.colorbar(im, ax=ax, label="log₁₀ |v − exact| / exact")
    ax.set_title("hard cases: relative difference from the closed form")
    fig.tight_layout()
    c.save_figure(fig, args.out, NAME)
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
