// slipwalk plan PLAN.toml --out FILE.csv [--progress]: a motion plan of the brute-force planner
// (thesis §5.4–5.5). The plan file is read and checked whole first (bad input: exit 2, nothing
// written; format in lib/planning/plan_file.hpp), then one CSV row per planning step
// (lib/planning/plan_csv.hpp) is written to a temporary file renamed when complete, with a
// provenance sidecar FILE.json beside it holding the summary. A step with no feasible option
// fails the plan (exit 1) and leaves no file.
#include <array>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "planning/plan_file.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

struct PlanCommand {
  std::string plan_file;
  std::string out;
  bool progress = false;

  void run() const {
    // Neither output may be the plan file (checked before it is read) or its waypoint file.
    std::filesystem::path sidecar = out;
    sidecar.replace_extension(".json");
    const auto check_outputs = [&](std::span<const std::filesystem::path> inputs) {
      core::check_output_path(out, "--out", inputs);
      core::check_output_path(sidecar, "--out (its sidecar " + sidecar.string() + ")", inputs);
    };
    check_outputs(std::array<std::filesystem::path, 1>{plan_file});
    const planning::PlanFile plan = planning::read_plan_file(plan_file);
    if (!plan.goal_file.empty()) {
      check_outputs(std::array<std::filesystem::path, 1>{plan.goal_file});
    }
    const nlohmann::json extra = {{"command", "plan"}};
    const planning::PlanRun result =
        planning::write_plan(plan, out, extra, progress ? &std::cerr : nullptr);
    if (progress) {
      const planning::PlanSummary& s = result.summary;
      std::ostringstream line;
      line << std::setprecision(3) << "slipwalk plan: " << s.steps << " steps; tracking distance "
           << s.mean_distance << " m mean, " << s.final_distance << " m final; " << s.evaluated
           << " options evaluated in " << std::fixed << std::setprecision(1) << result.wall_s
           << " s\n";
      std::cerr << line.str();
    }
  }
};

}  // namespace

void add_plan_command(CLI::App& app) {
  auto cmd = std::make_shared<PlanCommand>();
  auto* sub = app.add_subcommand(
      "plan",
      "a motion plan (thesis §5.4-5.5): at each step every leg in contact chooses a shaft speed "
      "so that the body tracks a goal trajectory; one CSV row per planning step (pose, goal, "
      "distance, chosen option, per-leg speed and phase)");
  sub->add_option("PLAN", cmd->plan_file, "plan file (TOML; format in lib/planning/plan_file.hpp)")
      ->required();
  sub->add_option("--out", cmd->out,
                  "CSV file to write (whole or not at all), with a provenance sidecar "
                  "<name>.json beside it holding the summary")
      ->required();
  sub->add_flag("--progress", cmd->progress, "print progress to stderr (about ten lines)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
