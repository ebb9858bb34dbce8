#include "calibration/wrench.hpp"

#include <cmath>

#include "core/error.hpp"

namespace slipwalk::calibration {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Wrench transform_wrench(const Frame& s_in_b, const Wrench& w_s) {
  const Eigen::Vector3d f = s_in_b.R * w_s.head<3>();
  Wrench w_b;
  w_b.head<3>() = f;
  w_b.tail<3>() = s_in_b.R * w_s.tail<3>() + s_in_b.p.cross(f);
  return w_b;
}

Eigen::Matrix<double, 6, 6> wrench_transform_matrix(const Frame& s_in_b) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m.topLeftCorner<3, 3>() = s_in_b.R;
  m.bottomLeftCorner<3, 3>() = skew(s_in_b.p) * s_in_b.R;
  m.bottomRightCorner<3, 3>() = s_in_b.R;
  return m;
}

Wrench force_at(const Eigen::Vector3d& f, const Eigen::Vector3d& x) {
  Wrench w;
  w.head<3>() = f;
  w.tail<3>() = x.cross(f);
  return w;
}

Eigen::Matrix3d cayley(const Eigen::Vector3d& q) {
  const Eigen::Matrix3d Q = skew(q);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // (I − Q) and (I + Q)^{-1} commute (both are functions of Q), so solving from the right is exact.
  return (I + Q).transpose().partialPivLu().solve((I - Q).transpose()).transpose();
}

Eigen::Vector3d cayley_inverse(const Eigen::Matrix3d& R) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (!R.allFinite() || (R.transpose() * R - I).norm() > 1e-9 || R.determinant() < 0.0) {
    throw core::InputError("rotation", "is not a rotation matrix (RᵀR ≠ I or det R < 0)");
  }
  // 1 + trace R = 2 (1 + cos θ): zero at θ = π, where I + R is singular.
  if (1.0 + R.trace() < 2.0 * (1.0 - std::cos(1e-6))) {
    throw core::InputError("rotation",
                           "turns by π (or within 1e-6 rad of it): no Cayley parameters");
  }
  const Eigen::Matrix3d Q =
      (I + R).transpose().partialPivLu().solve((I - R).transpose()).transpose();
  // Q is skew up to round-off; read q from its antisymmetric part.
  return 0.5 * Eigen::Vector3d(Q(2, 1) - Q(1, 2), Q(0, 2) - Q(2, 0), Q(1, 0) - Q(0, 1));
}

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) {
    return Eigen::Matrix3d::Identity();
  }
  return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace slipwalk::calibration
