// The fused, warm-started substep of fast_kernel.hpp. The spring-support part follows
// contact/support_newton.cpp step for step (same state v = (α, β, z), same rows a_j = (q_y, −q_x,
// 1), same scaled Newton system, same certificate); only its start differs: the previous
// substep's state and contact set instead of the all-feet plane.
#include "planning/fast_kernel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "contact/spring_support.hpp"
#include "contact/support_newton.hpp"
#include "core/lanes.hpp"
#include "friction/solvers.hpp"
#include "planning/option_kernel.hpp"

// The 32-byte vectors of the batch never cross a call (internal, inlined helpers), so GCC's note
// that passing them without AVX would change the ABI does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace slipwalk::planning::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxSteps = 8;  // then contact::spring_support decides
// The support route's certificate (contact/support_newton.hpp): a residual that needs no
// refinement, the cap below which a stalled refinement is accepted, and the feet this close
// (× rounding) to their plane that send the frame to the path search.
using contact::detail::kNearPlane;
using contact::detail::kPolished;
using contact::detail::kRoundingCap;
// The viscous balance is solved here only when its pivots clear 1e-9 × trace, three decades
// above friction's rank tolerance (1e-12, friction/balance.hpp): nearer to singular, the
// reference decides the rank and its least-norm answer.
constexpr double kFrictionPivotTol = 1e-9;
// Below this |x| sin, cos and sinc are their Taylor series to x⁹, x¹⁰, x⁸; the first omitted term
// is below 0.05¹⁰/10! < 3e-20 relative.
constexpr double kSeriesBelow = 0.05;

/// One option's feet at one substep, as rows (support_newton.cpp's layout).
struct Feet {
  std::array<double, kMaxPlanLegs> y;   // q_y
  std::array<double, kMaxPlanLegs> mx;  // −q_x
  std::array<double, kMaxPlanLegs> z;   // q_z
  std::array<double, kMaxPlanLegs> dx;  // q̇_x
  std::array<double, kMaxPlanLegs> dy;  // q̇_y
};

/// One pass at v: the cell's quadratic model (H, ∇U) on the contact set, the contact set read off
/// the heights, and the viscous balance's sums on that set.
struct Cell {
  double h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;  // Σ_C K a aᵀ
  double g0 = 0, g1 = 0, g2 = 0;                                // Σ_C K h a + Mg e_z
  std::uint32_t on = 0;                                         // the contact set, leg bits
  bool near = false;  // a foot within kNearPlane × rounding of its plane
  // Σ c, Σ c (−q_y), Σ c q_x, Σ c ‖q_xy‖², Σ c q̇ and Σ c (S q)ᵀ q̇ (friction/balance.cpp).
  double c = 0, cs0 = 0, cs1 = 0, css = 0, b0 = 0, b1 = 0, b2 = 0;
};

struct Consts {
  const double* K;
  const double* mu;
  int n;
  double Mg;
  double L;  // lever scale of the Newton system
  double size_y, size_x, size_z;
};

/// The rounding error of the heights at v (support_newton.cpp's Rows::noise), with the table's
/// bounds on the coordinates (never below this substep's: a safe margin).
double noise(const Consts& k, const double* v) {
  return 4.0 * kEps *
         (k.size_z + std::abs(v[2]) + std::abs(v[0]) * k.size_y + std::abs(v[1]) * k.size_x);
}

