"""The chapter 2 forensics: which settings the thesis does not state reproduce its numbers.

The thesis' regressions (§2.3.1: k(μ), b(μ); eq. 2.6: a, c, d, e and its largest error) came from
simulations on a force grid and a set of μ it does not
give. Given v_ss on a fine force grid shared by every μ (the inchworm_force_grid rows of
studies/ch2_inchworm/forensics.toml, one variant of the model or protocol per block), `numbers`
computes every one of those numbers for one setting — a variant, a force grid (start, step,
end) and a set of μ — exactly as the thesis describes its fits, and `search` scores every setting
of a candidate grid against each group of the thesis' numbers.

A setting explains a group only jointly: its distance to the group is the largest over the group's
numbers of |ours − thesis| / tolerance (the ledger entry's own `tol`), and the group is explained
when that largest distance is at most 1. Among the settings that explain a group, the model as
printed (the first variant) is preferred over a variant with a constant read otherwise. The best number-by-number fits (a different setting per
number) are reported beside it, never as an explanation.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

REL = 1e-9  # a force "above" a regime boundary by more than rounding


@dataclass(frozen=True)
class Grid:
    """Forces k·step (k = 1, 2, ...) from `start` to `end`, N; start "muMg" or "mumg": from just
    above that force of each μ (the grid still k·step), a number: from that force in N."""
    start: object
    step: float
    end: float

    def label(self) -> str:
        start = self.start if isinstance(self.start, str) else f"{self.start:g} N"
        return f"F = {start} to {self.end:g} N in steps of {self.step:g} N"


@dataclass(frozen=True)
class Setting:
    variant: str
    grid: Grid
    mu_set: str

    def label(self, mu_sets: dict) -> str:
        mus = mu_sets[self.mu_set]
        shown = (f"μ = {mus[0]:g}, {mus[1]:g}, …, {mus[-1]:g}" if len(mus) > 4
                 else "μ = " + ", ".join(f"{m:g}" for m in mus))
        return f"{self.variant}; {self.grid.label()}; {shown} ({len(mus)} values)"


@dataclass
class Variant:
    """One block's rows: for each μ the forces (ascending) and v_ss, and the model's constants."""
    name: str
    m: float
    M: float
    g: float
    L_max: float
    by_mu: dict[float, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)


@dataclass
class Group:
    name: str
    title: str
    numbers: dict[str, str]      # claim id -> number key
    thesis: dict[str, float]     # number key -> the thesis' value
    tol: dict[str, float]        # number key -> the entry's tolerance (rule "abs")
    # number key -> "abs" (within ±tol of the thesis), "at_least" or "at_most" (the thesis'
    # bound); absent: "abs"
    rule: dict[str, str] = field(default_factory=dict)


def line(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """Least-squares y = k x + b and its R² (NaN with fewer than 3 points)."""
    if x.size < 3:
        return math.nan, math.nan, math.nan
    dx, dy = x - x.mean(), y - y.mean()
    sxx, sxy, syy = float(dx @ dx), float(dx @ dy), float(dy @ dy)
    if sxx == 0 or syy == 0:
        return math.nan, math.nan, math.nan
    k = sxy / sxx
    return k, float(y.mean() - k * x.mean()), sxy * sxy / (sxx * syy)


def r_squared(y: np.ndarray, yhat: np.ndarray) -> float:
    ss = float(np.sum((y - y.mean()) ** 2))
    return 1.0 - float(np.sum((y - yhat) ** 2)) / ss if ss > 0 else math.nan


def lstsq(columns: list[np.ndarray], y: np.ndarray) -> tuple[np.ndarray, float]:
    A = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    return coef, r_squared(y, A @ coef)


def on_grid(F: np.ndarray, grid: Grid, floor: float) -> np.ndarray:
    """The forces of F on `grid` (multiples of its step from its start, up to its end) above
    `floor` (the regime's lower bound)."""
    start = grid.start if not isinstance(grid.start, str) else 0.0
    k = (F - start) / grid.step
    multiple = np.abs(k - np.round(k)) < 1e-6
    return multiple & (F >= start - 1e-9) & (F <= grid.end + 1e-9) & (F > floor * (1 + REL))


def regime_floor(v: Variant, mu: float, grid: Grid) -> float:
    """Where a grid's forces start for this μ: its own start when it names a regime boundary."""
    if grid.start == "muMg":
        return mu * v.M * v.g
    return mu * v.m * v.g


@dataclass
class MuFit:
    """One μ's regime II points on a grid: the line v = k F + b and eq. 2.6's columns."""
    k: float
    b: float
    X: np.ndarray  # rows (μ f̃, μ³ f̃, μ, 1), f̃ = F / (μ M g)
    Y: np.ndarray  # ṽ = v / sqrt(L_max g)


def per_mu(v: Variant, grid: Grid) -> dict[float, MuFit]:
    """Each μ's regime II fit on a grid (computed once per grid, shared by every set of μ)."""
    out = {}
    for mu, (F, vs) in v.by_mu.items():
        keep = on_grid(F, grid, max(regime_floor(v, mu, grid), mu * v.M * v.g))
        k, b, _ = line(F[keep], vs[keep])
        f = F[keep] / (mu * v.M * v.g)
        X = np.column_stack([mu * f, mu**3 * f, np.full(f.size, mu), np.ones(f.size)])
        out[mu] = MuFit(k, b, X, vs[keep] / math.sqrt(v.L_max * v.g))
    return out


def numbers(fits: dict[float, MuFit], mus: list[float], eq2_6_thesis: tuple) -> dict[str, float]:
    """Every regression number of one setting, as the thesis describes its fits: per μ a line
    through regime II, then k = k2 μ² + k0 and b = b1 μ + b0 over μ (§2.3.1); eq. 2.6 by linear
    least squares in ṽ over (μ f̃, μ³ f̃, μ, 1) -> (a, −a c, d, e), and the thesis' own law's
    largest relative error on the same points (§2.4.1)."""
    out: dict[str, float] = {}
    used = [mu for mu in mus if not math.isnan(fits[mu].k)]
    u = np.array(used)
    if u.size >= 3:
        ks = np.array([fits[mu].k for mu in used])
        bs = np.array([fits[mu].b for mu in used])
        (out["k2"], out["k0"]), out["k_r2"] = lstsq([u**2, np.ones_like(u)], ks)
        (out["b1"], out["b0"]), out["b_r2"] = lstsq([u, np.ones_like(u)], bs)
    X = np.vstack([fits[mu].X for mu in mus])
    Y = np.concatenate([fits[mu].Y for mu in mus])
    if Y.size >= 4:
        (a, ac, d, e), _ = lstsq(list(X.T), Y)
        out.update(a=float(a), c=float(-ac / a) if a else math.nan, d=float(d), e=float(e))
        ta, tc, td, te = eq2_6_thesis
        mu_col, f_col = X[:, 2], X[:, 0] / X[:, 2]
        law = ta * mu_col * (1 - tc * mu_col**2) * f_col + td * mu_col + te
        out["eq2_6_max_error"] = float(np.max(np.abs(law - Y) / Y))
    return {k: float(x) for k, x in out.items()}


def distance(nums: dict[str, float], group: Group) -> tuple[float, dict[str, float]]:
    """The largest |ours − thesis| / tol over the group, and each number's own."""
    each = {}
    for key in group.numbers.values():
        x, t = nums.get(key, math.nan), group.thesis[key]
        rule = group.rule.get(key, "abs")
        if not np.isfinite(x):
            each[key] = math.inf
        elif rule == "at_least":  # a bound: ≤ 1 exactly where it holds
            each[key] = t / x if x > 0 else math.inf
        elif rule == "at_most":
            each[key] = x / t
        else:
            each[key] = abs(x - t) / group.tol[key]
    return max(each.values()), each


@dataclass
class Found:
    """One group's search: the best joint setting, its numbers and distances, and the best fit of
    each number by a setting of its own (not an explanation)."""
    group: Group
    best: Setting | None = None
    best_distance: float = math.inf
    best_numbers: dict[str, float] = field(default_factory=dict)
    best_each: dict[str, float] = field(default_factory=dict)
    per_number: dict[str, tuple[float, Setting]] = field(default_factory=dict)
    scores: list[tuple[Setting, float]] = field(default_factory=list)
    ours: dict[str, float] = field(default_factory=dict)  # the numbers as our study samples
    n_settings: int = 0

    def score(self, setting, nums: dict[str, float]) -> None:
        """Records a setting's numbers: its distance, the best so far, each number's best."""
        d, each = distance(nums, self.group)
        self.scores.append((setting, d))
        if d < self.best_distance:
            self.best, self.best_distance, self.best_numbers, self.best_each = (setting, d, nums,
                                                                                each)
        for key, dk in each.items():
            if key not in self.per_number or dk < self.per_number[key][0]:
                self.per_number[key] = (dk, setting)

    @property
    def joint(self) -> bool:
        return self.best_distance <= 1.0

    @property
    def per_number_only(self) -> bool:
        """Every number is matched by some setting, but no one setting matches them all."""
        return not self.joint and all(d <= 1.0 for d, _ in self.per_number.values())


def settings(variants: list[str], starts: list, ends: list[float], steps: list[float],
             mu_sets: list[str]) -> list[Setting]:
    out = []
    for variant, start, end, step, mus in itertools.product(variants, starts, ends, steps, mu_sets):
        if not isinstance(start, str) and (start >= end or abs(start / step - round(start / step))
                                           > 1e-9):
            continue  # a grid starting between its own steps is the next start's grid
        out.append(Setting(variant, Grid(start, step, end), mus))
    return out


def search(variants: dict[str, Variant], candidates: list[Setting], mu_sets: dict[str, list],
           groups: list[Group], eq2_6_thesis: tuple) -> list[Found]:
    found = [Found(g) for g in groups]
    cache: dict[tuple[str, Grid], dict[float, MuFit]] = {}
    for s in candidates:
        key = (s.variant, s.grid)
        if key not in cache:
            cache.clear()  # settings come grid by grid (see settings())
            cache[key] = per_mu(variants[s.variant], s.grid)
        nums = numbers(cache[key], mu_sets[s.mu_set], eq2_6_thesis)
        for f in found:
            f.score(s, nums)
    for f in found:
        prefer_first_variant(f, variants, mu_sets, eq2_6_thesis)
    return found


def prefer_first_variant(f: Found, variants: dict[str, Variant], mu_sets: dict[str, list],
                         eq2_6_thesis: tuple) -> None:
    """Where the model as printed (the first variant) reproduces a group, its best setting is the
    group's: a misprint is assumed only when the printed model cannot do it. Likewise each later
    variant before the next."""
    order = list(dict.fromkeys(s.variant for s, _ in f.scores))
    for name in order:
        mine = [(s, d) for s, d in f.scores if s.variant == name and d <= 1.0]
        if mine:
            s, d = min(mine, key=lambda sd: sd[1])
            if s != f.best:
                nums = numbers(per_mu(variants[s.variant], s.grid), mu_sets[s.mu_set],
                               eq2_6_thesis)
                f.best, f.best_distance, f.best_numbers = s, d, nums
                f.best_each = distance(nums, f.group)[1]
            return


# ---------------------------------------------------------------------------------------------
# Fig. 2.3: where each regime's sampled forces start


@dataclass(frozen=True)
class RegimeStart:
    """Fig. 2.3's sampling: regime I from μmg + s_I (μMg − μmg) to μMg, regime II from
    μMg + s_II (F_max − μMg) to F_max, as fractions of each regime's band."""
    s_I: float
    s_II: float

    def label(self, _mu_sets=None) -> str:
        two = ("regime II over its whole band" if self.s_II == 0 else
               f"regime II from {self.s_II:.0%} of its band (μMg to the largest force)")
        return f"regime I from {self.s_I:.0%} of its band (μmg to μMg), {two}"


def regime_r2(F: np.ndarray, v: np.ndarray, lo: float, hi: float, s: float) -> float:
    """R² of the line through the points of [lo + s (hi − lo), hi] (lo excluded)."""
    keep = (F > lo * (1 + REL)) & (F >= lo + s * (hi - lo) - 1e-12) & (F <= hi * (1 + REL))
    return line(F[keep], v[keep])[2]


def fig2_3_numbers(curves: dict[str, tuple], bands: dict[str, tuple], setting: RegimeStart
                   ) -> dict[str, float]:
    """R² of each regime's line at each μ (curves: tag -> (F, v); bands: tag -> (μmg, μMg,
    largest F))."""
    out = {}
    for tag, (F, v) in curves.items():
        lo, boundary, top = bands[tag]
        out[f"r2_I_{tag}"] = regime_r2(F, v, lo, boundary, setting.s_I)
        out[f"r2_II_{tag}"] = regime_r2(F, v, boundary, top, setting.s_II)
    return out


def fig2_7_numbers(curves: dict[str, tuple], bands: dict[str, tuple], setting: RegimeStart
                   ) -> dict[str, float]:
    """The smallest R² of the regime I lines (one mass moving) over the dm model's curves."""
    r2 = [regime_r2(F, v, bands[tag][0], bands[tag][1], setting.s_I)
          for tag, (F, v) in curves.items()]
    return {"r2_R1_min": min(r2) if r2 and not any(math.isnan(x) for x in r2) else math.nan}


def search_regime_starts(curves: dict, bands: dict, candidates: list[RegimeStart], group: Group,
                         numbers_of=fig2_3_numbers) -> Found:
    """The starts in the order given (the smallest departure from sampling the whole band first);
    the group's setting is the first that reproduces it, else the nearest."""
    f = Found(group)
    for s in candidates:
        f.score(s, numbers_of(curves, bands, s))
    first = next((s for s, d in f.scores if d <= 1.0), None)
    if first is not None:
        f.best = first
        f.best_numbers = numbers_of(curves, bands, first)
        f.best_distance, f.best_each = distance(f.best_numbers, group)
    return f
