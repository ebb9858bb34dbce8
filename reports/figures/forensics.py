#!/usr/bin/python3
"""Chapter 2 forensics: the unstated settings under which the thesis' regression numbers appear.

Input: DATA/ch2_inchworm/forensics.csv (inchworm_force_grid rows: v_ss on forces k·0.5 N up to
100 N for μ = 0.05..1, one block per variant of the model or protocol), DATA/ch2_inchworm/
fig2_3.csv (Fig. 2.3's simulation points, for the R² of its regime lines) and the search's candidate
choices, data/thesis/forensics.toml (force grid start, end and step; sets of μ; the groups of the
thesis' numbers by ledger entry). For every setting (variant × grid × set of μ) the regressions
are computed as the thesis describes them (reports/plotting/forensics_search.py) and scored
against each group: a group is explained only by one setting bringing all its numbers within
their entries' tolerances. Output: OUT/forensics.png, OUT/forensics_table.html,
OUT/values/forensics.json.
"""
from __future__ import annotations

import html
import math
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "plotting"))  # the shared helpers
import common as c  # noqa: E402
import forensics_search as fs  # noqa: E402

NAME = "forensics"
SEARCH = c.REPO / "data" / "thesis" / "forensics.toml"
PRINTED = {"g": c.G, "m": 1.0, "M": c.M, "L_min": 0.02, "L_max": c.L_MAX}
UNITS = {"g": "m/s²", "m": "kg", "M": "kg", "L_min": "m", "L_max": "m"}
# Our own sampling for comparison: the regression study's range (from μMg to 5Mg, 20 μ).
OURS = fs.Grid("muMg", 0.5, 73.5)
OURS_MU_SET = "0.05 to 1 in steps of 0.05"


def load_search(path: Path) -> dict:
    """The search's candidate choices; exit 2 naming the file and what is wrong."""
    try:
        with open(path, "rb") as f:
            cfg = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        c.fail(f"{path}: {e}")
    for key, kind in (("grid", dict), ("mu_sets", dict), ("group", list)):
        if not isinstance(cfg.get(key), kind):
            c.fail(f"{path}: needs a [{key}] table" if kind is dict else
                   f"{path}: needs [[group]] entries")
    for key in ("F_start", "F_end", "F_step"):
        got = cfg["grid"].get(key)
        if not isinstance(got, list) or not got:
            c.fail(f"{path}: [grid] {key} must be a non-empty list")
    for g in cfg["group"]:
        if not isinstance(g.get("name"), str) or not isinstance(g.get("claims"), dict):
            c.fail(f"{path}: every [[group]] needs a name and a claims table")
    return cfg


def variant_label(t: c.Table, i: int) -> str:
    """A block's rows named by what they change against the model and method as printed."""
    method = str(t["method"][i])
    if method == "exact":
        head = "closed form"
    else:
        est = "running mean" if t["estimator"][i] == "running" else "last cycle"
        head = (f"thesis protocol ({est}, stop at {t['rtol'][i]:g})"
                if t["stop"][i] == "difference" else f"simulation ({method}, rtol {t['rtol'][i]:g})")
    changed = [f"{k} = {float(t[k][i]):g} {UNITS[k]}" for k, v in PRINTED.items()
               if not math.isclose(float(t[k][i]), v, rel_tol=1e-12)]
    return head + (", " + ", ".join(changed) if changed else ", as printed")


def load_variants(t: c.Table) -> dict[str, fs.Variant]:
    labels = [variant_label(t, i) for i in range(t.n)]
    variants: dict[str, fs.Variant] = {}
    for i, label in enumerate(labels):
        if label not in variants:
            variants[label] = fs.Variant(label, float(t["m"][i]), float(t["M"][i]),
                                         float(t["g"][i]), float(t["L_max"][i]))
    labels = np.array(labels, dtype=object)
    for label, v in variants.items():
        rows = labels == label
        for mu in np.unique(t["mu"][rows]):
            s = rows & (t["mu"] == mu)
            o = np.argsort(t["F"][s])
            v.by_mu[round(float(mu), 12)] = (t["F"][s][o], t["v_ss"][s][o])
    return variants