/// kRead: the contact set is read off the heights at v (h_j < −noise); else it is `given`.
template <bool kRead>
Cell pass(const Consts& k, const Feet& f, const double* v, std::uint32_t given) {
  const double threshold = -noise(k, v);
  const double margin = kNearPlane * noise(k, v);
  Cell c;
  double sk = 0, sy = 0, sx = 0, syy = 0, syx = 0, sxx = 0, gy = 0, gx = 0, gz = 0;
  double fc = 0, fs0 = 0, fs1 = 0, fss = 0, fb0 = 0, fb1 = 0, fb2 = 0;
  std::uint32_t on_bits = 0;
  bool near = false;
  for (int j = 0; j < k.n; ++j) {
    const double y = f.y[j];
    const double x = f.mx[j];
    const double h = y * v[0] + x * v[1] + (f.z[j] + v[2]);
    bool on = false;
    if constexpr (kRead) {
      on = h < threshold;
      near = near || h * h <= margin * margin;
    } else {
      on = ((given >> j) & 1U) != 0;
    }
    on_bits |= static_cast<std::uint32_t>(on) << j;
    const double w = on ? k.K[j] : 0.0;
    const double wy = w * y;
    const double wx = w * x;
    const double wh = w * h;
    sk += w;
    sy += wy;
    sx += wx;
    syy += wy * y;
    syx += wy * x;
    sxx += wx * x;
    gy += wh * y;
    gx += wh * x;
    gz += wh;
    if constexpr (kRead) {
      // c_k = μ_k F_z,k, F_z,k = −K_k h_j (eq. 3.7), as friction_weight reads it.
      double cf = on ? k.mu[j] * (-k.K[j] * h) : 0.0;
      cf = cf > 0.0 ? cf : 0.0;
      const double qx = -x;
      const double s0 = -cf * y;  // c (S q)_x = −c q_y
      const double s1 = cf * qx;  // c (S q)_y = c q_x
      const double gq0 = cf * f.dx[j];
      const double gq1 = cf * f.dy[j];
      fc += cf;
      fs0 += s0;
      fs1 += s1;
      fss += -y * s0 + qx * s1;
      fb0 += gq0;
      fb1 += gq1;
      fb2 += -y * gq0 + qx * gq1;
    }
  }
  c.h00 = syy;
  c.h01 = syx;
  c.h02 = sy;
  c.h11 = sxx;
  c.h12 = sx;
  c.h22 = sk;
  c.g0 = gy;
  c.g1 = gx;
  c.g2 = gz + k.Mg;
  c.on = on_bits;
  c.near = near;
  c.c = fc;
  c.cs0 = fs0;
  c.cs1 = fs1;
  c.css = fss;
  c.b0 = fb0;
  c.b1 = fb1;
  c.b2 = fb2;
  return c;
}

/// support_newton.cpp's newton_step: dv = −H⁻¹ g in the scaled state (αL, βL, z) by cofactors
/// (contact::detail::cell_newton_step, the same arithmetic); false when H̃ is not safely definite.
bool newton_step(const Cell& c, double L, double* dv) {
  const double il = 1.0 / L;
  return contact::detail::cell_newton_step(c.h00, c.h01, c.h11, c.h02, c.h12, c.h22, c.g0, c.g1,
                                           c.g2, il, dv[0], dv[1], dv[2]);
}

/// SupportSummary::residual from the gradient.
double residual(const Cell& c, double Mg, double L) {
  return std::max({std::abs(c.g2) / Mg, std::abs(c.g0) / (Mg * L), std::abs(c.g1) / (Mg * L)});
}

/// The active-set Newton from state v on contact set `on` (the previous substep's); on success v
/// and the returned cell are the certified balance and its pass. false: not certified.
bool warm_support(const Consts& k, const Feet& f, double* v, std::uint32_t on, Cell& out) {
  Cell cell = pass<false>(k, f, v, on);
  std::uint32_t set = on;
  double last = std::numeric_limits<double>::infinity();
  for (int step = 1; step <= kMaxSteps; ++step) {
    double dv[3];
    if (!newton_step(cell, k.L, dv)) {
      return false;
    }
    v[0] += dv[0];
    v[1] += dv[1];
    v[2] += dv[2];
    cell = pass<true>(k, f, v, 0);
    if (cell.on != set) {
      set = cell.on;
      last = std::numeric_limits<double>::infinity();
      continue;
    }
    if (cell.near) {
      return false;
    }
    const double r = residual(cell, k.Mg, k.L);
    if (r <= kPolished || (r >= 0.5 * last && r <= kRoundingCap)) {
      out = cell;
      return true;
    }
    last = r;
  }
  return false;
}

/// The isotropic viscous balance M̃ y = −b̃ (friction/balance.hpp, scaled by L) by cofactors; false
/// when a pivot is below kFrictionPivotTol × trace (the reference then solves it).
bool viscous_twist(const Cell& c, double L, double* twist) {
  const double il = 1.0 / L;
  const double a00 = c.c;
  const double a11 = c.c;
  const double a02 = c.cs0 * il;
  const double a12 = c.cs1 * il;
  const double a22 = c.css * il * il;
  const double floor = kFrictionPivotTol * (a00 + a11 + a22);
  const double m2 = a00 * a11;
  const double c0 = a11 * a22 - a12 * a12;
  const double c1 = a02 * a12;
  const double c2 = -a02 * a11;
  const double m3 = a00 * c0 + a02 * c2;
  if (!(a00 > floor && m2 > floor * a00 && m3 > floor * m2)) {
    return false;
  }
  const double c11 = a00 * a22 - a02 * a02;
  const double c12 = -a00 * a12;
  const double r0 = -c.b0;
  const double r1 = -c.b1;
  const double r2 = -c.b2 * il;
  const double inv = 1.0 / m3;
  twist[0] = (c0 * r0 + c1 * r1 + c2 * r2) * inv;
  twist[1] = (c1 * r0 + c11 * r1 + c12 * r2) * inv;
  twist[2] = (c2 * r0 + c12 * r1 + m2 * r2) * inv * il;
  return true;
}

