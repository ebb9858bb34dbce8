// The brute-force planner of thesis §5.4–5.5 (planning/planner.hpp) as sweep points: whole plans
// on BigANT from the thesis' start (planning::tripod_start), and the toe path of its leg.
//
//   plan_run      one row per planning step: the plan CSV's columns (planning/plan_csv.hpp, the
//                 one table that names them) after the point's own columns, and a last row, step
//                 = steps, with the state after the last step (no choice there: option −1, cost
//                 and speeds NaN). Figs. 5.9–5.11 draw these rows.
//   plan_summary  one row per plan: tracking error (mean, final, largest distance to the target;
//                 yaw error), where the body went (largest displacement from the origin: Fig.
//                 5.10's "less than 0.1 m"), how the legs moved (mean shaft speed per leg; the
//                 fraction of steps that move the legs as two tripods), and the cost (options
//                 evaluated, wall time). The look-ahead comparison sweeps it over (H, K).
//   foot_path     one row per sample of φ ∈ [0, 1): BigANT's toe in its leg's plane (Fig. 5.8).
//
// The goals are the thesis' three (§5.5.1.2) by name — straight: 0.2 m/s along x; turn: 0.2 rad/s
// in place; diagonal: (0.05, 0.02) m/s with the heading held — or any body twist (goal = "twist"
// with vx, vy, omega). A plan's wall time is the planner's own: the time spent writing rows in the
// step sink is left out.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "planning/cost.hpp"
#include "planning/goal.hpp"
#include "planning/plan_csv.hpp"
#include "planning/plan_robot.hpp"
#include "planning/planner.hpp"
#include "robots/bigant.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kLegs = robots::kBigAntLegs;

/// BigANT's planning robot, built once (the kinds only read it).
const planning::PlanRobot& bigant() {
  static const planning::PlanRobot robot = planning::bigant_plan_robot(kLegs);
  return robot;
}

// --- the inputs of a plan -----------------------------------------------------------------------

const std::vector<std::string_view> kPlanKeys = {"goal",      "vx",   "vy",  "omega",  "steps",
                                                 "lookahead", "beam", "law", "threads"};

struct PlanInputs {
  std::string goal = "straight";
  std::string law = "viscous";
  planning::Goal target;
  planning::PlanOptions options;
};

