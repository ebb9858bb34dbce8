// The friction laws of the multi-legged model (thesis ch. 3) on synthetic feet: no robot file,
// the feet are laid out by the point's keys. Each kind's keys are checked in its read_* function,
// and its rows are a struct with their column table above its run_* function.
//
//   legged_1d         §3.1.2, Fig. 3.1: N feet on a line with equal loads and random speeds;
//                     Coulomb friction gives −median, the viscous-Coulomb ansatz −mean
//   legged_compare    §3.6.2: both laws' balances for legs on a circle with random foot
//                     velocities of a given spread around a common one
//   legged_eps_error  §3.6.2, Fig. 3.15: relative error of a viscous-type force against the
//                     Coulomb force near the sliding velocity v = (|v|, 0)
//
// Balances come from the library's solvers (friction/solvers.hpp); legged_eps_error evaluates
// the single-foot forces in closed form.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

const double kNaN = std::nan("");

// --- legged_1d ---------------------------------------------------------------------------------

const std::vector<std::string_view> k1dKeys = {"N",     "seed",   "trials", "distribution",
                                               "scale", "offset", "speeds"};

struct OneDInputs {
  long long N = 0;
  long long seed = 0;
  long long trials = 1;
  std::string distribution = "uniform";
  double scale = 1.0;
  double offset = 0.0;
  std::vector<double> speeds;  ///< explicit speeds (`speeds`), else drawn
};

/// "0.5, -1, 2" -> {0.5, −1, 2}; nullopt if any item is not a finite number.
std::optional<std::vector<double>> parse_list(const std::string& s) {
  std::vector<double> out;
  std::size_t p = 0;
  while (p <= s.size()) {
    const std::size_t e = std::min(s.find(',', p), s.size());
    std::string item = s.substr(p, e - p);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (used != item.size() || !std::isfinite(x)) {
      return std::nullopt;
    }
    out.push_back(x);
    p = e + 1;
  }
  return out;
}

OneDInputs read_1d(const Point& point) {
  const Reader r(point, "legged_1d", k1dKeys);
  OneDInputs in;
  if (const auto speeds = r.text("speeds")) {
    const auto list = parse_list(*speeds);
    if (!list || list->empty()) {
      r.fail("speeds",
             "expected a comma-separated list of finite numbers (the feet's speeds "
             "relative to the body), got '" +
                 *speeds + "'");
    }
    in.speeds = *list;
    // The same bound as offset and scale: sums of N speeds stay finite and normal.
    for (const double v : in.speeds) {
      if (!(std::abs(v) <= 1e12)) {
        r.fail("speeds", "every speed must be in [-1e12, 1e12] m/s, got " + core::format_double(v));
      }
    }
    for (auto key : {"seed", "trials", "distribution", "scale", "offset"}) {
      if (r.has(key)) {
        r.fail(key, "not used with explicit speeds");
      }
    }
    in.N = static_cast<long long>(in.speeds.size());
    if (r.has("N") && r.integer("N", 0, 1, 100000) != in.N) {
      r.fail("N", "speeds has " + std::to_string(in.N) + " entries");
    }
    return in;
  }
  if (!r.has("N")) {
    r.fail("N", "required (the number of feet), or give explicit speeds");
  }
  in.N = r.integer("N", 0, 1, 10000);
  in.seed = r.integer("seed", 0, 0, 1LL << 53);
  in.trials = r.integer("trials", 1, 1, 1000000);
  in.distribution = r.choice("distribution", {"uniform", "normal", "exponential"});
  // Scales, speeds and lengths between 1e-12 and 1e12 keep every product and sum of the laws
  // (eqs. 3.9-3.14) finite and normal.
  in.scale = r.number("scale", 1.0, core::closed(1e-12, 1e12, "m/s"));
  in.offset = r.number("offset", 0.0, -1e12, 1e12, true);
  // A trial sorts and sums N speeds: 1e8 of them is seconds.
  r.limit_work("trials", "N · trials", static_cast<double>(in.N) * static_cast<double>(in.trials),
               1e8);
  return in;
}