/// sin, cos and sinc of a small angle.
void sin_cos_sinc(double a, double& s, double& c, double& k) {
  if (std::abs(a) < kSeriesBelow) {
    const double a2 = a * a;
    k = 1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0 * (1.0 - a2 / 72.0)));
    s = a * k;
    c = 1.0 -
        a2 / 2.0 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0 * (1.0 - a2 / 90.0))));
    return;
  }
  s = std::sin(a);
  c = std::cos(a);
  k = s / a;
}

/// The pose as core::advance moves it, with cos θ and sin θ carried.
struct Mover {
  double x, y, theta, c, s;
  void advance(const double* twist, double h) {
    const double a = twist[0] * h;
    const double b = twist[1] * h;
    const double phi = twist[2] * h;
    double sh = 0.0;
    double ch = 0.0;
    double k = 0.0;
    sin_cos_sinc(0.5 * phi, sh, ch, k);
    const double tx = k * (ch * a - sh * b);
    const double ty = k * (sh * a + ch * b);
    x += c * tx - s * ty;
    y += s * tx + c * ty;
    theta += phi;
    const double cp = ch * ch - sh * sh;  // cos φ, sin φ from the half angle
    const double sp = 2.0 * sh * ch;
    const double c1 = c * cp - s * sp;
    s = s * cp + c * sp;
    c = c1;
  }
};

/// frame.q, qdot from the rows (for the reference solvers).
void to_frame(const Feet& f, int n, contact::Frame& frame) {
  for (int j = 0; j < n; ++j) {
    frame.q(0, j) = -f.mx[j];
    frame.q(1, j) = f.y[j];
    frame.q(2, j) = f.z[j];
    frame.qdot(0, j) = f.dx[j];
    frame.qdot(1, j) = f.dy[j];
    frame.qdot(2, j) = 0.0;
  }
}

bool support_ok(const contact::SupportSummary& s) {
  using Status = contact::SupportSummary::Status;
  return s.status == Status::kBalanced || s.status == Status::kLine || s.status == Status::kPoint;
}

}  // namespace

void store_start_support(const PlanRobot& /*robot*/, const contact::Frame& frame,
                         NodeTable& table) {
  table.start_ok = support_ok(frame.support);
  table.start_alpha = frame.alpha;
  table.start_beta = frame.beta;
  table.start_z = frame.z;
  for (int i = 0; i < table.legs; ++i) {
    table.start_contact[static_cast<std::size_t>(i)] = frame.contact[static_cast<std::size_t>(i)];
    table.start_Fz(i) = frame.Fz(i);
  }
}