PlanInputs read_plan(const Point& point, std::string_view kind) {
  const Reader r(point, kind, kPlanKeys);
  PlanInputs in;
  in.goal = r.choice("goal", {"straight", "turn", "diagonal", "twist"});
  if (in.goal == "twist") {
    const core::Range speed = core::closed(-10.0, 10.0, "m/s");
    in.target.twist = {r.number("vx", 0.0, speed), r.number("vy", 0.0, speed),
                       r.number("omega", 0.0, core::closed(-100.0, 100.0, "rad/s"))};
  } else {
    for (const std::string_view key : {"vx", "vy", "omega"}) {
      if (r.has(key)) {
        r.fail(key, "only with goal = \"twist\" (goal \"" + in.goal + "\" fixes the twist)");
      }
    }
    in.target = planning::thesis_goal(in.goal);
  }
  planning::PlanOptions& o = in.options;
  o.steps = r.integer("steps", o.steps, 1, 100'000);
  o.lookahead = static_cast<int>(r.integer("lookahead", o.lookahead, 1, 16));
  o.beam = static_cast<int>(r.integer("beam", o.beam, 1, 64));
  o.threads = static_cast<int>(r.integer("threads", o.threads, 1, 256));
  in.law = r.choice("law", {"viscous", "coulomb"});
  o.law = in.law == "coulomb" ? connection::FrictionLaw::kCoulomb
                              : connection::FrictionLaw::kViscousCoulomb;
  // A level expands at most K nodes by M^N options; bound the options a point integrates.
  const double per_step = std::pow(static_cast<double>(o.speeds.size()), kLegs) *
                          (1.0 + static_cast<double>((o.lookahead - 1) * o.beam));
  r.limit_work("steps", "steps · options per step", static_cast<double>(o.steps) * per_step, 1e10);
  try {
    planning::validate(bigant(), o);
    planning::validate(in.target);
  } catch (const core::InputError& e) {
    r.fail("goal", e.what());
  }
  return in;
}

// --- plan_run: the plan, one row per step -------------------------------------------------------

/// The point's own columns, before the plan's: one table for header and cells.
struct PlanKeyColumn {
  const char* name;
  const char* unit;
  Cell (*cell)(long long id, const PlanInputs& in);
};

constexpr std::array kPlanKeyColumns = {
    PlanKeyColumn{"id", "", [](long long id, const PlanInputs&) { return Cell(id); }},
    PlanKeyColumn{"goal", "", [](long long, const PlanInputs& in) { return Cell(in.goal); }},
    PlanKeyColumn{"law", "", [](long long, const PlanInputs& in) { return Cell(in.law); }},
    PlanKeyColumn{"lookahead", "",
                  [](long long, const PlanInputs& in) {
                    return Cell(static_cast<long long>(in.options.lookahead));
                  }},
    PlanKeyColumn{"beam", "",
                  [](long long, const PlanInputs& in) {
                    return Cell(static_cast<long long>(in.options.beam));
                  }},
};

/// The plan's wall time per step, after the plan's columns (a timing: 0 under --no-timing).
constexpr const char* kStepWallColumn = "step_wall_s";

std::vector<ColumnInfo> plan_run_columns() {
  const std::vector<std::string> plan = planning::plan_columns(bigant());
  std::vector<ColumnInfo> columns;
  columns.reserve(kPlanKeyColumns.size() + plan.size() + 1);
  for (const PlanKeyColumn& c : kPlanKeyColumns) {
    columns.push_back({c.name, c.unit, false});
  }
  for (const std::string& name : plan) {
    columns.push_back({name, "", false});
  }
  columns.push_back({kStepWallColumn, "s", true});
  return columns;
}

/// Appends the cells of one CSV line (no quoting: the plan's cells are numbers) as texts, so the
/// sweep CSV holds exactly what plan_csv writes.
void append_cells(std::string_view line, Cells& cells) {
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(',', start);
    cells.emplace_back(std::string(line.substr(start, end - start)));
    if (end == std::string_view::npos) {
      return;
    }
    start = end + 1;
  }
}

/// A plan run with the planner's time measured apart from the sink's.
struct TimedPlan {
  planning::PlanSummary summary;
  std::vector<double> step_wall_s;  ///< per executed step: plan_step + execute
  double wall_s = 0.0;              ///< the sum
};

/// Runs the plan; `sink` sees each step (its time is not counted).
template <class Sink>
TimedPlan run_timed(const PlanInputs& in, Sink&& sink) {
  const planning::PlanRobot& robot = bigant();
  TimedPlan out;
  out.step_wall_s.reserve(static_cast<std::size_t>(in.options.steps));
  Clock::time_point mark = Clock::now();
  double current = 0.0;
  out.summary = planning::plan(
      robot, in.options, in.target, planning::tripod_start(robot),
      [&](const planning::StepRecord& r) {
        current = seconds_since(mark);  // plan_step
        sink(r);
        mark = Clock::now();
      },
      [&](long long, long long) {
        out.step_wall_s.push_back(current + seconds_since(mark));  // + execute
        mark = Clock::now();
      });
  for (const double s : out.step_wall_s) {
    out.wall_s += s;
  }
  return out;
}