/// The speeds of one trial: offset + scale·X with X uniform on [−1, 1], standard normal, or
/// exponential with mean 1 (skewed: mean and median differ most).
std::vector<double> draw_speeds(const OneDInputs& in, long long trial) {
  if (!in.speeds.empty()) {
    return in.speeds;
  }
  Random rng(static_cast<std::uint64_t>(in.seed), static_cast<std::uint64_t>(trial));
  std::vector<double> v(static_cast<std::size_t>(in.N));
  for (double& x : v) {
    if (in.distribution == "uniform") {
      x = in.offset + in.scale * (2.0 * rng.uniform() - 1.0);
    } else if (in.distribution == "normal") {
      x = in.offset + in.scale * rng.normal();
    } else {
      x = in.offset + in.scale * rng.exponential();
    }
  }
  return v;
}

/// One row per trial: both laws' body velocities against the median and mean of the speeds.
struct OneDRow {
  long long id = 0;
  long long N = 0;
  long long seed = 0;
  long long trial = 0;
  std::string distribution;  ///< uniform | normal | exponential, or "given" (explicit speeds)
  double scale = kNaN;       ///< NaN with explicit speeds
  double offset = kNaN;      ///< NaN with explicit speeds
  double v_coulomb = 0.0;
  double v_viscous = 0.0;
  double neg_median = 0.0;
  double neg_mean = 0.0;
  double interval_lo = 0.0;  ///< the Coulomb balances: [interval_lo, interval_hi]
  double interval_hi = 0.0;
  bool in_interval = false;  ///< v_coulomb within it (to 1e-7 of the speeds' range)
  bool unique = false;
  long long static_feet = 0;
  double vy_coulomb = 0.0;
  double w_coulomb = 0.0;
  double vy_viscous = 0.0;
  double w_viscous = 0.0;
  double speed_sd = 0.0;
  double speed_range = 0.0;
  bool converged = false;
  long long iterations = 0;
  double certificate = 0.0;
  std::string message;

  static std::vector<Column<OneDRow>> columns() {
    using R = OneDRow;
    return {value("id", &R::id),
            value("N", &R::N),
            value("seed", &R::seed),
            value("trial", &R::trial),
            value("distribution", &R::distribution),
            value("scale", &R::scale, "m/s"),
            value("offset", &R::offset, "m/s"),
            value("v_coulomb", &R::v_coulomb, "m/s"),
            value("v_viscous", &R::v_viscous, "m/s"),
            value("neg_median", &R::neg_median, "m/s"),
            value("neg_mean", &R::neg_mean, "m/s"),
            value("interval_lo", &R::interval_lo, "m/s"),
            value("interval_hi", &R::interval_hi, "m/s"),
            value("in_interval", &R::in_interval),
            value("unique", &R::unique),
            value("static_feet", &R::static_feet),
            value("vy_coulomb", &R::vy_coulomb, "m/s"),
            value("w_coulomb", &R::w_coulomb, "rad/s"),
            value("vy_viscous", &R::vy_viscous, "m/s"),
            value("w_viscous", &R::w_viscous, "rad/s"),
            value("speed_sd", &R::speed_sd, "m/s"),
            value("speed_range", &R::speed_range, "m/s"),
            value("converged", &R::converged),
            value("iterations", &R::iterations),
            value("certificate", &R::certificate),
            value("message", &R::message)};
  }
};

