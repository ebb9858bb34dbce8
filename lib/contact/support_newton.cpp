// The Newton route of the spring-support search (thesis §3.3; U, its gradient and its Hessian are
// derived in spring_support.cpp).
//
// Why a second route. Alg. 1 follows a path through the cells of the contact planes, and every
// contact change is a scan of all feet with per-foot tie rules; with its start, polish and outputs
// that made ~10 scalar passes of ~5 ns per foot (54 ns per leg measured on the disk robots of
// bench_friction) for about two contact changes per frame, whatever N.
//
// The route. U is convex, C¹ and piecewise quadratic; on the cell of a contact set C it equals the
// quadratic U_C, so from any state v the minimizer of U_C is one Newton step away,
//   v⁺ = v − H_C⁻¹ ∇U_C(v),   H_C = Σ_C K a aᵀ,   ∇U_C(v) = Σ_C K h a + Mg e_z,
// with a_j = (q_y, −q_x, 1) in the unscaled state v = (α, β, z). Reading the contact set off the
// heights at v⁺ and repeating is the semismooth Newton method on ∇U = 0 (the active-set method for
// this piecewise quadratic). It starts from the all-feet cell (the least-squares plane of all feet,
// like §3.3.1's Newton on z*, which also starts from all feet) and usually needs two or three
// steps: each step is one pass over the feet, two feet per SSE2 instruction, with no branch on
// data. Its Newton system is solved in the scaled state (αL, βL, z) of spring_support.cpp.
//
// Certificate. Stop when the contact set read off the heights at v (the outputs' convention:
// h_j < 0 beyond the rounding error of h_j) equals the set the step to v was computed on; then
// the gradient that pass summed is ∇U(v) itself, and it must be zero to rounding (the balance
// residual of SupportSummary ≤ 1e-14, or no longer halved by a further refinement step while
// ≤ 1e-10). The cell's Hessian must be safely definite, λ_min(H̃) > 1e-10 tr(H̃) (checked as
// 4 det H̃ > 1e-10 tr(H̃)³, since λ_min ≥ det/(tr/2)²): then U is strictly convex around v, the
// stationary point is its unique global minimizer, and the path search ends at the same state.
// Anything else (fewer than three contacts off a line on the way, the CoM outside the support,
// a cycling contact set — semismooth Newton without a line search is not globally convergent —
// or more than kMaxSteps steps) returns false and the caller runs Alg. 1.
#include "contact/support_newton.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace slipwalk::contact::detail {

