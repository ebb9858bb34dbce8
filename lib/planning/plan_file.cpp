// The plan file reader and writer (plan_file.hpp has the format): the whole file is checked
// before anything runs, with the scene reader's conventions (scene/toml_reader.hpp).
#include "planning/plan_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "contact/robot.hpp"
#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/provenance.hpp"
#include "core/toml_input.hpp"
#include "planning/plan_csv.hpp"
#include "robots/bigant.hpp"
#include "scene/run_writer.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::planning {

namespace {

using core::InputError;
using scene::TableReader;
using scene::TableSchema;

/// Every table a plan file may hold and its keys (the reader suggests from these).
const std::vector<TableSchema>& schema() {
  static const std::vector<TableSchema> tables = {
      {"plan",
       {"robot", "law", "tol", "max_iterations", "horizon", "substeps", "execute", "speeds",
        "swing_speed", "contact", "stance_half_width", "rotation_length", "steps", "lookahead",
        "beam", "deduplicate", "threads"}},
      {"goal", {"twist", "start", "waypoints"}},
      {"start", {"t", "pose", "phi"}},
  };
  return tables;
}

const TableSchema& schema_of(std::string_view name) { return scene::schema_table(schema(), name); }

const toml::table* table_of(const toml::table& doc, std::string_view name) {
  const toml::node* node = doc.get(name);
  return node == nullptr ? nullptr : node->as_table();
}

/// An integer key in `range` into `value` when present (a float is a wrong type, even 20.0).
template <typename Int>
void read_integer(const TableReader& t, std::string_view key, const core::Range& range,
                  Int& value) {
  if (const toml::node* n = t.find(key)) {
    const long long v = t.integer(*n, key);
    t.check(range.contains(static_cast<double>(v)), *n, key,
            "must be in " + range.describe() + ", got " + std::to_string(v));
    value = static_cast<Int>(v);
  }
}

/// An array node of `count` numbers (count < 0: any length ≥ 1), each in its range.
const toml::array& number_array(const TableReader& t, const toml::node& node, std::string_view key,
                                int count, std::string_view shape) {
  const toml::array* a = node.as_array();
  if (a == nullptr) {
    t.fail(node, key, "expected " + std::string(shape) + ", got " + scene::type_name(node));
  }
  if (count >= 0 && static_cast<int>(a->size()) != count) {
    t.fail(node, key,
           "expected " + std::string(shape) + ", got an array of " + std::to_string(a->size()));
  }
  return *a;
}

/// A pose [x, y, θ] in the world frame.
core::Pose2 read_pose(const TableReader& t, const toml::node& node, std::string_view key) {
  const toml::array& a = number_array(t, node, key, 3, "a pose [x, y, theta]");
  return {t.number_in(*a.get(0), key, contact::limits::kPosition),
          t.number_in(*a.get(1), key, contact::limits::kPosition),
          t.number_in(*a.get(2), key, contact::limits::kYaw)};
}

/// The robot: "bigant" or "bigant<N>" (N even, BigANT-like legs).
PlanRobot read_robot(const TableReader& plan) {
  const toml::node* node = plan.find("robot");
  if (node == nullptr) {
    return bigant_plan_robot();
  }
  const auto* s = node->as_string();
  if (s == nullptr) {
    plan.fail(*node, "robot", std::string("expected a string, got ") + scene::type_name(*node));
  }
  const std::string& name = s->get();
  constexpr std::string_view kPrefix = "bigant";
  int legs = robots::kBigAntLegs;
  bool ok = name.rfind(kPrefix, 0) == 0;
  if (ok && name.size() > kPrefix.size()) {
    const char* first = name.data() + kPrefix.size();
    const char* last = name.data() + name.size();
    const auto [ptr, ec] = std::from_chars(first, last, legs);
    ok = ec == std::errc() && ptr == last && *first != '0' && legs >= 2 &&
         legs <= robots::kBigAntMaxLegs && legs % 2 == 0;
  }
  plan.check(ok, *node, "robot",
             "unknown robot '" + name + "' (valid: bigant, or bigant<N> for an even N from 2 to " +
                 std::to_string(robots::kBigAntMaxLegs) + ")");
  return bigant_plan_robot(legs);
}

void read_plan(const TableReader& plan, PlanFile& file) {
  file.robot = read_robot(plan);
  PlanOptions& o = file.options;
  const int legs = file.robot.legs();

  // The friction law and, for Coulomb, its solver.
  if (const toml::node* n = plan.find("law")) {
    const std::string law = plan.choice(*n, "law", {"viscous", "coulomb"});
    o.law = law == "coulomb" ? connection::FrictionLaw::kCoulomb
                             : connection::FrictionLaw::kViscousCoulomb;
  }
  if (o.law == connection::FrictionLaw::kCoulomb) {
    plan.read_in("tol", core::closed(1e-15, 1.0), o.coulomb.tol);
    read_integer(plan, "max_iterations", core::closed(1.0, 1e6), o.coulomb.max_iterations);
  } else {
    plan.forbid("tol", "the coulomb law", "law = 'viscous'");
    plan.forbid("max_iterations", "the coulomb law", "law = 'viscous'");
  }

  // One option's integration and how much of it is executed.
  plan.read_in("horizon", ranges::kHorizon, o.horizon);
  read_integer(plan, "substeps", ranges::kSubsteps, o.substeps);
  if (const toml::node* n = plan.find("execute")) {
    read_integer(plan, "execute", ranges::kSubsteps, o.execute);
    plan.check(o.execute <= o.substeps, *n, "execute",
               "must be at most substeps = " + std::to_string(o.substeps) + ", got " +
                   std::to_string(o.execute));
  } else if (o.execute > o.substeps) {
    const toml::node& s = *plan.find("substeps");
    plan.fail(s, "substeps",
              "must be at least execute = " + std::to_string(o.execute) + " (its default), got " +
                  std::to_string(o.substeps));
  }

  // The choices, and how many options they make on this robot.
  if (const toml::node* n = plan.find("speeds")) {
    const toml::array& a = number_array(plan, *n, "speeds", -1, "an array of speeds");
    plan.check(ranges::kChoices.contains(static_cast<double>(a.size())), *n, "speeds",
               "the number of speeds must be in " + ranges::kChoices.describe() + ", got " +
                   std::to_string(a.size()));
    o.speeds.clear();
    for (const toml::node& s : a) {
      o.speeds.push_back(plan.number_in(s, "speeds", ranges::kSpeed));
    }
  }
  const double options_count =
      std::pow(static_cast<double>(o.speeds.size()), static_cast<double>(legs));
  if (options_count > static_cast<double>(kMaxOptions)) {
    const toml::node* n = plan.find("speeds");
    const std::string what = std::to_string(o.speeds.size()) + " speeds on " +
                             std::to_string(legs) + " legs make " +
                             core::format_double(options_count) +
                             " options per step; at most 2^24 (fewer speeds or legs)";
    plan.fail(n != nullptr ? *n : *plan.find("robot"), n != nullptr ? "speeds" : "robot", what);
  }
  plan.read_in("swing_speed", ranges::kSpeed, o.swing_speed);

  // Who chooses.
  std::string contact = "support";
  if (const toml::node* n = plan.find("contact")) {
    contact = plan.choice(*n, "contact", {"support", "stance_window", "all"});
  }
  o.contact = contact == "stance_window" ? ContactRule::kStanceWindow
              : contact == "all"         ? ContactRule::kAll
                                         : ContactRule::kSupport;
  if (o.contact == ContactRule::kStanceWindow) {
    plan.read_in("stance_half_width", ranges::kStanceHalfWidth, file.robot.stance_half_width);
  } else {
    plan.forbid("stance_half_width", "the stance_window rule", "contact = '" + contact + "'");
  }

  // The cost, the plan's length and the search.
  plan.read_in("rotation_length", ranges::kRotationLength, o.rotation_length);
  if (const toml::node* n = plan.find("steps")) {
    read_integer(plan, "steps", ranges::kSteps, o.steps);
    // The CSV's size is known now: refused here, at steps, before anything runs.
    const auto columns = static_cast<double>(plan_columns(file.robot).size());
    const double bytes = static_cast<double>(o.steps + 1) * columns * scene::kMaxCellBytes;
    plan.check(bytes <= kMaxPlanBytes, *n, "steps",
               "the plan would write up to " + core::format_double(bytes / 1e9) +
                   " GB of CSV; at most " + core::format_double(kMaxPlanBytes / 1e9) + " GB");
  }
  read_integer(plan, "lookahead", ranges::kLookahead, o.lookahead);
  read_integer(plan, "beam", ranges::kBeam, o.beam);
  if (const toml::node* n = plan.find("deduplicate")) {
    const auto* b = n->as_boolean();
    if (b == nullptr) {
      plan.fail(*n, "deduplicate", std::string("expected a boolean, got ") + scene::type_name(*n));
    }
    o.deduplicate = b->get();
  }
  read_integer(plan, "threads", ranges::kThreads, o.threads);
}

void read_goal(const TableReader& goal, const std::string& path, PlanFile& file) {
  const toml::node* twist = goal.find("twist");
  const toml::node* waypoints = goal.find("waypoints");
  if (twist != nullptr && waypoints != nullptr) {
    goal.fail(*waypoints, "waypoints", "give twist or waypoints, not both");
  }
  if (twist == nullptr && waypoints == nullptr) {
    throw InputError(goal.origin(), "missing required key 'twist' (or 'waypoints') in [goal]");
  }
  if (twist != nullptr) {
    const toml::array& a = number_array(goal, *twist, "twist", 3, "a twist [vx, vy, omega]");
    file.goal.twist = {goal.number_in(*a.get(0), "twist", ranges::kGoalSpeed),
                       goal.number_in(*a.get(1), "twist", ranges::kGoalSpeed),
                       goal.number_in(*a.get(2), "twist", ranges::kGoalRate)};
    file.goal.start = file.start.pose;
    if (const toml::node* s = goal.find("start")) {
      file.goal.start = read_pose(goal, *s, "start");
    }
    return;
  }
  goal.forbid("start", "a twist goal", "waypoints");
  const auto* name = waypoints->as_string();
  if (name == nullptr) {
    goal.fail(
        *waypoints, "waypoints",
        std::string("expected a string (a CSV file name), got ") + scene::type_name(*waypoints));
  }
  std::filesystem::path csv(name->get());
  if (csv.is_relative()) {
    csv = std::filesystem::path(path).parent_path() / csv;
  }
  std::string text;
  try {
    text = core::read_input_file(csv, "a waypoint CSV file");
  } catch (const InputError& e) {
    goal.fail(*waypoints, "waypoints", std::string("cannot read: ") + e.what());
  }
  file.goal_file = csv.string();
  parse_waypoints(text, file.goal_file, file.goal);
}

void read_start(const TableReader& start, PlanFile& file) {
  start.read_in("t", ranges::kTime, file.start.t);
  if (const toml::node* n = start.find("pose")) {
    file.start.pose = read_pose(start, *n, "pose");
  }
  if (const toml::node* n = start.find("phi")) {
    const int legs = file.robot.legs();
    const toml::array& a = number_array(start, *n, "phi", -1, "one shaft angle per leg");
    start.check(static_cast<int>(a.size()) == legs, *n, "phi",
                "one shaft angle per leg: the robot has " + std::to_string(legs) + " legs, got " +
                    std::to_string(a.size()));
    for (int i = 0; i < legs; ++i) {
      file.start.phi(i) = start.number_in(*a.get(static_cast<std::size_t>(i)), "phi", ranges::kPhi);
    }
  }
}

}  // namespace

