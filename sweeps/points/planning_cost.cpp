// planning_cost: what one step of the brute-force planner costs (thesis §5.5: "a single planning
// step takes 6.9 ms on the GPU", 4096 options × 20 substeps; 31 s on a CPU), on BigANT-like robots
// with 6–12 legs and M speed choices.
//
// Modes:
//  * full: planning steps enumerating all M^N options (deduplicate = false) at the tripod start,
//    the thesis' step; `repeats` steps timed one by one (wall clock, `threads` threads).
//  * dedup: the planner as it runs (deduplicate = true: each distinct motion once) over the
//    states of a `steps`-step plan walking straight at 0.2 m/s; every state's step timed, `repeats`
//    times; the median and quartiles are over all those step times.
//  * kernel, reference: the inner loop alone (planning/option_kernel.hpp, fast route or the
//    reference loop) over `options` random options of the tripod-start node with every leg
//    choosing, one thread, CPU time: the time per option-substep, from which a full step of M^N
//    options is extrapolated (the way to cost 10 and 12 legs, whose full steps have 4^10 and 4^12
//    options).
// The plan's states are collected before the clock starts and a step allocates nothing; the kind
// is timed, so the runner runs its points one at a time.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "planning/option_kernel.hpp"
#include "planning/planner.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

const double kNaN = std::nan("");
constexpr double kWalk = 0.2;      // m/s: the straight goal of the dedup plan
constexpr double kMaxWork = 1e10;  // option-substeps per point, at most (bound: M^N per step)

const std::vector<std::string_view> kKeys = {"legs",  "M",       "mode",    "threads",
                                             "steps", "repeats", "options", "seed"};
const std::vector<std::string_view> kModes = {"full", "dedup", "kernel", "reference"};

struct Inputs {
  int legs = 6;
  int m = 4;
  std::string mode = "full";
  int threads = 1;
  long long steps = 300;
  long long repeats = 11;
  long long options = 4096;
  long long seed = 1;
};

/// The M speed choices (turns/s): M = 4 is the thesis' {−1, 0, 1, 2}; fewer drop the fast and
/// then the backward speed, M = 5 adds 3.
std::vector<double> speeds(int m) {
  switch (m) {
    case 2:
      return {0.0, 1.0};
    case 3:
      return {-1.0, 0.0, 1.0};
    case 5:
      return {-1.0, 0.0, 1.0, 2.0, 3.0};
    default:
      return {-1.0, 0.0, 1.0, 2.0};
  }
}

Inputs read(const Point& point) {
  const Reader r(point, "planning_cost", kKeys);
  Inputs in;
  in.legs = static_cast<int>(r.integer("legs", 6, 6, 12));
  if (in.legs % 2 != 0) {
    r.fail("legs", "a BigANT-like robot has an even number of legs");
  }
  in.m = static_cast<int>(r.integer("M", 4, 2, 5));
  in.mode = r.choice("mode", kModes);
  in.threads = static_cast<int>(r.integer("threads", 1, 1, 16));
  in.steps = r.integer("steps", 300, 1, 100000);
  in.repeats = r.integer("repeats", 11, 1, 1001);
  in.options = r.integer("options", 4096, 1, 1 << 20);
  in.seed = r.integer("seed", 1, 0, 1LL << 40);
  const double all = std::pow(static_cast<double>(in.m), static_cast<double>(in.legs));
  const double per_step = in.mode == "full" || in.mode == "dedup" ? all : 0.0;
  const double work = in.mode == "full"    ? per_step * static_cast<double>(in.repeats)
                      : in.mode == "dedup" ? per_step * static_cast<double>(in.repeats * in.steps)
                                           : static_cast<double>(in.options * in.repeats);
  r.limit_work("repeats", "options × steps × repeats (at most)", work * 20.0, kMaxWork);
  return in;
}

struct Quartiles {
  double median = kNaN;
  double p25 = kNaN;
  double p75 = kNaN;
};

Quartiles quartiles(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return {quantile_of_sorted(x, 0.5), quantile_of_sorted(x, 0.25), quantile_of_sorted(x, 0.75)};
}

