// slipwalk sweep SPEC.toml [--jobs N] [--resume] [--quick] [--data DIR] (sweeps/README.md).
#include <array>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "sweeps/cli/commands.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::cli {

namespace {

struct SweepCommand {
  std::string spec;
  int jobs = 0;
  bool resume = false;
  bool quick = false;
  bool no_timing = false;
  std::string data = std::string(SLIPWALK_SOURCE_DIR) + "/data";
  long long max_points = -1;
  double progress_interval_s = 1.0;

  void run() const {
    if (jobs < 0 || jobs > 4096) {
      throw core::InputError(
          "--jobs", "must be from 1 to 4096 (0: one per core), got " + std::to_string(jobs));
    }
    if (max_points < -1) {
      throw core::InputError("--max-points", "must be non-negative");
    }
    // Everything is checked before anything is written, the destination included.
    core::check_output_dir(data, "--data");
    const sweeps::PreparedSweep sweep =
        sweeps::prepare(sweeps::load_spec(spec, quick), sweeps::points::all_kinds());
    const std::array<std::filesystem::path, 1> inputs{spec};
    for (const std::filesystem::path& out :
         {sweeps::csv_path(sweep.spec, data), sweeps::partial_path(sweep.spec, data)}) {
      core::check_output_path(out, "--data (output " + out.string() + ")", inputs, true);
    }
    sweeps::RunOptions options;
    options.data_dir = data;
    options.jobs = static_cast<unsigned>(jobs);
    options.resume = resume;
    options.timing = !no_timing;
    options.max_points = max_points;
    options.progress = &std::cerr;
    options.progress_interval_s = progress_interval_s;
    const sweeps::RunSummary s = sweeps::run(sweep, options);
    if (s.complete) {
      std::cout << s.csv.string() << ": " << s.points << " points (" << s.failed << " failed, "
                << s.resumed << " resumed) in " << s.wall_s << " s on " << s.jobs << " thread"
                << (s.jobs == 1 ? "" : "s") << "\n";
    } else {
      std::cout << s.partial.string() << ": " << (s.resumed + s.computed) << " of " << s.points
                << " points; continue with --resume\n";
    }
  }
};

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto cmd = std::make_shared<SweepCommand>();
  auto* sub = app.add_subcommand("sweep", "run a parameter sweep spec into <data>/<study>/");
  sub->add_option("SPEC", cmd->spec, "sweep spec (TOML, see sweeps/README.md)")->required();
  sub->add_option("--jobs,-j", cmd->jobs, "threads (default: one per core)");
  sub->add_flag("--resume", cmd->resume,
                "keep the points finished in <name>.partial.csv by an interrupted run");
  sub->add_flag("--quick", cmd->quick, "apply the spec's [quick] overrides (smoke runs)");
  sub->add_option("--data", cmd->data, "data folder (default <source>/data)");
  sub->add_flag("--no-timing", cmd->no_timing,
                "write wall_s as 0, so that reruns give byte-identical files");
  sub->add_option("--max-points", cmd->max_points,
                  "stop after computing this many points (tests of --resume)")
      ->group("");  // hidden
  sub->add_option("--progress-interval", cmd->progress_interval_s,
                  "seconds between progress lines (tests use 0: every point)")
      ->check(CLI::NonNegativeNumber)
      ->group("");  // hidden
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
