"""Shared helpers of the report scripts (thesis chapter 2, the inchworm).

Every figure script is run as `python3 reports/figures/<fig>.py --data DIR --out DIR`; it reads CSVs under
DIR/ch2_inchworm/, writes OUT/<fig>.png and OUT/values/<fig>.json (every number it measured) and
exits with a clear message when an input is missing. Only the standard library, numpy and
matplotlib are used (Debian's python3).
"""
from __future__ import annotations

import argparse
import csv
import functools
import json
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

# Model constants of thesis §2.3 (SI units). They are the defaults of lib/inchworm/params.hpp.
m = 1.0  # kg, the smaller mass
M = 1.5  # kg, the larger mass
L_MIN = 0.02  # m
L_MAX = 0.5  # m
G = 9.81  # m/s^2
DL = L_MAX - L_MIN
RHO = (M - m) / (M + m)  # CoM jump per unit of x - y at a swap

STUDY = "ch2_inchworm"
REPO = Path(__file__).resolve().parents[2]
# the claims ledger; build_report.py --claims passes another one down through the environment
LEDGER = Path(os.environ.get("SLIPWALK_CLAIMS", REPO / "data" / "thesis" / "claims.toml"))


def fail(msg: str) -> None:
    """Stops the script with a message on stderr and exit status 2."""
    prog = Path(sys.argv[0]).name
    print(f"{prog}: error: {msg}", file=sys.stderr)
    raise SystemExit(2)


def parse_args(description: str) -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--data", required=True, type=Path, help="data folder (holds ch2_inchworm/)")
    ap.add_argument("--out", required=True, type=Path, help="output folder")
    return ap.parse_args()


def study_file(data: Path, name: str, study: str = STUDY) -> Path:
    """DATA/<study>/<name>, or exit 2 naming the file and the study that writes it."""
    path = data / study / name
    if not path.is_file():
        fail(f"{path}: input file missing (run `slipwalk reproduce {study}` to produce it)")
    return path


def shown_path(path: Path) -> str:
    """A path as the pages name it: relative to the repository, else by its name alone (a page
    never shows a machine's absolute path)."""
    try:
        return str(Path(path).resolve().relative_to(REPO)) or "."
    except ValueError:
        return Path(path).resolve().name


# ---------------------------------------------------------------------------------------------
# The thesis' numbers live in the claims ledger only (DESIGN.md: no hand-copied numbers).


@functools.lru_cache(maxsize=None)
def load_ledger(path: Path = LEDGER) -> dict:
    import tomllib

    if not path.is_file():
        fail(f"{path}: claims ledger missing")
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        fail(f"{path}: {e}")


def claim(claim_id: str) -> dict:
    """A ledger entry by its id."""
    for entry in load_ledger().get("claim", []):
        if entry.get("id") == claim_id:
            return entry
    fail(f"{LEDGER}: no claim with id '{claim_id}'")


def thesis(claim_id: str):
    """The thesis' value of a ledger entry (its `thesis` field)."""
    return claim(claim_id)["thesis"]


def target(claim_id: str):
    """The number a ledger entry is judged against: its `target`, else its `thesis`."""
    entry = claim(claim_id)
    return entry.get("target", entry["thesis"])


# ---------------------------------------------------------------------------------------------
# CSV input


class Table:
    """A CSV file as columns. Numeric columns become float arrays ('nan' allowed), others str."""

    def __init__(self, path: Path, required: list[str] | None = None):
        self.path = path
        with open(path, newline="") as f:
            reader = csv.reader(f)
            try:
                header = next(reader)
            except StopIteration:
                fail(f"{path}: empty file (no header)")
            rows = [r for r in reader if r]
        header = [h.strip() for h in header]
        for i, r in enumerate(rows):
            if len(r) != len(header):
                fail(f"{path}:{i + 2}: {len(r)} cells, header has {len(header)}")
        self.columns: dict[str, np.ndarray] = {}
        for j, name in enumerate(header):
            raw = [r[j] for r in rows]
            try:
                self.columns[name] = np.array([float(v) if v != "" else math.nan for v in raw])
            except ValueError:
                self.columns[name] = np.array(raw, dtype=object)
        self.n = len(rows)
        for name in required or []:
            if name not in self.columns:
                fail(f"{path}: column '{name}' missing (have: {', '.join(header)})")

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self.columns:
            fail(f"{self.path}: column '{name}' missing")
        return self.columns[name]

    def str(self, name: str) -> np.ndarray:
        """A column as strings (numbers printed back as written by float())."""
        col = self[name]
        if col.dtype == object:
            return col
        return np.array(["" if math.isnan(v) else repr(v) for v in col], dtype=object)

    def subset(self, mask: np.ndarray) -> "Table":
        t = Table.__new__(Table)
        t.path = self.path
        t.columns = {k: v[mask] for k, v in self.columns.items()}
        t.n = int(np.count_nonzero(mask))
        return t


def read_table(data: Path, name: str, required: list[str] | None = None) -> Table:
    t = Table(study_file(data, name), required)
    if t.n == 0:
        fail(f"{t.path}: no data rows")
    return t


