// Coulomb friction with an external planar wrench on the body (solvers.hpp:
// solve_coulomb_loaded), e.g. gravity's component along a slope (thesis §5.2.1).
//
// Problem. In the scaled coordinates of balance.hpp, y = (v_x, v_y, L ω), foot k slides at
// u_k = J̃_k y + q̇_k and the load is f̃ = (F_x, F_y, M_z / L). Balance Σ J̃_kᵀ F_k + f̃ = 0 with
// F_k in foot k's friction ellipse {Fᵀ G_k⁻¹ F ≤ c_k²} (c_k = μ_k F_z,k, G_k = I + w_k w_kᵀ) and
// F_k = −c_k G_k u_k / ‖W_k u_k‖ for a sliding foot is the optimality condition of
//   Φ(y) = Σ_k c_k ‖W_k u_k(y)‖ − f̃ᵀ y,        (‖W u‖² = uᵀ G u)
// i.e. the dissipation minus the power of the load. Its dual: maximize Σ_k −F_k·q̇_k over forces
// in the ellipses that balance the load (‖W u‖ c = max over the ellipse of −F·u, then the
// infimum over y forces Σ J̃ᵀ F + f̃ = 0). Φ is bounded below iff f̃ is a wrench the ellipses can
// hold; its recession function is ρ(d) = Σ c_k ‖W_k J̃_k d‖ − f̃ᵀ d, and a d with ρ(d) < 0 proves
// that no quasi-static balance exists: Φ → −∞ along d, the robot slides.
//
// Method (a reference, not the flat fast path of coulomb.cpp): damped Newton on the smoothing
// Φ_δ(y) = Σ c_k √(‖W_k u_k‖² + δ²) − f̃ᵀ y from the viscous-Coulomb solution with the same load,
// δ divided by 10 per stage from the velocity scale V down to δ_min = 0.1 tol V. Its stationary
// points give balanced forces F_k = −c_k G_k u_k / √(‖W_k u_k‖² + δ²), strictly inside the
// ellipses, whose duality gap Σ c_k ‖W u‖ (1 − ‖W u‖/ρ) is at most ~0.3 δ Σ c_k. Small δ alone
// cannot certify, though: a static foot's force −c G u/ρ is u/δ, and u is known to rounding
// (~1e-17 m/s), so the balance degrades as δ shrinks. Hence a polish at the end of each stage
// from δ = 10⁻³ V on: the feet with ‖W u‖ ≤ 10 δ are taken as static (S), the body velocity is
// fixed where S does not slip (by S itself when it spans two points; the exact Φ minimized over
// the rotations about S's point when it is one point, by 1-D Newton; the exact Φ by Newton when S
// is empty), the sliding feet get their exact Coulomb forces and S the path's forces plus the
// least (c-weighted) correction that balances the load exactly (or, near the rims, a balanced
// point of the ellipses found by alternating projections). If those lie in their ellipses,
// the gap is zero to rounding and the answer is certified; otherwise the path goes on.
// Sliding is detected twice: (1) before any iteration,
// the pure translation along the load, ρ((e, 0)) = Σ c_k ‖W_k e‖ − ‖f_xy‖ < 0 with e = f_xy/‖f_xy‖
// (the load exceeds what all feet together can hold, e.g. tan σ > μ on a slope); (2) when the
// iterate runs away (‖y‖ > 10⁸ V), ρ(y/‖y‖) < 0 is checked (e.g. a moment the contacts cannot
// hold).
#include <algorithm>
#include <cmath>
#include <limits>

#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

namespace {

constexpr double kRunaway = 1e8;  // ‖y‖ > kRunaway V: test the recession direction

/// Φ_δ, its gradient and Hessian at y (δ² = d2; d2 = 0 gives Φ itself, value only).
struct Smoothed {
  const contact::Robot& robot;
  const contact::Frame& frame;
  const Eigen::Vector3d& load;  ///< f̃, scaled
  double inv_L;
  bool skip_static = false;  ///< leave out the feet marked static in frame.work_idx (polish)