// Fig. 3.1 in the body frame of the library: the N feet lie on the body's x axis at
// x_i = −1 … 1 (evenly spaced; one foot at 0), each with the same normal load Mg/N (set directly:
// the 1-D example assumes equal loads), μ = 1, foot i sliding relative to the body at (v_i, 0).
// The problem is mirror-symmetric about the x axis and the dissipation is strictly convex in
// (v_y, ω) (at least two feet at distinct x slide), so both laws give v_y = ω = 0 and the 2-D
// solvers answer the 1-D question.
Rows<OneDRow> run_1d(const Point& point) {
  const OneDInputs in = read_1d(point);
  const int n = static_cast<int>(in.N);
  const contact::Robot robot = contact::uniform_robot(n, 1.0, 1.0, 1.0);
  contact::Frame frame(robot);
  for (int i = 0; i < n; ++i) {
    frame.q.col(i) = Eigen::Vector3d(n == 1 ? 0.0 : -1.0 + 2.0 * i / (n - 1), 0.0, -0.1);
    frame.contact[static_cast<std::size_t>(i)] = 1;
    frame.Fz(i) = robot.Mg / n;
  }
  Rows<OneDRow> out;
  for (long long trial = 0; trial < in.trials; ++trial) {
    std::vector<double> v = draw_speeds(in, trial);
    for (int i = 0; i < n; ++i) {
      frame.qdot.col(i) = Eigen::Vector3d(v[static_cast<std::size_t>(i)], 0.0, 0.0);
    }
    std::vector<double> s = v;
    std::sort(s.begin(), s.end());
    const std::size_t h = s.size() / 2;
    const double median = s.size() % 2 == 1 ? s[h] : 0.5 * (s[h - 1] + s[h]);
    double mean = 0.0;
    for (double x : v) {
      mean += x;
    }
    mean /= n;
    double var = 0.0;
    for (double x : v) {
      var += (x - mean) * (x - mean);
    }
    const double sd = std::sqrt(var / n);
    // Coulomb balance: half the feet slide each way; the body velocity is −(the median speed),
    // for even N any value between minus the two middle speeds.
    const double lo = -s[h];
    const double hi = s.size() % 2 == 1 ? -s[h] : -s[h - 1];

    friction::solve_viscous_coulomb(robot, frame);
    const Eigen::Vector3d visc = frame.v_body;
    const contact::FrictionSummary visc_summary = frame.friction;
    friction::solve_coulomb(robot, frame);
    const Eigen::Vector3d coul = frame.v_body;
    const contact::FrictionSummary& cs = frame.friction;
    const double tol = 1e-7 * std::max(s.back() - s.front(), std::abs(median) + 1e-300);

    OneDRow row;
    row.id = point.id;
    row.N = n;
    row.seed = in.seed;
    row.trial = trial;
    row.distribution = in.speeds.empty() ? in.distribution : std::string("given");
    if (in.speeds.empty()) {
      row.scale = in.scale;
      row.offset = in.offset;
    }
    row.v_coulomb = coul(0);
    row.v_viscous = visc(0);
    row.neg_median = -median;
    row.neg_mean = -mean;
    row.interval_lo = lo;
    row.interval_hi = hi;
    row.in_interval = coul(0) >= lo - tol && coul(0) <= hi + tol;
    row.unique = cs.unique;
    row.static_feet = cs.static_feet;
    row.vy_coulomb = coul(1);
    row.w_coulomb = coul(2);
    row.vy_viscous = visc(1);
    row.w_viscous = visc(2);
    row.speed_sd = sd;
    row.speed_range = s.back() - s.front();
    row.converged = cs.converged;
    row.iterations = cs.iterations;
    row.certificate = cs.certificate;
    row.message = cs.message;
    if (!visc_summary.message.empty()) {
      row.message +=
          (row.message.empty() ? "" : "; ") + std::string("viscous: ") + visc_summary.message;
    }
    out.rows.push_back(std::move(row));
    if (!cs.converged && !out.failed) {
      out.failed = true;
      out.message =
          "Coulomb solve did not converge (trial " + std::to_string(trial) + "): " + cs.message;
    }
  }
  return out;
}

// --- legged_compare ------------------------------------------------------------------------------

const std::vector<std::string_view> kCompareKeys = {"N", "seed", "trials", "spread", "radius"};

struct CompareInputs {
  long long N = 6;
  long long seed = 0;
  long long trials = 1;
  double spread = 0.2;
  double radius = 0.3;
};

