#pragma once
// Each subcommand registers itself on the app with a callback that does its work. Errors are
// thrown: core::InputError (exit 2), anything else (exit 1); main() maps them to exit codes.
#include <CLI/CLI.hpp>
#include <string>

namespace slipwalk::cli {

void add_inchworm_command(CLI::App& app);   ///< inchworm vss | trace      (inchworm_command.cpp)
void add_sweep_command(CLI::App& app);      ///< sweep SPEC.toml            (sweep_command.cpp)
void add_reproduce_command(CLI::App& app);  ///< reproduce [--quick] [...]  (reproduce_command.cpp)
void add_model_command(CLI::App& app);      ///< model [--friction] [--in]   (model_command.cpp)
void add_run_command(CLI::App& app);        ///< run SCENE.toml --out FILE   (run_command.cpp)
void add_kinds_command(CLI::App& app);      ///< kinds [KIND...] [--json]   (kinds_command.cpp)
void add_plan_command(CLI::App& app);       ///< plan PLAN.toml --out FILE  (plan_command.cpp)
void add_residual_command(CLI::App& app);   ///< residual fit --trials ...  (residual_command.cpp)
void add_calibrate_command(CLI::App& app);  ///< calibrate [synth] ...      (calibrate_command.cpp)

/// The line an error is reported with, `slipwalk: error: <what>` and a newline, `what` cut so that
/// a value of megabytes cannot come back as a message of megabytes (main.cpp). Written with one
/// write, so that no other process's output lands inside it.
[[nodiscard]] std::string error_line(const char* what);

}  // namespace slipwalk::cli
