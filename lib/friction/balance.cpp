#include "friction/balance.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/lanes.hpp"
#include "core/sym3.hpp"

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
  out.set_lever_scale(L2);
  if (out.anisotropic) {
    for (int k = 0; k < frame.legs(); ++k) {
      frame.work_n(k) = 1.0 / (1.0 + std::sqrt(1.0 + robot.w.col(k).squaredNorm()));
    }
  }
  return out;
}

namespace {

// The scalar assembly for any robot (anisotropic feet, or a frame whose rows do not fit): scalars,
// not 2 × 2 temporaries, and no branch on the contact flags (a foot in the air, c = 0, adds exact
// zeros, so the contact pattern, which changes from frame to frame, is never mispredicted).
Contacts viscous_balance_general(const contact::Robot& robot, contact::Frame& frame,
                                 Eigen::Matrix3d& M, Eigen::Vector3d& b) {
  Contacts out;
  double L2 = 0.0;
  double c_sum = 0.0;
  double aniso = 0.0;  // Σ c (|w₀| + |w₁|): positive iff some foot with friction has w ≠ 0
  int active = 0;
  double m00 = 0.0, m01 = 0.0, m02 = 0.0, m11 = 0.0, m12 = 0.0, m22 = 0.0;
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = friction_weight(robot, frame, k);
    frame.work_n(k) = c;
    active += c > 0.0 ? 1 : 0;
    c_sum += c;
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    L2 = std::max(L2, c > 0.0 ? qx * qx + qy * qy : 0.0);
    // c G = c (I + w wᵀ), the unscaled lever s = S q = (−q_y, q_x), and c G s, c G q̇.
    const double w0 = robot.w(0, k);
    const double w1 = robot.w(1, k);
    aniso += c * (std::abs(w0) + std::abs(w1));
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
  out.active = active;
  out.c_sum = c_sum;
  out.anisotropic = aniso > 0.0;
  out.set_lever_squared(L2);
  out.unscaled = true;
  M << m00, m01, m02, m01, m11, m12, m02, m12, m22;
  b << b0, b1, b2;
  return out;
}

using Row = contact::ViscousScratch::Row;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The isotropic assembly (every foot G = I, the usual robot), which also leaves the feet as rows in
// frame.viscous (contact/robot.hpp) with their weights c_k. Returns false, with nothing assembled,
// for an anisotropic robot. kFromSupport: q_x, q_y and the contact flags are read from the padded
// rows the support's Newton route left in frame.support_newton (the same values: its certified
// outputs were written from them), four feet at a time with no partial last group and no
// conversion of the flags; otherwise from the frame's own (3 × N, chars). F_z from the frame (a
// row of the support's own would be one more buffer per frame to bring into the cache).
template <bool kFromSupport>
[[gnu::always_inline]] inline bool viscous_balance_rows_of(const contact::Robot& robot,
                                                           contact::Frame& frame,
                                                           Eigen::Matrix3d& M, Eigen::Vector3d& b,
                                                           Contacts& out) {
  using L = core::Lanes<4>;
  using V = L::V;
  const Eigen::Index n = frame.legs();
  auto& rows = frame.viscous.rows;
  double* const r[Row::kRows] = {rows.row(Row::kQx).data(), rows.row(Row::kQy).data(),
                                 rows.row(Row::kQdx).data(), rows.row(Row::kQdy).data(),
                                 rows.row(Row::kC).data()};
  // G = I for every foot: no anisotropy anywhere (checked on the robot, so that the pass below
  // carries no term for it; Robot::isotropic()'s test, inline in this clone).
  if (!core::all_within(robot.w.data(), robot.w.size(), 0.0)) {
    return false;
  }
  // One pass, four feet at a time: the feet into the rows (for the force pass after the solve and
  // the columns of A) and the sums of M and b with G = I (seven, where the general loop needs nine
  // and more products). The padding feet of the last group read as q = 0, c = 0.
  const double* const q = frame.q.data();
  const double* const qd = frame.qdot.data();
  const double* const Fz = frame.Fz.data();
  const double* const mu = robot.mu.data();
  const char* const contact = frame.contact.data();
  const contact::SupportNewtonScratch& W = frame.support_newton;
  V L2{};
  V active{};
  IsotropicSums sums;
  for (Eigen::Index j = 0; j < rows.cols(); j += 4) {  // a multiple of four
    V x;
    V y;
    V z;
    V dx;
    V dy;
    V dz;
    L::M down;
    if constexpr (kFromSupport) {
      y = L::load(W.qy.data() + j);
      x = -L::load(W.minus_qx.data() + j);
      down = L::load(W.on.data() + j);
    } else {
      core::load_columns3(q, n, j, x, y, z);
      down = core::load_flags(contact, n, j);
    }
    core::load_columns3(qd, n, j, dx, dy, dz);
    // friction_weight(): c = μ F_z for a foot in contact with finite positive c, else 0.
    const V cm = core::load_padded(mu, n, j) * core::load_padded(Fz, n, j);
    const L::M on = down & (cm > 0.0) & (cm < kInfinity);
    const V c = L::select(on, cm);
    L::store(r[Row::kC] + j, c);
    L::store(r[Row::kQx] + j, x);
    L::store(r[Row::kQy] + j, y);
    L::store(r[Row::kQdx] + j, dx);
    L::store(r[Row::kQdy] + j, dy);
    active += L::select(on, L::splat(1.0));
    const V rr = L::select(on, x * x + y * y);
    L2 = L2 < rr ? rr : L2;
    sums.add(c, x, y, dx, dy);
  }
  const V counts = core::lane_sums(active, sums.c, sums.cx, sums.cy);
  const V moments = core::lane_sums(sums.crr, sums.cdx, sums.cdy, sums.cm);
  out.active = static_cast<int>(counts[0]);
  out.c_sum = counts[1];
  out.anisotropic = false;
  out.rows = true;
  out.set_lever_squared(std::max(std::max(L2[0], L2[1]), std::max(L2[2], L2[3])));
  out.unscaled = true;
  const double sx = counts[2];
  const double sy = counts[3];
  M << out.c_sum, 0.0, -sy, 0.0, out.c_sum, sx, -sy, sx, moments[0];
  b << moments[1], moments[2], moments[3];
  return true;
}

SLIPWALK_CLONES bool viscous_balance_frame_rows(const contact::Robot& robot, contact::Frame& frame,
                                                Eigen::Matrix3d& M, Eigen::Vector3d& b,
                                                Contacts& out) {
  return viscous_balance_rows_of<false>(robot, frame, M, b, out);
}

SLIPWALK_CLONES bool viscous_balance_support_rows(const contact::Robot& robot,
                                                  contact::Frame& frame, Eigen::Matrix3d& M,
                                                  Eigen::Vector3d& b, Contacts& out) {
  return viscous_balance_rows_of<true>(robot, frame, M, b, out);
}

struct ForceLanes {
  using V = core::Lanes<4>::V;
  V fx{}, fy{}, mz{}, dissipation{}, scale{};
};

// Feet j … j + 3: their forces F = −c u written to Fxy (2 x N, foot by foot: interleaved in
// registers, two stores for four feet; lane by lane for the last, padded group) and summed.
[[gnu::always_inline]] inline void add_forces(const double* const* r, Eigen::Index j, int n,
                                              double* Fxy, double v0, double v1, double om,
                                              ForceLanes& s) {
  using L = core::Lanes<4>;
  using V = L::V;
  const V c = L::load(r[Row::kC] + j);
  const V x = L::load(r[Row::kQx] + j);
  const V y = L::load(r[Row::kQy] + j);
  const V dx = L::load(r[Row::kQdx] + j);
  const V dy = L::load(r[Row::kQdy] + j);
  const V u0 = L::splat(v0) - L::splat(om) * y + dx;
  const V u1 = L::splat(v1) + L::splat(om) * x + dy;
  const V F0 = -c * u0;  // zero for a foot without friction (c = 0) and the padding feet
  const V F1 = -c * u1;
  if (j + 4 <= n) {
    L::store(Fxy + 2 * j, __builtin_shufflevector(F0, F1, 0, 4, 1, 5));
    L::store(Fxy + 2 * j + 4, __builtin_shufflevector(F0, F1, 2, 6, 3, 7));
  } else {
    for (Eigen::Index i = 0; j + i < n; ++i) {
      Fxy[2 * (j + i)] = F0[i];
      Fxy[2 * (j + i) + 1] = F1[i];
    }
  }
  s.fx += F0;
  s.fy += F1;
  s.mz += x * F1 - y * F0;
  s.dissipation -= F0 * u0 + F1 * u1;
  s.scale += c * (L::abs(dx) + L::abs(dy) + L::abs(u0) + L::abs(u1));
}

}  // namespace

