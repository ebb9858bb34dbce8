// The Newton route of the spring-support search (thesis §3.3; U, its gradient and its Hessian are
// derived in spring_support.cpp).
//
// Why a second route. Alg. 1 follows a path through the cells of the contact planes, and every
// contact change is a scan of all feet with per-foot tie rules; with its start, polish and outputs
// that makes ~10 scalar passes of ~5 ns per foot (bench_friction's disk robots) for about two
// contact changes per frame, whatever N.
//
// The route. U is convex, C¹ and piecewise quadratic; on the cell of a contact set C it equals the
// quadratic U_C, so from any state v the minimizer of U_C is one Newton step away,
//   v⁺ = v − H_C⁻¹ ∇U_C(v),   H_C = Σ_C K a aᵀ,   ∇U_C(v) = Σ_C K h a + Mg e_z,
// with a_j = (q_y, −q_x, 1) in the unscaled state v = (α, β, z). Reading the contact set off the
// heights at v⁺ and repeating is the semismooth Newton method on ∇U = 0 (the active-set method for
// this piecewise quadratic). Each step is one pass over the feet, four at a time (an AVX2 clone
// where the CPU has it, else pairs of SSE2 registers: same operations, hence the same rounding —
// the clone leaves out FMA for that), with no branch on data, and a 3 × 3 solve by cofactors (one
// division). Its Newton system is solved in the scaled state (αL, βL, z) of spring_support.cpp.
// Two cold starts (a start is only a start: the certificate below does not depend on it):
//  * All feet (fewer than kLevelStartLegs legs): the all-feet cell at v = 0, whose Newton step is
//    the least-squares plane of all feet. From there each step drops about half of the feet still
//    in the cell, like a bisection of the contact set, so the steps grow with log N
//    (bench_friction's disk robots: 1.0 at 3 legs, 2.3 at 6, 3.2 at 12, 4.0 at 24, 4.7 at 50).
//  * Level (kLevelStartLegs legs or more): the cell of the feet below a height just under the
//    balance of the level body, §3.3.1's z* (level_height(): Newton steps in z alone, each a pass
//    of two sums). That cell holds every foot the level balance stands on and few more, so what is
//    left is mostly the tilt: 2.5 steps at 12 legs, 2.4 at 24, 2.5 at 50 on bench_friction's
//    disks; 1.7–1.8 from 12 to 50 legs on the cost study's frames, where the all-feet start takes
//    2.2–2.9. It costs a pass of its own (the start cell) besides its passes in z. In instructions
//    that pays from about 12 legs (callgrind, the whole model on BM_ModelViscous's disks: 2.6 %
//    fewer at 12 legs, 9 % at 24, 11 % at 50), in time only from about 20: builds run alternately
//    (the cost study's support rows, smallest of 15 runs), the level start took the support 12–13 %
//    longer at 12 legs and 4 % at 16, 1–3 % less at 20, 9 % less at 24 and 7 % at 50
//    (bench_friction, scripts/bench_ab.py: 3 % longer at 12 legs, 12–18 % less at 24 and 50). On a
//    few legs the tilt is most of the answer and this start leaves fewer than three feet down more
//    often than the all-feet start (14 % more instructions at 6 legs, 49 % at 3). Where it does not
//    certify, the all-feet start follows before the path search.
// Warm start (SupportOptions::warm_start): from a previous balance v0 and the feet below its plane
// there. Along a trajectory that is usually the answer's cell already, so one step and its
// confirming pass certify, where the all-feet start needs a second step whenever a foot is lifted.
//
// Certificate. Stop when the contact set read off the heights at v (the outputs' convention:
// h_j < 0 beyond the rounding error of the heights, Rows::noise) equals the set the step to v was
// computed on; then the gradient that pass summed is ∇U(v) itself, and it must be zero to rounding
// (the balance residual of SupportSummary ≤ 1e-14, or no longer halved by a further refinement step
// while ≤ 1e-10). The cell's Hessian must be safely definite, λ_min(H̃) > 1e-10 tr(H̃) (checked as 4
// det H̃ > 1e-10 tr(H̃)³, since λ_min ≥ det/(tr/2)²): then U is strictly convex around v, the
// stationary point is its unique global minimizer, and the path search ends at the same state —
// provided no foot sits at its plane (within kNearPlane × rounding): such a foot carries nothing
// and may be all that makes the cell definite, so those frames go to the path too.
// Anything else (fewer than three contacts off a line on the way, the CoM outside the support,
// a cycling contact set — semismooth Newton without a line search is not globally convergent —
// or more than kMaxSteps steps) returns false and the caller runs Alg. 1.
#include "contact/support_newton.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include "core/lanes.hpp"

