#pragma once
// The CSV of a plan (`slipwalk plan`, the ch5_planning study): one row per planning step, the
// state at the step's start and the choice made there. The columns come from one table
// (plan_csv.cpp): per-step columns, then per leg L (the robot's leg names) a group of columns.
//   step            planning step n (0-based)
//   t               s, the step's start, n · T_f · Δt/T_s
//   x, y, theta     the pose at t (world frame; theta unwrapped), m, m, rad
//   goal_x, goal_y, goal_theta   Ω^target(t)
//   distance        d(pose, Ω^target(t)), m (planning/cost.hpp): the tracking error now
//   cost            the chosen option's cost: d at t + Δt (lookahead 1), or the best leaf's sum
//   option          the chosen option index Σ c_i M^i (planner.hpp)
//   evaluated       options integrated for this step (all levels)
//   infeasible      of these, options the model could not follow
//   speed_L         φ̇ leg L executes over the step, turns/s (the swing speed when it swings)
//   phi_L           leg L's shaft angle at t, turns in [0, 1)
//   chooses_L       1 if leg L chose its speed (in contact by the rule), 0 if it swings
#include <string>
#include <vector>

#include "core/csv.hpp"
#include "planning/planner.hpp"

namespace slipwalk::planning {

/// The header of a plan of `robot`'s legs.
[[nodiscard]] std::vector<std::string> plan_columns(const PlanRobot& robot);

/// One row: the step `record` under `options` (for the distance's ρ).
void write_plan_row(core::CsvWriter& out, const PlanOptions& options, const StepRecord& record);

}  // namespace slipwalk::planning