SLIPWALK_CLONES ForceSums viscous_forces_rows(contact::Frame& frame, double v0, double v1,
                                              double om) {
  auto& rows = frame.viscous.rows;
  const double* const r[Row::kRows] = {rows.row(Row::kQx).data(), rows.row(Row::kQy).data(),
                                       rows.row(Row::kQdx).data(), rows.row(Row::kQdy).data(),
                                       rows.row(Row::kC).data()};
  double* const Fxy = frame.Fxy.data();
  ForceLanes s;
  for (Eigen::Index j = 0; j < rows.cols(); j += 4) {  // a multiple of four
    add_forces(r, j, frame.legs(), Fxy, v0, v1, om, s);
  }
  const core::Lanes<4>::V sums = core::lane_sums(s.fx, s.fy, s.mz, s.dissipation);
  return {sums[0], sums[1], sums[2], sums[3], core::Lanes<4>::sum(s.scale)};
}

Contacts viscous_balance(const contact::Robot& robot, contact::Frame& frame, Eigen::Matrix3d& M,
                         Eigen::Vector3d& b, bool from_support) {
  Contacts out;
  const int n = frame.legs();
  if (!frame.viscous.fits(n)) {
    return viscous_balance_general(robot, frame, M, b);
  }
  // The support's rows, where its Newton route wrote this frame's outputs from them (the route of
  // this call: spring_support sets it on every call) and they have the viscous rows' length.
  const bool support_rows =
      from_support && frame.support.route == contact::SupportSummary::Route::kNewton &&
      frame.support_newton.holds(n) && frame.support_newton.qy.cols() == frame.viscous.rows.cols();
  if (support_rows ? viscous_balance_support_rows(robot, frame, M, b, out)
                   : viscous_balance_frame_rows(robot, frame, M, b, out)) {
    return out;
  }
  return viscous_balance_general(robot, frame, M, b);
}

