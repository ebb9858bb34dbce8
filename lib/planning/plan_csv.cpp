#include "planning/plan_csv.hpp"

#include <array>

#include "planning/cost.hpp"

namespace slipwalk::planning {

namespace {

/// A per-step column: its name and how a row's cell is written.
struct StepColumn {
  const char* name;
  void (*write)(core::CsvWriter& out, const PlanOptions& options, const StepRecord& r);
};

/// A per-leg column group: the prefix of its names (prefix + leg name) and the cell of leg i.
struct LegColumn {
  const char* prefix;
  void (*write)(core::CsvWriter& out, const StepRecord& r, int leg);
};

constexpr std::array kStepColumns = {
    StepColumn{"step", [](auto& o, const auto&, const auto& r) { o.cell(r.step); }},
    StepColumn{"t", [](auto& o, const auto&, const auto& r) { o.cell(r.state.t); }},
    StepColumn{"x", [](auto& o, const auto&, const auto& r) { o.cell(r.state.pose.x); }},
    StepColumn{"y", [](auto& o, const auto&, const auto& r) { o.cell(r.state.pose.y); }},
    StepColumn{"theta", [](auto& o, const auto&, const auto& r) { o.cell(r.state.pose.theta); }},
    StepColumn{"goal_x", [](auto& o, const auto&, const auto& r) { o.cell(r.goal.x); }},
    StepColumn{"goal_y", [](auto& o, const auto&, const auto& r) { o.cell(r.goal.y); }},
    StepColumn{"goal_theta", [](auto& o, const auto&, const auto& r) { o.cell(r.goal.theta); }},
    StepColumn{"distance",
               [](auto& o, const auto& options, const auto& r) {
                 o.cell(se2_distance(r.state.pose, r.goal, options.rotation_length));
               }},
    StepColumn{"cost", [](auto& o, const auto&, const auto& r) { o.cell(r.choice.cost); }},
    StepColumn{"option", [](auto& o, const auto&, const auto& r) { o.cell(r.choice.option); }},
    StepColumn{"evaluated",
               [](auto& o, const auto&, const auto& r) { o.cell(r.choice.evaluated); }},
    StepColumn{"infeasible",
               [](auto& o, const auto&, const auto& r) { o.cell(r.choice.infeasible); }},
};

constexpr std::array kLegColumns = {
    LegColumn{"speed_", [](auto& o, const auto& r, int i) { o.cell(r.choice.speed(i)); }},
    LegColumn{"phi_", [](auto& o, const auto& r, int i) { o.cell(r.state.phi(i)); }},
    LegColumn{"chooses_",
              [](auto& o, const auto& r, int i) {
                o.cell(static_cast<int>(r.choice.chooses[static_cast<std::size_t>(i)]));
              }},
};

}  // namespace

std::vector<std::string> plan_columns(const PlanRobot& robot) {
  std::vector<std::string> columns;
  columns.reserve(kStepColumns.size() + kLegColumns.size() * robot.leg_names.size());
  for (const StepColumn& c : kStepColumns) {
    columns.emplace_back(c.name);
  }
  for (const LegColumn& c : kLegColumns) {
    for (const std::string& leg : robot.leg_names) {
      columns.push_back(c.prefix + leg);
    }
  }
  return columns;
}

void write_plan_row(core::CsvWriter& out, const PlanOptions& options, const StepRecord& record) {
  for (const StepColumn& c : kStepColumns) {
    c.write(out, options, record);
  }
  const int legs = static_cast<int>(record.state.phi.size());
  for (const LegColumn& c : kLegColumns) {
    for (int i = 0; i < legs; ++i) {
      c.write(out, record, i);
    }
  }
  out.end_row();
}

}  // namespace slipwalk::planning
