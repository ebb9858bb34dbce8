// Viscous-Coulomb friction (eqs. 3.14 with ε → ∞ and 3.19): the body-frame balance M x = −b of
// friction/balance.hpp, one 3 × 3 solve.
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

namespace {

template <bool kAniso>
void solve_viscous(const contact::Robot& robot, contact::Frame& frame, const detail::Contacts& cs) {
  // ---- the 3 × 3 balance in scaled coordinates, least norm when singular --------------------
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  detail::viscous_system<kAniso>(robot, frame, cs.inv_L, M, b);
  detail::Psd3 solver;
  solver.factorize(M);
  const Eigen::Vector3d y = -solver.solve(b);
  detail::set_velocity(frame, y, cs.L);

  // ---- forces F_k = −c_k G_k u_k, dissipation, balance and the size of the cancelling terms --
  const detail::Metric<kAniso> metric{robot, frame};
  detail::BalanceSum sum;
  double scale = 0.0;
  double dissipation = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = detail::friction_weight(robot, frame, k);
    if (c == 0.0) {
      frame.Fxy.col(k).setZero();
      continue;
    }
    const Eigen::Vector2d u = detail::slip(frame, k, detail::lever(frame, k, cs.inv_L), y);
    const Eigen::Vector2d Gu = metric.G(k, u);
    const Eigen::Vector2d F = -c * Gu;
    frame.Fxy.col(k) = F;
    sum.add(frame, k, F);
    dissipation += c * u.dot(Gu);
    // c ‖G‖ (‖q̇‖ + ‖J x‖), in 1-norms (a magnitude, no square roots needed).
    const double g = kAniso ? 1.0 + robot.w.col(k).squaredNorm() : 1.0;
    scale += c * g * (frame.qdot.col(k).head<2>().lpNorm<1>() + u.lpNorm<1>());
  }

  auto& s = frame.friction;
  s.converged = true;
  s.iterations = 0;
  s.certificate = 0.0;
  s.static_feet = 0;
  s.dissipation = dissipation;
  s.residual = sum.residual(scale, cs.L);
  s.unique = solver.rank() == 3;
  s.message.clear();
  if (cs.active == 0) {
    s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
  } else if (!s.unique) {
    s.message = "all contacts at one point: rotation about it undetermined (least-norm solution)";
  }
}

}  // namespace

void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame) {
  const detail::Contacts cs = detail::prepare(robot, frame);
  if (cs.anisotropic) {
    solve_viscous<true>(robot, frame, cs);
  } else {
    solve_viscous<false>(robot, frame, cs);
  }
}

}  // namespace slipwalk::friction