void parse_waypoints(std::string_view text, const std::string& file, Goal& goal) {
  goal.times.clear();
  goal.waypoints.clear();
  static constexpr std::array<std::string_view, 4> kHeader = {"t", "x", "y", "theta"};
  static constexpr std::array<const core::Range*, 4> kRange = {
      &ranges::kTime, &contact::limits::kPosition, &contact::limits::kPosition,
      &contact::limits::kYaw};
  std::vector<std::string_view> cells;
  std::vector<int> starts;
  long long last_line = 0;
  bool first = true;
  core::LineReader lines(text);
  for (std::string_view line; lines.next(line);) {
    const std::string_view content = line.substr(0, line.find('#'));
    if (core::trim_blanks(content).empty()) {
      continue;
    }
    const std::string where = file + ":" + std::to_string(lines.line_number());
    core::split_cells(content, cells, starts);
    if (cells.size() != 4) {
      throw InputError(where, "a waypoint is 4 values t, x, y, theta; the row has " +
                                  std::to_string(cells.size()));
    }
    bool header = first;
    for (std::size_t c = 0; c < 4 && header; ++c) {
      header = core::trim_blanks(cells[c]) == kHeader[c];
    }
    first = false;
    if (header) {
      continue;
    }
    std::array<double, 4> v{};
    for (std::size_t c = 0; c < 4; ++c) {
      const std::string_view cell = core::trim_blanks(cells[c]);
      const std::string at =
          where + ":" + std::to_string(starts[c] + static_cast<int>(cell.data() - cells[c].data()));
      const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v[c]);
      if (cell.empty() || ec != std::errc() || ptr != cell.data() + cell.size() ||
          !std::isfinite(v[c])) {
        throw InputError(
            at, std::string(kHeader[c]) + ": '" + std::string(cell) + "' is not a finite number");
      }
      core::require_in(at, v[c], *kRange[c]);
      if (c == 0 && !goal.times.empty() && !(v[0] > goal.times.back())) {
        throw InputError(at, "times must increase strictly; the row before has t = " +
                                 core::format_double(goal.times.back()));
      }
    }
    goal.times.push_back(v[0]);
    goal.waypoints.push_back({v[1], v[2], v[3]});
    last_line = lines.line_number();
  }
  if (goal.times.size() < 2) {
    throw InputError(file + ":" + std::to_string(std::max(last_line, 1LL)),
                     "a waypoint goal needs at least 2 rows t, x, y, theta; the file has " +
                         std::to_string(goal.times.size()));
  }
}

