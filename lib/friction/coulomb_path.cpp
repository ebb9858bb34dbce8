// The smoothing path and its active-set polish: the Coulomb solver's fallback when the fast path
// (coulomb.cpp; problem, dual and certificate are described there) does not certify, e.g. with
// several feet at rest at once, and its way to certify frames whose static feet sit at distinct
// points (a rigid gait).
//
//  1. Smoothing path: damped Newton steps (Armijo) on D_δ(y) = Σ √(‖r_k‖² + δ²) (smooth,
//     convex, its Hessian regularized only along directions no foot feels); a stage ends when
//     the Newton decrement falls below 3δ (or after 8 steps), and δ is then divided by 10, from
//     δ₀ = 0.1 D(start)/N down to δ_min = 0.1 tol D/N, where the smoothing error alone is within
//     the tolerance. Near δ_min the path's own dual λ_k = r_k/√(‖r_k‖² + δ²) is certified too.
//  2. Polish at the end of each stage (active set): feet with ‖r_k‖ ≤ min(10 δ, 0.01 D/N) are
//     static, and so is the slowest other foot if it is clearly apart (‖r‖ ≤ 0.1 × the next
//     and ≤ 10³ δ: a static foot whose force lies near the rim of its disk keeps
//     ‖r‖ = δ t/√(1 − t²) on the path). The body velocity is restricted to where the static feet
//     do not slip — a point if they span two distinct points, the rotations about their common
//     point if one, all of R³ if none — and the exact D of the sliding feet is minimized there
//     by Newton's method, which is smooth and converges quadratically if the static set is right
//     (the attempt is abandoned as soon as it does not: a step cut below 1/2, or a decrement
//     not falling 4× per step). Its dual is the fast path's (linearized directions) plus the
//     static feet's forces that balance the sliding feet (for static feet at distinct points,
//     whose internal force is free, a balancing choice inside the disks: fit_static_forces).
//     A right static set certifies to ~1e-15 in 1–3 steps.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "friction/coulomb_solver.hpp"

