// The point kinds of the multi-legged model (thesis ch. 3). Each kind's keys are checked in its
// read_* function, and its rows are a struct with their column table above its run_* function.
//
//   legged_1d            §3.1.2, Fig. 3.1: N feet on a line with equal loads and random speeds;
//                        Coulomb friction gives −median, the viscous-Coulomb ansatz −mean
//   legged_force_map     §3.1.2.4, Fig. 3.2: the total planar force over a grid of body
//                        velocities (ω = 0) under both laws, and each law's balance
//   legged_compare       §3.6.2: both laws' balances for legs on a circle with random foot
//                        velocities of a given spread around a common one
//   legged_support_path  §3.3, Figs. 3.3 and 3.4: the spring-support search path
//   legged_eps_error     §3.6.2, Fig. 3.15: relative error of a viscous-type force against the
//                        Coulomb force near the sliding velocity v = (|v|, 0)
//
// Robots are read from frame files (the DESIGN.md frame format, contact/frame_json.hpp) named
// relative to the spec file. Balances come from the library's solvers (friction/solvers.hpp),
// forces at a prescribed body velocity from friction::planar_forces (friction/planar_forces.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "contact/frame_json.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "friction/planar_forces.hpp"
#include "friction/solvers.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

using core::InputError;
using friction::ForceLaw;
const double kNaN = std::nan("");

// --- reading a point ----------------------------------------------------------------------------

/// The robot and frame of a frame file named by `key` (required), relative to the spec's folder.
/// A file that is missing or malformed fails at the key, with the file's own message.
contact::FrameInput read_robot(const Reader& r, std::string_view key, std::string& name) {
  const auto file = r.text(key);
  if (!file) {
    r.fail(key, "required (a robot frame file, JSON, relative to the spec file)");
  }
  name = *file;
  const std::filesystem::path path =
      std::filesystem::path(r.point().source).parent_path() / std::filesystem::path(*file);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    r.fail(key, "cannot read the robot file " + path.string());
  }
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return contact::parse_frame_json(text.str(), path.string());
  } catch (const InputError& e) {
    r.fail(key, std::string("bad robot file: ") + e.what());
  }
}

/// "spring support: <status>[: <message>]" when the search found no balance, else empty.
std::string support_failure(const contact::Frame& f) {
  using Status = contact::SupportSummary::Status;
  if (f.support.status != Status::kUnsupported && f.support.status != Status::kIterationLimit) {
    return {};
  }
  return std::string("spring support: ") + contact::status_name(f.support.status) +
         (f.support.message.empty() ? "" : ": " + f.support.message);
}
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
  in.scale = r.number("scale", 1.0, 0.0, 1e12);
  in.offset = r.number("offset", 0.0, -1e12, 1e12, true);
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
  in.spread = r.number("spread", 0.2, 0.0, 1e6, true);
  in.radius = r.number("radius", 0.3, 0.0, 1e6);
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

// --- legged_force_map -------------------------------------------------------------------------

const std::vector<std::string_view> kMapKeys = {"robot",  "n",     "vx_min",  "vx_max", "vy_min",
                                                "vy_max", "eps_n", "eps_min", "eps_max"};

struct MapInputs {
  std::string robot_name;
  std::optional<contact::FrameInput> robot;
  long long n = 101;
  std::optional<double> vx_min, vx_max, vy_min, vy_max;
  long long eps_n = 0;
  double eps_min = 1e-4;
  double eps_max = 1e2;
};

MapInputs read_map(const Point& point) {
  const Reader r(point, "legged_force_map", kMapKeys);
  MapInputs in;
  in.robot.emplace(read_robot(r, "robot", in.robot_name));
  in.n = r.integer("n", 101, 2, 2001);
  in.vx_min = r.number("vx_min");
  in.vx_max = r.number("vx_max");
  in.vy_min = r.number("vy_min");
  in.vy_max = r.number("vy_max");
  for (auto [a, b, ka, kb] : {std::tuple{in.vx_min, in.vx_max, "vx_min", "vx_max"},
                              std::tuple{in.vy_min, in.vy_max, "vy_min", "vy_max"}}) {
    if (a.has_value() != b.has_value()) {
      r.fail(a ? kb : ka,
             std::string("give both ") + ka + " and " + kb + " (or neither: automatic)");
    }
    if (a && !(std::isfinite(*a) && std::isfinite(*b) && *a < *b)) {
      r.fail(kb, std::string("must exceed ") + ka);
    }
  }
  in.eps_n = r.integer("eps_n", 0, 0, 1000);
  in.eps_min = r.number("eps_min", 1e-4, 0.0, 1e12);
  in.eps_max = r.number("eps_max", 1e2, 0.0, 1e12);
  if (!(in.eps_max > in.eps_min)) {
    r.fail("eps_max", "must exceed eps_min");
  }
  return in;
}