  [[nodiscard]] bool skipped(int k) const {
    return skip_static && frame.work_idx[static_cast<std::size_t>(k)] != 0;
  }

  [[nodiscard]] Eigen::Matrix2d G(int k) const {
    const auto w = robot.w.col(k);
    return Eigen::Matrix2d::Identity() + w * w.transpose();
  }

  [[nodiscard]] double value(const Eigen::Vector3d& y, double d2) const {
    double v = -load.dot(y);
    for (int k = 0; k < frame.legs(); ++k) {
      const double c = frame.work_n(k);
      if (c == 0.0 || skipped(k)) {
        continue;
      }
      const Eigen::Vector2d u = detail::slip(frame, k, detail::lever(frame, k, inv_L), y);
      v += c * std::sqrt(u.dot(G(k) * u) + d2);
    }
    return v;
  }

  void derivatives(const Eigen::Vector3d& y, double d2, Eigen::Vector3d& g,
                   Eigen::Matrix3d& H) const {
    g = -load;
    H.setZero();
    for (int k = 0; k < frame.legs(); ++k) {
      const double c = frame.work_n(k);
      if (c == 0.0 || skipped(k)) {
        continue;
      }
      const Eigen::Vector2d s = detail::lever(frame, k, inv_L);
      const Eigen::Vector2d u = detail::slip(frame, k, s, y);
      const Eigen::Matrix2d Gk = G(k);
      const Eigen::Vector2d Gu = Gk * u;
      const double rho = std::sqrt(u.dot(Gu) + d2);
      if (!(rho > 0.0)) {
        continue;  // δ = 0 and a foot at rest: no derivative (only used with δ > 0)
      }
      g += detail::jt(s, (c / rho) * Gu);
      detail::add_jt_p_j(H, s, (c / rho) * (Gk - Gu * Gu.transpose() / (rho * rho)));
    }
  }

