"""The thesis' Algorithm 1 (§3.2–§3.4) as its own Python would be written: NumPy over the legs,
a Python-level loop over the contact changes of the spring support, scipy.optimize.root
(method='lm') for the ε-smoothed Coulomb law, and the ε-continuation of §3.5.1.3.

A port written by us, not the thesis' code (which we do not have): the equations and every
convention (units, signs, which feet are down, the corrections to the printed eqs. 3.9, 3.12 and
3.16–3.20) are those of slipwalk's C++, derived in lib/contact/spring_support.cpp,
lib/friction/balance.hpp, lib/friction/planar_forces.cpp and lib/friction/thesis_coulomb.cpp.
It exists to time the thesis' algorithm in the thesis' language (reports/figures/perf_python.py).

Oracle: tests/reports/test_thesis_python.py runs the same frames through `slipwalk model` (CSV
batch mode): the contact sets equal, height, tilt, loads and the viscous-Coulomb body velocity to
rounding, the local connection A of a JSON frame to rounding, and the Coulomb velocity of the
ε-continuation within the continuation's own tolerance of slipwalk's certified Coulomb solve;
besides, the port's own answers balance force and moment.

Conventions (body frame, SI units): q (N × 3) foot positions, x forward, y left, z up, a foot
below the body has q_z < 0; qdot (N × 3) foot velocities (z unused); the body velocity is
v = (v_x, v_y, ω).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.optimize

EPS = np.finfo(float).eps
NOISE = 8.0 * EPS        # rounding error of a height h_j, relative to |u|₁ + |q_z,j|
RANK_TOL = 1e-13         # an eigenvalue of Σ a aᵀ below this × the largest: a null direction
FLAT_TOL = 1e-12         # a null-space moment below this × Mg is zero (CoM on the contacts' line)
RATE_TOL = 1e-13         # a height changing by less than this × |d| along a step stays put
POLISHED = 1e-14         # a balance residual that needs no polishing
FRICTION_RANK_TOL = 1e-12  # eigenvalues of the friction system below this × trace are zero
S = np.array([[0.0, -1.0], [1.0, 0.0]])  # S q = (−q_y, q_x): ω × q in the plane


@dataclass
class Robot:
    """Constants of a legged robot: stiffness K_j (N/m), friction μ_j, anisotropy w_j (eq.
    3.19, H ∝ I + w wᵀ, body frame) and the weight Mg (N) the legs carry."""
    K: np.ndarray
    mu: np.ndarray
    w: np.ndarray
    Mg: float

    @property
    def legs(self) -> int:
        return len(self.K)

    def metric(self) -> np.ndarray:
        """G_j = I + w_j w_jᵀ (N × 2 × 2)."""
        return np.eye(2) + self.w[:, :, None] * self.w[:, None, :]


def uniform_robot(n: int, K: float, mu: float, Mg: float) -> Robot:
    return Robot(np.full(n, K), np.full(n, mu), np.zeros((n, 2)), Mg)


@dataclass
class Support:
    """What the spring support found (§3.3): the body plane, the feet down and their loads."""
    alpha: float
    beta: float
    z: float
    contact: np.ndarray  # (N) bool: h_j < 0 beyond rounding
    Fz: np.ndarray       # (N) N, eq. 3.7
    status: str          # "balanced", "line", "point", "unsupported", "iteration-limit"
    changes: int = 0     # contact changes along the path
    tilts: int = 0       # steps of §3.3.3 (the contacts cannot hold the moment: eqs. 3.11, 3.12)


# ---------------------------------------------------------------------------------------------
# The spring support (§3.3, Alg. 1), in the scaled state u = (αL, βL, z), L = max |q_xy,j|:
# foot j's height is h_j = a_j·u + q_z,j with a_j = (q_y,j/L, −q_x,j/L, 1) (eq. 3.6).


@dataclass
class _Geometry:
    a: np.ndarray    # (N × 3)
    qz: np.ndarray   # (N)
    a_l1: np.ndarray  # |a_j|₁
    L: float

    def heights(self, u: np.ndarray) -> np.ndarray:
        return self.a @ u + self.qz  # eq. 3.6


def _geometry(q: np.ndarray) -> _Geometry:
    size = float(np.max(q[:, 0] ** 2 + q[:, 1] ** 2))
    L = np.sqrt(size) if size > 0.0 else 1.0
    a = np.column_stack([q[:, 1] / L, -q[:, 0] / L, np.ones(len(q))])
    return _Geometry(a, q[:, 2].copy(), np.abs(a).sum(axis=1), L)


@dataclass
class _Cell:
    """The quadratic model of U = Σ ½ K min(h, 0)² + Mg z on one contact set: ∇U, H_C = Σ K a aᵀ,
    and the split into its range and null space (from Σ a aᵀ, which does not depend on K)."""
    grad: np.ndarray
    H: np.ndarray
    basis: np.ndarray  # columns ascending: the first 3 − rank span the null space
    rank: int
    reduced: np.ndarray | None = None  # Rᵀ H R on the range basis R

    @property
    def range_basis(self) -> np.ndarray:
        return self.basis[:, 3 - self.rank:]

    def null_part(self, v: np.ndarray) -> np.ndarray:
        N = self.basis[:, :3 - self.rank]
        return N @ (N.T @ v)

    def newton(self, v: np.ndarray) -> np.ndarray:
        """−H_C⁺ v within the range of H_C (v may be a 3 × m matrix of right-hand sides)."""
        if self.rank == 0:
            return np.zeros_like(v)
        R = self.range_basis
        return -R @ np.linalg.solve(self.reduced, R.T @ v)


def _cell(g: _Geometry, K: np.ndarray, Mg: float, contact: np.ndarray, u: np.ndarray) -> _Cell:
    a, k = g.a[contact], K[contact]
    G = a.T @ a
    H = (a.T * k) @ a
    grad = np.array([0.0, 0.0, Mg]) + a.T @ (k * (a @ u + g.qz[contact]))  # eq. 3.9 as ∇U
    tr = np.trace(G)
    if np.linalg.det(G) > RANK_TOL * tr ** 3:
        basis, rank = np.eye(3), 3
    else:
        lam, basis = np.linalg.eigh(G)
        rank = int(np.sum((lam > RANK_TOL * lam[2]) & (lam > 0.0)))
    cell = _Cell(grad, H, basis, rank)
    R = cell.range_basis
    cell.reduced = H if rank == 3 else R.T @ H @ R
    return cell


def _initial_height(g: _Geometry, K: np.ndarray, Mg: float) -> float:
    """§3.3.1: z* with α = β = 0 and Σ F_z = Mg, by Newton's method on the piecewise linear
    F(z) = Σ K max(−q_z − z, 0) from below (every foot down), each pass a vectorized sum."""
    z = -np.inf
    for _ in range(len(K) + 1):
        below = g.qz < -z
        nxt = -(np.dot(K[below], g.qz[below]) + Mg) / np.sum(K[below])
        if not nxt > z:
            break
        z = nxt
    return z


def _first_change(g: _Geometry, cell: _Cell, u, d, contact, t_max, tilt, exempt):
    """Eq. 3.10: the first foot on u + t d, t ∈ (0, t_max], that lifts off (in the set, rising
    to h = 0) or touches down (out of it, coming down to h = 0). A foot at its plane changes only
    on a rate above the rounding error of the step; `exempt` (the foot that just changed) keeps
    its way. Returns (leg or −1, t, whether a foot at a tie was held on a rounding-level rate)."""
    size = np.linalg.norm(d)
    r = g.a @ d
    h = g.heights(u)
    h_noise = NOISE * (np.abs(u).sum() + np.abs(g.qz))
    plain = RATE_TOL * size * g.a_l1
    noise = plain.copy()
    if not tilt and cell.rank > 0:
        at_plane = np.abs(h) <= h_noise
        if at_plane.any():
            rate_error = NOISE * np.trace(cell.reduced) * size * np.linalg.norm(
                cell.newton(g.a[at_plane].T), axis=0)
            noise[at_plane] = np.maximum(noise[at_plane], h_noise[at_plane] + rate_error)
    checked = np.ones(len(h), bool)
    if tilt:
        checked &= ~contact  # along a tilt the contacts keep their compressions
    if exempt >= 0:
        checked[exempt] = False
    held = checked & (np.abs(r) <= noise)
    suppressed = bool(np.any(held & (np.abs(r) > plain)))
    moving = checked & ~held
    t = np.full(len(h), np.inf)
    lift = moving & contact & (r > 0.0)
    touch = moving & ~contact & (r < 0.0)
    t[lift] = np.maximum(-h[lift], 0.0) / r[lift]
    t[touch] = np.maximum(h[touch], 0.0) / -r[touch]
    leg = int(np.argmin(t))  # ties: the lowest index
    if not t[leg] < t_max:
        return -1, t_max, suppressed
    return leg, float(t[leg]), suppressed


def _touching(g: _Geometry, u: np.ndarray):
    """The output convention: a foot is down when h_j < 0 beyond the rounding error of h_j."""
    h = g.heights(u)
    noise = 4.0 * EPS * (np.abs(g.qz) + abs(u[2]) + np.abs(u[0] * g.a[:, 0])
                         + np.abs(u[1] * g.a[:, 1]))
    return h < -noise, h


def _balance_residual(g: _Geometry, K, Mg, q, u) -> float:
    """max(|ΣF_z − Mg|/Mg, |M_x|/(Mg L), |M_y|/(Mg L)) with the loads of eq. 3.7."""
    on, h = _touching(g, u)
    F = np.where(on, -K * h, 0.0)
    mx = -np.dot(q[:, 1], F)
    my = np.dot(q[:, 0], F)
    return max(abs(F.sum() - Mg) / Mg, abs(mx) / (Mg * g.L), abs(my) / (Mg * g.L))


def _polish(g, K, Mg, q, u, contact):
    """Refines the final balance: one Newton correction on the final set, then up to two on the
    set read off the heights; each kept only if it balances better."""
    best = _balance_residual(g, K, Mg, q, u)
    for step in range(3):
        if best <= POLISHED:
            break
        if step > 0:
            contact = _touching(g, u)[0]
        cell = _cell(g, K, Mg, contact, u)
        if cell.rank == 0:
            break
        trial = u + cell.newton(cell.grad)
        r = _balance_residual(g, K, Mg, q, trial)
        if r < best:
            u, best = trial, r
    return u, contact


def _reduce_free_tilt(g: _Geometry, cell: _Cell, u, contact):
    """Contacts on a line or at a point leave the tilt free along the null space: move toward
    the least |(α, β)|, stopping where a foot in the air would touch down."""
    k = 3 - cell.rank
    if k not in (1, 2):
        return u
    V = cell.basis[:2, :k]
    BtB = V.T @ V
    if not abs(np.linalg.det(BtB)) > RANK_TOL:
        return u
    d = cell.basis[:, :k] @ -np.linalg.solve(BtB, V.T @ u[:2])
    r = g.a @ d
    blocking = ~contact & (r < -RATE_TOL * np.linalg.norm(d) * g.a_l1)
    t = 1.0
    if blocking.any():
        t = min(t, float(np.min(np.maximum(g.heights(u)[blocking], 0.0) / -r[blocking])))
    return u + t * d


def spring_support(robot: Robot, q: np.ndarray, max_changes: int | None = None) -> Support:
    """Alg. 1 (§3.3): z* at zero tilt (§3.3.1), then along segments toward the balance of the
    current contact set (eq. 3.9), stopping at the first contact change (eq. 3.10, §3.3.2); where
    the contacts cannot hold the moment (one or two feet, or feet in a row) the body tilts under
    gravity (§3.3.3, eqs. 3.11, 3.12: the descent direction −g_N in the null space of H_C)."""
    g = _geometry(q)
    K, Mg, n = robot.K, robot.Mg, robot.legs
    limit = max_changes or 1 + n + n * (n - 1) // 2 + n * (n - 1) * (n - 2) // 6
    z0 = _initial_height(g, K, Mg)
    u = np.array([0.0, 0.0, z0])
    contact = g.qz < -z0
    status, changes, tilts, last, held = "balanced", 0, 0, -1, False
    while True:
        cell = _cell(g, K, Mg, contact, u)
        g_null = cell.null_part(cell.grad)
        tilt = np.linalg.norm(g_null) > FLAT_TOL * Mg
        d = -g_null if tilt else cell.newton(cell.grad)
        tilts += int(tilt)
        exempt = last if tilt or cell.rank == 3 else -1
        leg, t, suppressed = _first_change(g, cell, u, d, contact, np.inf if tilt else 1.0,
                                           tilt, exempt)
        held = held or suppressed
        if leg < 0:
            if tilt:
                status = "unsupported"  # nothing stops the tilt: the robot tips over
                break
            u = u + d  # the balance of this contact set keeps it: the global minimizer
            final = cell
            if held:
                u, contact = _polish(g, K, Mg, q, u, contact)
                final = _cell(g, K, Mg, contact, u)
            if final.rank < 3:
                status = "line" if final.rank == 2 else "point"
                u = _reduce_free_tilt(g, final, u, contact)
            break
        u = u + t * d  # eq. 3.10: to the first contact change, and switch that foot
        contact = contact.copy()
        contact[leg] = not contact[leg]
        last = leg
        changes += 1
        if changes >= limit:
            status = "iteration-limit"
            break
    down, h = _touching(g, u)
    Fz = np.where(down, -K * h, 0.0)  # eq. 3.7
    return Support(u[0] / g.L, u[1] / g.L, float(u[2]), down, Fz, status, changes, tilts)


# ---------------------------------------------------------------------------------------------
# Friction and the planar balance (§3.4). Foot k slides at u_k = v + ω S q_k + q̇_k (eq. 3.5 in
# the body frame) and feels F_k = −c_k φ(s_k) G_k u_k, c_k = μ_k F_z,k, G_k = I + w_k w_kᵀ,
# s_k = √(u_kᵀ G_k u_k): φ = 1 is the viscous-Coulomb ansatz (eq. 3.19), φ = (ε + s)/(ε + s²)
# the smoothed law of eq. 3.14. Balance: Σ F_k = 0 and Σ (q_k × F_k)_z = 0 (eqs. 3.16–3.18).


def friction_weights(robot: Robot, support: Support) -> np.ndarray:
    """c_k = μ_k F_z,k for a foot down, else 0."""
    c = robot.mu * support.Fz
    return np.where(support.contact & (c > 0.0), c, 0.0)


@dataclass
class ViscousSystem:
    """M̃ y = −b̃ of eq. 3.20 in the scaled unknowns y = (v_x, v_y, L ω), L the largest lever arm
    of a foot with friction: M̃ = Σ c J̃ᵀ G J̃, J̃_k = [I | S q_k / L], and M̃⁺."""
    L: float
    feet: np.ndarray   # indices of the feet with friction
    JtG: np.ndarray    # (k × 3 × 2) c_k J̃_kᵀ G_k
    pinv: np.ndarray   # M̃⁺ (least norm where the contacts are one point)


def viscous_system(robot: Robot, q: np.ndarray, c: np.ndarray) -> ViscousSystem:
    feet = np.flatnonzero(c > 0.0)
    qxy = q[feet, :2]
    lever2 = float(np.max(np.sum(qxy ** 2, axis=1))) if len(feet) else 0.0
    L = np.sqrt(lever2) if lever2 > 0.0 else 1.0
    J = np.zeros((len(feet), 2, 3))
    J[:, 0, 0] = J[:, 1, 1] = 1.0
    J[:, :, 2] = qxy @ S.T / L
    cG = c[feet, None, None] * robot.metric()[feet]
    JtG = np.einsum("kia,kij->kaj", J, cG)
    M = np.einsum("kaj,kjb->ab", JtG, J)
    lam, V = np.linalg.eigh(M)
    keep = lam > FRICTION_RANK_TOL * max(np.abs(lam).sum(), 0.0)
    inv = np.where(keep, 1.0 / np.where(keep, lam, 1.0), 0.0)
    return ViscousSystem(L, feet, JtG, (V * inv) @ V.T)


def local_connection(robot: Robot, q: np.ndarray, system: ViscousSystem) -> np.ndarray:
    """Eq. 3.20: A (3 × 2N) with v = A vec(q̇_xy), A_k = −D M̃⁺ c_k J̃_kᵀ G_k, D = diag(1, 1, 1/L);
    zero columns for the feet without friction."""
    A = np.zeros((3, 2 * robot.legs))
    cols = -np.einsum("ab,kbj->akj", system.pinv, system.JtG)
    cols[2] /= system.L
    A.reshape(3, robot.legs, 2)[:, system.feet, :] = cols
    return A


def viscous_balance(robot: Robot, q: np.ndarray, qdot: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The viscous-Coulomb body velocity (v_x, v_y, ω): eqs. 3.16–3.18 with φ = 1, a 3 × 3 solve."""
    system = viscous_system(robot, q, c)
    b = np.einsum("kaj,kj->a", system.JtG, qdot[system.feet, :2])
    y = -system.pinv @ b
    return np.array([y[0], y[1], y[2] / system.L])