def load_groups(cfg: dict, regime_starts: bool) -> list[fs.Group]:
    """The groups searched over force grids, or (regime_starts) over Fig. 2.3's regime starts."""
    ledger = {cl["id"]: cl for cl in c.load_ledger().get("claim", [])}
    groups = []
    for g in cfg["group"]:
        if ("regime_I_start" in g) != regime_starts:
            continue
        missing = [cid for cid in g["claims"] if cid not in ledger or not (
            "tol" in ledger[cid] or ledger[cid].get("compare") in ("at_least", "at_most"))]
        if missing:
            c.fail(f"{SEARCH}: group {g['name']}: no ledger entry with a tol or a bound for "
                   f"{missing}")
        groups.append(fs.Group(
            g["name"], g["title"], g["claims"],
            {k: float(ledger[cid]["thesis"]) for cid, k in g["claims"].items()},
            {k: float(ledger[cid].get("tol", 0.0)) for cid, k in g["claims"].items()},
            {k: ledger[cid]["compare"] if ledger[cid]["compare"] in ("at_least", "at_most")
             else "abs" for cid, k in g["claims"].items()}))
    return groups


def mu_sets_on(cfg: dict, variants: dict[str, fs.Variant]) -> dict[str, list[float]]:
    """Each set of μ as the sweep's values (a set naming a μ the sweep lacks is an error)."""
    have = sorted(set.intersection(*(set(v.by_mu) for v in variants.values())))
    out = {}
    for name, mus in cfg["mu_sets"].items():
        got = [next((h for h in have if abs(h - m) < 1e-9), None) for m in mus]
        if None in got:
            c.fail(f"{SEARCH}: mu set '{name}' names μ = "
                   f"{[m for m, g in zip(mus, got) if g is None]} that the sweep did not run")
        out[name] = got
    return out


def simulation_curves(data: Path, study: str, name: str, tags) -> tuple[dict, dict]:
    """A figure's simulation points by curve (tag -> selection of rows), and each curve's bands
    (μmg, μMg, its largest force)."""
    t = c.Table(c.study_file(data, name, study), c.SWEEP_COLUMNS)
    sim = (t["method"] == "analytic") & (t["converged"] == 1)
    curves, bands = {}, {}
    for tag, mu, pick in tags(t):
        s = sim & np.isclose(t["mu"], mu, rtol=0, atol=1e-12) & pick
        if np.count_nonzero(s) < 6:
            c.fail(f"{t.path}: too few simulation rows for the curve {tag}")
        o = np.argsort(t["F"][s])
        curves[tag] = (t["F"][s][o], t["v_ss"][s][o])
        bands[tag] = (mu * c.m * c.G, mu * c.M * c.G, float(np.max(t["F"][s])))
    return curves, bands


# The regime-start groups: the figure they read, its curves, and their numbers.
REGIME_FIGURES = {
    "fig2_3": ("ch2_inchworm", "fig2_3.csv",
               lambda t: [("mu1", 1.0, True), ("mu0.2", 0.2, True)], fs.fig2_3_numbers),
    "fig2_7": ("ch2_dm_swap", "fig2_7.csv",
               lambda t: [(f"mu{mu:g}_a{a:g}", mu, (t["model"] == "dm") & (t["alpha"] == a))
                          for mu in (0.1, 0.6, 1.0) for a in (1.0, 5.0, 10.0)], fs.fig2_7_numbers),
}


def regime_start_search(data: Path, cfg: dict, group: fs.Group) -> fs.Found | None:
    """A figure's regime lines from our simulation points, each regime from a fraction of its
    band on (None when the figure's study has not run)."""
    study, name, tags, numbers_of = REGIME_FIGURES[group.name]
    if not (data / study / name).is_file():
        return None
    curves, bands = simulation_curves(data, study, name, tags)
    spec = next(g for g in cfg["group"] if g["name"] == group.name)
    candidates = [fs.RegimeStart(a, b) for a in spec["regime_I_start"]
                  for b in spec.get("regime_II_start", [0.0])]
    found = fs.search_regime_starts(curves, bands, candidates, group, numbers_of)
    # Ours: each band from its first point, as our figure fits it.
    found.ours = numbers_of(curves, bands, fs.RegimeStart(0.0, 0.0))
    found.n_settings = len(candidates)
    return found


def missing_group(values: dict, group: fs.Group) -> None:
    """A regime-start group whose figure's study has not run: its values, each None, so that the
    ledger's texts still find them."""
    g = group.name
    study, name, *_ = REGIME_FIGURES[g]
    reason = f"{study}/{name} missing (run `slipwalk reproduce {study}`)"
    for key in ("n_settings", "best_distance", "joint", "best_setting", "best_variant",
                "per_number_max", "per_number_only", "settings_within", "ours_distance"):
        values[f"{g}_{key}"] = None
    for key in group.numbers.values():
        values[f"{g}_{key}"] = None
        values[f"{g}_ours_{key}"] = None
    values[f"{g}_explained_by_setting"] = None
    values[f"{g}_explained_by_setting_reason"] = reason