  /// ρ(d) = Σ c_k ‖W_k J̃_k d‖ − f̃ᵀ d: negative proves that Φ is unbounded below.
  [[nodiscard]] double recession(const Eigen::Vector3d& d) const {
    double r = -load.dot(d);
    for (int k = 0; k < frame.legs(); ++k) {
      const double c = frame.work_n(k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d s = detail::lever(frame, k, inv_L);
      const Eigen::Vector2d a(d(0) + d(2) * s(0), d(1) + d(2) * s(1));
      r += c * std::sqrt(a.dot(G(k) * a));
    }
    return r;
  }
};

/// No quasi-static balance: v_body = 0, no forces, the recession slope as the certificate.
void report_sliding(contact::Frame& frame, double slope, double scale, int iterations) {
  frame.v_body.setZero();
  frame.Fxy.setZero();
  auto& s = frame.friction;
  s.converged = false;
  s.iterations = iterations;
  s.residual = 0.0;
  s.certificate = scale > 0.0 ? slope / scale : slope;
  s.unique = false;
  s.static_feet = 0;
  s.dissipation = 0.0;
  s.message =
      "sliding: the friction forces cannot hold the external load (no quasi-static balance)";
}

/// What the solve knows besides the frame.
struct Context {
  const contact::Robot& robot;
  contact::Frame& frame;
  Smoothed& phi;
  const Eigen::Vector3d& f;  ///< the load, scaled
  double L;
  double V;        ///< velocity scale
  double c_scale;  ///< Σ c_k ‖G_k‖^{1/2}
  double scale;    ///< c_scale + ‖f̃‖, the force scale of the balance
  double tol;
};

/// The forces F_k (frame.Fxy), then the summary: the balance residual, the duality gap
/// (Σ c‖W u‖ − f̃ᵀy) − Σ −F·q̇ relative to max(Σ c‖W u‖, Σ c‖W q̇‖, |f̃ᵀy|, Σc V), the static
/// feet, the dissipation. Returns the relative gap.
double summarize(const Context& cx, const Eigen::Vector3d& y, double delta) {
  contact::Frame& frame = cx.frame;
  detail::BalanceSum sum;
  sum.force = Eigen::Vector2d(cx.f(0), cx.f(1));
  sum.moment = cx.f(2) * cx.L;
  double dual = 0.0;
  double dissipation_exact = 0.0;  // Σ c_k ‖W u‖ (Φ without the load term)
  double at_rest = 0.0;            // Σ c_k ‖W q̇‖ (Φ at y = 0)
  double dissipation = 0.0;
  int static_feet = 0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    if (c == 0.0) {
      frame.Fxy.col(k).setZero();
      continue;
    }
    const Eigen::Vector2d u = detail::slip(frame, k, detail::lever(frame, k, 1.0 / cx.L), y);
    const Eigen::Matrix2d Gk = cx.phi.G(k);
    const double r = std::sqrt(u.dot(Gk * u));
    const Eigen::Vector2d F = frame.Fxy.col(k);
    sum.add(frame, k, F);
    const Eigen::Vector2d qd = frame.qdot.col(k).head<2>();
    dual -= F.dot(qd);
    dissipation_exact += c * r;
    at_rest += c * std::sqrt(qd.dot(Gk * qd));
    dissipation -= F.dot(u);
    static_feet += r <= 10.0 * delta ? 1 : 0;
  }
  const double primal = dissipation_exact - cx.f.dot(y);
  const double ref =
      std::max({dissipation_exact, at_rest, std::abs(cx.f.dot(y)), cx.c_scale * cx.V});
  detail::set_velocity(frame, y, cx.L);
  auto& s = frame.friction;
  s.certificate = std::max(primal - dual, 0.0) / ref;
  s.residual = sum.residual(cx.scale, cx.L);
  s.static_feet = static_feet;
  s.dissipation = dissipation;
  return s.certificate;
}

/// The path's forces at (y, δ): F_k = −c_k G_k u_k / √(‖W u‖² + δ²), into frame.Fxy.
void path_forces(const Context& cx, const Eigen::Vector3d& y, double delta) {
  for (int k = 0; k < cx.frame.legs(); ++k) {
    const double c = cx.frame.work_n(k);
    if (c == 0.0) {
      cx.frame.Fxy.col(k).setZero();
      continue;
    }
    const Eigen::Vector2d u = detail::slip(cx.frame, k, detail::lever(cx.frame, k, 1.0 / cx.L), y);
    const Eigen::Vector2d Gu = cx.phi.G(k) * u;
    const double rho = std::sqrt(u.dot(Gu) + delta * delta);
    cx.frame.Fxy.col(k) = rho > 0.0 ? Eigen::Vector2d(-(c / rho) * Gu) : Eigen::Vector2d::Zero();
  }
}

/// Foot k's force inside its friction ellipse Fᵀ G⁻¹ F ≤ (shrink · c)² (G⁻¹ = I − w wᵀ/(1 + ‖w‖²))?
/// Returns the ratio √(Fᵀ G⁻¹ F) / c.
double ellipse_ratio(const Context& cx, int k, const Eigen::Vector2d& F) {
  const auto w = cx.robot.w.col(k);
  const double wf = w.dot(F);
  return std::sqrt(std::max(F.squaredNorm() - wf * wf / (1.0 + w.squaredNorm()), 0.0)) /
         cx.frame.work_n(k);
}

/// The static feet's forces (marked in work_idx; frame.Fxy holds the path's forces for them and
/// the exact ones for the sliding feet) made to balance the load exactly and to lie in their
/// ellipses. First the least c-weighted correction of the path's forces (N = Σ_S c_s J̃ᵀ J̃,
/// r = the imbalance); when a force leaves its ellipse (static feet near their rims: a load close
/// to what they can hold), alternating projections between the balanced forces and the ellipses
/// (shrunk by 1e-13; radial scaling, the projection for isotropic feet), which converge to a
/// point of both when one exists. Returns false if none is found.
bool fit_static_forces(const Context& cx, const Eigen::Matrix3d& N, const Eigen::Vector3d& r) {
  contact::Frame& frame = cx.frame;
  const double inv_L = 1.0 / cx.L;
  const auto is_static = [&](int k) { return frame.work_idx[static_cast<std::size_t>(k)] != 0; };
  // (a) the least c-weighted correction.
  detail::Psd3 weighted;
  weighted.factorize(N);
  const Eigen::Vector3d lambda = -weighted.solve(r);
  bool inside = true;
  Eigen::Matrix3d N_plain = Eigen::Matrix3d::Zero();
  for (int k = 0; k < frame.legs(); ++k) {
    if (!is_static(k)) {
      continue;
    }
    const double c = frame.work_n(k);
    const Eigen::Vector2d sk = detail::lever(frame, k, inv_L);
    frame.Fxy.col(k) +=
        c * Eigen::Vector2d(lambda(0) + lambda(2) * sk(0), lambda(1) + lambda(2) * sk(1));
    inside = inside && ellipse_ratio(cx, k, frame.Fxy.col(k)) <= 1.0 + 1e-12;
    detail::add_jt_p_j(N_plain, sk, Eigen::Matrix2d::Identity());
  }
  if (inside) {
    return true;
  }
  // (b) alternating projections.
  detail::Psd3 plain;
  plain.factorize(N_plain);
  constexpr double kShrink = 1.0 - 1e-13;
  for (int it = 0; it < 2000; ++it) {
    // Into the ellipses.
    for (int k = 0; k < frame.legs(); ++k) {
      if (is_static(k)) {
        const double ratio = ellipse_ratio(cx, k, frame.Fxy.col(k));
        if (ratio > kShrink) {
          frame.Fxy.col(k) *= kShrink / ratio;
        }
      }
    }
    // Onto the balance: the imbalance of all forces, removed by the least (plain) correction.
    Eigen::Vector3d imbalance = cx.f;
    for (int k = 0; k < frame.legs(); ++k) {
      if (frame.work_n(k) != 0.0) {
        imbalance += detail::jt(detail::lever(frame, k, inv_L), frame.Fxy.col(k));
      }
    }
    const Eigen::Vector3d mu = -plain.solve(imbalance);
    inside = true;
    for (int k = 0; k < frame.legs(); ++k) {
      if (is_static(k)) {
        const Eigen::Vector2d sk = detail::lever(frame, k, inv_L);
        frame.Fxy.col(k) += Eigen::Vector2d(mu(0) + mu(2) * sk(0), mu(1) + mu(2) * sk(1));
        inside = inside && ellipse_ratio(cx, k, frame.Fxy.col(k)) <= 1.0 + 1e-12;
      }
    }
    if (inside) {
      return true;
    }
  }
  return false;
}

/// The polish (see the top of the file) from the path's point y at δ, with the feet at
/// ‖W u‖ ≤ limit taken as static. On success frame.v_body, Fxy and the summary hold the certified
/// answer.
bool polish(Context& cx, const Eigen::Vector3d& y_path, double delta, double limit) {
  contact::Frame& frame = cx.frame;
  const double inv_L = 1.0 / cx.L;
  // ---- the static set S (marked in work_idx), its first foot and its spread ------------------
  int first = -1;
  int m = 0;
  double spread = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    int& mark = frame.work_idx[static_cast<std::size_t>(k)];
    mark = 0;
    if (c == 0.0) {
      continue;
    }
    const Eigen::Vector2d u = detail::slip(frame, k, detail::lever(frame, k, inv_L), y_path);
    if (std::sqrt(u.dot(cx.phi.G(k) * u)) <= limit) {
      mark = 1;
      ++m;
      if (first < 0) {
        first = k;
      } else {
        spread = std::max(spread, (frame.q.col(k) - frame.q.col(first)).head<2>().norm());
      }
    }
  }
  // ---- the body velocity where S does not slip ------------------------------------------------
  Eigen::Vector3d y = y_path;
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  cx.phi.skip_static = true;
  const double g_tol = 1e-15 * cx.scale;
  if (m > 0 && spread > 1e-9 * cx.L) {
    // S spans two points: it alone fixes y (least squares; it must be a rigid motion).
    Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int k = 0; k < frame.legs(); ++k) {
      if (frame.work_idx[static_cast<std::size_t>(k)] == 0) {
        continue;
      }
      const Eigen::Vector2d sk = detail::lever(frame, k, inv_L);
      detail::add_jt_p_j(N, sk, Eigen::Matrix2d::Identity());
      r -= detail::jt(sk, frame.qdot.col(k).head<2>());
    }
    detail::Psd3 solver;
    solver.factorize(N);
    y = solver.solve(r);
    for (int k = 0; k < frame.legs(); ++k) {
      if (frame.work_idx[static_cast<std::size_t>(k)] != 0 &&
          detail::slip(frame, k, detail::lever(frame, k, inv_L), y).norm() > 1e-9 * cx.V) {
        cx.phi.skip_static = false;
        return false;  // S does not move as one rigid body: not all of it can be static
      }
    }
  } else {
    // S is one point (rotations about it: the direction e) or empty (all of R³): Newton on the
    // exact Φ of the sliding feet, which is smooth there.
    const Eigen::Vector2d s0 = m > 0 ? detail::lever(frame, first, inv_L) : Eigen::Vector2d::Zero();
    const Eigen::Vector3d e(-s0(0), -s0(1), 1.0);
    if (m > 0) {
      const Eigen::Vector2d qd = frame.qdot.col(first).head<2>();
      y = Eigen::Vector3d(-qd(0) - y_path(2) * s0(0), -qd(1) - y_path(2) * s0(1), y_path(2));
    }
    for (int it = 0; it < 30; ++it) {
      cx.phi.derivatives(y, 0.0, g, H);
      Eigen::Vector3d p;
      double gn = 0.0;
      if (m > 0) {
        const double g1 = e.dot(g);
        const double h1 = e.dot(H * e);
        gn = std::abs(g1);
        if (gn <= g_tol) {
          break;
        }
        if (!(h1 > 0.0)) {
          cx.phi.skip_static = false;
          return false;
        }
        p = -(g1 / h1) * e;
      } else {
        gn = g.norm();
        if (gn <= g_tol) {
          break;
        }
        detail::Psd3 newton;
        if (!newton.factorize(H)) {
          cx.phi.skip_static = false;
          return false;
        }
        p = -newton.solve(g);
      }
      // Backtrack on the gradient's norm (Φ's changes are below rounding near the end).
      // At most 20 halvings: t down to 2^-20 ≈ 1e-6.
      constexpr int kHalvings = 20;
      double t = 1.0;
      Eigen::Vector3d g_trial;
      Eigen::Matrix3d H_trial;
      int halvings = 0;
      for (; halvings < kHalvings; ++halvings, t *= 0.5) {
        cx.phi.derivatives(y + t * p, 0.0, g_trial, H_trial);
        const double gt = m > 0 ? std::abs(e.dot(g_trial)) : g_trial.norm();
        if (gt < gn) {
          break;
        }
      }
      if (halvings == kHalvings) {
        break;
      }
      y += t * p;
    }
  }
  cx.phi.skip_static = false;
  // ---- forces: exact for the sliding feet, the path's plus a balancing correction for S ------
  path_forces(cx, y_path, delta);  // S keeps these as its starting forces
  Eigen::Vector3d r = cx.f;        // imbalance f̃ + Σ J̃ᵀ F
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    if (c == 0.0) {
      continue;
    }
    const Eigen::Vector2d sk = detail::lever(frame, k, inv_L);
    if (frame.work_idx[static_cast<std::size_t>(k)] == 0) {
      const Eigen::Vector2d u = detail::slip(frame, k, sk, y);
      const Eigen::Vector2d Gu = cx.phi.G(k) * u;
      const double rho = std::sqrt(u.dot(Gu));
      if (!(rho > 0.0)) {
        return false;
      }
      frame.Fxy.col(k) = -(c / rho) * Gu;
    } else {
      detail::add_jt_p_j(N, sk, c * Eigen::Matrix2d::Identity());
    }
    r += detail::jt(sk, frame.Fxy.col(k));
  }
  if (m > 0 && !fit_static_forces(cx, N, r)) {
    return false;
  }
  const double gap = summarize(cx, y, delta);
  if (!(gap <= cx.tol) || !(frame.friction.residual <= 1e-12)) {
    return false;
  }
  frame.friction.static_feet = m;
  return true;
}

