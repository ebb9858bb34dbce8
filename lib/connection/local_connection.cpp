// The local connection (eq. 3.20, with the signs and the moment row of friction/balance.hpp):
// A_k = −c_k M⁻¹ J_kᵀ G_k, least norm (M⁺) when the contacts are one point. Two passes over the
// feet: the system (friction::detail::viscous_balance) and the columns of A.
#include "connection/local_connection.hpp"

#include "friction/balance.hpp"

namespace slipwalk::connection {

void local_connection(const contact::Robot& robot, contact::Frame& frame) {
  namespace d = friction::detail;
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  const d::Contacts cs = d::viscous_balance(robot, frame, M, b);  // c_k in work_n
  d::Psd3 solver;
  solver.factorize(M);
  // Scaled coordinates: x = D y, so A_k = −D M̃⁺ (c_k J̃_kᵀ G_k), D = diag(1, 1, 1/L); with the
  // unscaled lever S q_k in J_k = [I | S q_k] this is −c_k (D M̃⁺ D) J_kᵀ G_k.
  Eigen::Matrix3d P = solver.inverse();
  P.row(2) *= cs.inv_L;
  P.col(2) *= cs.inv_L;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    // c G = c (I + w wᵀ), and the third row of J_kᵀ G_k, (S q)ᵀ G.
    const double w0 = robot.w(0, k);
    const double w1 = robot.w(1, k);
    const double g00 = c * (1.0 + w0 * w0);
    const double g01 = c * w0 * w1;
    const double g11 = c * (1.0 + w1 * w1);
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    const double s0 = -qy * g00 + qx * g01;
    const double s1 = -qy * g01 + qx * g11;
    for (int i = 0; i < 3; ++i) {  // zero columns for a foot without friction (c = 0)
      frame.A(i, 2 * k) = -(P(i, 0) * g00 + P(i, 1) * g01 + P(i, 2) * s0);
      frame.A(i, 2 * k + 1) = -(P(i, 0) * g01 + P(i, 1) * g11 + P(i, 2) * s1);
    }
  }
}

}  // namespace slipwalk::connection