def start_label(start) -> str:
    return start if isinstance(start, str) else f"{start:g}"


def heat(ax, found: fs.Found, cfg: dict, plt, index: int) -> None:
    """The smallest distance (over steps and sets of μ) for each start and end of the grid, in
    the variant of the group's best setting."""
    starts, ends = cfg["grid"]["F_start"], cfg["grid"]["F_end"]
    D = np.full((len(starts), len(ends)), np.inf)
    for s, d in found.scores:
        if s.variant != found.best.variant:
            continue
        i, j = starts.index(s.grid.start), ends.index(s.grid.end)
        D[i, j] = min(D[i, j], d)
    shown = np.log10(np.clip(D, 1e-2, 1e4))
    im = ax.imshow(shown, origin="lower", aspect="auto", cmap="YlGnBu_r", vmin=-1, vmax=3)
    ax.grid(False)
    for (i, j), d in np.ndenumerate(D):
        if d <= 1.0:
            ax.text(j, i, "✓", ha="center", va="center", color="white")
    ax.set_xticks(range(len(ends)), [f"{e:g}" for e in ends], rotation=60)
    ax.set_yticks(range(len(starts)), [start_label(s) for s in starts])
    ax.set_xlabel("grid ends at F [N]")
    ax.set_ylabel("grid starts at F [N]")
    ax.set_title(f"({'ab'[index]}) {found.group.name.replace('_', '.')}: best distance per (start, "
                 "end)\n✓ = every number within its tolerance")
    plt.colorbar(im, ax=ax, label="log₁₀ distance (1 = at the tolerance)")


def by_variant(found: list[fs.Found], variants: list[str]) -> dict[str, list[float]]:
    best = {f.group.name: {v: math.inf for v in variants} for f in found}
    for f in found:
        for s, d in f.scores:
            best[f.group.name][s.variant] = min(best[f.group.name][s.variant], d)
    return {g: [best[g][v] for v in variants] for g in best}


def table(found: list[fs.Found], ours: dict, mu_sets: dict, variants: list[str],
          best_by_variant: dict) -> str:
    out = []
    for f in found:
        g = f.group
        out.append(f"<h4>{html.escape(g.title)}</h4><p class='small'>Best joint setting: "
                   f"{html.escape(f.best.label(mu_sets)) if f.best else '—'} (distance "
                   f"{c.fmt(f.best_distance, 3)}; {'within every tolerance' if f.joint else 'not within every tolerance'}).</p>")
        out.append("<div class='scroll'><table class='data'><thead><tr><th>entry</th><th>thesis</th>"
                   "<th>tolerance</th><th>ours, as our study samples</th><th>best joint setting</th>"
                   "<th>each number's own best (a setting per number: not an explanation)</th>"
                   "</tr></thead><tbody>")
        for cid, key in g.numbers.items():
            d, s = f.per_number.get(key, (math.inf, None))
            out.append(f"<tr><td>{html.escape(cid)}</td><td>{c.fmt(g.thesis[key], 4)}</td>"
                       f"<td>{c.fmt(g.tol[key], 2)}</td><td>{c.fmt(ours.get(key), 4)}</td>"
                       f"<td>{c.fmt(f.best_numbers.get(key), 4)}</td>"
                       f"<td>distance {c.fmt(d, 2)}</td></tr>")
        out.append("</tbody></table></div>")
        if g.name not in best_by_variant:
            continue
        rows = "".join(f"<tr><td>{html.escape(v)}</td><td>{c.fmt(d, 3)}</td>"
                       f"<td>{'yes' if d <= 1 else 'ruled out'}</td></tr>"
                       for v, d in zip(variants, best_by_variant[g.name]))
        out.append("<details><summary>best distance by variant of the model or protocol</summary>"
                   "<table class='data'><thead><tr><th>variant</th><th>best distance</th>"
                   f"<th>reproduces the group</th></tr></thead><tbody>{rows}</tbody></table>"
                   "</details>")
    return "\n".join(out) + "\n"