PointResult run_plan(const Point& point) {
  const PlanInputs in = read_plan(point, "plan_run");
  const planning::PlanRobot& robot = bigant();
  Cells head;
  for (const PlanKeyColumn& c : kPlanKeyColumns) {
    head.push_back(c.cell(point.id, in));
  }
  PointResult out;
  std::ostringstream text;
  const auto write = [&](const planning::StepRecord& r) {
    text.str("");
    core::CsvWriter writer(text, planning::plan_columns(robot));
    const std::size_t header_end = text.str().size();
    planning::write_plan_row(writer, in.options, r);
    std::string line = text.str().substr(header_end);
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
    }
    Cells cells = head;
    append_cells(line, cells);
    out.rows.push_back(std::move(cells));
  };
  TimedPlan timed;
  try {
    timed = run_timed(in, write);
  } catch (const core::ComputationError& e) {
    out.failed = true;
    out.message = e.what();
  }
  for (std::size_t k = 0; k < out.rows.size(); ++k) {
    out.rows[k].emplace_back(k < timed.step_wall_s.size() ? timed.step_wall_s[k] : kNaN);
  }
  if (!out.failed) {
    // The state after the last step: the end of the trajectory the figures draw.
    planning::StepChoice none;
    none.speed = Eigen::VectorXd::Constant(robot.legs(), kNaN);
    none.chooses.assign(static_cast<std::size_t>(robot.legs()), 0);
    none.cost = kNaN;
    const core::Pose2 goal = planning::target_at(in.target, timed.summary.end.t);
    write({timed.summary.steps, timed.summary.end, goal, none});
    out.rows.back().emplace_back(0.0);
  }
  return out;
}

// --- plan_summary: one row per plan -------------------------------------------------------------

/// The legs as two tripods (tripod_start: HL, FL, MR at φ = 0.5 and ML, HR, FR at 0).
constexpr std::array<int, 3> kTripodA = {0, 2, 4};
constexpr std::array<int, 3> kTripodB = {1, 3, 5};

struct SummaryRow {
  long long id = 0;
  std::string goal;
  std::string law;
  long long lookahead = 1;
  long long beam = 1;
  long long threads = 1;
  long long steps = 0;
  double duration = 0.0;        ///< s of motion planned
  double goal_travel = 0.0;     ///< m, the target's path length over the plan
  double goal_turn = 0.0;       ///< rad, the target's heading change
  double mean_distance = 0.0;   ///< m, over the step starts (PlanSummary)
  double final_distance = 0.0;  ///< m, after the last step
  double max_distance = 0.0;    ///< m
  double mean_yaw_error = 0.0;  ///< rad, |θ − θ_target| over the step starts
  double final_yaw_error = 0.0;
  double max_yaw_error = 0.0;
  double max_radius = 0.0;  ///< m, largest |(x, y)| of the body (start at the origin)
  double final_x = 0.0;
  double final_y = 0.0;
  double final_theta = 0.0;
  double goal_x = 0.0;  ///< Ω^target at the end
  double goal_y = 0.0;
  double goal_theta = 0.0;
  std::array<double, kLegs> mean_speed{};  ///< turns/s, per leg over the plan
  double tripod_fraction = 0.0;            ///< steps whose speeds are equal within each tripod
  double evaluated_per_step = 0.0;
  long long infeasible = 0;
  double wall_s = 0.0;
  double wall_per_step_s = 0.0;

  static std::vector<Column<SummaryRow>> columns() {
    using R = SummaryRow;
    std::vector<Column<R>> c = {value("id", &R::id),
                                value("goal", &R::goal),
                                value("law", &R::law),
                                value("lookahead", &R::lookahead),
                                value("beam", &R::beam),
                                value("threads", &R::threads),
                                value("steps", &R::steps),
                                value("duration", &R::duration, "s"),
                                value("goal_travel", &R::goal_travel, "m"),
                                value("goal_turn", &R::goal_turn, "rad"),
                                value("mean_distance", &R::mean_distance, "m"),
                                value("final_distance", &R::final_distance, "m"),
                                value("max_distance", &R::max_distance, "m"),
                                value("mean_yaw_error", &R::mean_yaw_error, "rad"),
                                value("final_yaw_error", &R::final_yaw_error, "rad"),
                                value("max_yaw_error", &R::max_yaw_error, "rad"),
                                value("max_radius", &R::max_radius, "m"),
                                value("final_x", &R::final_x, "m"),
                                value("final_y", &R::final_y, "m"),
                                value("final_theta", &R::final_theta, "rad"),
                                value("goal_x", &R::goal_x, "m"),
                                value("goal_y", &R::goal_y, "m"),
                                value("goal_theta", &R::goal_theta, "rad")};
    const std::vector<std::string>& legs = bigant().leg_names;
    for (std::size_t i = 0; i < kLegs; ++i) {
      c.push_back(value_at("mean_speed_" + legs[i], &R::mean_speed, i, "turns/s"));
    }
    c.push_back(value("tripod_fraction", &R::tripod_fraction));
    c.push_back(value("evaluated_per_step", &R::evaluated_per_step));
    c.push_back(value("infeasible", &R::infeasible));
    c.push_back(timing("wall_s", &R::wall_s));
    c.push_back(timing("wall_per_step_s", &R::wall_per_step_s));
    return c;
  }
};