namespace {

/// The start of an option (substep 0 uses the node's support): state and contact set.
void start_state(const NodeTable& table, double* v, std::uint32_t& on) {
  v[0] = table.start_alpha;
  v[1] = table.start_beta;
  v[2] = table.start_z;
  on = 0;
  for (int j = 0; j < table.legs; ++j) {
    if (table.start_contact[static_cast<std::size_t>(j)] != 0) {
      on |= 1U << j;
    }
  }
}

/// One substep of one option by the scalar route: the support (the node's at substep 0, else the
/// warm-started Newton, else contact::spring_support), the balance (fast, else the reference),
/// the advance. v and on carry the support's state from substep to substep. false: infeasible.
bool scalar_substep(const PlanRobot& robot, const NodeTable& table, const Consts& k, int s,
                    const Feet& f, double* v, std::uint32_t& on, Mover& mover,
                    contact::Frame& frame, FastCounts* counts) {
  const int n = k.n;
  Cell cell;
  bool fast = true;
  if (s == 0) {
    // The node's own support (build_node): the same for every option; the viscous sums with
    // its loads (the heights at its state).
    start_state(table, v, on);
    cell = pass<true>(k, f, v, 0);
    fast = cell.on == on && !cell.near;
  } else {
    fast = warm_support(k, f, v, on, cell);
    on = cell.on;
  }
  if (counts != nullptr) {
    counts->support_fallbacks += fast ? 0 : 1;
  }
  double twist[3];
  if (fast && viscous_twist(cell, k.L, twist)) {
    mover.advance(twist, table.h);
    return true;
  }
  // ---- the reference for this substep: support (unless certified), then the friction --------
  to_frame(f, n, frame);
  if (s == 0) {
    frame.alpha = table.start_alpha;
    frame.beta = table.start_beta;
    frame.z = table.start_z;
    for (int j = 0; j < n; ++j) {
      frame.contact[static_cast<std::size_t>(j)] = table.start_contact[static_cast<std::size_t>(j)];
      frame.Fz(j) = table.start_Fz(j);
    }
  } else if (!fast) {
    contact::spring_support(robot.robot, frame);
    if (!support_ok(frame.support)) {
      return false;
    }
    v[0] = frame.alpha;
    v[1] = frame.beta;
    v[2] = frame.z;
    on = 0;
    for (int j = 0; j < n; ++j) {
      if (frame.contact[static_cast<std::size_t>(j)] != 0) {
        on |= 1U << j;
      }
    }
  } else {
    frame.alpha = v[0];
    frame.beta = v[1];
    frame.z = v[2];
    for (int j = 0; j < n; ++j) {
      const bool down = ((on >> j) & 1U) != 0;
      const double h = f.y[static_cast<std::size_t>(j)] * v[0] +
                       f.mx[static_cast<std::size_t>(j)] * v[1] +
                       (f.z[static_cast<std::size_t>(j)] + v[2]);
      frame.contact[static_cast<std::size_t>(j)] = down ? 1 : 0;
      frame.Fz(j) = down ? -k.K[j] * h : 0.0;
    }
  }
  if (counts != nullptr) {
    ++counts->friction_fallbacks;
  }
  friction::solve_viscous_coulomb(robot.robot, frame);
  if (!frame.friction.converged) {
    return false;
  }
  mover.advance(frame.v_body.data(), table.h);
  return true;
}

Consts consts_of(const PlanRobot& robot, const NodeTable& table) {
  return {robot.robot.K.data(), robot.robot.mu.data(), table.legs,   robot.robot.Mg,
          table.lever,          table.size_y,          table.size_x, table.size_z};
}

}  // namespace

bool integrate_option_scalar(const PlanRobot& robot, const PlanOptions& options,
                             const NodeTable& table, const int* columns, int substeps,
                             core::Pose2& pose, contact::Frame& frame, FastCounts* counts) {
  if (!table.isotropic || table.legs > 32) {
    if (counts != nullptr) {
      ++counts->reference;
    }
    return integrate_option_reference(robot, options, table, columns, substeps, pose, frame);
  }
  const int n = table.legs;
  const Consts k = consts_of(robot, table);
  Mover mover{pose.x, pose.y, pose.theta, std::cos(pose.theta), std::sin(pose.theta)};
  double v[3];
  std::uint32_t on = 0;
  Feet f;
  bool ok = substeps <= 0 || table.start_ok;
  for (int s = 0; s < substeps && ok; ++s) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Index col = table.at(s, columns[i], i);
      const double* q = table.q.col(col).data();
      const double* qd = table.qdot.col(col).data();
      f.y[static_cast<std::size_t>(i)] = q[1];
      f.mx[static_cast<std::size_t>(i)] = -q[0];
      f.z[static_cast<std::size_t>(i)] = q[2];
      f.dx[static_cast<std::size_t>(i)] = qd[0];
      f.dy[static_cast<std::size_t>(i)] = qd[1];
    }
    if (counts != nullptr) {
      ++counts->substeps;
    }
    ok = scalar_substep(robot, table, k, s, f, v, on, mover, frame, counts);
  }
  pose = {mover.x, mover.y, mover.theta};
  return ok && std::isfinite(pose.x + pose.y + pose.theta);
}

// ---- kBatch options at once ---------------------------------------------------------------------
// The common substep — one warm Newton step that certifies at once, a definite viscous balance,
// a small turn — for kBatch options side by side, one option per lane of GCC vector types: the
// same operations per lane as on one double, so an option's numbers do not depend on its
// neighbours. A lane that does not certify at once takes the scalar route above for that substep
// (from the same state: a function of its own inputs only). As in contact/support_newton.cpp,
// an AVX2 clone (without FMA, which would contract a·b + c and round differently) beside the
// portable default, which runs the same code on pairs of SSE2 registers.
// (SLIPWALK_CLONES: core/lanes.hpp.)

