#pragma once
// Plan files (`slipwalk plan PLAN.toml --out plan.csv`, thesis §5.4–5.5): which robot plans,
// with which options, towards which goal, from where. The whole file is read and checked before
// anything runs; every error is a core::InputError at file:line:col (the scene reader's
// conventions, scene/toml_reader.hpp: unknown keys refused with the nearest valid one, every
// number range-checked where it is read, with its unit). The keys are the fields of PlanOptions,
// Goal and PlanState (planner.hpp, goal.hpp); a key left out keeps the struct's default, so a
// file with only [goal] plans exactly as planner.hpp's defaults do.
//
//   [plan]                      # optional: every key has planner.hpp's default
//   robot = "bigant"            # "bigant" (6 legs) or "bigant<N>", N even in [2, 40]: the same
//                               # four-bar legs, N/2 per side (planning::bigant_plan_robot(N))
//   law = "viscous"             # "viscous" (viscous-Coulomb, §3.4) | "coulomb"
//   # tol = 1e-10               # coulomb only: the Coulomb solver's relative duality gap
//   # max_iterations = 500      # coulomb only
//   horizon = 0.05              # Δt, s: how far one option looks ahead, (0, 10]
//   substeps = 20               # T_s, integer in [1, 10000]
//   execute = 2                 # T_f, integer in [1, substeps]: substeps executed per step
//   speeds = [-1, 0, 1, 2]      # the M choices of φ̇, turns/s, each in [-100, 100]; M in [1, 64]
//                               # and M^N ≤ 2^24 options per step
//   swing_speed = 2.0           # φ̇ of a leg not in contact, turns/s
//   contact = "support"         # who chooses: "support" (the spring support's contact set) |
//                               # "stance_window" (φ within stance_half_width of 0) | "all"
//   # stance_half_width = 0.175 # stance_window only, turns in (0, 0.5)
//   rotation_length = 0.3       # ρ, m/rad, [0, 1000]: the cost's metres per radian (cost.hpp)
//   steps = 300                 # planning steps, integer ≥ 0 (the CSV is bounded at 4 GB)
//   lookahead = 1               # H, integer in [1, 16] (1: the thesis' greedy planner)
//   beam = 1                    # K, integer in [1, 64] (used when lookahead > 1)
//   deduplicate = true          # evaluate each distinct motion once (the plan does not change)
//   threads = 1                 # integer in [1, 256] (the plan does not change)
//
//   [goal]                      # required: exactly one of twist and waypoints
//   twist = [0.2, 0.0, 0.0]     # (v_x, v_y, ω) m/s, m/s, rad/s, a body twist held from `start`
//   # start = [0, 0, 0]         # twist only: the target at t = 0, (x, y, θ) m, m, rad;
//                               # default: [start].pose (the thesis' goals)
//   # waypoints = "goal.csv"    # a CSV relative to the plan file's folder: rows t, x, y, theta
//                               # (s, m, m, rad; θ unwrapped), t strictly increasing, ≥ 2 rows;
//                               # '#' comments and blank lines skipped; a first row
//                               # "t,x,y,theta" is a header
//
//   [start]                     # optional
//   t = 0.0                     # s, [-1e9, 1e9]
//   pose = [0, 0, 0]            # (x, y, θ) m, m, rad in the world frame
//   phi = [0.5, 0, 0.5, 0, 0.5, 0]  # one shaft angle per leg, turns in [0, 1);
//                               # default: planning::tripod_start (the two tripods out of phase)
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>

#include "core/range.hpp"
#include "planning/goal.hpp"
#include "planning/planner.hpp"

namespace slipwalk::planning {

namespace ranges {
/// A goal's translational speed and turning rate (and a waypoint's time): far beyond a walking
/// robot, bounded so that the target stays finite over any plan.
inline constexpr core::Range kGoalSpeed = contact::limits::kVelocity;
inline constexpr core::Range kGoalRate = core::closed(-1e3, 1e3, "rad/s");
inline constexpr core::Range kTime = core::closed(-1e9, 1e9, "s");
/// A shaft angle: [0, 1) turns.
inline constexpr core::Range kPhi = core::Range{0.0, 1.0, false, true, "turns"};
/// stance_half_width: (0, 0.5) turns (plan_robot.hpp).
inline constexpr core::Range kStanceHalfWidth = core::Range{0.0, 0.5, true, true, "turns"};
}  // namespace ranges

/// The largest plan CSV a file may ask for, bytes (as scene::kMaxRunBytes for a run).
inline constexpr double kMaxPlanBytes = 4e9;

/// A plan file, read and checked.
struct PlanFile {
  std::string path;       ///< the file, as named to read_plan_file (messages, provenance)
  PlanRobot robot;        ///< [plan] robot
  PlanOptions options;    ///< [plan]
  Goal goal;              ///< [goal]
  PlanState start;        ///< [start]
  std::string goal_file;  ///< [goal] waypoints as resolved; empty for a twist
};

/// Parses a plan from text; `path` names it in messages and locates a waypoint file. Throws
/// core::InputError naming path:line:col (or the waypoint file's file:line:col) for every error
/// the file can have: syntax, unknown key, wrong type, range, a missing or doubled goal, and the
/// cross-field ones (execute > substeps at execute, M^N > 2^24 at speeds, a phi count that is not
/// the robot's legs at phi, a CSV over kMaxPlanBytes at steps).
[[nodiscard]] PlanFile parse_plan_file(std::string_view text, const std::string& path);

/// Reads and parses a plan file; an unreadable file is an InputError naming it.
[[nodiscard]] PlanFile read_plan_file(const std::filesystem::path& path);

/// The waypoints of a goal CSV (format above) into goal.times and goal.waypoints. Throws
/// core::InputError at file:line:col for a cell that is not a finite number in range, a row of
/// other than 4 cells, a time that does not increase, and at file:line for fewer than 2 rows.
void parse_waypoints(std::string_view text, const std::string& file, Goal& goal);

/// The plan as JSON (provenance sidecars): robot, options, goal, start.
[[nodiscard]] nlohmann::json to_json(const PlanFile& plan);

/// What write_plan did.
struct PlanRun {
  PlanSummary summary;
  std::vector<std::string> columns;
  double wall_s = 0.0;  ///< the plan and its CSV, s
};

/// Plans `plan` and writes <csv> (plan_csv.hpp's rows, a temporary renamed when complete) and its
/// sidecar <csv stem>.json: `extra`'s keys first, then the plan, columns, the summary (steps,
/// mean and final tracking distance, options evaluated), wall time and build provenance; both
/// are renamed together (core::commit_with_sidecar), nothing is left on an error. `progress`,
/// when given, gets ten lines. Throws core::InputError("--out") when the sidecar would overwrite
/// the CSV, core::ComputationError when a step has no feasible option.
PlanRun write_plan(const PlanFile& plan, const std::filesystem::path& csv,
                   const nlohmann::json& extra, std::ostream* progress);

}  // namespace slipwalk::planning