/// One row per point. time_ms*: wall ms per planning step (full, dedup) or the full step of M^N
/// options extrapolated from the per-evaluation CPU time (kernel, reference: one thread).
struct Row {
  long long id = 0;
  long long legs = 0;
  long long M = 0;
  std::string mode;
  long long threads = 0;
  long long steps = 0;  ///< plan steps whose states were timed (dedup), else 1
  long long repeats = 0;
  double options_per_step = 0.0;  ///< mean options integrated per timed step (kernel: sampled)
  double infeasible_per_step = 0.0;
  double time_ms = kNaN;  ///< median wall time per step
  double time_ms_p25 = kNaN;
  double time_ms_p75 = kNaN;
  double time_ms_mean = kNaN;
  /// CPU time of all threads per step, mean (full, dedup): what two free cores would share; on
  /// a loaded machine the wall time also counts waiting for a core.
  double cpu_ms_mean = kNaN;
  double ns_per_evaluation = kNaN;  ///< per option-substep per thread: time × threads / evaluations
  double options_per_second = kNaN;  ///< options integrated per wall second

  static std::vector<Column<Row>> columns() {
    return {value("id", &Row::id),
            value("legs", &Row::legs),
            value("M", &Row::M),
            value("mode", &Row::mode),
            value("threads", &Row::threads),
            value("steps", &Row::steps),
            value("repeats", &Row::repeats),
            value("options_per_step", &Row::options_per_step),
            value("infeasible_per_step", &Row::infeasible_per_step),
            timing("time_ms", &Row::time_ms, "ms"),
            timing("time_ms_p25", &Row::time_ms_p25, "ms"),
            timing("time_ms_p75", &Row::time_ms_p75, "ms"),
            timing("time_ms_mean", &Row::time_ms_mean, "ms"),
            timing("cpu_ms_mean", &Row::cpu_ms_mean, "ms"),
            timing("ns_per_evaluation", &Row::ns_per_evaluation, "ns"),
            timing("options_per_second", &Row::options_per_second, "1/s")};
  }
};

/// full and dedup: plan steps timed one by one.
void time_steps(const Inputs& in, const planning::PlanRobot& robot,
                const planning::PlanOptions& options, Row& row) {
  planning::Goal goal;
  goal.twist = {kWalk, 0.0, 0.0};
  std::vector<planning::PlanState> states;
  if (in.mode == "dedup") {
    planning::PlanOptions walk = options;
    walk.steps = in.steps;
    states.reserve(static_cast<std::size_t>(in.steps));
    planning::plan(robot, walk, goal, planning::tripod_start(robot),
                   [&states](const planning::StepRecord& r) { states.push_back(r.state); });
  } else {
    states.push_back(planning::tripod_start(robot));
  }
  planning::PlanData data(robot, options);
  planning::StepChoice choice;
  planning::plan_step(robot, options, goal, states.front(), data, choice);  // warm
  std::vector<double> ms;
  ms.reserve(static_cast<std::size_t>(in.repeats) * states.size());
  long long evaluated = 0;
  long long infeasible = 0;
  double total_s = 0.0;
  const double cpu0 = core::process_cpu_seconds();
  for (long long r = 0; r < in.repeats; ++r) {
    for (const planning::PlanState& s : states) {
      const auto t0 = std::chrono::steady_clock::now();
      planning::plan_step(robot, options, goal, s, data, choice);
      const double dt = core::seconds_since(t0);
      total_s += dt;
      ms.push_back(1e3 * dt);
      evaluated += choice.evaluated;
      infeasible += choice.infeasible;
    }
  }
  const double cpu_s = core::process_cpu_seconds() - cpu0;
  const auto n = static_cast<double>(ms.size());
  const Quartiles q = quartiles(ms);
  row.steps = static_cast<long long>(states.size());
  row.options_per_step = static_cast<double>(evaluated) / n;
  row.infeasible_per_step = static_cast<double>(infeasible) / n;
  row.time_ms = q.median;
  row.time_ms_p25 = q.p25;
  row.time_ms_p75 = q.p75;
  row.time_ms_mean = 1e3 * total_s / n;
  row.cpu_ms_mean = 1e3 * cpu_s / n;
  row.ns_per_evaluation =
      1e9 * total_s * in.threads / (static_cast<double>(evaluated) * options.substeps);
  row.options_per_second = static_cast<double>(evaluated) / total_s;
}