namespace {

using V = double __attribute__((vector_size(8 * kBatch)));
using Mask = std::int64_t __attribute__((vector_size(8 * kBatch)));

[[gnu::always_inline]] inline V splat(double x) { return V{} + x; }
[[gnu::always_inline]] inline V select(Mask m, V a, V b) {
  return std::bit_cast<V>((std::bit_cast<Mask>(a) & m) | (std::bit_cast<Mask>(b) & ~m));
}
[[gnu::always_inline]] inline V vabs(V a) {
  return std::bit_cast<V>(std::bit_cast<Mask>(a) & (Mask{} + 0x7fffffffffffffffLL));
}

/// The feet of the batch at one substep, per foot a lane per option.
struct VFeet {
  std::array<V, kMaxPlanLegs> y, mx, z, dx, dy;
};

struct VCell {
  V h00, h01, h02, h11, h12, h22, g0, g1, g2;
  V changes, near;
  V c, cs0, cs1, css, b0, b1, b2;
};

[[gnu::always_inline]] inline V vnoise(const Consts& k, V v0, V v1, V v2) {
  return 4.0 * kEps * (k.size_z + vabs(v2) + vabs(v0) * k.size_y + vabs(v1) * k.size_x);
}

/// pass<kRead> per lane: kRead reads the set off the heights into `read` (1.0 / 0.0) and counts
/// the feet that changed from `on`; else the set is `on`.
template <bool kRead>
[[gnu::always_inline]] inline VCell vpass(const Consts& k, const VFeet& f, V v0, V v1, V v2,
                                          const std::array<V, kMaxPlanLegs>& on,
                                          std::array<V, kMaxPlanLegs>& read) {
  const V threshold = -vnoise(k, v0, v1, v2);
  const V margin = kNearPlane * vnoise(k, v0, v1, v2);
  const V zero{};
  const V one = splat(1.0);
  V sk{}, sy{}, sx{}, syy{}, syx{}, sxx{}, gy{}, gx{}, gz{}, changes{}, near{};
  V fc{}, fs0{}, fs1{}, fss{}, fb0{}, fb1{}, fb2{};
  for (int j = 0; j < k.n; ++j) {
    const auto u = static_cast<std::size_t>(j);
    const V y = f.y[u];
    const V x = f.mx[u];
    const V h = y * v0 + x * v1 + (f.z[u] + v2);
    const V K = splat(k.K[j]);
    V w;
    if constexpr (kRead) {
      const Mask touching = h < threshold;
      const V now = select(touching, one, zero);
      const V d = now - on[u];
      changes += d * d;
      near += select(h * h <= margin * margin, one, zero);
      read[u] = now;
      w = select(touching, K, zero);
    } else {
      w = K * on[u];  // K or 0 exactly
    }
    const V wy = w * y;
    const V wx = w * x;
    const V wh = w * h;
    sk += w;
    sy += wy;
    sx += wx;
    syy += wy * y;
    syx += wy * x;
    sxx += wx * x;
    gy += wh * y;
    gx += wh * x;
    gz += wh;
    if constexpr (kRead) {
      V cf = w * (splat(k.mu[j]) * -h);  // μ (−K h) on the contacts: w = K there
      cf = select(cf > zero, cf, zero);
      const V qx = -x;
      const V s0 = -cf * y;
      const V s1 = cf * qx;
      const V gq0 = cf * f.dx[u];
      const V gq1 = cf * f.dy[u];
      fc += cf;
      fs0 += s0;
      fs1 += s1;
      fss += -y * s0 + qx * s1;
      fb0 += gq0;
      fb1 += gq1;
      fb2 += -y * gq0 + qx * gq1;
    }
  }
  return {syy,     syx,  sy, sxx, sx,  sk,  gy,  gx,  gz + k.Mg,
          changes, near, fc, fs0, fs1, fss, fb0, fb1, fb2};
}

/// newton_step per lane (cell_newton_step on lanes); the mask says where H̃ is safely definite.
[[gnu::always_inline]] inline Mask vnewton(const VCell& c, double L, V& d0, V& d1, V& d2) {
  return contact::detail::cell_newton_step(c.h00, c.h01, c.h11, c.h02, c.h12, c.h22, c.g0, c.g1,
                                           c.g2, core::Lanes<kBatch>::splat(1.0 / L), d0, d1, d2);
}

/// viscous_twist per lane; the mask says where the balance's pivots pass.
[[gnu::always_inline]] inline Mask vviscous(const VCell& c, double L, V& t0, V& t1, V& t2) {
  const double il = 1.0 / L;
  const V a00 = c.c;
  const V a11 = c.c;
  const V a02 = c.cs0 * il;
  const V a12 = c.cs1 * il;
  const V a22 = c.css * (il * il);
  const V floor = kFrictionPivotTol * (a00 + a11 + a22);
  const V m2 = a00 * a11;
  const V c0 = a11 * a22 - a12 * a12;
  const V c1 = a02 * a12;
  const V c2 = -a02 * a11;
  const V m3 = a00 * c0 + a02 * c2;
  const Mask ok = (a00 > floor) & (m2 > floor * a00) & (m3 > floor * m2);
  const V c11 = a00 * a22 - a02 * a02;
  const V c12 = -a00 * a12;
  const V r0 = -c.b0;
  const V r1 = -c.b1;
  const V r2 = -c.b2 * il;
  const V inv = 1.0 / m3;
  t0 = (c0 * r0 + c1 * r1 + c2 * r2) * inv;
  t1 = (c1 * r0 + c11 * r1 + c12 * r2) * inv;
  t2 = (c2 * r0 + c12 * r1 + m2 * r2) * inv * il;
  return ok;
}

/// The balance residual (SupportSummary::residual) per lane in `r`, and where each of its
/// three parts is at most `bound` (false for NaN).
[[gnu::always_inline]] inline Mask below(const Consts& k, const VCell& c, double bound, V& r) {
  const double inv_mg = 1.0 / k.Mg;
  const double inv_mgl = 1.0 / (k.Mg * k.L);
  const V a = vabs(c.g2) * inv_mg;
  const V b = vabs(c.g0) * inv_mgl;
  const V d = vabs(c.g1) * inv_mgl;
  const V ab = select(a > b, a, b);
  r = select(ab > d, ab, d);
  return (a <= splat(bound)) & (b <= splat(bound)) & (d <= splat(bound));
}

[[gnu::always_inline]] inline VCell select_cell(Mask m, const VCell& a, const VCell& b) {
  return {select(m, a.h00, b.h00),         select(m, a.h01, b.h01),   select(m, a.h02, b.h02),
          select(m, a.h11, b.h11),         select(m, a.h12, b.h12),   select(m, a.h22, b.h22),
          select(m, a.g0, b.g0),           select(m, a.g1, b.g1),     select(m, a.g2, b.g2),
          select(m, a.changes, b.changes), select(m, a.near, b.near), select(m, a.c, b.c),
          select(m, a.cs0, b.cs0),         select(m, a.cs1, b.cs1),   select(m, a.css, b.css),
          select(m, a.b0, b.b0),           select(m, a.b1, b.b1),     select(m, a.b2, b.b2)};
}

struct VPose {
  V x, y, theta, c, s;
};

/// 1/i for the series' denominators.
constexpr std::array<double, 91> kInv = [] {
  std::array<double, 91> a{};
  for (std::size_t i = 1; i < a.size(); ++i) {
    a[i] = 1.0 / static_cast<double>(i);
  }
  return a;
}();

/// Mover::advance per lane (the series where |ω h / 2| < kSeriesBelow, else libm per lane).
[[gnu::always_inline]] inline VPose vadvance(const VPose& p, V t0, V t1, V t2, double h) {
  const V a = t0 * h;
  const V b = t1 * h;
  const V phi = t2 * h;
  const V half = 0.5 * phi;
  const V a2 = half * half;
  // Multiplications by the reciprocals (a division costs about ten multiplications here).
  V k = 1.0 - a2 * kInv[6] * (1.0 - a2 * kInv[20] * (1.0 - a2 * kInv[42] * (1.0 - a2 * kInv[72])));
  V sh = half * k;
  V ch =
      1.0 - a2 * 0.5 *
                (1.0 - a2 * kInv[12] *
                           (1.0 - a2 * kInv[30] * (1.0 - a2 * kInv[56] * (1.0 - a2 * kInv[90]))));
  const Mask series = vabs(half) < splat(kSeriesBelow);
  for (int l = 0; l < kBatch; ++l) {
    if (series[l] == 0) {
      double sl = 0.0;
      double cl = 0.0;
      double kl = 0.0;
      sin_cos_sinc(half[l], sl, cl, kl);
      sh[l] = sl;
      ch[l] = cl;
      k[l] = kl;
    }
  }
  const V tx = k * (ch * a - sh * b);
  const V ty = k * (sh * a + ch * b);
  VPose q;
  q.x = p.x + (p.c * tx - p.s * ty);
  q.y = p.y + (p.s * tx + p.c * ty);
  q.theta = p.theta + phi;
  const V cp = ch * ch - sh * sh;
  const V sp = 2.0 * sh * ch;
  q.c = p.c * cp - p.s * sp;
  q.s = p.s * cp + p.c * sp;
  return q;
}

}  // namespace

