// Random stress frames for the Coulomb solver and an independent oracle (coulomb_stress.hpp).
#include "sweeps/points/coulomb_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "contact/spring_support.hpp"
#include "sweeps/engine/random.hpp"

namespace slipwalk::sweeps::stress {

namespace {

// The ranges drawn from. μ and K span the extremes the model admits (contact::limits, the same
// bounds a robot file is checked against): μ from nearly frictionless to a glued foot, K from a
// sponge to steel; the products that enter the solver (c_k = μ F_z up to 1e6 N, d_k = c_k W q̇ up to
// 1e9 N m/s, their squares up to 1e18) stay far inside double precision, and so do the smallest
// ones (c_k ≥ 1e-18 N at μ = 1e-6 with a load 1e-6 of the mean: c_k² ≥ 1e-36, far above the
// subnormal range).
constexpr double kMuMin = contact::limits::kFriction.lo;
constexpr double kMuMax = contact::limits::kFriction.hi;
constexpr double kKMin = contact::limits::kStiffness.lo;  // N/m
constexpr double kKMax = contact::limits::kStiffness.hi;  // N/m
constexpr double kMgMin = 0.1;                            // N
constexpr double kMgMax = 1e4;                            // N
constexpr double kSizeMin = 1e-2;                         // m: the feet's spread
constexpr double kSizeMax = 10.0;                         // m
constexpr double kSpeedMin = 1e-4;                        // m/s
constexpr double kSpeedMax = 10.0;                        // m/s
constexpr double kAnisoMin = 1e-3;                        // ‖w‖ of eq. 3.19
constexpr double kAnisoMax = 10.0;

double log_uniform(Random& rng, double lo, double hi) {
  return std::exp(rng.uniform(std::log(lo), std::log(hi)));
}
int pick(Random& rng, int n) { return std::min(static_cast<int>(rng.uniform() * n), n - 1); }
Eigen::Vector2d unit(Random& rng) {
  const double a = rng.uniform(0.0, 2.0 * std::numbers::pi);
  return {std::cos(a), std::sin(a)};
}
Eigen::Vector2d in_disk(Random& rng, double r) { return r * std::sqrt(rng.uniform()) * unit(rng); }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v(1), v(0)}; }

contact::Robot draw_robot(Random& rng, int n) {
  contact::Robot robot;
  robot.Mg = log_uniform(rng, kMgMin, kMgMax);
  robot.K.resize(n);
  robot.mu.resize(n);
  robot.w = Eigen::Matrix2Xd::Zero(2, n);
  const bool same_k = rng.uniform() < 0.5;
  const double k0 = log_uniform(rng, kKMin, kKMax);
  for (int k = 0; k < n; ++k) {
    robot.K(k) = same_k ? k0 : std::clamp(k0 * log_uniform(rng, 1e-2, 1e2), kKMin, kKMax);
  }
  // μ: one value; one per foot around a base; one per foot over all decades; or some feet
  // without friction.
  const int mu_mode = pick(rng, 4);
  const double mu0 = log_uniform(rng, kMuMin, kMuMax);
  for (int k = 0; k < n; ++k) {
    double mu = mu0;
    if (mu_mode == 1) {
      mu = std::clamp(mu0 * log_uniform(rng, 0.1, 10.0), kMuMin, kMuMax);
    } else if (mu_mode == 2) {
      mu = log_uniform(rng, kMuMin, kMuMax);
    } else if (mu_mode == 3) {
      mu = rng.uniform() < 0.25 ? 0.0 : mu0;
    }
    robot.mu(k) = mu;
  }
  if (rng.uniform() < 0.5) {
    const bool common = rng.uniform() < 0.5;  // one direction for all feet (a rigid sole)
    const Eigen::Vector2d w0 = log_uniform(rng, kAnisoMin, kAnisoMax) * unit(rng);
    for (int k = 0; k < n; ++k) {
      robot.w.col(k) =
          common ? w0 : Eigen::Vector2d(log_uniform(rng, kAnisoMin, kAnisoMax) * unit(rng));
    }
  }
  return robot;
}

