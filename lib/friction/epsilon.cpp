// The ε-family of eq. 3.14: F_k = −c_k φ(s_k) G_k u_k, φ(s) = (ε + s)/(ε + s²), s_k = ‖W_k u_k‖.
//
// The balance Σ J_kᵀ F_k = 0 is the stationarity condition of the potential
//   Φ(x) = Σ c_k ψ(s_k),   ψ(s) = ∫₀ˢ t φ(t) dt = s + (ε/2) ln(1 + s²/ε) − √ε atan(s/√ε),
// since ∇_u ψ(‖W u‖) = φ(s) G u. So we minimize Φ by Newton's method with an Armijo line search,
// starting from the viscous-Coulomb solution (the ε → ∞ limit). ψ is convex for
// s ≤ 1 + √(1 + ε) and concave beyond (the force magnitude s φ(s) peaks there and falls back to 1:
// velocity weakening), so where the Newton matrix is not positive definite the step uses the
// IRLS matrix Σ c φ J̃ᵀ G J̃ instead (always positive semidefinite: a descent direction).
// For isotropic feet s_k = ‖u_k‖ exactly as in eq. 3.14; with anisotropy the same metric W as
// the Coulomb solver, so ε → 0 gives friction/coulomb.cpp's law and ε → ∞ eq. 3.19's.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

namespace {

struct EpsilonLaw {
  double eps;
  double root;  // √ε

  [[nodiscard]] double phi(double s) const { return (eps + s) / (eps + s * s); }
  [[nodiscard]] double dphi(double s) const {
    const double den = eps + s * s;
    return (eps - 2.0 * eps * s - s * s) / den / den;
  }
  [[nodiscard]] double psi(double s) const {
    const double z = s / root;
    // s − √ε atan(s/√ε) = √ε (z − atan z), by its series where it would cancel.
    double a;
    if (z < 1e-2) {
      const double z2 = z * z;
      a = root * z * z2 * (1.0 / 3.0 - z2 * (1.0 / 5.0 - z2 / 7.0));
    } else {
      a = s - root * std::atan(z);
    }
    // (ε/2) ln(1 + z²), written so that z² cannot overflow.
    const double b = z > 1.0 ? eps * (std::log(z) + 0.5 * std::log1p(1.0 / (z * z)))
                             : 0.5 * eps * std::log1p(z * z);
    return a + b;
  }
};

template <bool kAniso>
class EpsilonSolver {
 public:
  EpsilonSolver(const contact::Robot& robot, contact::Frame& frame, const detail::Contacts& cs,
                const EpsilonLaw& law)
      : robot_(robot), frame_(frame), cs_(cs), law_(law), metric_{robot, frame} {}

  void run(const EpsilonOptions& options) {
    // ---- start: the viscous-Coulomb solution (least norm if the contacts are one point) ----
    Eigen::Matrix3d M;
    Eigen::Vector3d b;
    detail::viscous_system<kAniso>(robot_, frame_, cs_.inv_L, M, b);
    detail::Psd3 viscous;
    viscous.factorize(M);
    Eigen::Vector3d y = -viscous.solve(b);
    double vscale = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (detail::friction_weight(robot_, frame_, k) > 0.0) {
        vscale = std::max(vscale, frame_.qdot.col(k).head<2>().norm());
      }
    }
    vscale = std::max(vscale, std::numeric_limits<double>::min());

    // ---- damped Newton on Φ ------------------------------------------------------------------
    auto& s = frame_.friction;
    s.converged = cs_.active == 0;
    s.iterations = 0;
    Eigen::Matrix3d H;
    Eigen::Matrix3d Mphi;
    Eigen::Vector3d g;
    detail::Psd3 solver;
    int tiny_steps = 0;
    while (!s.converged && s.iterations < options.max_iterations) {
      ++s.iterations;
      double gscale = 0.0;
      const double phi0 = assemble(y, g, H, Mphi, gscale);
      if (g.norm() <= 1e-13 * gscale) {
        s.converged = true;  // balanced to rounding
        break;
      }
      // Newton where Φ is convex (pseudo-inverse along directions no foot feels, as for the
      // viscous start), else the IRLS matrix.
      Eigen::Vector3d p;
      if (solver.factorize_definite(H) ||
          (!solver.factorize(H) && solver.rank() >= viscous.rank() && H.trace() > 0.0 &&
           min_eigenvalue_ok(H))) {
        p = -solver.solve(g);
      } else {
        solver.factorize(Mphi);
        p = -solver.solve(g);
      }
      // Stop after two steps below tol in a row (the second also settles the balance, which
      // the first may leave at tol × the stiffest foot's curvature).
      const double step_floor = options.tol * (y.norm() + vscale);
      if (p.norm() <= step_floor) {
        y += p;
        s.converged = ++tiny_steps >= 2;
        continue;
      }
      const double slope = g.dot(p);
      if (!(slope < 0.0)) {
        break;  // no descent direction left (rounding): not converged
      }
      const double slack = 8.0 * std::numeric_limits<double>::epsilon() * phi0;
      double t = 1.0;
      bool accepted = false;
      for (int j = 0; j < 60; ++j, t *= 0.5) {
        if (potential(y + t * p) <= phi0 + 1e-4 * t * slope + slack) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        break;
      }
      y += t * p;
      if (t * p.norm() <= step_floor && ++tiny_steps >= 2) {
        s.converged = true;  // rounding-level progress only
      }
    }
    y = viscous.project_to_range(y);
    detail::set_velocity(frame_, y, cs_.L);

