// The fused, warm-started substep of fast_kernel.hpp. The spring-support part follows
// contact/support_newton.cpp step for step (same state v = (α, β, z), same rows a_j = (q_y, −q_x,
// 1), same scaled Newton system, same certificate); only its start differs: the previous
// substep's state and contact set instead of the all-feet plane.
#include "planning/fast_kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "planning/option_kernel.hpp"

namespace slipwalk::planning::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxSteps = 8;            // then contact::spring_support decides
constexpr double kDefiniteTol = 1e-10;  // support_newton.cpp's test of the cell's Hessian
constexpr double kPolished = 1e-14;     // balance residual that needs no refinement
constexpr double kRoundingCap = 1e-10;  // a stalled refinement is accepted only below this
constexpr double kNearPlane = 1e3;      // feet this close (× rounding) to their plane: fall back
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

/// support_newton.cpp's newton_step: dv = −H⁻¹ g in the scaled state (αL, βL, z) by cofactors;
/// false when H̃ is not safely definite.
bool newton_step(const Cell& c, double L, double* dv) {
  const double il = 1.0 / L;
  const double h00 = c.h00 * il * il;
  const double h10 = c.h01 * il * il;
  const double h11 = c.h11 * il * il;
  const double h20 = c.h02 * il;
  const double h21 = c.h12 * il;
  const double h22 = c.h22;
  const double c00 = h11 * h22 - h21 * h21;
  const double c01 = h21 * h20 - h10 * h22;
  const double c02 = h10 * h21 - h11 * h20;
  const double c11 = h00 * h22 - h20 * h20;
  const double c12 = h10 * h20 - h00 * h21;
  const double c22 = h00 * h11 - h10 * h10;
  const double det = h00 * c00 + h10 * c01 + h20 * c02;
  const double tr = h00 + h11 + h22;
  if (!(h00 > 0.0) || !(c22 > 0.0) || !(4.0 * det > kDefiniteTol * tr * tr * tr)) {
    return false;
  }
  const double b0 = -c.g0 * il;
  const double b1 = -c.g1 * il;
  const double b2 = -c.g2;
  const double inv = 1.0 / det;
  dv[0] = (c00 * b0 + c01 * b1 + c02 * b2) * inv * il;
  dv[1] = (c01 * b0 + c11 * b1 + c12 * b2) * inv * il;
  dv[2] = (c02 * b0 + c12 * b1 + c22 * b2) * inv;
  return true;
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

bool integrate_option_fast(const PlanRobot& robot, const PlanOptions& options,
                           const NodeTable& table, const int* columns, int substeps,
                           core::Pose2& pose, contact::Frame& frame, FastCounts* counts) {
  if (!table.isotropic || table.legs > 32) {
    if (counts != nullptr) {
      ++counts->reference;
    }
    return integrate_option_reference(robot, options, table, columns, substeps, pose, frame);
  }
  const int n = table.legs;
  const Consts k{robot.robot.K.data(), robot.robot.mu.data(), n,
                 robot.robot.Mg,       table.lever,           table.size_y,
                 table.size_x,         table.size_z};
  Mover mover{pose.x, pose.y, pose.theta, std::cos(pose.theta), std::sin(pose.theta)};
  const auto give_back = [&pose, &mover]() { pose = {mover.x, mover.y, mover.theta}; };
  double v[3] = {table.start_alpha, table.start_beta, table.start_z};
  std::uint32_t on = 0;
  Feet f;
  for (int s = 0; s < substeps; ++s) {
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
    Cell cell;
    bool fast = true;
    if (s == 0) {
      // The node's own support (build_node): the same for every option.
      if (!table.start_ok) {
        give_back();
        return false;
      }
      for (int j = 0; j < n; ++j) {
        if (table.start_contact[static_cast<std::size_t>(j)] != 0) {
          on |= 1U << j;
        }
      }
      // The viscous sums with the table's loads (heights at the start state).
      cell = pass<true>(k, f, v, 0);
      fast = cell.on == on && !cell.near;
    } else {
      fast = warm_support(k, f, v, on, cell);
      on = cell.on;
    }
    if (counts != nullptr) {
      ++counts->substeps;
      counts->support_fallbacks += fast ? 0 : 1;
    }
    double twist[3];
    if (fast && viscous_twist(cell, k.L, twist)) {
      mover.advance(twist, table.h);
      continue;
    }
    // ---- the reference for this substep: support (unless certified), then the friction ------
    to_frame(f, n, frame);
    if (s == 0 || !fast) {
      if (s == 0) {
        frame.alpha = table.start_alpha;
        frame.beta = table.start_beta;
        frame.z = table.start_z;
        for (int j = 0; j < n; ++j) {
          frame.contact[static_cast<std::size_t>(j)] =
              table.start_contact[static_cast<std::size_t>(j)];
          frame.Fz(j) = table.start_Fz(j);
        }
      } else {
        contact::spring_support(robot.robot, frame);
        if (!support_ok(frame.support)) {
          give_back();
          return false;
        }
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
      give_back();
      return false;
    }
    mover.advance(frame.v_body.data(), table.h);
  }
  give_back();
  return std::isfinite(pose.x + pose.y + pose.theta);
}

}  // namespace slipwalk::planning::detail
