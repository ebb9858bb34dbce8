// The local connection (eq. 3.20, with the signs and the moment row of friction/balance.hpp):
// A_k = −c_k M⁻¹ J_kᵀ G_k, least norm (M⁺) when the contacts are one point.
#include "connection/local_connection.hpp"

#include "friction/balance.hpp"

namespace slipwalk::connection {

namespace {

template <bool kAniso>
void fill_connection(const contact::Robot& robot, contact::Frame& frame,
                     const friction::detail::Contacts& cs) {
  namespace d = friction::detail;
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  d::viscous_system<kAniso>(robot, frame, cs.inv_L, M, b);
  d::Psd3 solver;
  solver.factorize(M);
  // Scaled coordinates: x = D y, so A_k = −D M̃⁺ (c_k J̃_kᵀ G_k), D = diag(1, 1, 1/L).
  Eigen::Matrix3d Minv = solver.inverse();
  Minv.row(2) /= cs.L;
  const d::Metric<kAniso> metric{robot, frame};
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = d::friction_weight(robot, frame, k);
    if (c == 0.0) {
      frame.A.middleCols<2>(2 * k).setZero();
      continue;
    }
    const Eigen::Vector2d s = d::lever(frame, k, cs.inv_L);
    const Eigen::Matrix2d G = metric.G(k);
    Eigen::Matrix<double, 3, 2> JtG;
    JtG.topRows<2>() = G;
    JtG.row(2) = s.transpose() * G;
    frame.A.middleCols<2>(2 * k).noalias() = -c * (Minv * JtG);
  }
}

}  // namespace

void local_connection(const contact::Robot& robot, contact::Frame& frame) {
  const friction::detail::Contacts cs = friction::detail::prepare(robot, frame);
  if (cs.anisotropic) {
    fill_connection<true>(robot, frame, cs);
  } else {
    fill_connection<false>(robot, frame, cs);
  }
}

}  // namespace slipwalk::connection