def foot_forces(robot: Robot, q, qdot, c, v, epsilon: float = np.inf) -> np.ndarray:
    """F_k (N × 2) at body velocity v under eq. 3.14's law (ε = ∞: viscous-Coulomb, eq. 3.19)."""
    u = v[:2] + v[2] * (q[:, :2] @ S.T) + qdot[:, :2]
    Gu = u + robot.w * np.sum(robot.w * u, axis=1, keepdims=True)
    scale = c
    if np.isfinite(epsilon):
        s = np.sqrt(np.sum(u * Gu, axis=1))
        scale = c * (epsilon + s) / (epsilon + s * s)  # eq. 3.14
    return -scale[:, None] * Gu


def planar_balance(robot: Robot, q, qdot, c, v, epsilon: float = np.inf) -> np.ndarray:
    """(Σ F_x, Σ F_y, Σ M_z) at v: zero at the balance (eqs. 3.16–3.18)."""
    F = foot_forces(robot, q, qdot, c, v, epsilon)
    return np.array([F[:, 0].sum(), F[:, 1].sum(),
                     np.dot(q[:, 0], F[:, 1]) - np.dot(q[:, 1], F[:, 0])])


@dataclass
class Solve:
    v: np.ndarray
    converged: bool
    evaluations: int = 0  # of the balance, by the root finder
    eps_steps: int = 0    # ε values solved (the continuation)