namespace slipwalk::friction::coulomb {

namespace {

constexpr double kDelta0 = 0.1;  // δ₀ = kDelta0 · D(start)/N
constexpr double kSigma = 0.1;   // δ ← kSigma δ at the end of a stage
constexpr double kKappa = 10.0;  // static: ‖r_k‖ ≤ kKappa δ

}  // namespace

template <bool kLoaded>
void Solver<kLoaded>::path(Eigen::Vector3d y, Sums& S, double Dref) {
  auto& s = frame_.friction;
  const Eigen::Vector3d start = y;
  const int n = std::max(cs_.active, 1);
  const double delta_min = std::max(0.1 * options_.tol * Dref / n, 64.0 * kEps * Dref / n);
  double delta = std::max(kDelta0 * dissipation(value<true>(y, 0.0), y) / n, delta_min);
  assemble<true>(y, delta * delta, S);
  int stage_steps = 0;
  bool stalled = false;
  bool fresh = true;  // the row r2 holds ‖r_k(y)‖² (try_polish classifies from it)
  while (s.iterations < options_.max_iterations) {
    const Eigen::Vector3d p = smoothing_step(S);
    const double slope = S.g.dot(p);
    if (!(-slope > 3.0 * delta) || stalled || stage_steps >= 8 || delta <= delta_min) {
      // End of a stage at y.
      if constexpr (kLoaded) {
        if (anchor_.rho > 0.5) {
          adopt_interior(y, S, delta);  // near a holding limit: a deeper anchor
        }
      }
      if (delta <= 1e3 * delta_min) {
        // The smoothing path's own dual λ_k = r_k/ρ_k: its gap is O(N δ / D), so it is only
        // worth checking near the end of the path.
        const Dual dual{true, delta * delta, Eigen::Vector3d::Zero(), S.g};
        if (path_bound(y, S, delta) <= options_.tol) {
          classify(kKappa * delta);
          finish(y, dual);
          return;
        }
      }
      if (!fresh) {
        assemble<true>(y, delta * delta, S);  // ‖r_k(y)‖² back into the row r2
      }
      Eigen::Vector3d yp = y;
      Dual dual;
      fresh = false;  // a polish moves y
      if (try_polish(yp, std::min(kKappa * delta, 1e-2 * Dref / n), delta, dual)) {
        finish(yp, dual);
        return;
      }
      if (delta > delta_min) {
        delta = std::max(kSigma * delta, delta_min);
        assemble<true>(y, delta * delta, S);
        fresh = true;
        stage_steps = 0;
        stalled = false;
        continue;
      }
    }
    // One damped Newton step on D_δ (Armijo); the pass at the trial point is the next step's.
    ++s.iterations;
    ++stage_steps;
    stalled = !(slope < 0.0) || !line_search<true>(y, p, slope, delta * delta, 60, 0.0, S);
    fresh = fresh || !stalled;
    if constexpr (kLoaded) {
      if (ran_away(y)) {
        report_sliding();
        return;
      }
    }
  }
  // Out of iterations: the last point of the path with its own dual (loaded: unless the way the
  // path went proves sliding).
  if constexpr (kLoaded) {
    moved_downhill(start, y);
    if (sliding_ < 0.0) {
      report_sliding();
      return;
    }
  }
  classify(kKappa * delta);
  finish(y, Dual{true, delta * delta, Eigen::Vector3d::Zero(), S.g});
}

template <bool kLoaded>
template <bool kAll>
bool Solver<kLoaded>::line_search(Eigen::Vector3d& y, const Eigen::Vector3d& p, double slope,
                                  double d2, int halvings, double t_min, Sums& S) {
  const double f0 = S.f;
  const double slack = 8.0 * kEps * rounding_scale(f0, y);
  Sums T;
  assemble<kAll>(y + p, d2, T);
  if (T.f <= f0 + 1e-4 * slope + slack) {
    y += p;
    S = T;
    return true;
  }
  double t = 0.5;
  for (int j = 1; j < halvings && t >= t_min; ++j, t *= 0.5) {
    if (value<kAll>(y + t * p, d2) <= f0 + 1e-4 * t * slope + slack) {
      y += t * p;
      assemble<kAll>(y, d2, S);
      return true;
    }
  }
  return false;
}

template <bool kLoaded>
Eigen::Vector3d Solver<kLoaded>::smoothing_step(const Sums& S) const {
  Eigen::Matrix3d H = S.H;
  dual_.add_null_space(H, H.trace());
  detail::Psd3 solver;
  if (!solver.factorize_definite(H, 0.0)) {
    solver.factorize(H);
  }
  return -solver.solve(S.g);
}

template <bool kLoaded>
double Solver<kLoaded>::path_bound(const Eigen::Vector3d& y, const Sums& S, double delta) const {
  const double d2 = delta * delta;
  const double value = S.f - d2 * S.inv_rho - y.dot(S.g);
  const double lmax = std::sqrt(std::max(1.0 - d2 / (S.rho_max * S.rho_max), 0.0));
  const double dissipated = dissipation(S.f, y);  // Σ ρ_k ≥ D(y)
  const double lower = std::max(dissipated - cs_.active * delta, 0.0);
  const double gap = bound(S.f, value, lmax, S.g, y);
  const double denom = std::max(dissipated, D0_);
  return gap * denom / std::max(std::max(lower, D0_), kEps * denom);
}

template <bool kLoaded>
double Solver<kLoaded>::polish_bound(const Eigen::Vector3d& y, const Sums& S,
                                     const Eigen::Vector3d& p, int dim, int n_static, Dual& dual) {
  const Eigen::Vector3d gp = S.g + S.H * p;
  const double dec = p.dot(S.H * p);
  double lmax = S.r2_min < kInf ? std::sqrt(1.0 + std::max(dec, 0.0) / std::sqrt(S.r2_min)) : 1.0;
  StaticDual st;
  if (n_static > 0 && dim > 0) {
    st = static_duals(y, gp);
    lmax = std::max(lmax, st.lmax);
  }
  dual = Dual{false, 0.0, p, gp + st.force};
  return bound(S.f + st.primal, S.f - gp.dot(y) + st.value, lmax, dual.h, y);
}

template <bool kLoaded>
StaticDual Solver<kLoaded>::static_duals(const Eigen::Vector3d& y, const Eigen::Vector3d& gp) {
  // Scalar sums read off the rows, as in polish().
  const contact::CoulombScratch& R = frame_.coulomb;
  const double share = 1.0 / c_static_;
  double lmax2 = 0.0;
  double value = 0.0;
  double primal = 0.0;
  double f0 = 0.0;
  double f1 = 0.0;
  double f2 = 0.0;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) != kStatic) {
      continue;
    }
    const double b0 = R.B(0, k), b1 = R.B(1, k), b2 = R.B(2, k);
    const double b3 = R.B(3, k), b4 = R.B(4, k), b5 = R.B(5, k);
    const double d0 = R.d(0, k), d1 = R.d(1, k);
    // B_k,xy = c_k W_k is symmetric positive definite (W_k ⪰ I): λ = −B_k,xy⁻¹ (c_k/Σ_S c) g'_xy
    // by its closed-form inverse (one division), on the path of every polish step.
    const double a = -weight(k) * share / (b0 * b3 - b2 * b1);
    const double g0 = a * gp(0);
    const double g1 = a * gp(1);
    const double l0 = b3 * g0 - b2 * g1;
    const double l1 = b0 * g1 - b1 * g0;
    frame_.work_2n(0, k) = l0;
    frame_.work_2n(1, k) = l1;
    lmax2 = std::max(lmax2, l0 * l0 + l1 * l1);
    value += l0 * d0 + l1 * d1;
    f0 += b0 * l0 + b1 * l1;
    f1 += b2 * l0 + b3 * l1;
    f2 += b4 * l0 + b5 * l1;
    const double r0 = b0 * y(0) + b2 * y(1) + b4 * y(2) + d0;
    const double r1 = b1 * y(0) + b3 * y(1) + b5 * y(2) + d1;
    primal += std::sqrt(r0 * r0 + r1 * r1);
  }
  StaticDual st;
  st.lmax = std::sqrt(lmax2);
  st.value = value;
  st.primal = primal;
  st.force << f0, f1, f2;
  return st;
}