PlanFile parse_plan_file(std::string_view text, const std::string& path) {
  const toml::table doc = core::parse_toml(text, path);
  scene::check_top_level(doc, path, schema());
  const std::vector<TableSchema>& all = schema();
  PlanFile file;
  file.path = path;

  // [plan] first (it names the robot, which sizes [start]), then [start] (the twist goal starts
  // at its pose), then [goal].
  const toml::table empty;
  const toml::table* plan = table_of(doc, "plan");
  read_plan(TableReader(plan != nullptr ? *plan : empty, schema_of("plan"), path, all), file);
  file.start = tripod_start(file.robot);
  if (const toml::table* t = table_of(doc, "start")) {
    read_start(TableReader(*t, schema_of("start"), path, all), file);
  }
  const toml::table* goal = table_of(doc, "goal");
  if (goal == nullptr) {
    throw InputError(scene::origin_of(doc.source(), path), "missing required table [goal]");
  }
  read_goal(TableReader(*goal, schema_of("goal"), path, all), path, file);

  // Everything was checked where it was read; the planner's own checks must agree.
  try {
    validate(file.robot, file.options);
    validate(file.goal);
  } catch (const InputError& e) {
    throw InputError(path, e.what());
  }
  return file;
}

PlanFile read_plan_file(const std::filesystem::path& path) {
  return parse_plan_file(core::read_input_file(path, "a plan file"), path.string());
}