/// The feet's planar positions; `axis` is the layout's line direction (for kLine, kNearLine).
Eigen::Matrix2Xd draw_layout(Random& rng, Layout layout, int n, Eigen::Vector2d& axis) {
  const double R = log_uniform(rng, kSizeMin, kSizeMax);
  Eigen::Matrix2Xd p(2, n);
  axis = unit(rng);
  // Lines and points sometimes through the body origin (the CoM) exactly.
  const Eigen::Vector2d p0 = rng.uniform() < 0.3 ? Eigen::Vector2d::Zero() : in_disk(rng, 0.5 * R);
  switch (layout) {
    case Layout::kGeneral:
      for (int k = 0; k < n; ++k) {
        p.col(k) = in_disk(rng, R);
      }
      break;
    case Layout::kLine:
    case Layout::kNearLine: {
      const double off = layout == Layout::kNearLine ? R * log_uniform(rng, 1e-12, 1e-3) : 0.0;
      for (int k = 0; k < n; ++k) {
        p.col(k) = p0 + rng.uniform(-R, R) * axis + off * rng.normal() * perp(axis);
      }
      break;
    }
    case Layout::kCoincident: {
      const int distinct = std::max(2, n / 2);
      for (int k = 0; k < n; ++k) {
        p.col(k) = k < distinct ? in_disk(rng, R) : Eigen::Vector2d(p.col(pick(rng, distinct)));
      }
      break;
    }
    case Layout::kOnePoint:
      for (int k = 0; k < n; ++k) {
        p.col(k) = p0;
      }
      break;
    case Layout::kCircle: {
      const double phase = rng.uniform() < 0.5 ? 0.0 : rng.uniform(0.0, 2.0 * std::numbers::pi);
      for (int k = 0; k < n; ++k) {
        const double a = phase + 2.0 * std::numbers::pi * k / n;
        p.col(k) << R * std::cos(a), R * std::sin(a);
      }
      break;
    }
    case Layout::kMirror:
      // Pairs (x, ±y); an odd count puts one foot on the axis.
      for (int k = 0; k + 1 < n; k += 2) {
        const Eigen::Vector2d a(rng.uniform(-R, R), rng.uniform(0.0, R));
        p.col(k) = a;
        p.col(k + 1) << a(0), -a(1);
      }
      if (n % 2 == 1) {
        p.col(n - 1) << rng.uniform(-R, R), 0.0;
      }
      break;
  }
  return p;
}

/// Loads by the spring support: feet at a nominal height with jitter of a tenth of the static
/// sinkage s = Mg/ΣK, a third of them lifted by 0.2–3 s (swinging).
void support_loads(Random& rng, const contact::Robot& robot, contact::Frame& f) {
  // Heights stay inside contact::limits::kPosition (±1e3 m): a sponge-soft robot whose static
  // sinkage Mg/ΣK is beyond 100 m gets its feet placed as for 100 m (the support search still
  // finds its own balance).
  const double sink = std::min(robot.Mg / robot.K.sum(), 100.0);
  const double h0 = log_uniform(rng, 1e-3, 1.0);
  for (int k = 0; k < f.legs(); ++k) {
    f.q(2, k) = -h0 + rng.uniform(-0.1, 0.1) * sink;
    if (rng.uniform() < 1.0 / 3.0) {
      f.q(2, k) += rng.uniform(0.2, 3.0) * sink;
    }
  }
  contact::spring_support(robot, f);
}

/// Loads set directly: each foot in contact with probability 0.8, F_z spread over six decades
/// below Mg/N, or all within ±50 % of it.
void direct_loads(Random& rng, const contact::Robot& robot, contact::Frame& f) {
  const int n = f.legs();
  const bool spread = rng.uniform() < 0.5;
  const double mean = robot.Mg / n;
  for (int k = 0; k < n; ++k) {
    f.q(2, k) = -0.1;
    const bool down = rng.uniform() < 0.8;
    f.contact[static_cast<std::size_t>(k)] = down ? 1 : 0;
    f.Fz(k) = down ? mean * (spread ? log_uniform(rng, 1e-6, 1.0) : rng.uniform(0.5, 1.5)) : 0.0;
  }
}

