// Viscous-Coulomb friction (eqs. 3.14 with ε → ∞ and 3.19): the body-frame balance M x = −b of
// friction/balance.hpp, one 3 × 3 solve. Two passes over the feet: the system (with the contact
// summary, detail::viscous_balance) and the forces; both in scalars, since per foot there is
// only a handful of multiply-adds and any temporary or repeated lookup is a visible share.
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame) {
  // ---- the 3 × 3 balance in scaled coordinates, least norm when singular --------------------
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  const detail::Contacts cs = detail::viscous_balance(robot, frame, M, b);  // c_k in work_n
  detail::Psd3 solver;
  solver.factorize(M);
  const Eigen::Vector3d y = -solver.solve(b);
  detail::set_velocity(frame, y, cs.L);

  // ---- forces F_k = −c_k G_k u_k, dissipation, balance and the size of the cancelling terms --
  // u_k = v + ω S q_k + q̇_k in body coordinates (v = y_xy, ω = y_2/L).
  const double v0 = frame.v_body(0);
  const double v1 = frame.v_body(1);
  const double om = frame.v_body(2);
  double fx = 0.0;
  double fy = 0.0;
  double mz = 0.0;
  double scale = 0.0;
  double dissipation = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    const double u0 = v0 - om * qy + frame.qdot(0, k);
    const double u1 = v1 + om * qx + frame.qdot(1, k);
    const double w0 = robot.w(0, k);
    const double w1 = robot.w(1, k);
    const double wu = w0 * u0 + w1 * u1;  // G u = u + w (w·u)
    const double F0 = -c * (u0 + w0 * wu);
    const double F1 = -c * (u1 + w1 * wu);
    frame.Fxy(0, k) = F0;  // zero for a foot without friction (c = 0)
    frame.Fxy(1, k) = F1;
    fx += F0;
    fy += F1;
    mz += qx * F1 - qy * F0;
    dissipation -= F0 * u0 + F1 * u1;  // c uᵀG u
    // c ‖G‖ (‖q̇‖ + ‖J x‖), in 1-norms (a magnitude, no square roots needed).
    scale +=
        c * (1.0 + w0 * w0 + w1 * w1) *
        (std::abs(frame.qdot(0, k)) + std::abs(frame.qdot(1, k)) + std::abs(u0) + std::abs(u1));
  }
  detail::BalanceSum sum;
  sum.force << fx, fy;
  sum.moment = mz;

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

}  // namespace slipwalk::friction
