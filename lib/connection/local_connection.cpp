// The local connection (eq. 3.20, with the signs and the moment row of friction/balance.hpp):
// A_k = −c_k M⁻¹ J_kᵀ G_k, least norm (M⁺) when the contacts are one point. Two passes over the
// feet: the system (friction::ViscousSystem) and the columns of A.
#include "connection/local_connection.hpp"

#include <cstddef>

#include "core/lanes.hpp"

namespace slipwalk::connection {

namespace {

// A_k = −c_k P J_kᵀ G_k for every foot (P = M⁺). The isotropic instantiation (G = I, the usual
// robot) has no anisotropy terms: 6 multiply-adds per foot.
template <bool kAniso>
void columns(const contact::Robot& robot, contact::Frame& frame, const Eigen::Matrix3d& P,
             const double* weights) {
  const double p00 = P(0, 0), p01 = P(0, 1), p02 = P(0, 2);
  const double p10 = P(1, 0), p11 = P(1, 1), p12 = P(1, 2);
  const double p20 = P(2, 0), p21 = P(2, 1), p22 = P(2, 2);
  double* a = frame.A.data();  // column-major 3 × 2N: foot k's six entries are contiguous
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = weights[k];  // zero columns for a foot without friction (c = 0)
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    // c G = c (I + w wᵀ), and the third row of J_kᵀ G_k, (S q)ᵀ G.
    double g00 = c;
    double g01 = 0.0;
    double g11 = c;
    if constexpr (kAniso) {
      const double w0 = robot.w(0, k);
      const double w1 = robot.w(1, k);
      g00 = c * (1.0 + w0 * w0);
      g01 = c * w0 * w1;
      g11 = c * (1.0 + w1 * w1);
    }
    const double s0 = -qy * g00 + qx * g01;
    const double s1 = -qy * g01 + qx * g11;
    double* col = a + 6 * static_cast<std::ptrdiff_t>(k);
    col[0] = -(p00 * g00 + p01 * g01 + p02 * s0);
    col[1] = -(p10 * g00 + p11 * g01 + p12 * s0);
    col[2] = -(p20 * g00 + p21 * g01 + p22 * s0);
    col[3] = -(p00 * g01 + p01 * g11 + p02 * s1);
    col[4] = -(p10 * g01 + p11 * g11 + p12 * s1);
    col[5] = -(p20 * g01 + p21 * g11 + p22 * s1);
  }
}

// The isotropic columns from the rows the viscous assembly left (ViscousSystem::rows()): with
// G = I, J_kᵀ c_k = c_k [I; (S q_k)ᵀ], so the columns are −P (c, 0, −c q_y) and −P (0, c, c q_x):
// four products fewer per foot than columns<false>, and contiguous loads. Four feet at a time:
// their six entries each, a 6 × 4 block, are transposed in registers to A's layout (foot k's six
// entries side by side), so that four feet take six stores instead of twenty-four.
SLIPWALK_CLONES void columns_from_rows(contact::Frame& frame, const Eigen::Matrix3d& P) {
  using Row = contact::ViscousScratch::Row;
  using L = core::Lanes<4>;
  using V = L::V;
  const friction::detail::IsotropicColumns<V> columns{
      L::splat(P(0, 0)), L::splat(P(0, 1)), L::splat(P(0, 2)),  //
      L::splat(P(1, 0)), L::splat(P(1, 1)), L::splat(P(1, 2)),  //
      L::splat(P(2, 0)), L::splat(P(2, 1)), L::splat(P(2, 2))};
  const double* const cs = frame.viscous.rows.row(Row::kC).data();
  const double* const xs = frame.viscous.rows.row(Row::kQx).data();
  const double* const ys = frame.viscous.rows.row(Row::kQy).data();
  double* const a = frame.A.data();
  const Eigen::Index n = frame.legs();
  for (Eigen::Index j = 0; j < n; j += 4) {  // the rows are padded to a multiple of four
    V e[6];
    columns(L::load(cs + j), L::load(xs + j), L::load(ys + j), e);
    double* const col = a + 6 * j;
    if (j + 4 <= n) {
      // Lanes 0 and 2, then 1 and 3, of each pair of rows; then the four feet's runs of six.
      const V t01 = __builtin_shufflevector(e[0], e[1], 0, 4, 2, 6);
      const V t23 = __builtin_shufflevector(e[2], e[3], 0, 4, 2, 6);
      const V t45 = __builtin_shufflevector(e[4], e[5], 0, 4, 2, 6);
      const V u01 = __builtin_shufflevector(e[0], e[1], 1, 5, 3, 7);
      const V u23 = __builtin_shufflevector(e[2], e[3], 1, 5, 3, 7);
      const V u45 = __builtin_shufflevector(e[4], e[5], 1, 5, 3, 7);
      L::store(col, __builtin_shufflevector(t01, t23, 0, 1, 4, 5));
      L::store(col + 4, __builtin_shufflevector(t45, u01, 0, 1, 4, 5));
      L::store(col + 8, __builtin_shufflevector(u23, u45, 0, 1, 4, 5));
      L::store(col + 12, __builtin_shufflevector(t01, t23, 2, 3, 6, 7));
      L::store(col + 16, __builtin_shufflevector(t45, u01, 2, 3, 6, 7));
      L::store(col + 20, __builtin_shufflevector(u23, u45, 2, 3, 6, 7));
      continue;
    }
    for (Eigen::Index i = 0; j + i < n; ++i) {  // the last feet, entry by entry
      for (int r = 0; r < 6; ++r) {
        col[6 * i + r] = e[r][i];
      }
    }
  }
}

}  // namespace

void local_connection(const contact::Robot& robot, contact::Frame& frame,
                      const friction::ViscousSystem& system) {
  // With the unscaled lever S q_k in J_k = [I | S q_k], A_k = −c_k M⁺ J_kᵀ G_k.
  const Eigen::Matrix3d P = system.inverse();
  if (system.rows()) {
    columns_from_rows(frame, P);
  } else if (system.anisotropic()) {
    columns<true>(robot, frame, P, system.weights());
  } else {
    columns<false>(robot, frame, P, system.weights());
  }
}

void local_connection(const contact::Robot& robot, contact::Frame& frame) {
  local_connection(robot, frame, friction::ViscousSystem(robot, frame));
}

}  // namespace slipwalk::connection
