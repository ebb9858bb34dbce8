// slipwalk reproduce [--quick] [--jobs N] [--data DIR] [--report DIR] [--studies DIR] [--fresh]
// [--keep-finished] [--no-report] [STUDY...]: every study's traces, scene runs and sweeps, then
// the report: the pipeline of sweeps/engine/reproduce.hpp with the options mapped and its
// summary printed.
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
  const std::string source = SLIPWALK_SOURCE_DIR;
  bool quick = false;
  bool fresh = false;
  bool keep_finished = false;
  bool no_report = false;
  int jobs = 0;
  std::string data = source + "/data";
  std::string report = source + "/reports/out";
  std::string studies = source + "/studies";
  std::vector<std::string> names;

  void run() const {
    core::check_output_dir(data, "--data");
    core::check_output_dir(report, "--report");
    sweeps::ReproduceOptions options;
    options.studies_dir = studies;
    options.names = names;
    options.data_dir = data;
    options.quick = quick;
    options.resume = !fresh;
    options.keep_finished = keep_finished;
    options.jobs = jobs;
    options.report = !no_report;
    options.report_dir = report;
    options.python = SLIPWALK_PYTHON;
    options.report_builder = source + "/reports/site/build_report.py";
    options.kinds = sweeps::points::all_kinds();
    options.log = &std::cout;
    options.progress = &std::cerr;
    const sweeps::ReproduceSummary summary = sweeps::reproduce(options);
    if (summary.report == sweeps::ReportOutcome::kOff) {
      std::cout << "== report skipped (--no-report)" << std::endl;
    } else if (summary.report == sweeps::ReportOutcome::kFailed) {
      throw core::ComputationError(summary.report_message);
    }
    std::cout << summary.brief_report() << std::endl;
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
  sub->add_flag("--fresh", cmd->fresh, "discard checkpoints of interrupted sweeps");
  sub->add_flag("--keep-finished", cmd->keep_finished,
                "do not rerun a job whose outputs this build wrote for the same inputs");
  sub->add_flag("--no-report", cmd->no_report, "run the studies only, not the report builder");
  sub->add_option("--jobs,-j", cmd->jobs, "threads per sweep (default: one per core)");
  sub->add_option("--data", cmd->data, "data folder (default <source>/data)");
  sub->add_option("--report", cmd->report, "report folder (default <source>/reports/out)");
  sub->add_option("--studies", cmd->studies, "studies folder (default <source>/studies)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
