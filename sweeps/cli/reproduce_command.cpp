// slipwalk reproduce [--quick|--full] [--jobs N] [--data DIR] [--report DIR] [--studies DIR]
// [--fresh]
// [--keep-finished] [--no-report] [STUDY...]: every study's traces, scene runs and sweeps, then
// the report: the pipeline of sweeps/engine/reproduce.hpp with the options mapped and its
// summary printed. Exit 1 when a sweep point failed (after everything else is written), unless
// every failure is in a sweep named by --expect-failures.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "sweeps/cli/commands.hpp"
#include "sweeps/engine/reproduce.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::cli {

namespace {

struct ReproduceCommand {
  bool quick = false;
  bool full = false;
  bool fresh = false;
  bool keep_finished = false;
  bool no_report = false;
  int jobs = 0;
  std::string data = SLIPWALK_SOURCE_DIR "/data";
  std::string report = SLIPWALK_SOURCE_DIR "/reports/out";
  std::string studies = SLIPWALK_SOURCE_DIR "/studies";
  std::vector<std::string> names;
  std::vector<std::string> expected_failures;

  void run() const {
    core::check_output_dir(data, "--data");
    core::check_output_dir(report, "--report");
    sweeps::ReproduceOptions options;
    options.studies_dir = studies;
    options.names = names;
    options.data_dir = data;
    options.quick = quick;
    options.full = full;
    options.expected_failures = expected_failures;
    options.resume = !fresh;
    options.keep_finished = keep_finished;
    options.jobs = jobs;
    options.report = !no_report;
    options.report_dir = report;
    options.python = SLIPWALK_PYTHON;
    options.report_builder = SLIPWALK_SOURCE_DIR "/reports/site/build_report.py";
    options.kinds = sweeps::points::all_kinds();
    options.log = &std::cout;
    options.progress = &std::cerr;
    const sweeps::ReproduceSummary summary = sweeps::reproduce(options);
    if (summary.report == sweeps::ReportOutcome::kOff) {
      std::cout << "== report skipped (--no-report)" << std::endl;
    } else if (summary.report == sweeps::ReportOutcome::kFailed) {
      throw core::ComputationError(summary.report_message);
    }
    std::cout << summary.failures_report() << summary.brief_report() << std::endl;
    if (summary.unexpected_failed_points() > 0) {
      // Everything else is written; a failed point is something that should not have happened.
      throw core::ComputationError(std::to_string(summary.unexpected_failed_points()) +
                                   " sweep points failed (listed above by study and kind)");
    }
  }
};

}  // namespace

void add_reproduce_command(CLI::App& app) {
  auto cmd = std::make_shared<ReproduceCommand>();
  auto* sub = app.add_subcommand(
      "reproduce", "run every study's traces, scene runs and sweeps, then the report");
  sub->add_option("STUDY", cmd->names,
                  "studies to run (folder names under --studies; default all)");
  sub->add_flag("--quick", cmd->quick, "the specs' [quick] overrides: a smoke run");
  sub->add_flag("--full", cmd->full, "the specs' [full] overrides: each study's long version");
  sub->add_flag("--fresh", cmd->fresh, "discard checkpoints of interrupted sweeps");
  sub->add_flag("--keep-finished", cmd->keep_finished,
                "do not rerun a job whose outputs this build wrote for the same inputs");
  sub->add_flag("--no-report", cmd->no_report, "run the studies only, not the report builder");
  sub->add_option("--expect-failures", cmd->expected_failures,
                  "sweeps (study/name) whose failed points are a known open defect: still listed, "
                  "but they alone do not make the exit status 1")
      ->delimiter(',');
  sub->add_option("--jobs,-j", cmd->jobs, "threads per sweep (default: one per core)");
  sub->add_option("--data", cmd->data, "data folder (default <source>/data)");
  sub->add_option("--report", cmd->report, "report folder (default <source>/reports/out)");
  sub->add_option("--studies", cmd->studies, "studies folder (default <source>/studies)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