/// The polish with growing static sets (see solve_coulomb_loaded): thresholds at each candidate
/// foot's ‖W u‖ in increasing order. Uses frame.work_2n's first row for the ‖W u‖.
bool try_static_sets(Context& cx, const Eigen::Vector3d& y, double delta) {
  contact::Frame& frame = cx.frame;
  const double cap = 1e3 * delta;
  int candidates = 0;
  for (int k = 0; k < frame.legs(); ++k) {
    double r = std::numeric_limits<double>::infinity();
    if (frame.work_n(k) != 0.0) {
      const Eigen::Vector2d u = detail::slip(frame, k, detail::lever(frame, k, 1.0 / cx.L), y);
      r = std::sqrt(u.dot(cx.phi.G(k) * u));
    }
    frame.work_2n(0, k) = r;
    candidates += r <= cap ? 1 : 0;
  }
  if (candidates == 0) {
    return polish(cx, y, delta, -1.0);
  }
  double previous = -1.0;
  for (int j = 0; j < candidates; ++j) {
    double next = std::numeric_limits<double>::infinity();
    for (int k = 0; k < frame.legs(); ++k) {
      const double r = frame.work_2n(0, k);
      if (r > previous && r < next) {
        next = r;
      }
    }
    if (!(next <= cap)) {
      break;
    }
    if (polish(cx, y, delta, next)) {
      return true;
    }
    previous = next;
  }
  return false;
}