SWEEP_COLUMNS = ["id", "mu", "F", "method", "v_ss", "converged"]


def read_sidecar(path_csv: Path) -> dict | None:
    side = path_csv.with_suffix(".json")
    if not side.is_file():
        return None
    try:
        return json.loads(side.read_text())
    except json.JSONDecodeError as e:
        fail(f"{side}: not valid JSON: {e}")


def mu_static(t: Table) -> np.ndarray:
    """μ_s per row; NaN or missing means μ_s = μ."""
    mu = t["mu"]
    if "mu_s" not in t.columns:
        return mu.copy()
    ms = t["mu_s"].astype(float)
    return np.where(np.isnan(ms), mu, ms)


# ---------------------------------------------------------------------------------------------
# Output


def to_jsonable(x):
    if isinstance(x, dict):
        return {str(k): to_jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [to_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return [to_jsonable(v) for v in x.tolist()]
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        v = float(x)
        return v if math.isfinite(v) else None
    return x


def atomic_write_text(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_values(out: Path, name: str, values: dict) -> None:
    """OUT/values/<name>.json: every number the script measured (NaN/inf become null)."""
    atomic_write_text(out / "values" / f"{name}.json",
                      json.dumps(to_jsonable(values), indent=1, sort_keys=True) + "\n")


FIGURE_DPI = 130


def save_figure(fig, out: Path, name: str) -> None:
    """OUT/<name>.png, and OUT/layout/<name>.json: the figure's size in inches and the size of
    every text drawn into it, so that the page check (reports/site/check_pages.py) can tell the
    smallest text as the page shows it: displayed pt = font pt x shown width / (96 x width_in)."""
    import matplotlib.pyplot as plt
    from matplotlib.text import Text

    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.png"
    fd, tmp = tempfile.mkstemp(dir=out, prefix=name + ".", suffix=".tmp.png")
    os.close(fd)
    drawn: list[tuple[float, str]] = []
    draw = Text.draw

    # Only the texts matplotlib draws count (tick labels outside the view exist but are not
    # drawn), so the sizes are recorded by wrapping Text.draw while the figure is saved.
    def recording_draw(text, renderer):
        if text.get_visible() and text.get_text().strip():
            drawn.append((float(text.get_fontsize()), text.get_text().strip()))
        return draw(text, renderer)

    Text.draw = recording_draw
    try:
        fig.savefig(tmp, dpi=FIGURE_DPI)
        os.replace(tmp, path)
    finally:
        Text.draw = draw
        if os.path.exists(tmp):
            os.unlink(tmp)
        width_in, height_in = (float(x) for x in fig.get_size_inches())
        plt.close(fig)
    drawn.sort()
    layout = {"width_in": width_in, "height_in": height_in, "dpi": FIGURE_DPI,
              "texts": len(drawn), "text_min_pt": drawn[0][0] if drawn else None,
              "smallest": [{"pt": pt, "text": t[:40]} for pt, t in drawn[:8]]}
    atomic_write_text(out / "layout" / f"{name}.json", json.dumps(layout, indent=1) + "\n")


def setup_matplotlib():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({
        "figure.dpi": 100,
        # The page shows a wide figure ~1300 CSS px wide: a 14-inch figure's 9.5 pt text is
        # then 9.2 pt on screen, above the report's 8 pt floor (reports/site/check_pages.py).
        "font.size": 10,
        "axes.labelsize": 10,
        "xtick.labelsize": 9.5,
        "ytick.labelsize": 9.5,
        "axes.grid": True,
        "grid.alpha": 0.3,
        "legend.fontsize": 9.5,
        "axes.titlesize": 10.5,
    })
    return plt


# ---------------------------------------------------------------------------------------------
# Palette of the chapter-3 figures: one meaning per colour, the thesis' own where its captions
# state one. Figs. 3.5-3.10: viscous-Coulomb orange, Coulomb blue, spring support purple,
# measurements (motion capture, F/T) red; Fig. 3.11: the model's estimate blue; Fig. 3.12: the
# estimate orange, filtered blue. Fig. 3.14 drew MuJoCo orange and the thesis' model blue, which
# would clash with Figs. 3.5-3.10; MuJoCo gets a colour of its own here instead.

VISCOUS = "tab:orange"    # the viscous-Coulomb ansatz (eq. 3.19)
COULOMB = "tab:blue"      # classical Coulomb friction (and the ε-family's Coulomb end)
SUPPORT = "tab:purple"    # the spring support: roll, pitch, F_z (eq. 3.6, Alg. 1)
ESTIMATE = "tab:blue"     # Fig. 3.11: the model's estimate of a Multipod
FILTERED = "tab:blue"     # Fig. 3.12: the estimate through the IIR filter (§3.5.2.2)
MUJOCO = "tab:green"      # MuJoCo, the peer simulator, also where it stands in for the robot
# The thesis' measurements: we have none, so no data of ours is drawn red, except where a peer
# stands in for the measured robot of a thesis figure (§5.3: MuJoCo's Multipod is the motion
# capture B is fitted to, Figs. 5.5, 5.6).
MEASURED = "tab:red"
REFERENCE = "0.15"        # a law, closed form, target or bound drawn for reference
NEUTRAL = "0.45"          # a difference of two of our runs, a spread, a secondary curve
# Series without a thesis meaning (legs, feet, distributions, robot sizes, components): none of
# the colours above, so that orange, blue, purple, green and red keep theirs.
CATEGORICAL = ("tab:cyan", "tab:olive", "tab:brown", "tab:pink", "0.3", "0.62")


def log_ticks(axis, lo: float, hi: float) -> None:
    """Labelled ticks on a log axis that may span less than a decade: 1-2-5 per decade, or
    1-1.5-2-3-5-7 when that leaves fewer than four, printed as plain numbers."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

    decades = range(math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1)
    for mantissas in ((1, 2, 5), (1, 1.5, 2, 3, 5, 7)):
        ticks = [mt * 10.0**e for e in decades for mt in mantissas]
        ticks = [v for v in ticks if lo <= v <= hi]
        if len(ticks) >= 4:
            break
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


# ---------------------------------------------------------------------------------------------
# Fits


def linfit(x: np.ndarray, y: np.ndarray) -> dict:
    """Least-squares line y = k x + b with R² = 1 − SS_res/SS_tot; None fields if < 3 points."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if x.size < 3 or np.ptp(x) == 0:
        return {"k": None, "b": None, "r2": None, "n": int(x.size)}
    k, b = np.polyfit(x, y, 1)
    return {"k": float(k), "b": float(b), "r2": r_squared(y, k * x + b), "n": int(x.size)}


def r_squared(y: np.ndarray, yhat: np.ndarray) -> float | None:
    y = np.asarray(y, float)
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    if ss_tot == 0.0:
        return None
    return 1.0 - float(np.sum((y - yhat) ** 2)) / ss_tot


def lstsq_fit(columns: list[np.ndarray], y: np.ndarray) -> tuple[np.ndarray, float | None]:
    """Linear least squares y ≈ Σ c_i columns_i; returns (c, R²)."""
    A = np.column_stack(columns)
    c, *_ = np.linalg.lstsq(A, y, rcond=None)
    return c, r_squared(y, A @ c)


def fmt(x, digits: int = 4) -> str:
    if x is None:
        return "—"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    x = float(x)
    if not math.isfinite(x):
        return "—"
    if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e5):
        return f"{x:.{digits - 1}e}"
    return f"{x:.{digits}g}"


# ---------------------------------------------------------------------------------------------
# Closed form (used only for cross-checks and by reports/dev/fake_data.py; figures plot the C++ data)


def closed_form(F: float, mu: float, variant: str = "corrected") -> dict:
    """Steady state of the instant-swap inchworm (thesis §2.4) for μ_s = μ.

    variant "corrected": the stroke length equation ½ r1 t1² + r1 t1 t2 + ½ r2 t2² = ΔL.
    variant "printed": eq. 2.9 as printed in the thesis, without the ½ on the t2² term.
    """
    a_x = (F - mu * m * G) / m
    b = (F + mu * M * G) / M
    r1 = F / m + F / M
    kappa = F / (F + mu * M * G)
    if F <= mu * M * G:
        r2 = a_x
        a2 = (F - mu * m * G) / (m + M)
        regime = 1
    else:
        r2 = a_x + (F - mu * M * G) / M
        a2 = mu * G * RHO
        regime = 2
    u = (1.0 - kappa) / a2
    v = 1.0 / b
    half = 0.5 if variant == "corrected" else 1.0
    Q = 0.5 * r1 * v * v + r1 * v * u + half * r2 * u * u
    c0 = math.sqrt(DL / Q)
    T = c0 * (v + u)
    vss = 0.5 * (1.0 + kappa) * c0 + RHO * DL / (2.0 * T)
    return {"v_ss": vss, "c0": c0, "period": T, "regime": regime, "kappa": kappa}


def eq2_6_coefficients() -> tuple[float, float, float, float]:
    """(a, c, d, e) of eq. 2.6, ṽ = a μ (1 − c μ²) f̃ + d μ + e, from the ledger."""
    return tuple(float(thesis(k)) for k in ("2.3.1.1-eq2.6-a", "2.3.1.1-eq2.6-c",
                                             "2.3.1.1-eq2.6-d", "2.3.1.1-eq2.6-e"))


def eq2_6(F, mu, coef, scale: str = "sqrt_Lmax_g"):
    """The nondimensional law of eq. 2.6 in m/s (f̃ = F/(μMg), v = ṽ·scale)."""
    a, cc, d, e = coef
    F = np.asarray(F, float)
    mu = np.asarray(mu, float)
    f = F / (mu * M * G)
    vt = a * mu * (1.0 - cc * mu**2) * f + d * mu + e
    return vt * velocity_scale(scale)


def velocity_scale(scale: str) -> float:
    if scale == "sqrt_Lmax_g":
        return math.sqrt(L_MAX * G)
    if scale == "sqrt_2g_Lmax":
        return math.sqrt(2.0 * G * L_MAX)
    raise ValueError(scale)