bool Psd3::ldlt(const Eigen::Matrix3d& M, double pivot_tol, double L2) {
  // Unpivoted LDLᵀ of a symmetric matrix; a pivot ≤ pivot_tol · trace means "not definite".
  // Written through the leading minors m₁, m₂, m₃ (d₀ = m₁, d₁ = m₂/m₁, d₂ = m₃/m₂), so that the
  // three divisions are independent instead of chained, and the reciprocal pivots are kept for
  // solve(): a 3 × 3 solve sits on the serial path of every Newton step, where latency shows.
  // The test is that of D M D, D = diag(1, 1, 1/L): leading minors m₁, m₂ and m₃ / L², trace
  // T = M₀₀ + M₁₁ + M₂₂ / L², each side multiplied by L² (no division; L2 = 1: M's own test).
  const double floor = pivot_tol * std::max((M(0, 0) + M(1, 1)) * L2 + M(2, 2), 0.0);  // tol T L²
  const core::Sym3Adjugate<double> adj =
      core::sym3_adjugate(M(0, 0), M(1, 0), M(1, 1), M(2, 0), M(2, 1), M(2, 2));
  const double m1 = M(0, 0);
  const double m2 = adj.c22;
  const double m3 = adj.det;
  if (!(m1 * L2 > floor && m2 * L2 > floor * m1 && m3 > floor * m2)) {
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

bool Psd3::factorize_definite(const Eigen::Matrix3d& M, double pivot_tol, double L2) {
  chol_ = ldlt(M, pivot_tol, L2);
  rank_ = chol_ ? 3 : -1;
  return chol_;
}

bool Psd3::factorize(const Eigen::Matrix3d& M) {
  if (ldlt(M, kRankTol, 1.0)) {
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

void factorize_system(Psd3& solver, Contacts& cs, Eigen::Matrix3d& M, Eigen::Vector3d& b) {
  if (cs.unscaled && solver.factorize_definite(M, kRankTol, cs.L2)) {
    return;
  }
  if (cs.unscaled) {
    // M̃ = D M D and b̃ = D b, D = diag(1, 1, 1/L): the products of a scaled assembly, in its order.
    cs.set_lever_scale(cs.L2);
    const double il = cs.inv_L;
    M(0, 2) *= il;
    M(1, 2) *= il;
    M(2, 0) *= il;
    M(2, 1) *= il;
    M(2, 2) = M(2, 2) * il * il;
    b(2) *= il;
    cs.unscaled = false;
  }
  solver.factorize(M);
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
    // M⁻¹ = L⁻ᵀ D⁻¹ L⁻¹ with the unit lower triangular L⁻¹ = [1 0 0; −l₁₀ 1 0; n₂₀ −l₂₁ 1],
    // n₂₀ = l₂₁ l₁₀ − l₂₀, written out: independent products instead of three chained solves.
    const double n10 = -l10_;
    const double n20 = l21_ * l10_ - l20_;
    const double n21 = -l21_;
    const double e0 = inv_d_(0);
    const double e1 = inv_d_(1);
    const double e2 = inv_d_(2);
    Eigen::Matrix3d inv;
    inv(2, 2) = e2;
    inv(2, 1) = e2 * n21;
    inv(2, 0) = e2 * n20;
    inv(1, 1) = e1 + e2 * n21 * n21;
    inv(1, 0) = e1 * n10 + e2 * n21 * n20;
    inv(0, 0) = e0 + e1 * n10 * n10 + e2 * n20 * n20;
    inv(0, 1) = inv(1, 0);
    inv(0, 2) = inv(2, 0);
    inv(1, 2) = inv(2, 1);
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