/// kernel and reference: the inner loop over random options, CPU time per option-substep.
void time_kernel(const Inputs& in, const planning::PlanRobot& robot, planning::PlanOptions options,
                 Row& row) {
  options.contact = planning::ContactRule::kAll;
  planning::NodeTable table;
  planning::size_node(robot, options, table);
  contact::Frame frame(robot.robot);
  planning::build_node(robot, options, planning::tripod_start(robot).phi, table, frame);
  std::mt19937_64 rng(static_cast<std::uint64_t>(in.seed));
  std::uniform_int_distribution<int> digit(0, in.m - 1);
  std::vector<std::array<int, planning::kMaxPlanLegs>> columns(
      static_cast<std::size_t>(in.options));
  for (auto& c : columns) {
    std::array<int, planning::kMaxPlanLegs> digits{};
    for (int i = 0; i < in.legs; ++i) {
      digits[static_cast<std::size_t>(i)] = digit(rng);
    }
    planning::option_columns(table, digits.data(), c.data());
  }
  const bool fast = in.mode == "kernel";
  long long infeasible = 0;
  const auto pass = [&] {
    if (fast) {
      // As the planner calls it: planning::kOptionBatch options at a time.
      std::array<const int*, planning::kOptionBatch> pointers{};
      std::array<core::Pose2, planning::kOptionBatch> poses{};
      std::array<bool, planning::kOptionBatch> ok{};
      for (std::size_t o = 0; o < columns.size(); o += planning::kOptionBatch) {
        const int lanes =
            static_cast<int>(std::min<std::size_t>(planning::kOptionBatch, columns.size() - o));
        for (int l = 0; l < lanes; ++l) {
          pointers[static_cast<std::size_t>(l)] = columns[o + static_cast<std::size_t>(l)].data();
          poses[static_cast<std::size_t>(l)] = core::Pose2{};
        }
        planning::integrate_options(robot, options, table, pointers.data(), lanes, table.substeps,
                                    poses.data(), ok.data(), frame);
        for (int l = 0; l < lanes; ++l) {
          infeasible += ok[static_cast<std::size_t>(l)] ? 0 : 1;
        }
      }
      return;
    }
    for (const auto& c : columns) {
      core::Pose2 pose;
      infeasible += planning::integrate_option_reference(robot, options, table, c.data(),
                                                         table.substeps, pose, frame)
                        ? 0
                        : 1;
    }
  };
  pass();  // warm
  infeasible = 0;
  std::vector<double> ns;
  ns.reserve(static_cast<std::size_t>(in.repeats));
  for (long long r = 0; r < in.repeats; ++r) {
    const double t0 = thread_cpu_seconds();
    pass();
    ns.push_back(1e9 * (thread_cpu_seconds() - t0) /
                 static_cast<double>(in.options * options.substeps));
  }
  const Quartiles q = quartiles(ns);
  const double all = std::pow(static_cast<double>(in.m), static_cast<double>(in.legs));
  const double per_step_ms = 1e-6 * all * options.substeps;  // ms per ns of one evaluation
  row.steps = 1;
  row.options_per_step = static_cast<double>(in.options);
  row.infeasible_per_step = static_cast<double>(infeasible) / static_cast<double>(in.repeats);
  row.time_ms = q.median * per_step_ms;
  row.time_ms_p25 = q.p25 * per_step_ms;
  row.time_ms_p75 = q.p75 * per_step_ms;
  row.time_ms_mean = row.time_ms;
  row.ns_per_evaluation = q.median;
  row.options_per_second = 1e9 / (q.median * options.substeps);
}

Rows<Row> run(const Point& point) {
  const Inputs in = read(point);
  const planning::PlanRobot robot = planning::bigant_plan_robot(in.legs);
  planning::PlanOptions options;
  options.speeds = speeds(in.m);
  options.threads = in.threads;
  options.deduplicate = in.mode == "dedup";
  Row row;
  row.id = point.id;
  row.legs = in.legs;
  row.M = in.m;
  row.mode = in.mode;
  row.threads = in.threads;
  row.repeats = in.repeats;
  if (in.mode == "full" || in.mode == "dedup") {
    time_steps(in, robot, options, row);
  } else {
    time_kernel(in, robot, options, row);
  }
  Rows<Row> out;
  out.rows.push_back(row);
  return out;
}

}  // namespace

std::vector<PointKind> planning_cost_kinds() {
  return {make_point_kind<Row>(
      "planning_cost",
      "§5.5: wall time of one planning step (all M^N options, or each distinct motion once over "
      "a plan) and the inner loop's time per option-substep, BigANT-like robots of 6-12 legs, "
      "M choices, 1+ threads (one row per point)",
      Timed::kYes, [](const Point& p) { (void)read(p); }, run)};
}

}  // namespace slipwalk::sweeps::points