/// One row of a force map: a "foot", a "balance" or a "grid" row (or a lone "support" row when
/// the spring support finds no balance). A row's cells that do not apply to its kind are NaN
/// (numbers), empty (texts) or −1 (foot).
struct ForceMapRow {
  long long id = 0;
  std::string robot;      ///< the frame file
  std::string row;        ///< foot | balance | grid | support
  std::string law;        ///< viscous | coulomb | epsilon (balance, grid)
  double epsilon = kNaN;  ///< ε of an epsilon balance, m/s
  long long foot = -1;    ///< the foot of a foot row
  double vx = kNaN;       ///< body velocity: a foot's rest velocity, a balance, a grid point
  double vy = kNaN;
  double omega = kNaN;
  double Fx = kNaN;  ///< Σ F_k at (vx, vy, omega)
  double Fy = kNaN;
  double Mz = kNaN;      ///< Σ (q_k × F_k)_z at (vx, vy, omega)
  double F_norm = kNaN;  ///< ‖Σ F_k‖
  double qx = kNaN;      ///< a foot's position, velocity relative to the body and load
  double qy = kNaN;
  double qdx = kNaN;
  double qdy = kNaN;
  double Fz = kNaN;
  double unique = kNaN;  ///< a balance's solver summary (0/1, 0/1, count; NaN elsewhere)
  double converged = kNaN;
  double iterations = kNaN;
  double residual = kNaN;
  std::string message;

  static std::vector<Column<ForceMapRow>> columns() {
    using R = ForceMapRow;
    return {value("id", &R::id),
            value("robot", &R::robot),
            value("row", &R::row),
            value("law", &R::law),
            value("epsilon", &R::epsilon, "m/s"),
            value("foot", &R::foot),
            value("vx", &R::vx, "m/s"),
            value("vy", &R::vy, "m/s"),
            value("omega", &R::omega, "rad/s"),
            value("Fx", &R::Fx, "N"),
            value("Fy", &R::Fy, "N"),
            value("Mz", &R::Mz, "N m"),
            value("F_norm", &R::F_norm, "N"),
            value("qx", &R::qx, "m"),
            value("qy", &R::qy, "m"),
            value("qdx", &R::qdx, "m/s"),
            value("qdy", &R::qdy, "m/s"),
            value("Fz", &R::Fz, "N"),
            value("unique", &R::unique),
            value("converged", &R::converged),
            value("iterations", &R::iterations),
            value("residual", &R::residual),
            value("message", &R::message)};
  }
};

const char* law_name(ForceLaw law) {
  return law == ForceLaw::kViscousCoulomb ? "viscous" : "coulomb";
}