CompareInputs read_compare(const Point& point) {
  const Reader r(point, "legged_compare", kCompareKeys);
  CompareInputs in;
  if (!r.has("N")) {
    r.fail("N", "required (the number of legs)");
  }
  in.N = r.integer("N", 6, 3, 1000);
  in.seed = r.integer("seed", 0, 0, 1LL << 53);
  in.trials = r.integer("trials", 1, 1, 1000000);
  in.spread = r.number("spread", 0.2, core::closed(0.0, 1e6, "m/s"));
  in.radius = r.number("radius", 0.3, core::closed(1e-6, 1e6, "m"));
  // A trial is one Coulomb solve of N legs (an interior-point method, about N² per iteration).
  r.limit_work(
      "trials", "N² · trials",
      static_cast<double>(in.N) * static_cast<double>(in.N) * static_cast<double>(in.trials), 1e9);
  return in;
}

/// One row per trial: both laws' balances and how far apart they are.
struct CompareRow {
  long long id = 0;
  long long N = 0;
  long long seed = 0;
  long long trial = 0;
  double spread = 0.0;
  double vx_viscous = 0.0;
  double vy_viscous = 0.0;
  double w_viscous = 0.0;
  double vx_coulomb = 0.0;
  double vy_coulomb = 0.0;
  double w_coulomb = 0.0;
  double diff = 0.0;        ///< ‖(Δv_x, Δv_y, radius·Δω)‖
  double rel_diff = 0.0;    ///< diff / mean_speed
  double mean_speed = 0.0;  ///< the mean of ‖q̇_k‖
  long long static_feet = 0;
  bool unique = false;
  bool converged = false;
  std::string message;

  static std::vector<Column<CompareRow>> columns() {
    using R = CompareRow;
    return {value("id", &R::id),
            value("N", &R::N),
            value("seed", &R::seed),
            value("trial", &R::trial),
            value("spread", &R::spread, "m/s"),
            value("vx_viscous", &R::vx_viscous, "m/s"),
            value("vy_viscous", &R::vy_viscous, "m/s"),
            value("w_viscous", &R::w_viscous, "rad/s"),
            value("vx_coulomb", &R::vx_coulomb, "m/s"),
            value("vy_coulomb", &R::vy_coulomb, "m/s"),
            value("w_coulomb", &R::w_coulomb, "rad/s"),
            value("diff", &R::diff, "m/s"),
            value("rel_diff", &R::rel_diff),
            value("mean_speed", &R::mean_speed, "m/s"),
            value("static_feet", &R::static_feet),
            value("unique", &R::unique),
            value("converged", &R::converged),
            value("message", &R::message)};
  }
};

// §3.1.2.4 and §3.6.2 beyond one example: N legs equally spaced on a circle of the given radius
// (all at the same height: the spring support gives equal loads), every foot sliding backwards
// relative to the body at 1 m/s plus a random planar velocity of standard deviation `spread`
// m/s per component. Each trial solves both balances; diff = ‖(Δv_x, Δv_y, radius·Δω)‖ between
// them (the largest difference of a foot's velocity at the rim), rel_diff = diff / the mean foot
// speed ‖q̇_k‖.
Rows<CompareRow> run_compare(const Point& point) {
  const CompareInputs in = read_compare(point);
  const int n = static_cast<int>(in.N);
  const contact::Robot robot = contact::uniform_robot(n, 10.0, 1.0, 1.0);
  contact::Frame frame(robot);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    frame.q.col(k) = Eigen::Vector3d(in.radius * std::cos(a), in.radius * std::sin(a), -0.1);
  }
  contact::spring_support(robot, frame);
  Rows<CompareRow> out;
  for (long long trial = 0; trial < in.trials; ++trial) {
    Random rng(static_cast<std::uint64_t>(in.seed), static_cast<std::uint64_t>(trial));
    double mean_speed = 0.0;
    for (int k = 0; k < n; ++k) {
      const double dx = rng.normal();
      const double dy = rng.normal();
      frame.qdot.col(k) = Eigen::Vector3d(-1.0 + in.spread * dx, in.spread * dy, 0.0);
      mean_speed += frame.qdot.col(k).head<2>().norm() / n;
    }
    friction::solve_viscous_coulomb(robot, frame);
    const Eigen::Vector3d visc = frame.v_body;
    friction::solve_coulomb(robot, frame);
    const Eigen::Vector3d coul = frame.v_body;
    const contact::FrictionSummary& cs = frame.friction;
    const Eigen::Vector3d d = visc - coul;
    const double diff = std::sqrt(d(0) * d(0) + d(1) * d(1) + in.radius * in.radius * d(2) * d(2));
    out.rows.push_back({point.id, in.N, in.seed, trial, in.spread, visc(0), visc(1), visc(2),
                        coul(0), coul(1), coul(2), diff, diff / mean_speed, mean_speed,
                        cs.static_feet, cs.unique, cs.converged, cs.message});
    if (!cs.converged && !out.failed) {
      out.failed = true;
      out.message =
          "Coulomb solve did not converge (trial " + std::to_string(trial) + "): " + cs.message;
    }
  }
  return out;
}