SLIPWALK_CLONES void integrate_batch_vector(const PlanRobot& robot, const NodeTable& table,
                                            const int* const* columns, int count, int substeps,
                                            core::Pose2* poses, bool* ok, contact::Frame& frame,
                                            FastCounts* counts) {
  const int n = table.legs;
  const Consts k = consts_of(robot, table);
  VPose p;
  for (int l = 0; l < kBatch; ++l) {
    const core::Pose2& q = poses[l < count ? l : 0];
    p.x[l] = q.x;
    p.y[l] = q.y;
    p.theta[l] = q.theta;
    // The options of a node start from one pose: cos and sin once (the same numbers).
    if (l > 0 && q.theta == p.theta[l - 1]) {
      p.c[l] = p.c[l - 1];
      p.s[l] = p.s[l - 1];
    } else {
      p.c[l] = std::cos(q.theta);
      p.s[l] = std::sin(q.theta);
    }
  }
  std::array<bool, kBatch> alive{};
  for (int l = 0; l < kBatch; ++l) {
    alive[static_cast<std::size_t>(l)] = substeps <= 0 || table.start_ok;
  }
  V v0 = splat(table.start_alpha);
  V v1 = splat(table.start_beta);
  V v2 = splat(table.start_z);
  std::array<V, kMaxPlanLegs> on{};
  std::array<V, kMaxPlanLegs> read{};
  for (int j = 0; j < n; ++j) {
    on[static_cast<std::size_t>(j)] =
        splat(table.start_contact[static_cast<std::size_t>(j)] != 0 ? 1.0 : 0.0);
  }
  VFeet f;
  const double* q = table.q.data();
  const double* qd = table.qdot.data();
  for (int s = 0; s < substeps; ++s) {
    bool any = false;
    for (int l = 0; l < kBatch; ++l) {
      any = any || alive[static_cast<std::size_t>(l)];
    }
    if (!any) {
      break;
    }
    for (int j = 0; j < n; ++j) {
      const auto u = static_cast<std::size_t>(j);
      for (int l = 0; l < kBatch; ++l) {
        const int* c = columns[l < count ? l : 0];
        const Eigen::Index col = 3 * table.at(s, c[j], j);
        f.y[u][l] = q[col + 1];
        f.mx[u][l] = -q[col];
        f.z[u][l] = q[col + 2];
        f.dx[u][l] = qd[col];
        f.dy[u][l] = qd[col + 1];
      }
    }
    if (counts != nullptr) {
      for (int l = 0; l < count; ++l) {
        counts->substeps += alive[static_cast<std::size_t>(l)] ? 1 : 0;
      }
    }
    const V zero{};
    Mask good;
    if (s == 0) {
      // The node's support, as the scalar route: its loads, if the set read off repeats.
      const VCell cell = vpass<true>(k, f, v0, v1, v2, on, read);
      V t0, t1, t2;
      good = vviscous(cell, k.L, t0, t1, t2) & (cell.changes == zero) & (cell.near == zero);
      const VPose moved = vadvance(p, t0, t1, t2, table.h);
      p = {select(good, moved.x, p.x), select(good, moved.y, p.y),
           select(good, moved.theta, p.theta), select(good, moved.c, p.c),
           select(good, moved.s, p.s)};
    } else {
      const VCell start = vpass<false>(k, f, v0, v1, v2, on, read);
      V d0, d1, d2;
      const Mask definite = vnewton(start, k.L, d0, d1, d2);
      V n0 = v0 + d0;
      V n1 = v1 + d1;
      V n2 = v2 + d2;
      VCell cell = vpass<true>(k, f, n0, n1, n2, on, read);
      V r1;
      Mask settled =
          definite & (cell.changes == zero) & (cell.near == zero) & below(k, cell, kPolished, r1);
      // A second step where the first changed the contact set, or kept it and left the balance
      // above rounding (warm_support's rule: then a step that no longer halves the residual
      // certifies below kRoundingCap).
      const Mask again = definite & ~settled & ((cell.changes != zero) | (cell.near == zero));
      bool any_again = false;
      for (int l = 0; l < kBatch; ++l) {
        any_again = any_again || again[l] != 0;
      }
      if (any_again) {
        V e0, e1, e2;
        const Mask definite2 = vnewton(cell, k.L, e0, e1, e2);
        const V m0 = n0 + e0;
        const V m1 = n1 + e1;
        const V m2 = n2 + e2;
        std::array<V, kMaxPlanLegs> read2{};
        const VCell cell2 = vpass<true>(k, f, m0, m1, m2, read, read2);
        V r2;
        V unused;
        const Mask polished = below(k, cell2, kPolished, r2);
        const Mask stalled =
            (cell.changes == zero) & below(k, cell2, kRoundingCap, unused) & (r2 >= 0.5 * r1);
        const Mask settled2 = again & definite2 & (cell2.changes == zero) & (cell2.near == zero) &
                              (polished | stalled);
        cell = select_cell(settled2, cell2, cell);
        n0 = select(settled2, m0, n0);
        n1 = select(settled2, m1, n1);
        n2 = select(settled2, m2, n2);
        for (int j = 0; j < n; ++j) {
          const auto u = static_cast<std::size_t>(j);
          read[u] = select(settled2, read2[u], read[u]);
        }
        settled |= settled2;
      }
      V t0, t1, t2;
      good = vviscous(cell, k.L, t0, t1, t2) & settled;
      const VPose moved = vadvance(p, t0, t1, t2, table.h);
      p = {select(good, moved.x, p.x), select(good, moved.y, p.y),
           select(good, moved.theta, p.theta), select(good, moved.c, p.c),
           select(good, moved.s, p.s)};
      v0 = select(good, n0, v0);
      v1 = select(good, n1, v1);
      v2 = select(good, n2, v2);
      for (int j = 0; j < n; ++j) {
        const auto u = static_cast<std::size_t>(j);
        on[u] = select(good, read[u], on[u]);
      }
    }
    // ---- the lanes that did not certify at once: the scalar route for this substep -----------
    for (int l = 0; l < kBatch; ++l) {
      const auto ul = static_cast<std::size_t>(l);
      if (!alive[ul] || good[l] != 0) {
        continue;
      }
      if (l >= count) {
        alive[ul] = false;  // padding: nobody reads it
        continue;
      }
      if (counts != nullptr) {
        ++counts->scalar;
      }
      Feet one;
      std::uint32_t bits = 0;
      for (int j = 0; j < n; ++j) {
        const auto u = static_cast<std::size_t>(j);
        one.y[u] = f.y[u][l];
        one.mx[u] = f.mx[u][l];
        one.z[u] = f.z[u][l];
        one.dx[u] = f.dx[u][l];
        one.dy[u] = f.dy[u][l];
        bits |= (on[u][l] != 0.0 ? 1U : 0U) << j;
      }
      double v[3] = {v0[l], v1[l], v2[l]};
      Mover mover{p.x[l], p.y[l], p.theta[l], p.c[l], p.s[l]};
      if (!scalar_substep(robot, table, k, s, one, v, bits, mover, frame, counts)) {
        alive[ul] = false;
        continue;
      }
      v0[l] = v[0];
      v1[l] = v[1];
      v2[l] = v[2];
      for (int j = 0; j < n; ++j) {
        on[static_cast<std::size_t>(j)][l] = ((bits >> j) & 1U) != 0 ? 1.0 : 0.0;
      }
      p.x[l] = mover.x;
      p.y[l] = mover.y;
      p.theta[l] = mover.theta;
      p.c[l] = mover.c;
      p.s[l] = mover.s;
    }
  }
  for (int l = 0; l < count; ++l) {
    poses[l] = {p.x[l], p.y[l], p.theta[l]};
    ok[l] = alive[static_cast<std::size_t>(l)] &&
            std::isfinite(poses[l].x + poses[l].y + poses[l].theta);
  }
}

void integrate_batch(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                     const int* const* columns, int count, int substeps, core::Pose2* poses,
                     bool* ok, contact::Frame& frame, FastCounts* counts) {
  if (!table.isotropic || table.legs > 32) {
    for (int l = 0; l < count; ++l) {
      if (counts != nullptr) {
        ++counts->reference;
      }
      ok[l] =
          integrate_option_reference(robot, options, table, columns[l], substeps, poses[l], frame);
    }
    return;
  }
  integrate_batch_vector(robot, table, columns, count, substeps, poses, ok, frame, counts);
}

}  // namespace slipwalk::planning::detail