namespace {

// Two feet per SSE2 register. GCC/Clang vector extensions rather than Eigen arrays, because the
// per-foot contact test is a lane mask (Eigen 3.4 does not vectorize select()).
using V2 = double __attribute__((vector_size(16)));
using M2 = std::int64_t __attribute__((vector_size(16)));

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxSteps = 12;
constexpr double kDefiniteTol = 1e-10;  // λ_min(H̃) / tr(H̃) below this: leave it to the path
constexpr double kPolished = 1e-14;     // balance residual that needs no refinement
constexpr double kRoundingCap = 1e-10;  // a stalled refinement is accepted only below this
// The padding foot (odd N) sits this far above the ground: never in contact, K = 0.
constexpr double kAboveGround = 1e300;

// Rows of frame.work_rows: the feet's a_j, q_z,j and K_j, and the contact flags (1.0 / 0.0) of
// the last pass.
enum Row : int { kY = 0, kMinusX, kQz, kK, kOn, kRows };

V2 load(const double* p) {
  V2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
void store(double* p, V2 v) { std::memcpy(p, &v, sizeof v); }
V2 splat(double x) { return V2{x, x}; }
V2 select(M2 mask, V2 x) { return std::bit_cast<V2>(std::bit_cast<M2>(x) & mask); }
double lanes_sum(V2 v) { return v[0] + v[1]; }

struct Rows {
  const double* in[kOn];
  double* on;
  Eigen::Index cols;
  Eigen::Vector3d size;  // max |q_y|, max |q_x|, max |q_z| over the feet
  // The rounding error of every foot's height at v: h_j = a_j·v + q_z,j is computed to about
  // 4ε (|q_z,j| + |z| + |α q_y,j| + |β q_x,j|) (touching() in spring_support.cpp), bounded here
  // with the largest coordinates so that the passes need no per-foot term.
  [[nodiscard]] double noise(const Eigen::Vector3d& v) const {
    return 4.0 * kEps *
           (size(2) + std::abs(v(2)) + std::abs(v(0)) * size(0) + std::abs(v(1)) * size(1));
  }
};

// The quadratic model of U on the contact set read off at v, and how many feet changed set.
struct Cell {
  Eigen::Matrix3d H;  // Σ_C K a aᵀ
  Eigen::Vector3d g;  // Σ_C K h a + Mg e_z = (M_x, M_y, Mg − ΣF_z)
  double changes = 0.0;
};

// One pass over the feet at v. kAll: every foot counts (the start); else the feet with
// h_j < −noise (Rows::noise), whose flags are stored in row kOn and compared with the previous
// ones.
template <bool kAll>
Cell pass(const Rows& R, const Eigen::Vector3d& v, double Mg) {
  const V2 v0 = splat(v(0));
  const V2 v1 = splat(v(1));
  const V2 v2 = splat(v(2));
  const V2 threshold = splat(-R.noise(v));
  const V2 one = splat(1.0);
  V2 s_k{}, s_y{}, s_x{}, s_yy{}, s_yx{}, s_xx{}, g_y{}, g_x{}, g_z{}, changes{};
  for (Eigen::Index j = 0; j < R.cols; j += 2) {
    const V2 y = load(R.in[kY] + j);
    const V2 x = load(R.in[kMinusX] + j);
    const V2 K = load(R.in[kK] + j);
    const V2 h = y * v0 + x * v1 + (load(R.in[kQz] + j) + v2);  // eq. 3.6
    V2 w;
    V2 on;
    if constexpr (kAll) {
      w = K;
      on = select(K > splat(0.0), one);
    } else {
      const M2 touching = h < threshold;
      w = select(touching, K);
      on = select(touching, one);
      const V2 d = on - load(R.on + j);
      changes += d * d;
    }
    store(R.on + j, on);
    const V2 wy = w * y;
    const V2 wx = w * x;
    const V2 wh = w * h;
    s_k += w;
    s_y += wy;
    s_x += wx;
    s_yy += wy * y;
    s_yx += wy * x;
    s_xx += wx * x;
    g_y += wh * y;
    g_x += wh * x;
    g_z += wh;
  }
  Cell c;
  c.H << lanes_sum(s_yy), lanes_sum(s_yx), lanes_sum(s_y),  //
      lanes_sum(s_yx), lanes_sum(s_xx), lanes_sum(s_x),     //
      lanes_sum(s_y), lanes_sum(s_x), lanes_sum(s_k);
  c.g << lanes_sum(g_y), lanes_sum(g_x), lanes_sum(g_z) + Mg;
  c.changes = lanes_sum(changes);
  return c;
}

// dv = −H⁻¹ g, solved in the scaled state ũ = D v, D = diag(L, L, 1) (H̃ = D⁻¹ H D⁻¹,
// g̃ = D⁻¹ g) by an unpivoted LDLᵀ; false when H̃ is not safely definite (see the top).
bool newton_step(const Cell& c, double L, Eigen::Vector3d& dv) {
  const double il = 1.0 / L;
  const double h00 = c.H(0, 0) * il * il;
  const double h10 = c.H(1, 0) * il * il;
  const double h11 = c.H(1, 1) * il * il;
  const double h20 = c.H(2, 0) * il;
  const double h21 = c.H(2, 1) * il;
  const double h22 = c.H(2, 2);
  const double d0 = h00;
  if (!(d0 > 0.0)) {
    return false;
  }
  const double l10 = h10 / d0;
  const double l20 = h20 / d0;
  const double d1 = h11 - l10 * h10;
  if (!(d1 > 0.0)) {
    return false;
  }
  const double l21 = (h21 - l20 * h10) / d1;
  const double d2 = h22 - l20 * h20 - l21 * l21 * d1;
  const double tr = h00 + h11 + h22;
  if (!(d2 > 0.0) || !(4.0 * d0 * d1 * d2 > kDefiniteTol * tr * tr * tr)) {
    return false;
  }
  const double b0 = -c.g(0) * il;
  const double b1 = -c.g(1) * il - l10 * b0;
  const double b2 = -c.g(2) - l20 * b0 - l21 * b1;
  const double x2 = b2 / d2;
  const double x1 = b1 / d1 - l21 * x2;
  const double x0 = b0 / d0 - l10 * x1 - l20 * x2;
  dv = Eigen::Vector3d(x0 * il, x1 * il, x2);
  return true;
}

// SupportSummary::residual from the gradient: max(|Mg − ΣF_z|/Mg, |M_x|/(Mg L), |M_y|/(Mg L)).
double residual(const Cell& c, double Mg, double L) {
  return std::max(
      {std::abs(c.g(2)) / Mg, std::abs(c.g(0)) / (Mg * L), std::abs(c.g(1)) / (Mg * L)});
}

}  // namespace

bool support_by_newton(const Robot& robot, Frame& frame) {
  const int n = frame.legs();
  auto& W = frame.work_rows;
  if (W.rows() < kRows || W.cols() < n || W.cols() % 2 != 0) {
    return false;  // a frame resized by hand: leave it to the path search
  }
  // ---- the feet as rows, two per register; the padding foot far above the ground -------------
  double* row[kRows];
  for (int i = 0; i < kRows; ++i) {
    row[i] = W.row(i).data();
  }
  double size2 = 0.0;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  for (int j = 0; j < n; ++j) {
    const double qx = frame.q(0, j);
    const double qy = frame.q(1, j);
    const double qz = frame.q(2, j);
    row[kY][j] = qy;
    row[kMinusX][j] = -qx;
    row[kQz][j] = qz;
    row[kK][j] = robot.K(j);
    size = size.cwiseMax(Eigen::Vector3d(std::abs(qy), std::abs(qx), std::abs(qz)));
    size2 = std::max(size2, qx * qx + qy * qy);
  }
  for (Eigen::Index j = n; j < W.cols(); ++j) {
    for (int i = 0; i < kRows; ++i) {
      row[i][j] = 0.0;
    }
    row[kQz][j] = kAboveGround;
  }
  const double L = size2 > 0.0 ? std::sqrt(size2) : 1.0;
  const double Mg = robot.Mg;
  const Rows R{{row[kY], row[kMinusX], row[kQz], row[kK]}, row[kOn], W.cols(), size};

  // ---- Newton steps until the contact set repeats and the gradient vanishes -------------------
  SupportSummary& summary = frame.support;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Cell cell = pass<true>(R, v, Mg);  // the all-feet cell
  double changes = 0.0;
  double last = kInf;  // residual after the previous step, if its contact set was consistent
  for (int step = 1; step <= kMaxSteps; ++step) {
    Eigen::Vector3d dv;
    if (!newton_step(cell, L, dv)) {
      summary.newton_steps = step - 1;
      return false;
    }
    v += dv;
    cell = pass<false>(R, v, Mg);
    changes += cell.changes;
    summary.newton_steps = step;
    if (cell.changes != 0.0) {
      last = kInf;
      continue;
    }
    const double r = residual(cell, Mg, L);
    if (r <= kPolished || (r >= 0.5 * last && r <= kRoundingCap)) {
      // ---- certified: the outputs, with the loads of eq. 3.7 -------------------------------
      frame.alpha = v(0);
      frame.beta = v(1);
      frame.z = v(2);
      for (int j = 0; j < n; ++j) {
        const bool on = row[kOn][j] != 0.0;
        const double h = row[kY][j] * v(0) + row[kMinusX][j] * v(1) + (row[kQz][j] + v(2));
        frame.contact[static_cast<std::size_t>(j)] = on ? 1 : 0;
        frame.Fz(j) = on ? -robot.K(j) * h : 0.0;
      }
      summary.status = SupportSummary::Status::kBalanced;
      summary.route = SupportSummary::Route::kNewton;
      summary.iterations = static_cast<int>(changes);
      summary.residual = r;
      return true;
    }
    last = r;
  }
  return false;
}

}  // namespace slipwalk::contact::detail