def epsilon_balance(robot: Robot, q, qdot, c, epsilon: float, start) -> Solve:
    """One ε solve of eq. 3.14's balance by scipy.optimize.root(method='lm') from `start`
    (MINPACK's Levenberg–Marquardt, forward-difference Jacobian, its default tolerances)."""
    feet = np.flatnonzero(c > 0.0)
    sub = Robot(robot.K[feet], robot.mu[feet], robot.w[feet], robot.Mg)
    qf, qdf, cf = q[feet], qdot[feet], c[feet]
    sol = scipy.optimize.root(lambda x: planar_balance(sub, qf, qdf, cf, x, epsilon),
                              np.asarray(start, float), method="lm")
    return Solve(sol.x, bool(sol.success) and bool(np.all(np.isfinite(sol.x))), int(sol.nfev))


def coulomb_by_continuation(robot: Robot, q, qdot, c, start, eps_start: float = 1e-5,
                            eps_factor: float = 0.1, rel_change: float = 1e-3,
                            max_steps: int = 30) -> Solve:
    """§3.5.1.3: ε = 1e-5, then ε × eps_factor (the factor is not stated), each solve started
    from the last, until two consecutive solutions differ by ≤ rel_change of the newer's L2
    norm (as lib/friction/thesis_coulomb.cpp reads the thesis' sentence)."""
    last = np.asarray(start, float)
    eps, steps, settled, evaluations, ok = eps_start, 0, False, 0, True
    while not settled and steps < max_steps:
        one = epsilon_balance(robot, q, qdot, c, eps, last)
        steps += 1
        evaluations += one.evaluations
        if not one.converged:
            ok = False
            break
        settled = steps > 1 and np.linalg.norm(one.v - last) <= rel_change * np.linalg.norm(one.v)
        last = one.v
        eps *= eps_factor
    return Solve(last, ok and settled, evaluations, steps)


