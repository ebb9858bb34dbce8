// Classical Coulomb friction (eq. 3.13) as a convex program, with a certificate.
//
// Problem. With r_k(y) = c_k W_k u_k(y) (c_k = μ_k F_z,k, W_k = (I + w_k w_kᵀ)^{1/2}, scaled
// coordinates of friction/balance.hpp) the balance of F_k = −c_k W_k r_k/‖r_k‖ is the optimality
// condition of the dissipation
//   D(y) = Σ_k ‖r_k(y)‖ = Σ_k μ_k F_z,k ‖W_k u_k‖      (a sum of Euclidean norms; convex).
// Anisotropy: the friction force set of foot k is the ellipse {F : Fᵀ G_k⁻¹ F ≤ c_k²} (semi-axis
// c_k √(1 + ‖w_k‖²) along w_k, c_k across: eq. 3.19's ellipse), whose support function is
// c_k ‖W_k u‖; maximum dissipation then gives F_k = −c_k G_k u_k/‖W_k u_k‖, the viscous force
// −c_k G_k u_k rescaled, so eq. 3.14's family joins the two laws for any w.
//
// Dual. ‖r‖ = max_{‖λ‖≤1} λᵀr gives  max Σ_k λ_kᵀ d_k  over  ‖λ_k‖ ≤ 1, Σ_k B_kᵀ λ_k = 0
// (B_k = c_k W_k J̃_k, d_k = c_k W_k q̇_k): with F_k = −c_k W_k λ_k this is "maximize Σ F_k·(−q̇_k)
// over balanced forces in the friction ellipses". Any such λ bounds D from below; the relative
// gap (D(y) − Σ λ_kᵀ d_k) / max(D(y), D(0)) is the certificate.
//
// Algorithm (always terminates: every loop is bounded by options.max_iterations).
//  1. Start at the viscous-Coulomb solution (if nothing slips there, certify that at once).
//  2. Smoothing path: damped Newton steps (Armijo) on D_δ(y) = Σ √(‖r_k‖² + δ²) (smooth,
//     convex, its Hessian regularized only along directions no foot feels); a stage ends when
//     the Newton decrement falls below 3δ (or after 8 steps), and δ is then divided by 10, from
//     δ₀ = 0.1 D(start)/N down to δ_min = 0.1 tol D/N, where the smoothing error alone is within
//     the tolerance. Near δ_min the path's own dual λ_k = r_k/√(‖r_k‖² + δ²) is certified too.
//  3. Polish at the end of each stage (active set): feet with ‖r_k‖ ≤ min(10 δ, 0.01 D/N) are
//     static, and so is the slowest other foot if it is clearly apart (‖r‖ ≤ 0.1 × the next
//     and ≤ 10³ δ: a static foot whose force lies near the rim of its disk keeps
//     ‖r‖ = δ t/√(1 − t²) on the path). The body velocity is restricted to where the static feet
//     do not slip — a point if they span two distinct points, the rotations about their common
//     point if one, all of R³ if none — and the exact D of the sliding feet is minimized there
//     by Newton's method, which is smooth and converges quadratically if the static set is right
//     (the attempt is abandoned as soon as it does not: a step cut below 1/2, or a decrement
//     not falling 4× per step). The static feet's dual forces are the least-norm ones that
//     balance the sliding feet (for static feet at distinct points, whose internal force is
//     free, a balancing choice inside the disks: fit_static_forces). A right static set
//     certifies to ~1e-15 in 1–3 steps.
//  4. Certificate: the dual candidate is made exactly balanced by the least-norm correction
//     λ_k −= B_k (Σ B_jᵀB_j)⁺ Σ B_jᵀλ_j and scaled into the disks; its gap is then a true bound
//     (up to rounding) whatever the quality of y. Converged ⇔ gap ≤ tol.
// Cost: O(N) per step, 5–9 steps on random frames (more static feet → more steps): about 10×
// the viscous-Coulomb solve, see tests/bench/bench_friction.cpp.
//
// Non-uniqueness. At an optimum with dual λ, a direction e keeps y optimal iff B_k e ∥ λ_k for
// sliding feet and for static feet on the disk's rim (with λ_kᵀ B_k e ≥ 0 there: the foot starts
// sliding along its force) and B_k e = 0 for static feet inside their disk. The first two are
// linear: e must lie in the null space of Q = Σ B_kᵀ P_k B_k (P_k the projector across λ_k, or I).
// A null vector of Q (eigenvalue ≤ 1e-10 trace) that passes the sign test means a flat
// direction of D at the optimum: a continuum of minimizers (the even-N 1-D example of §3.1.2).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/csv.hpp"
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kSlip = 0;
constexpr int kStatic = 1;
constexpr int kInactive = -1;
constexpr double kDelta0 = 0.1;  // δ₀ = kDelta0 · D(viscous)/N
constexpr double kSigma = 0.1;   // δ ← kSigma δ at the end of a stage
constexpr double kKappa = 10.0;  // static: ‖r_k‖ ≤ kKappa δ