template <bool kLoaded>
void Solver<kLoaded>::zero_static_duals() {
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kStatic) {
      frame_.work_2n.col(k).setZero();
    }
  }
}

template <bool kLoaded>
bool Solver<kLoaded>::find_anchor(Eigen::Vector3d y) {
  auto& s = frame_.friction;
  const Eigen::Vector3d start = y;
  const int n = std::max(cs_.active, 1);
  const double delta = std::max(dissipation(value<true>(y, 0.0), y) / n, kEps * D0_);
  if (!(delta > 0.0)) {
    return false;
  }
  const double d2 = delta * delta;
  Sums S;
  assemble<true>(y, d2, S);
  for (int it = 0; it < 100 && s.iterations < options_.max_iterations; ++it) {
    const Eigen::Vector3d p = smoothing_step(S);
    const double slope = S.g.dot(p);
    // The correction's size² is about the decrement over δ (M₂ ≈ δ H where the feet slide
    // slowly against δ): converged once that is ~1e-16, a step after the decrement falls below it.
    if (!(-slope > 1e-16 * delta) || !line_search<true>(y, p, slope, d2, 60, 0.0, S)) {
      break;
    }
    ++s.iterations;
    if (ran_away(y)) {
      return false;
    }
    if ((y - start).norm() > 10.0 * V_) {  // far out: does the way it went prove sliding?
      moved_downhill(start, y);
      if (sliding_ < 0.0) {
        return false;
      }
    }
  }
  adopt_interior(y, S, delta);
  if (anchor_.rho < 1.0) {
    return true;
  }
  // No minimizer within reach: past the holding limit Φ_δ runs away along a direction of descent
  // slowly when the limit is near (too slowly for the runaway test); the way it went proves it.
  moved_downhill(start, y);
  return false;
}

template <bool kLoaded>
void Solver<kLoaded>::moved_downhill(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  for (const Eigen::Vector3d& e : {Eigen::Vector3d(to - from), to}) {
    const double n = e.norm();
    if (n > 0.0 && std::isfinite(n)) {
      sliding_ = std::min(sliding_, recession(e / n));
    }
  }
}

template <bool kLoaded>
void Solver<kLoaded>::adopt_interior(const Eigen::Vector3d& y, const Sums& S, double delta) {
  // λ_k = r_k/ρ_k is balanced up to S.g (Φ_δ's gradient); M₂'s correction balances it exactly.
  const Eigen::Vector3d mu = dual_.solve(S.g);
  const double d2 = delta * delta;
  double rho2 = 0.0;
  double value = 0.0;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    const Eigen::Vector2d r = residual(k, y);
    const Eigen::Vector2d lam = r / std::sqrt(r.squaredNorm() + d2) - B(k) * mu;
    rho2 = std::max(rho2, lam.squaredNorm());
    value += lam.dot(d(k));
  }
  const double rho = std::sqrt(rho2);
  if (rho < anchor_.rho) {
    anchor_ = Interior{true, y, d2, mu, rho, value};
  }
}