namespace slipwalk::contact::detail {

namespace {

// From this many legs the cold start is the level start (see the top: where it starts to save
// time, not instructions). Its height takes steps in z alone until one is taken from a cell of at
// most kLevelCellFeet feet or where the feet carry at most kLevelNear × Mg (close to the level
// balance, however many feet it stands on), at most kLevelSteps.
constexpr int kLevelStartLegs = 20;
constexpr int kLevelCellFeet = 24;
constexpr double kLevelNear = 4.0;
constexpr int kLevelSteps = 8;
// The padding foot (odd N) sits this far above the ground: never in contact, K = 0.
constexpr double kAboveGround = 1e300;
// A moment the contacts cannot take below kFlatTilt × Mg is zero (spring_support.cpp's kFlatTol).
constexpr double kFlatTilt = 1e-12;

// The rows of frame.support_newton in the order the passes index them: the feet's a_j, q_z,j and
// K_j (the contact flags of the last pass, lane masks, are a row of their own: Rows::on).
enum Row : int { kY = 0, kMinusX, kQz, kK, kRows };

// One pass handles four feet at a time in core::Lanes (an AVX2 clone of support_by_newton where
// the CPU has it, else pairs of SSE2 registers: the same rounding).
using core::Lanes;

struct Rows {
  const double* in[kRows];
  std::int64_t* on;
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

// The quadratic model of U on the contact set read off at v, and which feet changed set.
struct Cell {
  Eigen::Matrix3d H;      // Σ_C K a aᵀ
  Eigen::Vector3d g;      // Σ_C K h a + Mg e_z = (M_x, M_y, Mg − ΣF_z)
  Lanes<4>::M changed{};  // per lane, minus the count of feet whose flag changed
  [[nodiscard]] bool settled() const { return !core::any(changed); }
};

// The sums of one pass, per lane. Ten accumulators: with the temporaries of a step they fit the
// sixteen vector registers of x86-64, where an eleventh (the count of feet near their plane) was
// kept in memory and put a store and a load on the loop's critical path; that count is needed
// only where a pass may certify, and is taken with the outputs there (loads_unless_near()).
struct Sums {
  using V = Lanes<4>::V;
  V k{}, y{}, x{}, yy{}, yx{}, xx{}, gy{}, gx{}, gz{};
  Lanes<4>::M changes{};  // minus the count of feet whose flag changed (integer lanes)
};

// The quadratic model of the sums, written into c (the Newton loop's own cell, in place).
[[gnu::always_inline]] inline void cell_of(const Sums& s, double Mg, Cell& c) {
  const Sums::V first = core::lane_sums(s.k, s.y, s.x, s.yy);
  const Sums::V second = core::lane_sums(s.yx, s.xx, s.gy, s.gx);
  const double sy = first[1];
  const double sx = first[2];
  const double syx = second[0];
  c.H << first[3], syx, sy,  //
      syx, second[1], sx,    //
      sy, sx, first[0];
  c.g << second[2], second[3], Lanes<4>::sum(s.gz) + Mg;
  c.changed = s.changes;
}

// Feet j … j + 3 of a pass at v (see pass()).
[[gnu::always_inline]] inline void add_feet(const Rows& R, Eigen::Index j, const Eigen::Vector3d& v,
                                            double threshold, Sums& s) {
  using L = Lanes<4>;
  using V = L::V;
  const V y = L::load(R.in[kY] + j);
  const V x = L::load(R.in[kMinusX] + j);
  const V h = y * L::splat(v(0)) + x * L::splat(v(1)) + (L::load(R.in[kQz] + j) + L::splat(v(2)));
  const L::M touching = h < L::splat(threshold);
  s.changes += touching ^ L::load(R.on + j);  // −1 where the flag changed
  L::store(R.on + j, touching);
  accumulate_cell(s, L::select(touching, L::load(R.in[kK] + j)), y, x, h);
}

// One pass over the feet at v, four at a time, into c: the feet with h_j < threshold (by default
// −noise, Rows::noise: the outputs' contact convention) make the cell; their flags are stored in
// Rows::on and compared with the previous ones.
[[gnu::always_inline]] inline void pass(const Rows& R, const Eigen::Vector3d& v, double Mg,
                                        double threshold, Cell& c) {
  Sums s;
  for (Eigen::Index j = 0; j < R.cols; j += 4) {  // the rows' length is a multiple of four
    add_feet(R, j, v, threshold, s);
  }
  cell_of(s, Mg, c);
}

// The outputs at a certified v, four feet at a time: the contact flags of the last pass and
// the loads of eq. 3.7, F_z = −K h. Returns whether a foot is within kNearPlane × the heights'
// rounding error (Rows::noise) of its plane, either side (h² ≤ margin², no abs needed; the
// padding feet are far above): then the outputs are the path search's to write over. (Plain
// pointers: a store through char* may alias anything, and through the frame's members it would
// reload every pointer at every foot.)
[[gnu::always_inline]] inline bool loads_unless_near(const Rows& R, const Eigen::Vector3d& v,
                                                     Eigen::Index n, char* contact, double* Fz) {
  using L = Lanes<4>;
  using V = L::V;
  const double margin = kNearPlane * R.noise(v);
  L::M near{};
  for (Eigen::Index j = 0; j < n; j += 4) {
    const V h = L::load(R.in[kY] + j) * L::splat(v(0)) +
                L::load(R.in[kMinusX] + j) * L::splat(v(1)) +
                (L::load(R.in[kQz] + j) + L::splat(v(2)));
    near |= h * h <= L::splat(margin * margin);
    const L::M on = L::load(R.on + j);
    core::store_flags(contact, n, j, on);
    core::store_padded(Fz, n, j, L::select(on, -L::load(R.in[kK] + j) * h));
  }
  return core::any(near);
}

// dv = −H⁻¹ g of the cell (cell_newton_step, support_newton.hpp: in the scaled state, by the
// adjugate); false when H̃ is not safely definite (see the top).
[[gnu::always_inline]] inline bool newton_step(const Cell& c, double il, Eigen::Vector3d& dv) {
  double d0 = 0.0;
  double d1 = 0.0;
  double d2 = 0.0;
  if (!cell_newton_step(c.H(0, 0), c.H(1, 0), c.H(1, 1), c.H(2, 0), c.H(2, 1), c.H(2, 2), c.g(0),
                        c.g(1), c.g(2), il, d0, d1, d2)) {
    return false;
  }
  dv = Eigen::Vector3d(d0, d1, d2);
  return true;
}

// SupportSummary::residual from the gradient: max(|Mg − ΣF_z|/Mg, |M_x|/(Mg L), |M_y|/(Mg L)),
// with inv_mg = 1/Mg and il = 1/L (multiplications: it sits on the serial path of every step).
double residual(const Cell& c, double inv_mg, double il) {
  return std::max({std::abs(c.g(2)), std::abs(c.g(0)) * il, std::abs(c.g(1)) * il}) * inv_mg;
}

// The part of the scaled gradient g̃ = D⁻¹ g in the null space of the scaled Hessian
// H̃ = D⁻¹ H D⁻¹ = Σ_C K ã ãᵀ of a cell that is not safely definite (ã_j = D⁻¹ a_j). One or two
// contacts (what an overshoot usually leaves) in closed form: the null space is the plane ⟂ ã₁,
// or the line along ã₁ × ã₂. Otherwise (none, three or more on a line, or two so close to one
// point that the cross product is rounding) the eigenvectors of H̃ below kDefiniteTol · tr H̃.
Eigen::Vector3d null_part(const Rows& R, int n, const Cell& cell, const Eigen::Vector3d& scale) {
  const Eigen::Vector3d g = cell.g.cwiseQuotient(scale);
  int count = 0;
  int on[2] = {-1, -1};
  for (int j = 0; j < n; ++j) {
    if (R.on[j] != 0) {
      if (count < 2) {
        on[count] = j;
      }
      ++count;
    }
  }
  const auto a = [&R, &scale](int j) {
    return Eigen::Vector3d(R.in[kY][j] / scale(0), R.in[kMinusX][j] / scale(1), 1.0);
  };
  if (count == 1) {
    const Eigen::Vector3d a1 = a(on[0]);
    return g - a1 * (a1.dot(g) / a1.squaredNorm());
  }
  if (count == 2) {
    const Eigen::Vector3d a1 = a(on[0]);
    const Eigen::Vector3d a2 = a(on[1]);
    const Eigen::Vector3d axis = a1.cross(a2);
    const double axis2 = axis.squaredNorm();
    if (axis2 > 1e-8 * a1.squaredNorm() * a2.squaredNorm()) {  // sin² of their angle > 1e-8
      return axis * (axis.dot(g) / axis2);
    }
  }
  const Eigen::Matrix3d H =
      scale.cwiseInverse().asDiagonal() * cell.H * scale.cwiseInverse().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(H);
  const double floor = kDefiniteTol * std::max(H.trace(), 0.0);
  Eigen::Vector3d g_null = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (es.eigenvalues()(i) <= floor) {
      g_null += es.eigenvectors().col(i) * es.eigenvectors().col(i).dot(g);
    }
  }
  return g_null;
}

// A step from a cell that is not safely definite: fewer than three contacts off a line at v
// (the previous step overshot). Its quadratic has no minimizer; Alg. 1 would tilt here (eqs.
// 3.11, 3.12: d = −g_N, the moment the contacts cannot take, spring_support.cpp), keeping every
// contact's compression, until the first foot in the air touches down. So does this step: the
// tilt to that touch-down, then the Newton step of the cell with that foot added (the body turns
// onto the next foot and settles on the new cell's balance), repeated while the cell is still
// not definite (one contact: two tilts). It changes only where the route goes, never what it
// certifies (the checks at the end are those of every step). Returns false where Alg. 1 ends:
// nothing stops the tilt (the robot tips), or the CoM is over the contacts' line or point (no
// tilt: a line or point support), or kMaxTilts tilts did not give a definite cell.
constexpr int kMaxTilts = 3;
// (The caller passes copies of its state and cell and takes the step as the result: a reference to
// its own would make it keep them in memory, a store and a reload on the serial path of every
// step, tilted or not.)
std::optional<Eigen::Vector3d> tilt_step(const Rows& R, int n, const Eigen::Vector3d& v, double Mg,
                                         double L, double il, Cell cell) {
  const Eigen::Vector3d scale(L, L, 1.0);  // scaled state ũ = D v (spring_support.cpp)
  Eigen::Vector3d at = v;
  for (int tilt = 0; tilt < kMaxTilts; ++tilt) {
    const Eigen::Vector3d g_null = null_part(R, n, cell, scale);
    if (!(g_null.norm() > kFlatTilt * Mg)) {
      return std::nullopt;  // nothing to tilt: a line or point support under the CoM
    }
    const Eigen::Vector3d d = (-g_null).cwiseQuotient(scale);
    // The first foot in the air to touch down along at + t d (contacts keep their heights).
    double t = kInf;
    int first = -1;
    for (int j = 0; j < n; ++j) {
      if (R.on[j] != 0) {
        continue;
      }
      const double r = R.in[kY][j] * d(0) + R.in[kMinusX][j] * d(1) + d(2);
      const double h = R.in[kY][j] * at(0) + R.in[kMinusX][j] * at(1) + (R.in[kQz][j] + at(2));
      if (r < 0.0 && std::max(h, 0.0) < t * -r) {
        t = std::max(h, 0.0) / -r;
        first = j;
      }
    }
    if (first < 0) {
      return std::nullopt;  // the robot tips: Alg. 1 reports it
    }
    at += t * d;
    // The cell of the contacts and the foot that touched down (at its plane now, h ≈ 0).
    const double h_first =
        R.in[kY][first] * at(0) + R.in[kMinusX][first] * at(1) + (R.in[kQz][first] + at(2));
    pass(R, at, Mg, std::nextafter(std::max(h_first, -R.noise(at)), kInf), cell);
    Eigen::Vector3d dv;
    if (newton_step(cell, il, dv)) {
      return Eigen::Vector3d(dv + (at - v));
    }
  }
  return std::nullopt;
}

// Where the Newton steps start (see the top): the all-feet cell at v = 0, the balance of the level
// body (a cell near the answer's, for many legs), or a previous balance (warm).
enum class Start { kAllFeet, kLevel, kWarm };

// Writes the feet into the rows (the padding feet far above the ground, K = 0) and sums the start
// cell at v0, four feet at a time: q is 3 × N column-major (core::load_columns3). All feet (at
// v0 = 0): every foot with K > 0 (h = q_z). Level: only Σ K and Σ K q_z over all feet (in Sums::k
// and Sums::gz), where level_height() begins. Warm: the feet with h_j(v0) < 0, the
// contact set of the previous balance where v0 is that balance and the feet moved little. Also the
// largest |q_y|, |q_x|, |q_z| (Rows::size) and q_x² + q_y² over the feet. A NaN coordinate reaches
// the sums either way: a foot out of the cell enters them with weight 0, and 0 · NaN is NaN (the
// level start's sums carry only q_z; its start cell's pass carries the rest).
template <Start kStart>
[[gnu::always_inline]] inline Sums rows_and_start(const Robot& robot, const Frame& frame,
                                                  const Eigen::Vector3d& v0, double* const* row,
                                                  std::int64_t* on, Eigen::Index cols,
                                                  Eigen::Vector3d& size, double& size2) {
  using L = Lanes<4>;
  using V = L::V;
  const Eigen::Index n = frame.q.cols();
  const double* const q = frame.q.data();
  const double* const K = robot.K.data();
  Sums s;
  V max_y{};
  V max_x{};
  V max_z{};
  V max_r2{};
  for (Eigen::Index j = 0; j < cols; j += 4) {
    V x;
    V y;
    V z;
    core::load_columns3(q, n, j, x, y, z);
    const V k = core::load_padded(K, n, j);
    const V z_row = core::lanes_below(j, n) ? z : L::splat(kAboveGround);
    const V minus_x = -x;
    L::store(row[kY] + j, y);
    L::store(row[kMinusX] + j, minus_x);
    L::store(row[kQz] + j, z_row);
    L::store(row[kK] + j, k);
    max_y = max_y < L::abs(y) ? L::abs(y) : max_y;
    max_x = max_x < L::abs(x) ? L::abs(x) : max_x;
    max_z = max_z < L::abs(z) ? L::abs(z) : max_z;
    const V r2 = x * x + y * y;
    max_r2 = max_r2 < r2 ? r2 : max_r2;
    if constexpr (kStart == Start::kWarm) {
      const V h = y * L::splat(v0(0)) + minus_x * L::splat(v0(1)) + (z_row + L::splat(v0(2)));
      const L::M touching = h < L::splat(0.0);
      L::store(on + j, touching);
      accumulate_cell(s, L::select(touching, k), y, minus_x, h);
    } else if constexpr (kStart == Start::kLevel) {
      s.k += k;
      s.gz += k * z;  // the start cell's pass writes the flags
    } else {
      L::store(on + j, k > L::splat(0.0));
      accumulate_cell(s, k, y, minus_x, z);  // the all-feet cell at v = 0: h = q_z, weight K
    }
  }
  size.setZero();
  size2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    size = size.cwiseMax(Eigen::Vector3d(max_y[i], max_x[i], max_z[i]));
    size2 = std::max(size2, max_r2[i]);
  }
  return s;
}

// The level start's height (thesis §3.3.1's z*, approached from below). With α = β = 0 the
// balance ΣF_z = Mg is a problem in z alone: F(z) = Σ K max(−(q_z + z), 0) = Mg, F convex and
// falling. The all-feet root z₀ = −(Mg + Σ K q_z)/Σ K (from the sums `all` of rows_and_start) is
// where the linear springs of every foot, pulling ones included, carry Mg; F is at least that sum,
// so F(z₀) ≥ Mg and z₀ ≤ z*. A Newton step on F from below stays below z* (F lies above its
// tangents, −Σ_{h<0} K being its slope to the right), so the feet below every height returned here
// include every foot the level balance stands on; and since F ≥ Mg > 0 at each height stepped
// from, some foot is below it and the stiffness a step divides by is positive. Each step is one
// pass of two sums (a quarter of a Newton pass's work) and, like the all-feet start, about halves
// the feet below; they stop after the one taken from a cell of at most kLevelCellFeet feet, which
// the Newton steps take on faster, or from a height where the feet carry at most kLevelNear × Mg,
// already near z*.
[[gnu::always_inline]] inline double level_height(const Rows& R, const Sums& all, double Mg) {
  using L = Lanes<4>;
  using V = L::V;
  double z = -(Mg + L::sum(all.gz)) / L::sum(all.k);
  for (int step = 0; step < kLevelSteps; ++step) {
    V stiffness{};
    V pull{};  // Σ K h over the feet below z: −F(z)
    L::M count{};
    for (Eigen::Index j = 0; j < R.cols; j += 4) {
      const V h = L::load(R.in[kQz] + j) + L::splat(z);
      const L::M below = h < L::splat(0.0);
      const V w = L::select(below, L::load(R.in[kK] + j));
      stiffness += w;
      pull += w * h;
      count -= below;
    }
    const double F = -L::sum(pull);
    z += (F - Mg) / L::sum(stiffness);
    if (count[0] + count[1] + count[2] + count[3] <= kLevelCellFeet || F <= kLevelNear * Mg) {
      break;
    }
  }
  return z;
}

// The route from v0 (all feet and level: 0; warm: the previous balance, see rows_and_start).
template <Start kStart>
[[gnu::always_inline]] inline bool newton_route(const Robot& robot, Frame& frame,
                                                const Eigen::Vector3d& v0) {
  const int n = frame.legs();
  SupportNewtonScratch& W = frame.support_newton;
  if (!W.holds(n)) {
    return false;  // a frame resized by hand: leave it to the path search
  }
  const Eigen::Index cols = W.qy.cols();
  // ---- the feet as rows, and the start cell at v0, in one pass --------------------------------
  double* const row[kRows] = {W.qy.data(), W.minus_qx.data(), W.qz.data(), W.K.data()};
  Eigen::Vector3d size;
  double size2 = 0.0;
  const Sums start = rows_and_start<kStart>(robot, frame, v0, row, W.on.data(), cols, size, size2);
  const double L = size2 > 0.0 ? std::sqrt(size2) : 1.0;
  const double il = 1.0 / L;
  const double Mg = robot.Mg;
  const double inv_mg = 1.0 / Mg;
  const Rows R{{row[kY], row[kMinusX], row[kQz], row[kK]}, W.on.data(), cols, size};

  // ---- Newton steps until the contact set repeats and the gradient vanishes -------------------
  SupportSummary& summary = frame.support;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Cell cell;
  if constexpr (kStart == Start::kLevel) {
    v(2) = level_height(R, start, Mg);
    pass(R, v, Mg, 0.0, cell);  // the start cell: the feet below the level start
  } else {
    if constexpr (kStart == Start::kWarm) {
      v = v0;
    }
    cell_of(start, Mg, cell);  // the start cell
  }
  // check_frame's range test of q, on the way: the largest |q_x|, |q_y|, |q_z| within
  // limits::kPosition (an infinity is the largest), and no NaN, which the maxima skip but the
  // start cell's sums Σ K q_y, Σ K q_x and Σ K h carry (a foot out of the cell has weight 0, and
  // 0 · NaN is NaN; a NaN q_z makes the level start's height NaN). Else the caller's check_frame
  // names the culprit.
  if (!(std::max({size(0), size(1), size(2)}) <= limits::kPosition.hi) ||
      std::isnan(cell.H(2, 0) + cell.H(2, 1) + cell.g(2))) {
    return false;
  }
  Lanes<4>::M changes{};  // per lane, minus the contact changes of all steps
  // The residual after the previous step, if its contact set was consistent. A warm start's cell
  // is the set read off the heights at v0 (h < 0; the outputs' convention differs only for feet
  // within rounding of their plane, which carry rounding), so its residual counts as one: from a
  // balance the first step's residual is rounding that a step no longer halves, and that step
  // certifies.
  double last = kStart == Start::kWarm ? residual(cell, inv_mg, il) : kInf;
  for (int step = 1; step <= kMaxSteps; ++step) {
    Eigen::Vector3d dv;
    if (!newton_step(cell, il, dv)) {
      // (A start cell that is not definite: all feet, when they lie on a line, with nothing to
      // tilt onto; warm, when the previous balance is no start, and the cold start follows;
      // level, when few feet are below its height, which tilt like any cell.)
      const std::optional<Eigen::Vector3d> tilted =
          step == 1 && kStart != Start::kLevel
              ? std::nullopt
              : tilt_step(R, n, Eigen::Vector3d(v), Mg, L, il, cell);
      if (!tilted) {
        summary.newton_steps = step - 1;
        return false;
      }
      dv = *tilted;
    }
    v += dv;
    pass(R, v, Mg, -R.noise(v), cell);
    changes += cell.changed;
    summary.newton_steps = step;
    if (!cell.settled()) {
      last = kInf;
      continue;
    }
    const double r = residual(cell, inv_mg, il);
    if (r <= kPolished || (r >= 0.5 * last && r <= kRoundingCap)) {
      // ---- certified: the outputs, with the loads of eq. 3.7 -------------------------------
      if (loads_unless_near(R, v, n, frame.contact.data(), frame.Fz.data())) {
        return false;  // not strictly complementary: let Alg. 1 handle the tie
      }
      frame.alpha = v(0);
      frame.beta = v(1);
      frame.z = v(2);
      summary.status = SupportSummary::Status::kBalanced;
      summary.route = SupportSummary::Route::kNewton;
      summary.iterations = static_cast<int>(-(changes[0] + changes[1] + changes[2] + changes[3]));
      summary.residual = r;
      return true;
    }
    last = r;
  }
  return false;
}

// The level start, then the all-feet start where it does not certify (so that no frame the
// all-feet start certifies goes to the path search; the steps of both are counted). A clone of its
// own, called only from kLevelStartLegs legs, as the warm route is, so that support_by_newton keeps
// for every smaller robot the code it had before the level start existed: with both routes inlined
// there, the support at 3 and 6 legs measured 4–6 % slower than before, and 0.98–1.03 of before
// this way (bench_friction and the cost study's rows, builds run alternately; identical builds
// differ by up to 2–3 %).
SLIPWALK_CLONES bool support_by_newton_level(const Robot& robot, Frame& frame) {
  if (newton_route<Start::kLevel>(robot, frame, Eigen::Vector3d::Zero())) {
    return true;
  }
  const int level_steps = frame.support.newton_steps;
  const bool certified = newton_route<Start::kAllFeet>(robot, frame, Eigen::Vector3d::Zero());
  frame.support.newton_steps += level_steps;
  return certified;
}

}  // namespace

SLIPWALK_CLONES bool support_by_newton(const Robot& robot, Frame& frame) {
  if (frame.legs() >= kLevelStartLegs) {
    return support_by_newton_level(robot, frame);  // a call: this clone stays as small as before
  }
  return newton_route<Start::kAllFeet>(robot, frame, Eigen::Vector3d::Zero());
}

SLIPWALK_CLONES bool support_by_newton_warm(const Robot& robot, Frame& frame,
                                            const Eigen::Vector3d& v0) {
  if (newton_route<Start::kWarm>(robot, frame, v0)) {
    return true;
  }
  // The previous balance was no start for these feet (fewer than three of them down there, or
  // no certificate from it): the cold start, with the steps of both counted.
  const int warm_steps = frame.support.newton_steps;
  const bool certified = support_by_newton(robot, frame);  // a call: this clone stays small
  frame.support.newton_steps += warm_steps;
  return certified;
}

}  // namespace slipwalk::contact::detail