template <bool kAniso>
class CoulombSolver {
 public:
  CoulombSolver(const contact::Robot& robot, contact::Frame& frame, const detail::Contacts& cs,
                const CoulombOptions& options)
      : robot_(robot), frame_(frame), cs_(cs), options_(options), metric_{robot, frame} {}

  void run() {
    auto& s = frame_.friction;
    s.iterations = 0;
    s.message.clear();

    // ---- constants: Σ B_kᵀB_k (dual projection, degeneracy), D(0), the viscous start --------
    Eigen::Matrix3d M1;
    Eigen::Vector3d b1;
    detail::viscous_system<kAniso>(robot_, frame_, cs_.inv_L, M1, b1);
    detail::Psd3 viscous;
    viscous.factorize(M1);
    Eigen::Vector3d y = -viscous.solve(b1);
    Eigen::Matrix3d M2 = Eigen::Matrix3d::Zero();
    D0_ = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      state(k) = c > 0.0 ? kSlip : kInactive;
      frame_.Fxy.col(k).setZero();
      if (c == 0.0) {
        continue;
      }
      detail::add_jt_p_j(M2, lever(k), c * c * metric_.G(k));
      D0_ += c * metric_.W(k, qdot(k)).norm();
    }
    dual_.factorize(M2);

    // ---- trivial cases: no friction, nothing moves, or the viscous start slips nowhere -------
    const int n = std::max(cs_.active, 1);
    double D = dissipation(y);
    const double Dref = std::max(D, D0_);
    double cert = 1.0;
    bool done = false;
    if (cs_.active == 0 || Dref == 0.0) {
      cert = 0.0;  // y = 0 (the viscous least-norm answer) is exact, forces zero
      classify(0.0);
      done = true;
    } else if (D <= 1e-12 * Dref) {
      classify(1e-9 * Dref / n);
      Eigen::Vector3d yp = y;
      if (polish(yp, 0.0, cert)) {
        y = yp;
        done = true;
      } else {
        dissipation(y);
      }
    }