// ---- the active set ---------------------------------------------------------------------------
template <bool kLoaded>
int Solver<kLoaded>::classify(double threshold) {
  const double t2 = threshold * threshold;
  int n = 0;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    const bool st = slip2(k) <= t2;
    set_state(k, st ? kStatic : kSlip);
    n += st ? 1 : 0;
  }
  return n;
}

template <bool kLoaded>
bool Solver<kLoaded>::try_polish(Eigen::Vector3d& y, double threshold, double delta, Dual& dual) {
  const double t2 = threshold * threshold;
  // Classify, and find the three slowest sliding feet: k1, k2 with ‖r‖² = r1 ≤ r2 ≤ r3.
  int k1 = -1;
  int k2 = -1;
  double r1 = kInf;
  double r2 = kInf;
  double r3 = kInf;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    const double nr = slip2(k);
    set_state(k, nr <= t2 ? kStatic : kSlip);
    if (state(k) == kStatic) {
      continue;
    }
    if (nr < r1) {
      r3 = r2;
      r2 = r1;
      k2 = k1;
      r1 = nr;
      k1 = k;
    } else if (nr < r2) {
      r3 = r2;
      r2 = nr;
      k2 = k;
    } else if (nr < r3) {
      r3 = nr;
    }
  }
  const double apart = 1e3 * delta * 1e3 * delta;
  if (k2 >= 0 && r2 <= 0.01 * r3 && r2 <= apart) {
    set_state(k1, kStatic);  // two feet clearly apart (e.g. a rigid pair: their forces are
    set_state(k2, kStatic);  // not unique, and either may sit on its rim)
  } else if (k1 >= 0 && r1 <= 0.01 * r2 && r1 <= apart) {
    set_state(k1, kStatic);
  }
  return polish(y, delta, dual);
}