bool equal_within(const Eigen::VectorXd& speed, const std::array<int, 3>& legs) {
  return speed(legs[0]) == speed(legs[1]) && speed(legs[1]) == speed(legs[2]);
}

Rows<SummaryRow> run_summary(const Point& point) {
  const PlanInputs in = read_plan(point, "plan_summary");
  const double rho = in.options.rotation_length;
  SummaryRow row;
  row.id = point.id;
  row.goal = in.goal;
  row.law = in.law;
  row.lookahead = in.options.lookahead;
  row.beam = in.options.beam;
  row.threads = in.options.threads;
  double yaw_sum = 0.0;
  long long tripods = 0;
  const auto radius = [](const core::Pose2& p) { return std::hypot(p.x, p.y); };
  const auto observe = [&](const core::Pose2& pose, const core::Pose2& goal) {
    const double yaw = std::abs(pose.theta - goal.theta);  // both unwrapped from 0
    row.max_distance = std::max(row.max_distance, planning::se2_distance(pose, goal, rho));
    row.max_yaw_error = std::max(row.max_yaw_error, yaw);
    row.max_radius = std::max(row.max_radius, radius(pose));
    return yaw;
  };
  Rows<SummaryRow> out;
  TimedPlan timed;
  try {
    timed = run_timed(in, [&](const planning::StepRecord& r) {
      yaw_sum += observe(r.state.pose, r.goal);
      for (int i = 0; i < kLegs; ++i) {
        row.mean_speed[static_cast<std::size_t>(i)] += r.choice.speed(i);
      }
      tripods +=
          equal_within(r.choice.speed, kTripodA) && equal_within(r.choice.speed, kTripodB) ? 1 : 0;
    });
  } catch (const core::ComputationError& e) {
    out.failed = true;
    out.message = e.what();
    row.steps = static_cast<long long>(timed.step_wall_s.size());
    out.rows.push_back(row);
    return out;
  }
  const planning::PlanSummary& s = timed.summary;
  const auto n = static_cast<double>(s.steps);
  const core::Pose2 goal = planning::target_at(in.target, s.end.t);
  row.final_yaw_error = observe(s.end.pose, goal);
  row.steps = s.steps;
  row.duration = s.end.t;
  row.goal_travel = std::hypot(in.target.twist(0), in.target.twist(1)) * s.end.t;
  row.goal_turn = in.target.twist(2) * s.end.t;
  row.mean_distance = s.mean_distance;
  row.final_distance = s.final_distance;
  row.mean_yaw_error = yaw_sum / n;
  row.final_x = s.end.pose.x;
  row.final_y = s.end.pose.y;
  row.final_theta = s.end.pose.theta;
  row.goal_x = goal.x;
  row.goal_y = goal.y;
  row.goal_theta = goal.theta;
  for (double& v : row.mean_speed) {
    v /= n;
  }
  row.tripod_fraction = static_cast<double>(tripods) / n;
  row.evaluated_per_step = static_cast<double>(s.evaluated) / n;
  row.infeasible = s.infeasible;
  row.wall_s = timed.wall_s;
  row.wall_per_step_s = timed.wall_s / n;
  out.rows.push_back(row);
  return out;
}

// --- foot_path: Fig. 5.8 ------------------------------------------------------------------------