// --- legged_eps_error --------------------------------------------------------------------------

const std::vector<std::string_view> kEpsKeys = {"model", "epsilon", "speed", "shape",
                                                "range", "n",       "angles"};

struct EpsInputs {
  std::string model = "viscous";
  double epsilon = kNaN;
  double speed = 1.0;
  std::string shape = "grid";
  double range = 0.3;
  long long n = 121;
  long long angles = 360;
};

EpsInputs read_eps(const Point& point) {
  const Reader r(point, "legged_eps_error", kEpsKeys);
  EpsInputs in;
  in.model = r.choice("model", {"viscous", "tangent", "epsilon"});
  if (in.model == "epsilon") {
    if (!r.has("epsilon")) {
      r.fail("epsilon", "required with model = \"epsilon\" (eq. 3.14's ε, m/s)");
    }
    in.epsilon = r.number("epsilon", 1.0, core::closed(1e-12, 1e12, "m/s"));
  } else if (r.has("epsilon")) {
    r.fail("epsilon", "only used with model = \"epsilon\"");
  }
  in.speed = r.number("speed", 1.0, core::closed(1e-12, 1e12, "m/s"));
  in.shape = r.choice("shape", {"grid", "polar"});
  in.range = r.number("range", 0.3, 0.0, 0.99);
  in.n = r.integer("n", in.shape == "grid" ? 121 : 41, 2, 4001);
  if (r.has("angles") && in.shape != "polar") {
    r.fail("angles", "only used with shape = \"polar\"");
  }
  in.angles = r.integer("angles", 360, 4, 100000);
  if (in.shape == "polar") {
    r.limit_work("angles", "n · angles", static_cast<double>(in.n) * static_cast<double>(in.angles),
                 1e7);
  }
  return in;
}

/// One row per velocity error δv.
struct EpsErrorRow {
  long long id = 0;
  std::string model;      ///< viscous | tangent | epsilon
  double epsilon = kNaN;  ///< ε of the epsilon model, m/s (NaN otherwise)
  double speed = 0.0;     ///< |v|, m/s
  std::string shape;      ///< grid | polar
  double dvx = 0.0;       ///< δv/|v|
  double dvy = 0.0;
  double dv_rel = 0.0;  ///< |δv|/|v|
  double angle = 0.0;   ///< direction of δv, rad
  double rel_error = 0.0;

  static std::vector<Column<EpsErrorRow>> columns() {
    using R = EpsErrorRow;
    return {value("id", &R::id),
            value("model", &R::model),
            value("epsilon", &R::epsilon, "m/s"),
            value("speed", &R::speed, "m/s"),
            value("shape", &R::shape),
            value("dvx", &R::dvx),
            value("dvy", &R::dvy),
            value("dv_rel", &R::dv_rel),
            value("angle", &R::angle, "rad"),
            value("rel_error", &R::rel_error)};
  }
};