nlohmann::json to_json(const PlanFile& plan) {
  const PlanOptions& o = plan.options;
  const char* contact = o.contact == ContactRule::kStanceWindow ? "stance_window"
                        : o.contact == ContactRule::kAll        ? "all"
                                                                : "support";
  const bool coulomb = o.law == connection::FrictionLaw::kCoulomb;
  nlohmann::json p = {
      {"robot", plan.robot.name},
      {"law", coulomb ? "coulomb" : "viscous"},
      {"horizon", o.horizon},
      {"substeps", o.substeps},
      {"execute", o.execute},
      {"speeds", o.speeds},
      {"swing_speed", o.swing_speed},
      {"contact", contact},
      {"rotation_length", o.rotation_length},
      {"steps", o.steps},
      {"lookahead", o.lookahead},
      {"beam", o.beam},
      {"deduplicate", o.deduplicate},
      {"threads", o.threads},
  };
  if (coulomb) {
    p["tol"] = o.coulomb.tol;
    p["max_iterations"] = o.coulomb.max_iterations;
  }
  if (o.contact == ContactRule::kStanceWindow) {
    p["stance_half_width"] = plan.robot.stance_half_width;
  }
  nlohmann::json goal;
  if (plan.goal_file.empty()) {
    goal = {{"twist", {plan.goal.twist(0), plan.goal.twist(1), plan.goal.twist(2)}},
            {"start", {plan.goal.start.x, plan.goal.start.y, plan.goal.start.theta}}};
  } else {
    goal = {{"waypoints", plan.goal_file}, {"rows", plan.goal.times.size()}};
  }
  const PlanState& s = plan.start;
  return {
      {"file", plan.path},
      {"plan", p},
      {"goal", goal},
      {"start",
       {{"t", s.t},
        {"pose", {s.pose.x, s.pose.y, s.pose.theta}},
        {"phi", std::vector<double>(s.phi.data(), s.phi.data() + s.phi.size())}}},
  };
}