const std::vector<std::string_view> kFootKeys = {"samples", "leg"};

struct FootInputs {
  long long samples = 200;
  int leg = 2;  ///< FL
};

FootInputs read_foot(const Point& point) {
  const Reader r(point, "foot_path", kFootKeys);
  FootInputs in;
  in.samples = r.integer("samples", in.samples, 5, 1'000'000);
  if (in.samples % 5 != 0) {
    r.fail("samples", "must be a multiple of 5 (the figure's points φ = 0, 0.2, … are samples)");
  }
  const std::vector<std::string>& names = bigant().leg_names;
  std::vector<std::string_view> legs(names.begin(), names.end());
  std::rotate(legs.begin(), legs.begin() + 2, legs.end());  // FL first: the default
  const std::string leg = r.choice("leg", legs);
  in.leg = static_cast<int>(std::find(names.begin(), names.end(), leg) - names.begin());
  return in;
}

struct FootRow {
  long long id = 0;
  std::string leg;
  double phi = 0.0;
  double x = 0.0;  ///< toe, body frame
  double y = 0.0;
  double z = 0.0;
  double dx_dphi = 0.0;
  double dz_dphi = 0.0;
  bool marked = false;     ///< φ ∈ {0, 0.2, 0.4, 0.6, 0.8}: Fig. 5.8's stars
  bool in_window = false;  ///< |φ| ≤ the stance half-width (ContactRule::kStanceWindow)

  static std::vector<Column<FootRow>> columns() {
    using R = FootRow;
    return {value("id", &R::id),
            value("leg", &R::leg),
            value("phi", &R::phi, "turns"),
            value("x", &R::x, "m"),
            value("y", &R::y, "m"),
            value("z", &R::z, "m"),
            value("dx_dphi", &R::dx_dphi, "m/turn"),
            value("dz_dphi", &R::dz_dphi, "m/turn"),
            value("marked", &R::marked),
            value("in_window", &R::in_window)};
  }
};

Rows<FootRow> run_foot(const Point& point) {
  const FootInputs in = read_foot(point);
  const planning::PlanRobot& robot = bigant();
  Rows<FootRow> out;
  const long long fifth = in.samples / 5;
  for (long long k = 0; k < in.samples; ++k) {
    const double phi = static_cast<double>(k) / static_cast<double>(in.samples);
    Eigen::Vector3d q;
    Eigen::Vector3d dq;
    robot.toe(in.leg, phi, q, dq);
    const double from_zero = std::min(phi, 1.0 - phi);
    out.rows.push_back({point.id, robot.leg_names[static_cast<std::size_t>(in.leg)], phi, q(0),
                        q(1), q(2), dq(0), dq(2), k % fifth == 0,
                        from_zero <= robot.stance_half_width});
  }
  return out;
}

}  // namespace

std::vector<PointKind> planning_kinds() {
  PointKind plan;
  plan.name = "plan_run";
  plan.summary =
      "§5.5: one plan of the brute-force planner on BigANT (one row per planning step, the plan "
      "CSV's columns, and the state after the last step)";
  plan.columns = plan_run_columns();
  plan.timed = Timed::kYes;
  plan.check = [](const Point& p) { (void)read_plan(p, "plan_run"); };
  plan.run = run_plan;
  std::vector<PointKind> kinds;
  kinds.push_back(std::move(plan));
  kinds.push_back(make_point_kind<SummaryRow>(
      "plan_summary",
      "§5.5, §5.7.3: one plan's tracking error, leg motion and cost (one row; the look-ahead "
      "comparison sweeps it)",
      Timed::kYes, [](const Point& p) { (void)read_plan(p, "plan_summary"); }, run_summary));
  kinds.push_back(make_point_kind<FootRow>(
      "foot_path", "Fig. 5.8: BigANT's toe over one turn of its shaft (one row per sample of φ)",
      Timed::kNo, [](const Point& p) { (void)read_foot(p); }, run_foot));
  return kinds;
}

}  // namespace slipwalk::sweeps::points