void draw_motion(Random& rng, Motion motion, const Eigen::Vector2d& axis, contact::Frame& f) {
  const int n = f.legs();
  const double V = log_uniform(rng, kSpeedMin, kSpeedMax);
  double R = 0.0;
  for (int k = 0; k < n; ++k) {
    R = std::max(R, f.q.col(k).head<2>().norm());
  }
  // A rigid motion of the body (v0, ω0), and the feet's own slip around it.
  const Eigen::Vector2d v0 = V * Eigen::Vector2d(rng.normal(), rng.normal());
  const double w0 = R > 0.0 ? V * rng.normal() / R : 0.0;
  const double spread = log_uniform(rng, 1e-3, 3.0);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d q = f.q.col(k).head<2>();
    const Eigen::Vector2d rigid = -(v0 + w0 * perp(q));
    const Eigen::Vector2d own = V * spread * Eigen::Vector2d(rng.normal(), rng.normal());
    Eigen::Vector2d qd = rigid + own;
    switch (motion) {
      case Motion::kGeneral:
      case Motion::kMirror:
        break;
      case Motion::kRest:
        qd.setZero();
        break;
      case Motion::kSomeZero:
        qd = rng.uniform() < 0.5 ? Eigen::Vector2d::Zero() : qd;
        break;
      case Motion::kRigid:
        qd = rigid;
        break;
      case Motion::kAlongLine:
        qd = V * rng.normal() * axis;
        break;
    }
    f.qdot.col(k) << qd, 0.0;
  }
  if (motion == Motion::kMirror) {  // the layout is mirrored (make_stress_frame): mirror q̇ too
    for (int k = 0; k + 1 < n; k += 2) {
      f.qdot(0, k + 1) = f.qdot(0, k);
      f.qdot(1, k + 1) = -f.qdot(1, k);
    }
    if (n % 2 == 1) {
      f.qdot(1, n - 1) = 0.0;
    }
  }
}

}  // namespace

std::string_view layout_name(Layout layout) {
  constexpr std::string_view names[kLayouts] = {"general",   "line",   "near_line", "coincident",
                                                "one_point", "circle", "mirror"};
  return names[static_cast<int>(layout)];
}

std::string_view motion_name(Motion motion) {
  constexpr std::string_view names[kMotions] = {"general", "rest",       "some_zero",
                                                "rigid",   "along_line", "mirror"};
  return names[static_cast<int>(motion)];
}

StressFrame make_stress_frame(std::uint64_t seed, std::uint64_t index) {
  Random rng(seed, index);
  const int n = rng.uniform() < 0.5 ? 3 + pick(rng, 6) : 3 + pick(rng, 48);
  Layout layout = static_cast<Layout>(pick(rng, kLayouts));
  const auto motion = static_cast<Motion>(pick(rng, kMotions));
  if (motion == Motion::kMirror) {
    layout = Layout::kMirror;
  }
  const Loads loads = rng.uniform() < 0.5 ? Loads::kSupport : Loads::kDirect;
  contact::Robot robot = draw_robot(rng, n);
  contact::validate(robot);
  contact::Frame frame(robot);
  Eigen::Vector2d axis;
  frame.q.topRows<2>() = draw_layout(rng, layout, n, axis);
  if (loads == Loads::kSupport) {
    support_loads(rng, robot, frame);
  } else {
    direct_loads(rng, robot, frame);
  }
  draw_motion(rng, motion, axis, frame);
  contact::check_frame(robot, frame);
  return StressFrame{std::move(robot), std::move(frame), layout, motion, loads};
}