    // ---- the smoothing path, with polish attempts at the end of each stage --------------------
    const double delta_min = std::max(0.1 * options_.tol * Dref / n, 64.0 * kEps * Dref / n);
    double delta = std::max(kDelta0 * D / n, delta_min);
    while (!done && s.iterations < options_.max_iterations) {
      const double decrement = smoothed_step(y, delta);  // leaves r(y) in work_2n
      ++s.iterations;
      if (decrement > 3.0 * delta && s.iterations % 8 != 0 && delta > delta_min) {
        continue;  // stay on this stage of the path
      }
      if (delta <= 1e3 * delta_min) {
        // The smoothing path's own dual λ_k = r_k/√(‖r_k‖² + δ²): its gap is O(N δ / D), so
        // it is only worth checking near the end of the path.
        smoothing_dual(delta);
        cert = certificate();
        if (cert <= options_.tol) {
          classify(kKappa * delta);
          done = true;
          break;
        }
      }
      if (try_polish(y, std::min(kKappa * delta, 1e-2 * Dref / n), delta, cert)) {
        done = true;
        break;
      }
      delta = std::max(kSigma * delta, delta_min);
    }
    if (!done) {
      // Out of iterations: the last point of the path with its own certificate.
      dissipation(y);
      smoothing_dual(delta);
      cert = certificate();
      classify(kKappa * delta);
    }
    finish(y, cert);
  }

 private:
  // ---- per-foot pieces (s̃ = the lever of foot k, c = μ F_z) ----------------------------------
  [[nodiscard]] double weight(int k) const { return detail::friction_weight(robot_, frame_, k); }
  [[nodiscard]] Eigen::Vector2d lever(int k) const { return detail::lever(frame_, k, cs_.inv_L); }
  [[nodiscard]] Eigen::Vector2d qdot(int k) const { return frame_.qdot.col(k).head<2>(); }
  [[nodiscard]] int& state(int k) { return frame_.work_idx[static_cast<std::size_t>(k)]; }
  [[nodiscard]] int state(int k) const { return frame_.work_idx[static_cast<std::size_t>(k)]; }
  /// r_k(y) = c W u.
  [[nodiscard]] Eigen::Vector2d residual(int k, double c, const Eigen::Vector2d& sl,
                                         const Eigen::Vector3d& y) const {
    return c * metric_.W(k, detail::slip(frame_, k, sl, y));
  }
  /// B_kᵀ a = c J̃ᵀ W a.
  [[nodiscard]] Eigen::Vector3d bt(int k, double c, const Eigen::Vector2d& sl,
                                   const Eigen::Vector2d& a) const {
    return detail::jt(sl, c * metric_.W(k, a));
  }
  /// B_k z = c W J̃ z.
  [[nodiscard]] Eigen::Vector2d bz(int k, double c, const Eigen::Vector2d& sl,
                                   const Eigen::Vector3d& z) const {
    return c * metric_.W(k, Eigen::Vector2d(z(0) + z(2) * sl(0), z(1) + z(2) * sl(1)));
  }
  /// M += B_kᵀ P B_k = c² J̃ᵀ W P W J̃ (pass c = √w to add w J̃ᵀ W P W J̃ instead).
  void add_btpb(Eigen::Matrix3d& M, int k, double c, const Eigen::Vector2d& sl,
                const Eigen::Matrix2d& P) const {
    if constexpr (kAniso) {
      const Eigen::Matrix2d W = metric_.W(k);
      detail::add_jt_p_j(M, sl, c * c * (W * P * W));
    } else {
      (void)k;
      detail::add_jt_p_j(M, sl, c * c * P);
    }
  }

  /// D(y) = D_δ(y) at δ = 0; leaves r_k(y) in work_2n.
  double dissipation(const Eigen::Vector3d& y) { return smoothed(y, 0.0); }

  /// D_δ(y) = Σ √(‖r_k‖² + δ²); leaves r_k(y) in work_2n.
  double smoothed(const Eigen::Vector3d& y, double d2) {
    double f = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d r = residual(k, c, lever(k), y);
      frame_.work_2n.col(k) = r;
      f += std::sqrt(r.squaredNorm() + d2);
    }
    return f;
  }

  /// One damped Newton step on D_δ; returns the Newton decrement −∇D_δᵀ p (0 if no step was
  /// taken) and leaves r_k(y) of the new y in work_2n.
  double smoothed_step(Eigen::Vector3d& y, double delta) {
    const double d2 = delta * delta;
    double f = 0.0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d sl = lever(k);
      const Eigen::Vector2d r = residual(k, c, sl, y);
      const double rho2 = r.squaredNorm() + d2;
      const double rho = std::sqrt(rho2);
      f += rho;
      g += bt(k, c, sl, r / rho);
      // ∇²√(‖r‖² + δ²) = (δ² I + r⊥ r⊥ᵀ)/ρ³.
      Eigen::Matrix2d P;
      P << r(1) * r(1) + d2, -r(0) * r(1), -r(0) * r(1), r(0) * r(0) + d2;
      add_btpb(H, k, c, sl, P / (rho2 * rho));
    }
    // H is positive definite on the range of Σ B_kᵀB_k (whatever δ: no rank threshold here, the
    // directions of a foot near rest are legitimately stiff); its null space (contacts at one
    // point) is filled in so that the step has no component there.
    dual_.add_null_space(H, H.trace());
    detail::Psd3 solver;
    if (!solver.factorize_definite(H, 0.0)) {
      solver.factorize(H);
    }
    const Eigen::Vector3d p = -solver.solve(g);
    const double slope = g.dot(p);
    if (slope < 0.0) {
      const double slack = 8.0 * kEps * f;
      double t = 1.0;
      for (int j = 0; j < 60; ++j, t *= 0.5) {
        const Eigen::Vector3d trial = y + t * p;
        if (smoothed(trial, d2) <= f + 1e-4 * t * slope + slack) {
          y = trial;
          return -slope;
        }
      }
    }
    dissipation(y);
    return 0.0;
  }

  /// λ_k = r_k/√(‖r_k‖² + δ²) into Fxy from r_k in work_2n.
  void smoothing_dual(double delta) {
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kInactive) {
        const Eigen::Vector2d r = frame_.work_2n.col(k);
        frame_.Fxy.col(k) = r / std::sqrt(r.squaredNorm() + delta * delta);
      }
    }
  }

  /// Marks feet with ‖r_k‖ ≤ threshold static (work_idx); returns how many.
  int classify(double threshold) {
    int n = 0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kInactive) {
        continue;
      }
      const bool st = frame_.work_2n.col(k).norm() <= threshold;
      state(k) = st ? kStatic : kSlip;
      n += st ? 1 : 0;
    }
    return n;
  }

  /// Makes the dual candidate λ in Fxy exactly balanced (least-norm correction) and feasible
  /// (scaled into the unit disks), and returns its relative gap against D(y) = Σ ‖r_k‖ with
  /// r_k(y) in work_2n.
  double certificate() {
    Eigen::Vector3d imbalance = Eigen::Vector3d::Zero();
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c != 0.0) {
        imbalance += bt(k, c, lever(k), frame_.Fxy.col(k));
      }
    }
    const Eigen::Vector3d mu = dual_.solve(imbalance);
    double lmax2 = 0.0;
    double primal = 0.0;
    double dual = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d lam = frame_.Fxy.col(k) - bz(k, c, lever(k), mu);
      frame_.Fxy.col(k) = lam;
      lmax2 = std::max(lmax2, lam.squaredNorm());
      primal += frame_.work_2n.col(k).norm();
      dual += lam.dot(c * metric_.W(k, qdot(k)));
    }
    if (lmax2 > 1.0) {
      const double shrink = 1.0 / std::sqrt(lmax2);
      frame_.Fxy *= shrink;
      dual *= shrink;
    }
    const double denom = std::max(primal, D0_);
    return denom > 0.0 ? std::max(primal - dual, 0.0) / denom : 0.0;
  }

  /// A polish attempt at the end of a smoothing stage (r_k(y) in work_2n): the feet with
  /// ‖r_k‖ ≤ threshold are static, and the slowest other foot too if it is clearly apart (step 3
  /// of the header).
  bool try_polish(Eigen::Vector3d& y, double threshold, double delta, double& cert) {
    classify(threshold);
    // The three slowest sliding feet: k1, k2 with ‖r‖ = r1 ≤ r2 ≤ r3.
    int k1 = -1;
    int k2 = -1;
    double r1 = std::numeric_limits<double>::infinity();
    double r2 = r1;
    double r3 = r1;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kSlip) {
        continue;
      }
      const double nr = frame_.work_2n.col(k).norm();
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
    if (k2 >= 0 && r2 <= 0.1 * r3 && r2 <= 1e3 * delta) {
      state(k1) = kStatic;  // two feet clearly apart (e.g. a rigid pair: their forces are
      state(k2) = kStatic;  // not unique, and either may sit on its rim)
    } else if (k1 >= 0 && r1 <= 0.1 * r2 && r1 <= 1e3 * delta) {
      state(k1) = kStatic;
    }
    Eigen::Vector3d yp = y;
    if (polish(yp, delta, cert)) {
      y = yp;
      return true;
    }
    return false;  // work_2n and Fxy now hold the failed attempt's r and λ
  }

  /// Active-set polish from y (a point of the smoothing path at δ, r_k(y) in work_2n) with the
  /// static feet marked in work_idx. On success (relative gap ≤ tol) y, Fxy (dual), work_2n (r)
  /// hold the certified solution.
  bool polish(Eigen::Vector3d& y, double delta, double& cert) {
    auto& s = frame_.friction;
    // The path's dual of the static feet, kept in Fxy as a start for fit_static_forces.
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        const Eigen::Vector2d r = frame_.work_2n.col(k);
        const double rho = std::sqrt(r.squaredNorm() + delta * delta);
        frame_.Fxy.col(k) = delta > 0.0 ? Eigen::Vector2d(r / rho) : Eigen::Vector2d::Zero();
      }
    }
    // ---- where the static feet do not slip: all of R³, a line or a point --------------------
    int n_static = 0;
    int first = -1;
    bool one_point = true;
    Eigen::Matrix3d MS = Eigen::Matrix3d::Zero();
    Eigen::Vector3d bS = Eigen::Vector3d::Zero();
    Eigen::Matrix2d GS = Eigen::Matrix2d::Zero();
    Eigen::Vector2d hS = Eigen::Vector2d::Zero();
    double cS = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kStatic) {
        continue;
      }
      ++n_static;
      if (first < 0) {
        first = k;
      } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).norm() >
                 1e-6 * cs_.L) {
        one_point = false;
      }
      const double c = weight(k);
      const Eigen::Matrix2d G = metric_.G(k);
      detail::add_jt_p_j(MS, lever(k), c * c * G);
      bS += detail::jt(lever(k), c * c * (G * qdot(k)));
      GS += c * c * G;
      hS += c * c * (G * qdot(k));
      cS += c;
    }
    int dim = 3;
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    detail::Psd3 static_solver;
    if (n_static > 0 && one_point) {
      // v = −q̇_S − ω̃ s̃_p: the static feet's common point p stays put; ω̃ is free.
      dim = 1;
      const Eigen::Vector2d sp = lever(first);
      y.head<2>() = -(GS.inverse() * hS) - y(2) * sp;
      e = Eigen::Vector3d(-sp(0), -sp(1), 1.0).normalized();
    } else if (n_static > 0) {
      // Two or more distinct static points fix y; feet that then do not slip either (a rigid
      // gait) join the static set, for the dual below.
      dim = 0;
      static_solver.factorize(MS);
      y = -static_solver.solve(bS);
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kSlip) {
          continue;
        }
        const double c = weight(k);
        if (residual(k, c, lever(k), y).norm() <= 1e-12 * D0_) {
          state(k) = kStatic;
          ++n_static;
          const Eigen::Matrix2d G = metric_.G(k);
          detail::add_jt_p_j(MS, lever(k), c * c * G);
        }
      }
      static_solver.factorize(MS);
    }

    // ---- exact Newton on the sliding feet's D over that set (quadratic, or give up) ---------
    // Armijo steps; the attempt is given up as soon as a step after the first needs damping
    // below 1/2 or the decrement does not fall 4× per step.
    double prev = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 8 && dim > 0 && s.iterations < options_.max_iterations; ++it) {
      ++s.iterations;
      double f = 0.0;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
      double ge = 0.0;  // dim 1: eᵀ∇D and eᵀ∇²D e, and the size of the latter's terms
      double he = 0.0;
      double he_scale = 0.0;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kSlip) {
          continue;
        }
        const double c = weight(k);
        const Eigen::Vector2d sl = lever(k);
        const Eigen::Vector2d r = residual(k, c, sl, y);
        const double nr = r.norm();
        if (!(nr > 1e-14 * D0_)) {
          return false;  // a sliding foot came to rest: the static set is wrong
        }
        f += nr;
        const Eigen::Vector2d n = r / nr;
        if (dim == 1) {
          const Eigen::Vector2d b = bz(k, c, sl, e);
          const double across = n(0) * b(1) - n(1) * b(0);
          ge += n.dot(b);
          he += across * across / nr;
          he_scale += c * c * (1.0 + sl.squaredNorm()) / nr;
        } else {
          g += bt(k, c, sl, n);
          Eigen::Matrix2d P;
          P << n(1) * n(1), -n(0) * n(1), -n(0) * n(1), n(0) * n(0);
          add_btpb(H, k, c, sl, P / nr);
        }
      }
      const double slack = 8.0 * kEps * f;
      Eigen::Vector3d p;
      double decrement;
      if (dim == 3) {
        detail::Psd3 solver;
        solver.factorize(H);
        p = -solver.solve(g);
        decrement = -g.dot(p);
      } else {
        // e is felt by no sliding foot (e.g. all at the static point): nothing to do.
        const bool felt = he > detail::kRankTol * he_scale;
        p = felt ? Eigen::Vector3d(-(ge / he) * e) : Eigen::Vector3d::Zero();
        decrement = felt ? ge * ge / he : 0.0;
      }
      if (!(decrement > 1e-3 * options_.tol * std::max(f, D0_))) {
        if (decrement > 0.0) {
          y += p;  // the last, tiny, full step
        }
        break;
      }
      if (it >= 2 && decrement > 0.25 * prev) {
        return false;  // not converging quadratically: a kink nearby, wrong static set
      }
      prev = decrement;
      double t = 1.0;
      bool accepted = false;
      for (int j = 0; j < 30; ++j, t *= 0.5) {
        if (sliding(y + t * p) <= f - 1e-4 * t * decrement + slack) {
          accepted = true;
          break;
        }
      }
      if (!accepted || (it >= 1 && t < 0.5)) {
        return false;  // damping needed after the first step: a kink nearby
      }
      y += t * p;
    }

    // ---- dual: unit directions for sliding feet, least-norm balancing forces for static ones -
    Eigen::Vector3d g_slip = Eigen::Vector3d::Zero();
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d sl = lever(k);
      const Eigen::Vector2d r = residual(k, c, sl, y);
      frame_.work_2n.col(k) = r;
      if (state(k) == kSlip) {
        const double nr = r.norm();
        if (!(nr > 0.0)) {
          return false;
        }
        frame_.Fxy.col(k) = r / nr;
        g_slip += bt(k, c, sl, frame_.Fxy.col(k));
      }
    }
    if (n_static > 0 && dim == 0 && n_static > 2) {
      fit_static_forces(static_solver, g_slip, n_static);
    } else if (n_static > 0) {
      const Eigen::Vector3d mu =
          dim == 0 ? Eigen::Vector3d(-static_solver.solve(g_slip)) : Eigen::Vector3d::Zero();
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kStatic) {
          continue;
        }
        if (dim == 0) {
          frame_.Fxy.col(k) = bz(k, weight(k), lever(k), mu);
        } else {
          // Σ_S c_k W_k λ_k = −(g_slip)_xy, shared in proportion to c_k.
          frame_.Fxy.col(k) = metric_.W_inv(k, Eigen::Vector2d(-g_slip.head<2>() / cS));
        }
      }
      if (dim == 0) {
        fit_static_forces(static_solver, g_slip, n_static);
      }
    }
    cert = certificate();
    return cert <= options_.tol;
  }

  /// Static feet at two or more distinct points balance the sliding ones (Σ_S B_kᵀλ_k = −g) with
  /// an undetermined internal force, so a balancing choice inside the disks must be searched.
  /// Two feet (Fxy = the least-norm choice): the internal force is a multiple t of the push
  /// along the line between them, each disk allows an interval of t, and the t nearest 0 in both
  /// is taken. More feet (Fxy = the smoothing path's λ, O(δ) from an optimal dual): alternating
  /// projections between the balance and the disks, at most 200 (rigid gaits only).
  void fit_static_forces(const detail::Psd3& static_solver, const Eigen::Vector3d& g,
                         int n_static) {
    double worst = 0.0;
    int a = -1;
    int b = -1;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        worst = std::max(worst, frame_.Fxy.col(k).squaredNorm());
        (a < 0 ? a : b) = k;
      }
    }
    if (n_static == 2 && worst <= 1.0) {
      return;
    }
    worst = 2.0;  // several feet: always enforce the balance first
    if (n_static == 2) {
      // λ_a + t z_a, λ_b + t z_b with c_a W_a z_a = d = −c_b W_b z_b, d ∥ q_a − q_b.
      const Eigen::Vector2d d = frame_.q.col(a).head<2>() - frame_.q.col(b).head<2>();
      const Eigen::Vector2d za = metric_.W_inv(a, d) / weight(a);
      const Eigen::Vector2d zb = -metric_.W_inv(b, d) / weight(b);
      double lo = -std::numeric_limits<double>::infinity();
      double hi = std::numeric_limits<double>::infinity();
      for (const auto& [k, z] : {std::pair{a, za}, std::pair{b, zb}}) {
        const Eigen::Vector2d l0 = frame_.Fxy.col(k);
        const double A = z.squaredNorm();
        const double B = l0.dot(z);
        const double disc = B * B - A * (l0.squaredNorm() - 1.0);
        if (!(A > 0.0) || disc < 0.0) {
          return;  // this disk cannot be reached: no feasible choice, the certificate will say
        }
        const double root = std::sqrt(disc);
        lo = std::max(lo, (-B - root) / A);
        hi = std::min(hi, (-B + root) / A);
      }
      if (lo <= hi) {
        const double t = std::clamp(0.0, lo, hi);
        frame_.Fxy.col(a) += t * za;
        frame_.Fxy.col(b) += t * zb;
      }
      return;
    }
    for (int it = 0; it < 200 && worst > 1.0; ++it) {
      // Project onto the disks (not before the first balance), then back onto the balance
      // Σ_S B_kᵀλ_k = −g (least-norm correction).
      Eigen::Vector3d imbalance = g;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kStatic) {
          const double n2 = frame_.Fxy.col(k).squaredNorm();
          if (n2 > 1.0 && it > 0) {
            frame_.Fxy.col(k) /= std::sqrt(n2);
          }
          imbalance += bt(k, weight(k), lever(k), frame_.Fxy.col(k));
        }
      }
      const Eigen::Vector3d mu = static_solver.solve(imbalance);
      worst = 0.0;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kStatic) {
          frame_.Fxy.col(k) -= bz(k, weight(k), lever(k), mu);
          worst = std::max(worst, frame_.Fxy.col(k).squaredNorm());
        }
      }
      worst = worst > 1.0 + 1e-14 ? worst : 0.0;
    }
  }

  [[nodiscard]] double sliding(const Eigen::Vector3d& y) const {
    double f = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kSlip) {
        f += residual(k, weight(k), lever(k), y).norm();
      }
    }
    return f;
  }

  /// Whether D has a flat direction at y (see the header comment); needs Fxy = certified dual.
  bool flat_direction() {
    Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d lam = frame_.Fxy.col(k);
      const double nl = lam.norm();
      Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
      if (state(k) == kSlip || nl >= 1.0 - 1e-9) {
        const Eigen::Vector2d n =
            state(k) == kSlip ? Eigen::Vector2d(frame_.work_2n.col(k).normalized()) : lam / nl;
        const Eigen::Vector2d np(-n(1), n(0));
        P = np * np.transpose();
      }
      add_btpb(Q, k, std::sqrt(c), lever(k), P);  // weight c (any positive weight will do)
    }
    const double tr = Q.trace();
    if (!(tr > 0.0)) {
      return true;
    }
    // Quick exit: pivots ≥ 1e-3 tr bound the smallest eigenvalue below by ~1e-9 tr.
    detail::Psd3 quick;
    if (quick.factorize_definite(Q, 1e-3)) {
      return false;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Q);
    for (int i = 0; i < 3; ++i) {
      if (es.eigenvalues()(i) > 1e-10 * tr) {
        continue;
      }
      const Eigen::Vector3d e = es.eigenvectors().col(i);
      // Static feet on the rim must start sliding along their force: λ_kᵀ B_k e of one sign.
      bool plus = true;
      bool minus = true;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kStatic) {
          continue;
        }
        const Eigen::Vector2d lam = frame_.Fxy.col(k);
        if (lam.norm() < 1.0 - 1e-9) {
          continue;
        }
        const Eigen::Vector2d Be = bz(k, weight(k), lever(k), e);
        const double t = lam.dot(Be);
        const double tol = 1e-9 * Be.norm();
        plus = plus && t >= -tol;
        minus = minus && t <= tol;
      }
      if (plus || minus) {
        return true;
      }
    }
    return false;
  }

  void finish(Eigen::Vector3d y, double cert) {
    auto& s = frame_.friction;
    s.certificate = cert;
    s.converged = cert <= options_.tol;
    int n_static = 0;
    bool distinct = false;
    int first = -1;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        ++n_static;
        if (first < 0) {
          first = k;
        } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).norm() >
                   1e-6 * cs_.L) {
          distinct = true;
        }
      }
    }
    s.static_feet = n_static;
    s.unique = cs_.active > 0 && dual_.rank() == 3 && !flat_direction();
    // Least norm along directions no foot feels (contacts at one point), then the body velocity.
    y = dual_.project_to_range(y);
    detail::set_velocity(frame_, y, cs_.L);
    // Forces F_k = −c_k W_k λ_k, dissipation Σ ‖r_k‖ and the balance residual.
    detail::BalanceSum sum;
    double scale = 0.0;
    double dissipation = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = weight(k);
      if (c == 0.0) {
        frame_.Fxy.col(k).setZero();
        continue;
      }
      const Eigen::Vector2d F = -c * metric_.W(k, Eigen::Vector2d(frame_.Fxy.col(k)));
      frame_.Fxy.col(k) = F;
      sum.add(frame_, k, F);
      dissipation += frame_.work_2n.col(k).norm();
      scale += kAniso ? c * std::sqrt(1.0 + robot_.w.col(k).squaredNorm()) : c;
    }
    s.dissipation = dissipation;
    s.residual = sum.residual(scale, cs_.L);
    if (cs_.active == 0) {
      s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
    } else if (!s.converged) {
      s.message = "iteration limit: relative duality gap " + core::format_double(cert) +
                  " above the tolerance " + core::format_double(options_.tol);
    } else if (dual_.rank() < 3) {
      s.message = "all contacts at one point: rotation about it undetermined (least-norm solution)";
    } else if (!s.unique) {
      s.message = "flat minimum of the dissipation: a continuum of body velocities balance";
    } else if (distinct) {
      s.message =
          "static feet at distinct points: their internal force is undetermined (least-norm "
          "forces reported)";
    }
  }

  const contact::Robot& robot_;
  contact::Frame& frame_;
  detail::Contacts cs_;
  CoulombOptions options_;
  detail::Metric<kAniso> metric_;
  detail::Psd3 dual_;
  double D0_ = 0.0;
};

}  // namespace

void solve_coulomb(const contact::Robot& robot, contact::Frame& frame,
                   const CoulombOptions& options) {
  const detail::Contacts cs = detail::prepare(robot, frame);
  if (cs.anisotropic) {
    CoulombSolver<true>(robot, frame, cs, options).run();
  } else {
    CoulombSolver<false>(robot, frame, cs, options).run();
  }
}

}  // namespace slipwalk::friction