# ---------------------------------------------------------------------------------------------
# One frame of the model (Alg. 1): spring support, the local connection, the viscous balance.


@dataclass
class FrameResult:
    support: Support
    A: np.ndarray
    v: np.ndarray


def model(robot: Robot, q: np.ndarray, qdot: np.ndarray) -> FrameResult:
    """Alg. 1: (A) the spring support, (B) the local connection A of eq. 3.20 and the body
    velocity v = A vec(q̇_xy)."""
    support = spring_support(robot, q)
    system = viscous_system(robot, q, friction_weights(robot, support))
    A = local_connection(robot, q, system)
    return FrameResult(support, A, A @ qdot[:, :2].ravel())


# ---------------------------------------------------------------------------------------------
# The per-frame cost study's robots and random frames (sweeps/points/legged_cost.cpp), drawn
# with NumPy's generator instead of slipwalk's: the same distributions, not the same frames.

BODY_WEIGHT = 8.18 * 9.81  # N: BigANT's 8.18 kg
SINKAGE = 0.01             # m: the static sinkage with every foot down
HEIGHT = 0.1               # m: the feet this far below the body frame
RIM = 0.3                  # m: the disk robots' radius


def disk_robot(n: int) -> tuple[Robot, np.ndarray]:
    """n legs equally spaced on a 0.3 m rim (§3.5.3), K such that the body sinks 1 cm with all
    feet down, μ = 1; returns the robot and its nominal feet (n × 3)."""
    a = 2.0 * np.pi * np.arange(n) / n
    nominal = np.column_stack([RIM * np.cos(a), RIM * np.sin(a), np.full(n, -HEIGHT)])
    return uniform_robot(n, BODY_WEIGHT / (n * SINKAGE), 1.0, BODY_WEIGHT), nominal


