#include "friction/balance.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace slipwalk::friction::detail {

Contacts prepare(const contact::Robot& robot, contact::Frame& frame) {
  Contacts out;
  double L2 = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = friction_weight(robot, frame, k);
    if (c == 0.0) {
      continue;
    }
    ++out.active;
    out.c_sum += c;
    L2 = std::max(L2, frame.q.col(k).head<2>().squaredNorm());
    const double w2 = robot.w.col(k).squaredNorm();
    if (w2 > 0.0) {
      out.anisotropic = true;
    }
  }
  out.L = L2 > 0.0 ? std::sqrt(L2) : 1.0;
  out.inv_L = 1.0 / out.L;
  if (out.anisotropic) {
    for (int k = 0; k < frame.legs(); ++k) {
      frame.work_n(k) = 1.0 / (1.0 + std::sqrt(1.0 + robot.w.col(k).squaredNorm()));
    }
  }
  return out;
}

Contacts viscous_balance(const contact::Robot& robot, contact::Frame& frame, Eigen::Matrix3d& M,
                         Eigen::Vector3d& b) {
  // Scalars, not 2 × 2 temporaries: this loop is most of a viscous solve's per-foot cost.
  Contacts out;
  double L2 = 0.0;
  double m00 = 0.0, m01 = 0.0, m02 = 0.0, m11 = 0.0, m12 = 0.0, m22 = 0.0;
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = friction_weight(robot, frame, k);
    frame.work_n(k) = c;
    if (c == 0.0) {
      continue;
    }
    ++out.active;
    out.c_sum += c;
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    L2 = std::max(L2, qx * qx + qy * qy);
    // c G = c (I + w wᵀ), the unscaled lever s = S q = (−q_y, q_x), and c G s, c G q̇.
    const double w0 = robot.w(0, k);
    const double w1 = robot.w(1, k);
    out.anisotropic = out.anisotropic || w0 != 0.0 || w1 != 0.0;
    const double g00 = c * (1.0 + w0 * w0);
    const double g01 = c * w0 * w1;
    const double g11 = c * (1.0 + w1 * w1);
    const double gs0 = -g00 * qy + g01 * qx;
    const double gs1 = -g01 * qy + g11 * qx;
    const double gq0 = g00 * frame.qdot(0, k) + g01 * frame.qdot(1, k);
    const double gq1 = g01 * frame.qdot(0, k) + g11 * frame.qdot(1, k);
    m00 += g00;
    m01 += g01;
    m11 += g11;
    m02 += gs0;
    m12 += gs1;
    m22 += -qy * gs0 + qx * gs1;
    b0 += gq0;
    b1 += gq1;
    b2 += -qy * gq0 + qx * gq1;
  }
  out.L = L2 > 0.0 ? std::sqrt(L2) : 1.0;
  out.inv_L = 1.0 / out.L;
  const double il = out.inv_L;
  M << m00, m01, m02 * il, m01, m11, m12 * il, m02 * il, m12 * il, m22 * il * il;
  b << b0, b1, b2 * il;
  return out;
}

bool Psd3::ldlt(const Eigen::Matrix3d& M, double pivot_tol) {
  // Unpivoted LDLᵀ of a symmetric matrix; a pivot ≤ pivot_tol · trace means "not definite".
  // Written through the leading minors m₁, m₂, m₃ (d₀ = m₁, d₁ = m₂/m₁, d₂ = m₃/m₂), so that the
  // three divisions are independent instead of chained, and the reciprocal pivots are kept for
  // solve(): a 3 × 3 solve sits on the serial path of every Newton step, where latency shows.
  const double floor = pivot_tol * std::max(M.trace(), 0.0);
  const double m1 = M(0, 0);
  const double m2 = M(0, 0) * M(1, 1) - M(1, 0) * M(1, 0);
  const double c0 = M(1, 1) * M(2, 2) - M(2, 1) * M(2, 1);
  const double c1 = M(2, 0) * M(2, 1) - M(1, 0) * M(2, 2);
  const double c2 = M(1, 0) * M(2, 1) - M(2, 0) * M(1, 1);
  const double m3 = M(0, 0) * c0 + M(1, 0) * c1 + M(2, 0) * c2;
  if (!(m1 > floor && m2 > floor * m1 && m3 > floor * m2)) {
    return false;
  }
  const double i1 = 1.0 / m1;
  const double i2 = 1.0 / m2;
  const double i3 = 1.0 / m3;
  d_ << m1, m2 * i1, m3 * i2;
  inv_d_ << i1, m1 * i2, m2 * i3;
  l10_ = M(1, 0) * i1;
  l20_ = M(2, 0) * i1;
  l21_ = (M(2, 1) * M(0, 0) - M(2, 0) * M(1, 0)) * i2;
  return true;
}

bool Psd3::factorize_definite(const Eigen::Matrix3d& M, double pivot_tol) {
  chol_ = ldlt(M, pivot_tol);
  rank_ = chol_ ? 3 : -1;
  return chol_;
}

bool Psd3::factorize(const Eigen::Matrix3d& M) {
  if (ldlt(M, kRankTol)) {
    chol_ = true;
    rank_ = 3;
    return true;
  }
  chol_ = false;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M);
  const Eigen::Vector3d& lam = es.eigenvalues();
  const double floor = kRankTol * std::max(lam.cwiseAbs().sum(), 0.0);
  V_ = es.eigenvectors();
  rank_ = 0;
  for (int i = 0; i < 3; ++i) {
    if (lam(i) > floor && floor > 0.0) {
      inv_lambda_(i) = 1.0 / lam(i);
      ++rank_;
    } else {
      inv_lambda_(i) = 0.0;
    }
  }
  return false;
}

Eigen::Vector3d Psd3::solve(const Eigen::Vector3d& b) const {
  if (chol_) {
    // L z = b, D w = z, Lᵀ x = w.
    const double z0 = b(0);
    const double z1 = b(1) - l10_ * z0;
    const double z2 = b(2) - l20_ * z0 - l21_ * z1;
    const double x2 = z2 * inv_d_(2);
    const double x1 = z1 * inv_d_(1) - l21_ * x2;
    const double x0 = z0 * inv_d_(0) - l10_ * x1 - l20_ * x2;
    return {x0, x1, x2};
  }
  return V_ * inv_lambda_.cwiseProduct(V_.transpose() * b);
}

Eigen::Matrix3d Psd3::inverse() const {
  if (chol_) {
    Eigen::Matrix3d inv;
    for (int j = 0; j < 3; ++j) {
      inv.col(j) = solve(Eigen::Vector3d::Unit(j));
    }
    return inv;
  }
  return V_ * inv_lambda_.asDiagonal() * V_.transpose();
}

void Psd3::add_null_space(Eigen::Matrix3d& A, double scale) const {
  if (chol_ || rank_ == 3) {
    return;
  }
  for (int i = 0; i < 3; ++i) {
    if (inv_lambda_(i) == 0.0) {
      A += scale * V_.col(i) * V_.col(i).transpose();
    }
  }
}

Eigen::Vector3d Psd3::project_to_range(const Eigen::Vector3d& y) const {
  if (chol_ || rank_ == 3) {
    return y;
  }
  Eigen::Vector3d out = y;
  for (int i = 0; i < 3; ++i) {
    if (inv_lambda_(i) == 0.0) {
      out -= V_.col(i) * V_.col(i).dot(y);
    }
  }
  return out;
}

void mark_non_finite(contact::Frame& frame) {
  frame.friction.converged = false;
  frame.friction.message =
      "the body velocity or the forces are not finite (inputs outside the model's ranges)";
}

}  // namespace slipwalk::friction::detail
