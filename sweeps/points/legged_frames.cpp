// The multi-legged model (thesis ch. 3) on robot frame files: the feet's positions, velocities
// and stiffnesses come from a frame file (the DESIGN.md frame format, contact/frame_json.hpp)
// named relative to the spec file. Each kind's keys are checked in its read_* or check_*
// function, and its rows are a struct with their column table above its run_* function.
//
//   legged_force_map     §3.1.2.4, Fig. 3.2: the total planar force over a grid of body
//                        velocities (ω = 0) under both laws, and each law's balance
//   legged_support_path  §3.3, Figs. 3.3 and 3.4: the spring-support search path
//
// Loads come from the spring support (contact/spring_support.hpp), balances from the library's
// solvers (friction/solvers.hpp), forces at a prescribed body velocity from
// friction::planar_forces (friction/planar_forces.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "contact/frame_json.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"
#include "friction/planar_forces.hpp"
#include "friction/solvers.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/spec.hpp"
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
  try {
    return contact::parse_frame_json(core::read_json_text(path), path.string());
  } catch (const InputError& e) {
    r.fail(key, std::string("bad robot file: ") + e.what());
  }
}

/// "spring support: <status>[: <message>]" when the search found no balance, else empty.
std::string support_failure(const contact::Frame& f) {
  using Status = contact::SupportSummary::Status;
  if (f.support.status != Status::kUnsupported && f.support.status != Status::kIterationLimit &&
      f.support.status != Status::kNonFinite) {
    return {};
  }
  return std::string("spring support: ") + contact::status_name(f.support.status) +
         (f.support.message.empty() ? "" : ": " + f.support.message);
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
  in.eps_min = r.number("eps_min", 1e-4, core::closed(1e-12, 1e12, "m/s"));
  in.eps_max = r.number("eps_max", 1e2, core::closed(1e-12, 1e12, "m/s"));
  // n² grid points per law, each a sum over the legs.
  r.limit_work("n", "n² · legs",
               static_cast<double>(in.n) * static_cast<double>(in.n) *
                   static_cast<double>(in.robot->robot.legs()),
               1e9);
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
      h.reserve(static_cast<std::size_t>(n));
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

}  // namespace

std::vector<PointKind> legged_frame_kinds() {
  return {
      make_point_kind<ForceMapRow>(
          "legged_force_map",
          "Fig. 3.2: total planar force over a (v_x, v_y) grid at ω = 0 under Coulomb and "
          "viscous-Coulomb friction, the feet's rest velocities and each law's balance",
          Timed::kNo, [](const Point& p) { (void)read_map(p); }, run_map),
      make_point_kind<SupportPathRow>(
          "legged_support_path",
          "Figs. 3.3, 3.4: the spring-support search path in (α, β, z) with its contact sets",
          Timed::kNo, check_path, run_path),
  };
}

}  // namespace slipwalk::sweeps::points