def hexapod_robot() -> tuple[Robot, np.ndarray]:
    """BigANT-like: feet at x ∈ {−0.3, 0, 0.3} m, y = ±0.2 m, otherwise as disk_robot."""
    k = np.arange(6)
    nominal = np.column_stack([0.3 * (k // 2 - 1), np.where(k % 2 == 0, 0.2, -0.2),
                               np.full(6, -HEIGHT)])
    return uniform_robot(6, BODY_WEIGHT / (6 * SINKAGE), 1.0, BODY_WEIGHT), nominal


def random_frame(robot: Robot, nominal: np.ndarray, rng: np.random.Generator,
                 speed: float = 0.1, spread: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Feet jittered by ±2 cm in x, y and ±2 mm in z, each lifted by 0.5–4 cm with probability ½,
    drawn again until the support balances; foot velocities speed·(−1 + spread n₁, spread n₂)
    plus a common turn of rate speed·spread·n₃ / 0.3 m (n_i standard normal)."""
    n = robot.legs
    for _ in range(1000):
        q = nominal + np.column_stack([rng.uniform(-0.02, 0.02, n), rng.uniform(-0.02, 0.02, n),
                                       rng.uniform(-0.002, 0.002, n)])
        q[:, 2] += np.where(rng.uniform(size=n) < 0.5, rng.uniform(0.005, 0.04, n), 0.0)
        if spring_support(robot, q).status == "balanced":
            break
    turn = speed * spread * rng.normal() / RIM
    qdot = np.column_stack([speed * (-1.0 + spread * rng.normal(size=n)) - turn * q[:, 1],
                            speed * spread * rng.normal(size=n) + turn * q[:, 0], np.zeros(n)])
    return q, qdot