double dissipation(const contact::Robot& robot, const contact::Frame& frame,
                   const Eigen::Vector3d& v) {
  double D = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c =
        frame.contact[static_cast<std::size_t>(k)] != 0 ? robot.mu(k) * frame.Fz(k) : 0.0;
    if (!(c > 0.0)) {
      continue;
    }
    const Eigen::Vector2d q = frame.q.col(k).head<2>();
    const Eigen::Vector2d u = v.head<2>() + v(2) * perp(q) + frame.qdot.col(k).head<2>();
    const double wu = robot.w.col(k).dot(u);
    D += c * std::sqrt(u.squaredNorm() + wu * wu);  // ‖W u‖² = uᵀ(I + w wᵀ)u
  }
  return D;
}

OracleCheck check_coulomb(const contact::Robot& robot, const contact::Frame& frame) {
  OracleCheck o;
  const Eigen::Vector3d v = frame.v_body;
  o.finite = v.allFinite() && frame.Fxy.allFinite() && std::isfinite(frame.friction.certificate) &&
             std::isfinite(frame.friction.residual);
  if (!o.finite) {
    return o;
  }
  double scale = 0.0;
  double L = 0.0;
  double complementarity = 0.0;
  double idle = 0.0;
  double rounding = 0.0;
  double c_min = std::numeric_limits<double>::infinity();
  double c_max = 0.0;
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  double moment = 0.0;
  o.outside = -1.0;
  for (int k = 0; k < frame.legs(); ++k) {
    const Eigen::Vector2d F = frame.Fxy.col(k);
    const double c =
        frame.contact[static_cast<std::size_t>(k)] != 0 ? robot.mu(k) * frame.Fz(k) : 0.0;
    if (!(c > 0.0)) {
      idle = std::max(idle, F.norm());
      continue;
    }
    const Eigen::Vector2d w = robot.w.col(k);
    const double ww = w.squaredNorm();
    const Eigen::Vector2d q = frame.q.col(k).head<2>();
    const Eigen::Vector2d qd = frame.qdot.col(k).head<2>();
    const Eigen::Vector2d u = v.head<2>() + v(2) * perp(q) + qd;
    const double wu = w.dot(u);
    const double wq = w.dot(qd);
    const double su = c * std::sqrt(u.squaredNorm() + wu * wu);
    o.dissipation += su;
    o.d0 += c * std::sqrt(qd.squaredNorm() + wq * wq);
    complementarity += su + F.dot(u);  // ≥ 0 for F in the ellipse: the support function
    scale += c * std::sqrt(1.0 + ww);
    rounding +=
        c * std::sqrt(1.0 + ww) * (v.head<2>().norm() + std::abs(v(2)) * q.norm() + qd.norm());
    c_min = std::min(c_min, c);
    c_max = std::max(c_max, c);
    L = std::max(L, q.norm());
    force += F;
    moment += q(0) * F(1) - q(1) * F(0);
    const double wf = w.dot(F);
    o.outside = std::max(o.outside, (F.squaredNorm() - wf * wf / (1.0 + ww)) / (c * c) - 1.0);
  }
  // Σ F·(−q̇) = Σ F·(−u) + v_b·ΣF + ω ΣM_z, so D(v) − Σ F·(−q̇) = Σ (c‖Wu‖ + F·u) − v_b·ΣF − ω ΣM.
  const double gap = complementarity - v.head<2>().dot(force) - v(2) * moment;
  const double denom = std::max(o.dissipation, o.d0);
  o.gap = denom > 0.0 ? gap / denom : 0.0;
  o.rounding = denom > 0.0 ? 8.0 * std::numeric_limits<double>::epsilon() * rounding / denom : 0.0;
  o.weight_decades = c_max > 0.0 ? std::log10(c_max / c_min) : 0.0;
  if (scale > 0.0) {
    o.imbalance = force.norm() / scale;
    if (L > 0.0) {
      o.imbalance = std::max(o.imbalance, std::abs(moment) / (scale * L));
    }
    o.idle_force = idle / scale;
  } else {
    o.idle_force = idle;
    o.outside = 0.0;
  }
  return o;
}

}  // namespace slipwalk::sweeps::stress