// Thesis §3.6.2, Fig. 3.15: one foot with μ F_z = 1 slides at v = (speed, 0) + δv. The Coulomb
// force is F_C = −u/|u|. The models, each equal to F_C at δv = 0 (calibrated at v):
//   viscous  the viscous-Coulomb ansatz, F = −u/|v| (linear in u; eq. 3.14 with ε → ∞, scaled)
//   tangent  the Coulomb force linearized at v: F = −v/|v| − (I − v̂v̂ᵀ) δv/|v| (affine)
//   epsilon  eq. 3.14: F = −u (ε + |u|)/(ε + |u|²), divided by its value factor at v
// rel_error = |F − F_C| / |F_C|. Grid: δv/|v| over [−range, range]², n × n. Polar: |δv|/|v| =
// range·i/(n − 1), i = 0 … n − 1, at `angles` directions.
Rows<EpsErrorRow> run_eps(const Point& point) {
  const EpsInputs in = read_eps(point);
  const double v0 = in.speed;
  const auto phi = [&](double s) { return (in.epsilon + s) / (in.epsilon + s * s); };
  const double calib = in.model == "epsilon" ? 1.0 / (phi(v0) * v0) : 1.0 / v0;
  Rows<EpsErrorRow> out;
  const auto emit = [&](double dx, double dy, double angle) {
    const Eigen::Vector2d u(v0 + dx, dy);
    const double s = u.norm();
    const Eigen::Vector2d Fc = s > 0.0 ? Eigen::Vector2d(-u / s) : Eigen::Vector2d::Zero();
    Eigen::Vector2d Fm;
    if (in.model == "viscous") {
      Fm = -calib * u;
    } else if (in.model == "tangent") {
      Fm = Eigen::Vector2d(-1.0, -dy / v0);
    } else {
      Fm = -calib * phi(s) * u;
    }
    const double err = s > 0.0 ? (Fm - Fc).norm() / Fc.norm() : kNaN;
    out.rows.push_back({point.id, in.model, in.epsilon, v0, in.shape, dx / v0, dy / v0,
                        std::hypot(dx, dy) / v0, angle, err});
  };
  if (in.shape == "grid") {
    const std::vector<double> g = linspace(-in.range, in.range, in.n);
    for (double y : g) {
      for (double x : g) {
        emit(x * v0, y * v0, std::atan2(y, x));
      }
    }
  } else {
    for (long long i = 0; i < in.n; ++i) {
      const double rad = in.range * static_cast<double>(i) / static_cast<double>(in.n - 1);
      for (long long j = 0; j < in.angles; ++j) {
        const double a =
            2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(in.angles);
        emit(rad * v0 * std::cos(a), rad * v0 * std::sin(a), a);
      }
    }
  }
  return out;
}

}  // namespace

std::vector<PointKind> legged_law_kinds() {
  return {
      make_point_kind<OneDRow>(
          "legged_1d",
          "Fig. 3.1: N feet on a line, equal loads, random speeds: Coulomb vs viscous-Coulomb body "
          "velocity against the median and mean (one row per trial)",
          Timed::kNo, [](const Point& p) { (void)read_1d(p); }, run_1d),
      make_point_kind<CompareRow>(
          "legged_compare",
          "§3.6.2: viscous-Coulomb vs Coulomb balance of N legs on a circle with random foot "
          "velocities around (−1, 0) (one row per trial)",
          Timed::kNo, [](const Point& p) { (void)read_compare(p); }, run_compare),
      make_point_kind<EpsErrorRow>(
          "legged_eps_error",
          "Fig. 3.15: relative error of viscous-type friction against Coulomb friction near v = "
          "(|v|, 0) (one row per δv)",
          Timed::kNo, [](const Point& p) { (void)read_eps(p); }, run_eps),
  };
}

}  // namespace slipwalk::sweeps::points