template <bool kLoaded>
bool Solver<kLoaded>::polish(Eigen::Vector3d& y, double delta, Dual& dual) {
  auto& s = frame_.friction;
  // ---- where the static feet do not slip: all of R³, a line or a point --------------------
  // The path's dual of the static feet (λ = r/ρ) goes to work_2n as a start for
  // fit_static_forces.
  int n_static = 0;
  int first = -1;
  bool one_point = true;
  // Σ_S B_kᵀB_k (upper triangle 00 01 02 11 12 22) and Σ_S B_kᵀd_k in scalars, read off the
  // rows (small Eigen sums here stall on store forwarding); their xy blocks are Σ_S G and h_S.
  const contact::CoulombScratch& R = frame_.coulomb;
  double ms[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double bs[3] = {0.0, 0.0, 0.0};
  const double apart2 = 1e-12 * cs_.L * cs_.L;  // (1e-6 L)²: distinct static points
  c_static_ = 0.0;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) != kStatic) {
      continue;
    }
    ++n_static;
    if (first < 0) {
      first = k;
    } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).squaredNorm() > apart2) {
      one_point = false;
    }
    if (delta > 0.0) {
      const Eigen::Vector2d r = residual(k, y);
      frame_.work_2n.col(k) = r / std::sqrt(r.squaredNorm() + delta * delta);
    } else {
      frame_.work_2n.col(k).setZero();
    }
    const double b0 = R.B(0, k), b1 = R.B(1, k), b2 = R.B(2, k);
    const double b3 = R.B(3, k), b4 = R.B(4, k), b5 = R.B(5, k);
    const double d0 = R.d(0, k), d1 = R.d(1, k);
    ms[0] += b0 * b0 + b1 * b1;
    ms[1] += b0 * b2 + b1 * b3;
    ms[2] += b0 * b4 + b1 * b5;
    ms[3] += b2 * b2 + b3 * b3;
    ms[4] += b2 * b4 + b3 * b5;
    ms[5] += b4 * b4 + b5 * b5;
    bs[0] += b0 * d0 + b1 * d1;
    bs[1] += b2 * d0 + b3 * d1;
    bs[2] += b4 * d0 + b5 * d1;
    c_static_ += weight(k);
  }
  Eigen::Matrix3d MS;
  MS << ms[0], ms[1], ms[2], ms[1], ms[3], ms[4], ms[2], ms[4], ms[5];
  const Eigen::Vector3d bS(bs[0], bs[1], bs[2]);
  int dim = 3;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  detail::Psd3 static_solver;
  if (n_static > 0 && one_point) {
    // v = −q̇_S − ω̃ s̃_p: the static feet's common point p stays put; ω̃ is free. s̃_p is the
    // lever of the first static foot: B_xy⁻¹ B_ω.
    dim = 1;
    const Mat23 Bf = B(first);
    const Eigen::Vector2d sp = Bf.leftCols<2>().inverse() * Eigen::Vector2d(Bf.col(2));
    y.head<2>() = -(MS.topLeftCorner<2, 2>().inverse() * bS.head<2>()) - y(2) * sp;
    e = Eigen::Vector3d(-sp(0), -sp(1), 1.0).normalized();
  } else if (n_static > 0) {
    // Two or more distinct static points fix y; feet that then do not slip either (a rigid
    // gait) join the static set, for the dual below.
    dim = 0;
    static_solver.factorize(MS);
    y = -static_solver.solve(bS);
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kSlip && residual(k, y).norm() <= 1e-12 * D0_) {
        set_state(k, kStatic);
        frame_.work_2n.col(k).setZero();
        ++n_static;
        MS += B(k).transpose() * B(k);
      }
    }
    static_solver.factorize(MS);
  }
  Sums S;
  assemble<false>(y, 0.0, S);
  if (!(S.r2_min > 1e-28 * D0_ * D0_)) {
    return false;  // a sliding foot is at rest: the static set is wrong
  }
  if (dim == 0) {
    return fixed_point_dual(y, S, static_solver, n_static, dual);
  }

  // ---- exact Newton on the sliding feet's D over that set (quadratic, or give up) ---------
  // Armijo steps; the attempt is given up as soon as a step after the first needs damping
  // below 1/2 or the decrement does not fall 4× per step. Each point is first checked with
  // the dual of its Newton step, then (when the step is tiny) with the plain directions.
  double prev = kInf;
  for (int it = 0;; ++it) {
    Eigen::Vector3d p;
    double decrement;
    if (dim == 3) {
      detail::Psd3 solver;
      solver.factorize(S.H);
      p = -solver.solve(S.g);
      decrement = -S.g.dot(p);
    } else {
      // e is felt by no sliding foot (e.g. all at the static point): nothing to do.
      const double ge = S.g.dot(e);
      const double he = e.dot(S.H * e);
      const bool felt = he > detail::kRankTol * S.H.trace();
      p = felt ? Eigen::Vector3d(-(ge / he) * e) : Eigen::Vector3d::Zero();
      decrement = felt ? ge * ge / he : 0.0;
    }
    // Certified only once the decrement is tiny (then finish()'s Newton point y + p is exact
    // to ~1e-13, see kink_newton); near a sliding foot at rest the linearized dual is loose,
    // the plain directions n_k (p = 0) are not.
    if (!(decrement > 1e-3 * options_.tol * std::max(dissipation(S.f, y), D0_))) {
      return polish_bound(y, S, p, dim, n_static, dual) <= options_.tol ||
             polish_bound(y, S, Eigen::Vector3d::Zero(), dim, n_static, dual) <= options_.tol;
    }
    if ((it >= 2 && decrement > 0.25 * prev) || it >= 8 ||
        s.iterations >= options_.max_iterations) {
      return false;  // not converging quadratically: a kink nearby, wrong static set
    }
    prev = decrement;
    ++s.iterations;
    if (!line_search<false>(y, p, -decrement, 0.0, it == 0 ? 30 : 2, it == 0 ? 0.0 : 0.5, S) ||
        !(S.r2_min > 1e-28 * D0_ * D0_)) {
      return false;  // damping needed after the first step: a kink nearby
    }
  }
}