def main():
    args = c.parse_args(__doc__.splitlines()[0])
    plt = c.setup_matplotlib()
    t = c.read_table(args.data, "forensics.csv", ["mu", "F", "method", "stop", "estimator", "rtol",
                                                  "g", "m", "M", "L_min", "L_max", "v_ss",
                                                  "status"])
    if np.any(t["status"] != "converged"):
        c.fail(f"{t.path}: {int(np.sum(t['status'] != 'converged'))} rows did not converge")
    cfg = load_search(SEARCH)
    variants = load_variants(t)
    mu_sets = mu_sets_on(cfg, variants)
    groups = load_groups(cfg, regime_starts=False)
    eq = c.eq2_6_coefficients()
    names = list(variants)
    candidates = fs.settings(names, cfg["grid"]["F_start"], cfg["grid"]["F_end"],
                             cfg["grid"]["F_step"], list(mu_sets))
    t0 = time.process_time()
    found = fs.search(variants, candidates, mu_sets, groups, eq)
    search_s = time.process_time() - t0
    pending: dict = {}  # the values of groups whose figure's study has not run
    printed = names[0]
    ours = fs.numbers(fs.per_mu(variants[printed], OURS), mu_sets[OURS_MU_SET], eq)
    best_by_variant = by_variant(found, names)
    regime_found = []
    for g in load_groups(cfg, regime_starts=True):
        f = regime_start_search(args.data, cfg, g)
        if f is None:
            missing_group(pending, g)
        else:
            regime_found.append(f)

    values: dict = {**pending, "n_settings": len(candidates), "n_variants": len(names), "variants": names,
                    "search_cpu_s": search_s, "F_step_data": float(np.min(np.diff(np.unique(t["F"]))))}
    for f in found + regime_found:
        g = f.group.name
        grid_group = any(f is x for x in found)
        n = len(candidates) if grid_group else f.n_settings
        mine = ours if grid_group else f.ours
        values[f"{g}_n_settings"] = n
        values[f"{g}_best_distance"] = f.best_distance
        values[f"{g}_joint"] = f.joint
        values[f"{g}_best_setting"] = f.best.label(mu_sets) if f.best else None
        values[f"{g}_best_variant"] = f.best.variant if grid_group and f.best else None
        values[f"{g}_per_number_max"] = max(d for d, _ in f.per_number.values())
        values[f"{g}_per_number_only"] = f.per_number_only
        values[f"{g}_settings_within"] = int(sum(1 for _, d in f.scores if d <= 1.0))
        values[f"{g}_ours_distance"] = fs.distance(mine, f.group)[0]
        for key in f.group.numbers.values():
            values[f"{g}_{key}"] = f.best_numbers.get(key)
            values[f"{g}_ours_{key}"] = mine.get(key)
        if grid_group:
            values[f"{g}_best_by_variant"] = best_by_variant[g]
            values[f"{g}_ruled_out_variants"] = [v for v, d in zip(names, best_by_variant[g])
                                                 if d > 1]
        # The check behind an explanation: set only when one setting reproduces the group.
        values[f"{g}_explained_by_setting"] = f.best_distance if f.joint else None
        values[f"{g}_explained_by_setting_reason"] = None if f.joint else (
            f"no setting of {n} brings every number within its tolerance (best "
            f"{f.best_distance:.3g})")

    # One setting for every group at once (the same simulations behind §2.3.1 and eq. 2.6?).
    together = [max(ds) for ds in zip(*([d for _, d in f.scores] for f in found))]
    i_best = int(np.argmin(together))
    values["all_groups_best_distance"] = together[i_best]
    values["all_groups_best_setting"] = found[0].scores[i_best][0].label(mu_sets)
    values["all_groups_settings_within"] = int(sum(1 for d in together if d <= 1.0))

    fig = plt.figure(figsize=(6.6 * len(found), 9.6), layout="constrained")
    grid = fig.add_gridspec(2, len(found), height_ratios=[1.0, 0.75])
    for i, f in enumerate(found):
        if f.best is not None:
            heat(fig.add_subplot(grid[0, i]), f, cfg, plt, i)
    ax = fig.add_subplot(grid[1, :])
    y = np.arange(len(names))
    for i, f in enumerate(found):
        d = np.clip(best_by_variant[f.group.name], 1e-2, 1e4)
        ax.barh(y + (i - 0.5) * 0.35, d, height=0.35, color=c.CATEGORICAL[i],
                label=f.group.title)
    ax.axvline(1.0, color="0.3", lw=0.8, ls="--")
    ax.set_xscale("log")
    ax.set_yticks(y, names)
    ax.set_xlabel("best distance over every grid and set of μ (1 = at the tolerance)")
    ax.set_title("(c) best distance by variant of the model or protocol")
    ax.legend(loc="lower right")
    c.save_figure(fig, args.out, NAME)
    c.atomic_write_text(args.out / "forensics_table.html",
                        table(found, ours, mu_sets, names, best_by_variant)
                        + table(regime_found, regime_found[0].ours if regime_found else {},
                                mu_sets, [], {}))
    c.write_values(args.out, NAME, values)


if __name__ == "__main__":
    main()