// Thesis Fig. 3.2: the robot's loads from the spring support (§3.3); then
//  * one "foot" row per foot in contact: position, velocity relative to the body, load, and the
//    body velocity (ω = 0) that puts it at rest (vx, vy = −q̇_xy: a point discontinuity of the
//    Coulomb force map);
//  * one "balance" row per law: the full force–moment balance (v_x, v_y, ω) from the library
//    solvers, and with eps_n > 0 the ε-family of eq. 3.14 from eps_max down to eps_min; its
//    Fx, Fy, Mz are the viscous-Coulomb sums on the viscous row and the Coulomb sums on the
//    others (on an ε row: how far its balance is from Coulomb's);
//  * n × n "grid" rows per law: Σ F and Σ M_z at (v_x, v_y, ω = 0), F_norm = ‖Σ F‖.
// The grid spans the feet's rest velocities and the balances, 25 % wider, unless given.
Rows<ForceMapRow> run_map(const Point& point) {
  MapInputs in = read_map(point);
  const contact::Robot& robot = in.robot->robot;
  contact::Frame& frame = in.robot->frame;
  Rows<ForceMapRow> out;
  const auto row = [&](const char* kind, std::string law, double eps, long long foot) {
    ForceMapRow r;
    r.id = point.id;
    r.robot = in.robot_name;
    r.row = kind;
    r.law = std::move(law);
    r.epsilon = eps;
    r.foot = foot;
    return r;
  };
  contact::spring_support(robot, frame);
  if (const std::string failure = support_failure(frame); !failure.empty()) {
    out.failed = true;
    out.message = failure;
    ForceMapRow r = row("support", "", kNaN, -1);
    r.message = failure;
    out.rows.push_back(std::move(r));
    return out;
  }
  double lo_x = 0.0, hi_x = 0.0, lo_y = 0.0, hi_y = 0.0;
  bool first = true;
  const auto extend = [&](double x, double y) {
    lo_x = first ? x : std::min(lo_x, x);
    hi_x = first ? x : std::max(hi_x, x);
    lo_y = first ? y : std::min(lo_y, y);
    hi_y = first ? y : std::max(hi_y, y);
    first = false;
  };
  for (int k = 0; k < frame.legs(); ++k) {
    if (frame.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    ForceMapRow r = row("foot", "", kNaN, k);
    r.vx = -frame.qdot(0, k);
    r.vy = -frame.qdot(1, k);
    r.qx = frame.q(0, k);
    r.qy = frame.q(1, k);
    r.qdx = frame.qdot(0, k);
    r.qdy = frame.qdot(1, k);
    r.Fz = frame.Fz(k);
    extend(-frame.qdot(0, k), -frame.qdot(1, k));
    out.rows.push_back(std::move(r));
  }
  const auto balance = [&](const std::string& law, double eps) {
    if (law == "viscous") {
      friction::solve_viscous_coulomb(robot, frame);
    } else if (law == "coulomb") {
      friction::solve_coulomb(robot, frame);
    } else {
      friction::solve_epsilon(robot, frame, eps);
    }
    const Eigen::Vector3d x = frame.v_body;
    const friction::PlanarSum sum =
        friction::planar_forces(robot, frame, x.head<2>(), x(2),
                                law == "viscous" ? ForceLaw::kViscousCoulomb : ForceLaw::kCoulomb);
    ForceMapRow r = row("balance", law, eps, -1);
    r.vx = x(0);
    r.vy = x(1);
    r.omega = x(2);
    r.Fx = sum.force(0);
    r.Fy = sum.force(1);
    r.Mz = sum.moment;
    r.F_norm = sum.force.norm();
    r.unique = frame.friction.unique ? 1.0 : 0.0;
    r.converged = frame.friction.converged ? 1.0 : 0.0;
    r.iterations = frame.friction.iterations;
    r.residual = frame.friction.residual;
    r.message = frame.friction.message;
    if (!frame.friction.converged && !out.failed) {
      out.failed = true;
      out.message = law + " balance did not converge: " + frame.friction.message;
    }
    if (law != "epsilon") {
      extend(x(0), x(1));
    }
    out.rows.push_back(std::move(r));
  };
  balance("viscous", kNaN);
  balance("coulomb", kNaN);
  for (long long i = 0; i < in.eps_n; ++i) {
    const double t =
        in.eps_n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(in.eps_n - 1);
    balance("epsilon", in.eps_max * std::pow(in.eps_min / in.eps_max, t));
  }
  // The grid: given, or the box around the rest velocities and balances, 25 % wider each way.
  const double mx = 0.25 * std::max(hi_x - lo_x, 1e-3);
  const double my = 0.25 * std::max(hi_y - lo_y, 1e-3);
  const double x0 = in.vx_min.value_or(lo_x - mx), x1 = in.vx_max.value_or(hi_x + mx);
  const double y0 = in.vy_min.value_or(lo_y - my), y1 = in.vy_max.value_or(hi_y + my);
  const std::vector<double> xs = linspace(x0, x1, in.n);
  const std::vector<double> ys = linspace(y0, y1, in.n);
  for (ForceLaw law : {ForceLaw::kCoulomb, ForceLaw::kViscousCoulomb}) {
    for (double y : ys) {
      for (double x : xs) {
        const friction::PlanarSum sum =
            friction::planar_forces(robot, frame, Eigen::Vector2d(x, y), 0.0, law);
        ForceMapRow r = row("grid", law_name(law), kNaN, -1);
        r.vx = x;
        r.vy = y;
        r.omega = 0.0;
        r.Fx = sum.force(0);
        r.Fy = sum.force(1);
        r.Mz = sum.moment;
        r.F_norm = sum.force.norm();
        out.rows.push_back(std::move(r));
      }
    }
  }
  return out;
}

// --- legged_support_path ------------------------------------------------------------------------

const std::vector<std::string_view> kPathKeys = {"robot"};

void check_path(const Point& point) {
  const Reader r(point, "legged_support_path", kPathKeys);
  std::string name;
  (void)read_robot(r, "robot", name);
}

/// One row of a support path: a "foot" row per leg, a "step" row per recorded state of the
/// search and one "result" row. A row's cells that do not apply to its kind are NaN (numbers),
/// empty (texts) or −1 (step, foot).
struct SupportPathRow {
  long long id = 0;
  std::string robot;    ///< the frame file
  std::string row;      ///< foot | step | result
  long long step = -1;  ///< a step's index; on the result row, the number of steps
  long long foot = -1;  ///< the leg of a foot row
  double alpha = kNaN;  ///< the state (eq. 3.6) of a step or the result
  double beta = kNaN;
  double z = kNaN;
  double contacts = kNaN;      ///< feet in contact (step, result)
  double changed = kNaN;       ///< the leg whose contact changed at a step (−1: none)
  std::string mask;            ///< contact set, "C" in contact, "-" in the air, one per leg
  double target_alpha = kNaN;  ///< the balance of the step's contact set (eq. 3.9), if any
  double target_beta = kNaN;
  double target_z = kNaN;
  double qx = kNaN;  ///< a foot's position, stiffness and final load
  double qy = kNaN;
  double qz = kNaN;
  double K = kNaN;
  double Fz = kNaN;
  std::string status;        ///< the search's outcome (result)
  double iterations = kNaN;  ///< (result)
  double residual = kNaN;    ///< (result)
  std::string message;

  static std::vector<Column<SupportPathRow>> columns() {
    using R = SupportPathRow;
    return {value("id", &R::id),
            value("robot", &R::robot),
            value("row", &R::row),
            value("step", &R::step),
            value("foot", &R::foot),
            value("alpha", &R::alpha),
            value("beta", &R::beta),
            value("z", &R::z, "m"),
            value("contacts", &R::contacts),
            value("changed", &R::changed),
            value("mask", &R::mask),
            value("target_alpha", &R::target_alpha),
            value("target_beta", &R::target_beta),
            value("target_z", &R::target_z, "m"),
            value("qx", &R::qx, "m"),
            value("qy", &R::qy, "m"),
            value("qz", &R::qz, "m"),
            value("K", &R::K, "N/m"),
            value("Fz", &R::Fz, "N"),
            value("status", &R::status),
            value("iterations", &R::iterations),
            value("residual", &R::residual),
            value("message", &R::message)};
  }
};

/// The balance of a fixed contact set (eq. 3.9, as the minimizer of the quadratic potential of
/// contact/spring_support.hpp): Σ_{k∈C} K_k h_k a_k + Mg e_z = 0 with a_k = (q_y, −q_x, 1) in
/// (α, β, z). Least-norm in the directions no foot of the robot can feel (α for a robot whose feet
/// all have q_y = 0). Empty when the set cannot balance the moment (fewer independent contacts
/// than the robot's geometry has: the search tilts instead, eqs. 3.11, 3.12).
std::optional<Eigen::Vector3d> contact_set_balance(const contact::Robot& robot,
                                                   const contact::Frame& f,
                                                   const std::string& mask) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d H_all = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs(0.0, 0.0, -robot.Mg);
  for (int k = 0; k < f.legs(); ++k) {
    const Eigen::Vector3d a(f.q(1, k), -f.q(0, k), 1.0);
    H_all += a * a.transpose();
    if (mask[static_cast<std::size_t>(k)] == 'C') {
      H += robot.K(k) * a * a.transpose();
      rhs -= robot.K(k) * f.q(2, k) * a;
    }
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d> all(H_all);
  all.setThreshold(1e-12);
  Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d> cod(H);
  cod.setThreshold(1e-12);
  if (cod.rank() < all.rank()) {
    return std::nullopt;
  }
  return cod.solve(rhs);
}

Rows<SupportPathRow> run_path(const Point& point) {
  const Reader r(point, "legged_support_path", kPathKeys);
  std::string name;
  contact::FrameInput in = read_robot(r, "robot", name);
  const contact::Robot& robot = in.robot;
  contact::Frame& f = in.frame;
  std::vector<contact::SupportStep> path;
  contact::SupportOptions options;
  options.path = &path;
  contact::spring_support(robot, f, options);

  Rows<SupportPathRow> out;
  const auto row = [&](const char* kind, long long step, long long foot) {
    SupportPathRow x;
    x.id = point.id;
    x.robot = name;
    x.row = kind;
    x.step = step;
    x.foot = foot;
    return x;
  };
  const int n = f.legs();
  for (int j = 0; j < n; ++j) {
    SupportPathRow x = row("foot", -1, j);
    x.qx = f.q(0, j);
    x.qy = f.q(1, j);
    x.qz = f.q(2, j);
    x.K = robot.K(j);
    x.Fz = f.Fz(j);
    out.rows.push_back(std::move(x));
  }
  // The contact set along the path ("C" in contact, "-" in the air, one character per leg): the
  // lowest feet at the start, then each recorded change toggles its leg (a state on a contact
  // plane has that foot at h = 0 exactly).
  std::string mask(static_cast<std::size_t>(n), '-');
  for (std::size_t i = 0; i < path.size(); ++i) {
    const contact::SupportStep& s = path[i];
    if (i == 0) {
      std::vector<std::pair<double, int>> h;
      for (int j = 0; j < n; ++j) {
        h.emplace_back(contact::foot_height(f, j, s.alpha, s.beta, s.z), j);
      }
      std::sort(h.begin(), h.end());
      for (int k = 0; k < s.contacts && k < n; ++k) {
        mask[static_cast<std::size_t>(h[static_cast<std::size_t>(k)].second)] = 'C';
      }
    } else if (s.changed >= 0 && s.changed < n) {
      char& c = mask[static_cast<std::size_t>(s.changed)];
      c = c == 'C' ? '-' : 'C';
    }
    SupportPathRow x = row("step", static_cast<long long>(i), -1);
    x.alpha = s.alpha;
    x.beta = s.beta;
    x.z = s.z;
    x.contacts = s.contacts;
    x.changed = s.changed;
    x.mask = mask;
    if (const auto t = contact_set_balance(robot, f, mask)) {
      x.target_alpha = (*t)(0);
      x.target_beta = (*t)(1);
      x.target_z = (*t)(2);
    }
    out.rows.push_back(std::move(x));
  }
  SupportPathRow x = row("result", static_cast<long long>(path.size()), -1);
  x.alpha = f.alpha;
  x.beta = f.beta;
  x.z = f.z;
  int contacts = 0;
  for (int j = 0; j < n; ++j) {
    contacts += f.contact[static_cast<std::size_t>(j)] != 0 ? 1 : 0;
    x.mask += f.contact[static_cast<std::size_t>(j)] != 0 ? 'C' : '-';
  }
  x.contacts = contacts;
  x.status = contact::status_name(f.support.status);
  x.iterations = f.support.iterations;
  x.residual = f.support.residual;
  x.message = f.support.message;
  out.rows.push_back(std::move(x));
  if (std::string failure = support_failure(f); !failure.empty()) {
    out.failed = true;
    out.message = std::move(failure);
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
    in.epsilon = r.number("epsilon", 1.0, 0.0, 1e12);
  } else if (r.has("epsilon")) {
    r.fail("epsilon", "only used with model = \"epsilon\"");
  }
  in.speed = r.number("speed", 1.0, 0.0, 1e12);
  in.shape = r.choice("shape", {"grid", "polar"});
  in.range = r.number("range", 0.3, 0.0, 0.99);
  in.n = r.integer("n", in.shape == "grid" ? 121 : 41, 2, 4001);
  if (r.has("angles") && in.shape != "polar") {
    r.fail("angles", "only used with shape = \"polar\"");
  }
  in.angles = r.integer("angles", 360, 4, 100000);
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

std::vector<PointKind> legged_kinds() {
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
      make_point_kind<ForceMapRow>(
          "legged_force_map",
          "Fig. 3.2: total planar force over a (v_x, v_y) grid at ω = 0 under Coulomb and "
          "viscous-Coulomb friction, the feet's rest velocities and each law's balance",
          Timed::kNo, [](const Point& p) { (void)read_map(p); }, run_map),
      make_point_kind<SupportPathRow>(
          "legged_support_path",
          "Figs. 3.3, 3.4: the spring-support search path in (α, β, z) with its contact sets",
          Timed::kNo, check_path, run_path),
      make_point_kind<EpsErrorRow>(
          "legged_eps_error",
          "Fig. 3.15: relative error of viscous-type friction against Coulomb friction near v = "
          "(|v|, 0) (one row per δv)",
          Timed::kNo, [](const Point& p) { (void)read_eps(p); }, run_eps),
  };
}

}  // namespace slipwalk::sweeps::points