/// solve_coulomb_loaded without its end-of-solve check (several exits).
void solve_loaded(const contact::Robot& robot, contact::Frame& frame, const Eigen::Vector3d& load,
                  const CoulombOptions& options) {
  if (load(0) == 0.0 && load(1) == 0.0 && load(2) == 0.0) {
    // No load is the flat problem: its fast solver (a slope of angle 0 is flat bit for bit).
    solve_coulomb(robot, frame, options);
    return;
  }
  frame.friction.route = contact::FrictionSummary::Route::kPath;  // the smoothing path only
  // ---- the viscous-Coulomb system gives L, c_k (in work_n) and the starting point -----------
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  const detail::Contacts cs = detail::viscous_balance(robot, frame, M, b);
  const Eigen::Vector3d f(load(0), load(1), load(2) * cs.inv_L);
  Smoothed phi{robot, frame, f, cs.inv_L};
  double c_scale = 0.0;  // Σ c_k ‖G_k‖^{1/2}: the largest force the feet can exert together
  double V = 0.0;        // velocity scale: the fastest foot
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    if (c > 0.0) {
      c_scale += c * std::sqrt(1.0 + robot.w.col(k).squaredNorm());
      V = std::max(V, frame.qdot.col(k).head<2>().norm());
    }
  }
  const double scale = c_scale + f.norm();

  // ---- (1) sliding along the load: all feet together cannot hold its force ------------------
  if (cs.active == 0 && f.squaredNorm() > 0.0) {
    report_sliding(frame, -f.norm(), scale, 0);
    return;
  }
  const double f_xy = f.head<2>().norm();
  if (f_xy > 0.0) {
    const Eigen::Vector3d e(f(0) / f_xy, f(1) / f_xy, 0.0);
    const double slope = phi.recession(e);
    if (slope < 0.0) {
      report_sliding(frame, slope, scale, 0);
      return;
    }
  }

  // ---- start: the viscous-Coulomb velocity under the same load -------------------------------
  detail::Psd3 solver;
  solver.factorize(M);
  Eigen::Vector3d y = solver.solve(f - b);
  V = std::max(V, y.norm());
  auto& s = frame.friction;
  s = contact::FrictionSummary{};
  if (cs.active == 0 || !(V > 0.0)) {
    // No friction and no load, or nothing moves: at rest, no force.
    frame.v_body.setZero();
    frame.Fxy.setZero();
    s.unique = cs.active > 0;
    if (cs.active == 0) {
      s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
    }
    return;
  }
  s.route = contact::FrictionSummary::Route::kPath;
  Context cx{robot, frame, phi, f, cs.L, V, c_scale, scale, options.tol};

  // ---- the smoothing path: damped Newton per stage, δ ← δ/10, a polish after each stage ------
  const double delta_min = std::max(0.1 * options.tol * V, 1e-300);
  double delta = V;
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  int stage_steps = 0;
  while (s.iterations < options.max_iterations) {
    const double d2 = delta * delta;
    phi.derivatives(y, d2, g, H);
    // A tiny ridge keeps H definite along directions no foot feels (a moment about one point).
    H.diagonal().array() += 1e-14 * H.trace() + 1e-300;
    detail::Psd3 newton;
    newton.factorize(H);
    const Eigen::Vector3d p = -newton.solve(g);
    const double decrement = -g.dot(p);  // λ², in units of Φ
    bool stage_end = !(decrement > 0.1 * delta * c_scale) || stage_steps >= 12;
    if (!stage_end) {
      // Armijo backtracking on Φ_δ.
      const double v0 = phi.value(y, d2);
      double t = 1.0;
      Eigen::Vector3d trial = y + p;
      while (phi.value(trial, d2) > v0 - 1e-4 * t * decrement && t > 1e-10) {
        t *= 0.5;
        trial = y + t * p;
      }
      ++s.iterations;
      ++stage_steps;
      if (t <= 1e-10) {
        stage_end = true;  // no descent left at rounding level
      } else {
        y = trial;
        if (y.norm() > kRunaway * V) {
          // ---- (2) the iterate runs away: does Φ decrease without bound along it? ----------
          const double slope = phi.recession(y / y.norm());
          if (slope < 0.0) {
            report_sliding(frame, slope, scale, s.iterations);
            return;
          }
        }
      }
    }
    if (stage_end) {
      // A static foot whose force is the fraction t of its limit keeps ‖W u‖ = δ t/√(1 − t²)
      // on the path (7 δ at t = 0.99), so near a holding limit no fixed threshold separates
      // static from slowly sliding feet: the candidates are the feet with ‖W u‖ ≤ 10³ δ, and the
      // static sets tried are the slowest one, two, ... of them (a wrong set fails the polish's
      // checks); with none, the empty set.
      if (delta <= 1e-3 * V && try_static_sets(cx, y, delta)) {
        s.converged = true;
        s.unique = true;
        return;
      }
      if (delta <= delta_min) {
        break;
      }
      delta = std::max(0.1 * delta, delta_min);
      stage_steps = 0;
    }
  }

  // ---- no polish certified: the path's own forces and their gap -------------------------------
  path_forces(cx, y, delta);
  summarize(cx, y, delta);
  s.converged = s.certificate <= options.tol;
  phi.derivatives(y, delta * delta, g, H);
  detail::Psd3 rank;
  rank.factorize(H);
  s.unique = rank.rank() == 3;
  s.message.clear();
  if (!s.converged) {
    s.message = "loaded Coulomb: the duality gap did not reach the tolerance";
  } else if (!s.unique) {
    s.message = "a continuum of body velocities balances the load (flat minimum)";
  }
}

}  // namespace

void solve_coulomb_loaded(const contact::Robot& robot, contact::Frame& frame,
                          const Eigen::Vector3d& load, const CoulombOptions& options) {
  solve_loaded(robot, frame, load, options);
  detail::flag_non_finite(frame, frame.Fxy.sum());
}

}  // namespace slipwalk::friction
