// The batched viscous-Coulomb balance and local connection (viscous_batch.hpp): the isotropic
// assembly of balance.cpp (viscous_balance_rows_of), Psd3's LDLᵀ through the leading minors, its
// solve and inverse, the columns of connection/local_connection.cpp (columns_from_rows) and the
// force pass of viscous_coulomb.cpp (viscous_forces_rows, finish) — each written once more with
// lane i holding frame i, because there one frame's feet fill the lanes and the sums end in
// reductions across them. Two passes over the feet: the gather and the sums (into the scratch's
// rows), then the columns of A and the forces, scattered into each frame.
#include "friction/viscous_batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/lanes.hpp"
#include "friction/balance.hpp"

namespace slipwalk::friction {

namespace {

using L = core::Lanes<4>;
using V = L::V;
using Mask = L::M;
constexpr int kLanes = 4;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

[[gnu::always_inline]] inline V max_of(V a, V b) { return a < b ? b : a; }

SLIPWALK_CLONES unsigned viscous_group(const contact::Robot& robot, contact::Frame* const* frames,
                                       int m, contact::BatchScratch& S) {
  const int n = robot.legs();
  // G = I for every foot (the isotropic assembly's test, viscous_balance_rows_of).
  if (!core::all_within(robot.w.data(), robot.w.size(), 0.0)) {
    return 0;
  }
  const double* q[kLanes];
  const double* qd[kLanes];
  const double* fz[kLanes];
  const char* down[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const contact::Frame& f = *frames[i < m ? i : 0];
    q[i] = f.q.data();
    qd[i] = f.qdot.data();
    fz[i] = f.Fz.data();
    down[i] = f.contact.data();
  }
  double* const xs = S.x.data();
  double* const ys = S.y.data();
  double* const dxs = S.dx.data();
  double* const dys = S.dy.data();
  double* const cs = S.c.data();
  const double* const mu = robot.mu.data();

  // ---- the system M̃ x = −b̃ of every lane (balance.hpp, isotropic: seven sums) ----------------
  V L2{};
  detail::IsotropicSums sums;
  for (std::ptrdiff_t j = 0; j < n; ++j) {
    const std::ptrdiff_t p = 3 * j;
    const V x{q[0][p], q[1][p], q[2][p], q[3][p]};
    const V y{q[0][p + 1], q[1][p + 1], q[2][p + 1], q[3][p + 1]};
    const V dx{qd[0][p], qd[1][p], qd[2][p], qd[3][p]};
    const V dy{qd[0][p + 1], qd[1][p + 1], qd[2][p + 1], qd[3][p + 1]};
    const Mask in_contact{down[0][j] != 0 ? -1 : 0, down[1][j] != 0 ? -1 : 0,
                          down[2][j] != 0 ? -1 : 0, down[3][j] != 0 ? -1 : 0};
    // friction_weight(): c = μ F_z for a foot in contact with finite positive c, else 0.
    const V cm = L::splat(mu[j]) * V{fz[0][j], fz[1][j], fz[2][j], fz[3][j]};
    const Mask on = in_contact & (cm > 0.0) & (cm < kInfinity);
    const V c = L::select(on, cm);
    L::store(cs + kLanes * j, c);
    L::store(xs + kLanes * j, x);
    L::store(ys + kLanes * j, y);
    L::store(dxs + kLanes * j, dx);
    L::store(dys + kLanes * j, dy);
    L2 = max_of(L2, L::select(on, x * x + y * y));
    sums.add(c, x, y, dx, dy);
  }
  V lever{};  // Contacts::set_lever_scale
  for (int i = 0; i < kLanes; ++i) {
    lever[i] = L2[i] > 0.0 ? std::sqrt(L2[i]) : 1.0;
  }
  const V il = 1.0 / lever;
  const V m00 = sums.c;
  const V m02 = -(sums.cy * il);
  const V m12 = sums.cx * il;
  const V m22 = sums.crr * il * il;
  const V b0 = sums.cdx;
  const V b1 = sums.cdy;
  const V b2 = sums.cm * il;

  // ---- Psd3::factorize's LDLᵀ (m01 = 0, m11 = m00): safely definite, or the caller's ----------
  const V floor = detail::kRankTol * max_of((m00 + m00) + m22, V{});
  const V m2 = m00 * m00;
  const V c0 = m00 * m22 - m12 * m12;
  const V c1 = m02 * m12;
  const V c2 = -(m02 * m00);
  const V m3 = m00 * c0 + m02 * c2;
  (void)c1;  // multiplies m01 = 0 in m3
  Mask solved = (m00 > floor) & (m2 > floor * m00) & (m3 > floor * m2) & (Mask{0, 1, 2, 3} < m);
  if (!core::any(solved)) {
    return 0;
  }
  const V i1 = 1.0 / m00;
  const V i2 = 1.0 / m2;
  const V i3 = 1.0 / m3;
  const V e0 = i1;
  const V e1 = m00 * i2;
  const V e2 = m2 * i3;
  const V l20 = m02 * i1;
  const V l21 = (m12 * m00) * i2;
  // Psd3::solve of −b̃ (l10 = 0), and v_body (set_velocity: ω = y₂ / L).
  const V z0 = -b0;
  const V z1 = -b1;
  const V z2 = -b2 - l20 * z0 - l21 * z1;
  const V y2 = z2 * e2;
  const V y1 = z1 * e1 - l21 * y2;
  const V y0 = z0 * e0 - l20 * y2;
  const V v0 = y0;
  const V v1 = y1;
  const V om = y2 / lever;
  // Psd3::inverse (n10 = 0), unscaled as ViscousSystem::inverse (row and column 2 over L).
  const V n20 = -l20;
  const V n21 = -l21;
  const V p00 = e0 + e2 * n20 * n20;
  const V p01 = e2 * n21 * n20;
  const V p11 = e1 + e2 * n21 * n21;
  const V p02 = e2 * n20 * il;
  const V p12 = e2 * n21 * il;
  const V p22 = e2 * il * il;
  const detail::IsotropicColumns<V> columns{p00, p01, p02, p01, p11, p12, p02, p12, p22};

  // ---- the columns of A (−P (c, 0, −c q_y), −P (0, c, c q_x)) and the forces F = −c u --------
  double* A[kLanes];
  double* F[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    A[i] = frames[i < m ? i : 0]->A.data();
    F[i] = frames[i < m ? i : 0]->Fxy.data();
  }
  V fx{}, fy{}, mz{}, dissipation{}, scale{};
  for (std::ptrdiff_t j = 0; j < n; ++j) {
    const V c = L::load(cs + kLanes * j);
    const V x = L::load(xs + kLanes * j);
    const V y = L::load(ys + kLanes * j);
    const V dx = L::load(dxs + kLanes * j);
    const V dy = L::load(dys + kLanes * j);
    V a[6];
    columns(c, x, y, a);
    const V u0 = v0 - om * y + dx;
    const V u1 = v1 + om * x + dy;
    const V F0 = -c * u0;
    const V F1 = -c * u1;
    for (int i = 0; i < m; ++i) {
      if (solved[i] == 0) {
        continue;
      }
      double* const col = A[i] + 6 * j;
      for (int e = 0; e < 6; ++e) {
        col[e] = a[e][i];
      }
      F[i][2 * j] = F0[i];
      F[i][2 * j + 1] = F1[i];
    }
    fx += F0;
    fy += F1;
    mz += x * F1 - y * F0;
    dissipation -= F0 * u0 + F1 * u1;
    scale += c * (L::abs(dx) + L::abs(dy) + L::abs(u0) + L::abs(u1));
  }

  // ---- the summaries (viscous_coulomb.cpp's finish) ------------------------------------------
  unsigned out = 0;
  for (int i = 0; i < m; ++i) {
    if (solved[i] == 0) {
      continue;
    }
    contact::Frame& f = *frames[i];
    f.v_body = Eigen::Vector3d(v0[i], v1[i], om[i]);
    detail::BalanceSum sum;
    sum.force << fx[i], fy[i];
    sum.moment = mz[i];
    auto& s = f.friction;
    s.converged = true;
    s.iterations = 0;
    s.certificate = 0.0;
    s.static_feet = 0;
    s.dissipation = dissipation[i];
    s.residual = sum.residual(scale[i], lever[i]);
    s.unique = true;  // rank 3
    s.message.clear();
    if (!std::isfinite(fx[i] + fy[i] + v0[i] + v1[i] + om[i] + s.residual + s.dissipation))
        [[unlikely]] {
      detail::mark_non_finite(f);
    }
    out |= 1U << static_cast<unsigned>(i);
  }
  return out;
}

}  // namespace

unsigned solve_viscous_coulomb_group(const contact::Robot& robot, contact::Frame* const* frames,
                                     int m, contact::BatchScratch& scratch) {
  if (!scratch.holds(robot.legs())) {
    scratch = contact::BatchScratch(robot.legs());
  }
  return viscous_group(robot, frames, m, scratch);
}

}  // namespace slipwalk::friction