    // ---- forces, residual, summary -----------------------------------------------------------
    detail::BalanceSum sum;
    double scale = 0.0;
    double dissipation = 0.0;
    double s_max = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = detail::friction_weight(robot_, frame_, k);
      if (c == 0.0) {
        frame_.Fxy.col(k).setZero();
        continue;
      }
      const Eigen::Vector2d u = detail::slip(frame_, k, detail::lever(frame_, k, cs_.inv_L), y);
      const Eigen::Vector2d Gu = metric_.G(k, u);
      const double sk = std::sqrt(std::max(u.dot(Gu), 0.0));
      const double cf = c * law_.phi(sk);
      const Eigen::Vector2d F = -cf * Gu;
      frame_.Fxy.col(k) = F;
      sum.add(frame_, k, F);
      dissipation += cf * u.dot(Gu);
      const double gnorm = kAniso ? 1.0 + robot_.w.col(k).squaredNorm() : 1.0;
      scale += cf * gnorm * (frame_.qdot.col(k).head<2>().lpNorm<1>() + u.lpNorm<1>());
      s_max = std::max(s_max, sk);
    }
    s.residual = sum.residual(scale, cs_.L);
    s.certificate = 0.0;
    s.static_feet = 0;
    s.dissipation = dissipation;
    s.unique = viscous.rank() == 3;
    s.message.clear();
    if (cs_.active == 0) {
      s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
    } else if (!s.converged) {
      s.message = "iteration limit reached before the velocity settled";
    } else if (!s.unique) {
      s.message = "all contacts at one point: rotation about it undetermined (least-norm solution)";
    } else if (s_max > 1.0 + std::sqrt(1.0 + law_.eps)) {
      s.message =
          "a foot slides where the eq. 3.14 law weakens with speed (s > 1 + sqrt(1 + eps)): the "
          "balance found may not be the only one";
    }
  }

 private:
  /// Φ, ∇Φ, the Newton matrix and the IRLS matrix at y (scaled coordinates).
  /// gscale: the size of the terms that cancel in ∇Φ.
  double assemble(const Eigen::Vector3d& y, Eigen::Vector3d& g, Eigen::Matrix3d& H,
                  Eigen::Matrix3d& Mphi, double& gscale) const {
    double phi_sum = 0.0;
    g.setZero();
    H.setZero();
    Mphi.setZero();
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = detail::friction_weight(robot_, frame_, k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d sl = detail::lever(frame_, k, cs_.inv_L);
      const Eigen::Vector2d u = detail::slip(frame_, k, sl, y);
      const Eigen::Vector2d Gu = metric_.G(k, u);
      const double sk = std::sqrt(std::max(u.dot(Gu), 0.0));
      const double ph = law_.phi(sk);
      phi_sum += c * law_.psi(sk);
      g += detail::jt(sl, c * ph * Gu);
      const double gnorm = kAniso ? 1.0 + robot_.w.col(k).squaredNorm() : 1.0;
      gscale += c * ph * gnorm * (1.0 + sl.lpNorm<1>()) *
                (frame_.qdot.col(k).head<2>().lpNorm<1>() +
                 (u - frame_.qdot.col(k).head<2>()).lpNorm<1>());
      const Eigen::Matrix2d G = metric_.G(k);
      detail::add_jt_p_j(Mphi, sl, c * ph * G);
      Eigen::Matrix2d P = ph * G;
      if (sk > 0.0) {
        // ∇²_u ψ(‖W u‖) = φ G + φ'(s) s t tᵀ with t = G u / s.
        const Eigen::Vector2d t = Gu / sk;
        P += (law_.dphi(sk) * sk) * t * t.transpose();
      }
      detail::add_jt_p_j(H, sl, c * P);
    }
    return phi_sum;
  }

  /// H has no eigenvalue below −kRankTol · trace (positive semidefinite up to rounding).
  [[nodiscard]] static bool min_eigenvalue_ok(const Eigen::Matrix3d& H) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H, Eigen::EigenvaluesOnly);
    return es.eigenvalues()(0) >= -detail::kRankTol * H.trace();
  }

  [[nodiscard]] double potential(const Eigen::Vector3d& y) const {
    double phi_sum = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = detail::friction_weight(robot_, frame_, k);
      if (c == 0.0) {
        continue;
      }
      const Eigen::Vector2d u = detail::slip(frame_, k, detail::lever(frame_, k, cs_.inv_L), y);
      phi_sum += c * law_.psi(metric_.W(k, u).norm());
    }
    return phi_sum;
  }

  const contact::Robot& robot_;
  contact::Frame& frame_;
  detail::Contacts cs_;
  EpsilonLaw law_;
  detail::Metric<kAniso> metric_;
};

}  // namespace

void solve_epsilon(const contact::Robot& robot, contact::Frame& frame, double epsilon,
                   const EpsilonOptions& options) {
  if (std::isnan(epsilon) || epsilon <= 0.0) {
    throw core::InputError("epsilon", "must be positive, got " + core::format_double(epsilon));
  }
  if (std::isinf(epsilon)) {
    solve_viscous_coulomb(robot, frame);  // the ε → ∞ limit, exactly
    return;
  }
  const detail::Contacts cs = detail::prepare(robot, frame);
  const EpsilonLaw law{epsilon, std::sqrt(epsilon)};
  if (cs.anisotropic) {
    EpsilonSolver<true>(robot, frame, cs, law).run(options);
  } else {
    EpsilonSolver<false>(robot, frame, cs, law).run(options);
  }
  detail::flag_non_finite(frame, frame.Fxy.sum());
}

}  // namespace slipwalk::friction