template <bool kLoaded>
bool Solver<kLoaded>::fixed_point_dual(const Eigen::Vector3d& y, const Sums& S,
                                       const detail::Psd3& static_solver, int n_static,
                                       Dual& dual) {
  if (n_static > 2) {
    fit_static_forces(static_solver, S.g, n_static);
  } else {
    const Eigen::Vector3d mu = -static_solver.solve(S.g);
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        frame_.work_2n.col(k) = B(k) * mu;
      }
    }
    fit_static_forces(static_solver, S.g, n_static);
  }
  StaticDual st;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kStatic) {
      const Eigen::Vector2d lam = frame_.work_2n.col(k);
      st.lmax = std::max(st.lmax, lam.norm());
      st.value += lam.dot(d(k));
      st.force += B(k).transpose() * lam;
      st.primal += residual(k, y).norm();
    }
  }
  dual = Dual{false, 0.0, Eigen::Vector3d::Zero(), S.g + st.force};
  return bound(S.f + st.primal, S.f - S.g.dot(y) + st.value, std::max(1.0, st.lmax), dual.h, y) <=
         options_.tol;
}

template <bool kLoaded>
void Solver<kLoaded>::fit_static_forces(const detail::Psd3& static_solver, const Eigen::Vector3d& g,
                                        int n_static) {
  auto lam = [this](int k) { return frame_.work_2n.col(k); };
  double worst = 0.0;
  int a = -1;
  int b = -1;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kStatic) {
      worst = std::max(worst, lam(k).squaredNorm());
      (a < 0 ? a : b) = k;
    }
  }
  if (n_static == 2 && worst <= 1.0) {
    return;
  }
  worst = 2.0;  // several feet: always enforce the balance first
  if (n_static == 2) {
    // λ_a + t z_a, λ_b + t z_b with c_a W_a z_a = dq = −c_b W_b z_b, dq ∥ q_a − q_b.
    const Eigen::Vector2d dq = frame_.q.col(a).head<2>() - frame_.q.col(b).head<2>();
    const Eigen::Vector2d za = B(a).template leftCols<2>().partialPivLu().solve(dq);
    const Eigen::Vector2d zb = -B(b).template leftCols<2>().partialPivLu().solve(dq);
    double lo = -kInf;
    double hi = kInf;
    for (const auto& [k, z] : {std::pair{a, za}, std::pair{b, zb}}) {
      const Eigen::Vector2d l0 = lam(k);
      const double A = z.squaredNorm();
      const double Bz = l0.dot(z);
      const double disc = Bz * Bz - A * (l0.squaredNorm() - 1.0);
      if (!(A > 0.0) || disc < 0.0) {
        return;  // this disk cannot be reached: no feasible choice, the certificate will say
      }
      const double root = std::sqrt(disc);
      lo = std::max(lo, (-Bz - root) / A);
      hi = std::min(hi, (-Bz + root) / A);
    }
    if (lo <= hi) {
      const double t = std::clamp(0.0, lo, hi);
      lam(a) += t * za;
      lam(b) += t * zb;
    }
    return;
  }
  for (int it = 0; it < 200 && worst > 1.0; ++it) {
    // Project onto the disks (not before the first balance), then back onto the balance
    // Σ_S B_kᵀλ_k = −g (least-norm correction).
    Eigen::Vector3d imbalance = g;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        const double n2 = lam(k).squaredNorm();
        if (n2 > 1.0 && it > 0) {
          lam(k) /= std::sqrt(n2);
        }
        imbalance += B(k).transpose() * lam(k);
      }
    }
    const Eigen::Vector3d mu = static_solver.solve(imbalance);
    worst = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        lam(k) -= B(k) * mu;
        worst = std::max(worst, lam(k).squaredNorm());
      }
    }
    worst = worst > 1.0 + 1e-14 ? worst : 0.0;
  }
}

// The members coulomb.cpp calls (which instantiates the class itself); the rest follow from them.
template void Solver<false>::path(Eigen::Vector3d, Sums&, double);
template void Solver<true>::path(Eigen::Vector3d, Sums&, double);
template bool Solver<false>::polish(Eigen::Vector3d&, double, Dual&);
template bool Solver<true>::polish(Eigen::Vector3d&, double, Dual&);
template int Solver<false>::classify(double);
template int Solver<true>::classify(double);
template void Solver<false>::zero_static_duals();
template void Solver<true>::zero_static_duals();
template bool Solver<true>::find_anchor(Eigen::Vector3d);

}  // namespace slipwalk::friction::coulomb