PlanRun write_plan(const PlanFile& plan, const std::filesystem::path& csv_path,
                   const nlohmann::json& extra, std::ostream* progress) {
  std::filesystem::path sidecar_path = csv_path;
  sidecar_path.replace_extension(".json");
  if (sidecar_path == csv_path) {
    std::string what = "'";
    what.append(csv_path.string()).append("' would be overwritten by its sidecar; use .csv");
    throw InputError("--out", what);
  }
  PlanRun result;
  result.columns = plan_columns(plan.robot);

  // One row per planning step, into a temporary file renamed when complete.
  core::AtomicFile file(csv_path);
  core::CsvWriter csv(file.stream(), result.columns);
  const PlanOptions& options = plan.options;
  const long long every = std::max<long long>(1, options.steps / 10);
  const double tau = static_cast<double>(options.execute) * options.horizon /
                     static_cast<double>(options.substeps);
  const auto start = std::chrono::steady_clock::now();
  try {
    result.summary = planning::plan(
        plan.robot, options, plan.goal, plan.start,
        [&](const StepRecord& r) { write_plan_row(csv, options, r); },
        [&](long long done, long long total) {
          if (done % every != 0 && done != total) {
            return;
          }
          file.check();  // a full disk stops the plan here, not at its end
          if (progress != nullptr) {
            std::ostringstream line;
            line << "slipwalk plan: " << done << "/" << total << " steps (t = "
                 << core::format_double(plan.start.t + static_cast<double>(done) * tau) << " s; "
                 << std::fixed << std::setprecision(1) << core::seconds_since(start)
                 << " s elapsed)\n";
            *progress << line.str() << std::flush;
          }
        });
  } catch (const core::ComputationError& e) {
    // The rows so far are not a result: the temporary goes with `file`.
    throw core::ComputationError(plan.path + ": " + e.what());
  }
  result.wall_s = core::seconds_since(start);
  file.finish();

  // The provenance sidecar.
  nlohmann::json sidecar = extra.is_object() ? extra : nlohmann::json::object();
  const PlanSummary& summary = result.summary;
  const PlanState& end = summary.end;
  sidecar.update({
      {"plan_file", plan.path},
      {"plan", to_json(plan)},
      {"robot", plan.robot.name},
      {"legs", plan.robot.leg_names},
      {"csv", csv_path.filename().string()},
      {"columns", result.columns},
      {"summary",
       {{"steps", summary.steps},
        {"duration_s", static_cast<double>(summary.steps) * tau},
        {"mean_distance", summary.mean_distance},
        {"final_distance", summary.final_distance},
        {"evaluated", summary.evaluated},
        {"infeasible", summary.infeasible},
        {"end", {{"t", end.t}, {"pose", {end.pose.x, end.pose.y, end.pose.theta}}}}}},
      {"wall_s", result.wall_s},
      {"threads", options.threads},
      {"provenance", core::build_provenance()},
  });
  // Both files are complete before either is renamed; the CSV is renamed last.
  core::AtomicFile side(sidecar_path);
  side.stream() << sidecar.dump(1) << "\n";
  core::commit_with_sidecar(file, side);
  return result;
}

}  // namespace slipwalk::planning
