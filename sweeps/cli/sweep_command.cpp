// slipwalk sweep SPEC.toml [--jobs N] [--resume] [--quick|--full] [--data DIR] [--shard k/n]
// [--mpi] slipwalk sweep merge SPEC.toml [--quick|--full] [--data DIR] [--shards N] [--keep-shards]
// Under an MPI launcher (mpirun -np R slipwalk sweep ...) the points go over the ranks
// (sweeps/engine/mpi/mpi_run.hpp); see sweeps/README.md.
#include <array>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "sweeps/cli/commands.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/shards.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::cli {

namespace {

/// "N at their budget, " where points stopped at a budget their spec expects; "" when none.
std::string budget_text(long long at_budget) {
  return at_budget > 0 ? std::to_string(at_budget) + " at their budget, " : std::string();
}

using core::InputError;

std::string default_data() { return SLIPWALK_SOURCE_DIR "/data"; }

struct SweepCommand {
  std::string spec;
  int jobs = 0;
  bool resume = false;
  bool quick = false;
  bool full = false;
  bool no_timing = false;
  std::string data = default_data();
  std::string shard;
  CLI::Option* shard_option = nullptr;  // given at all: `--shard ""` is a bad k/n, not none
  bool mpi = false;
  int coordinator_jobs = -1;
  long long max_points = -1;
  double progress_interval_s = 1.0;

  void check_options() const {
    if (spec.empty()) {
      throw InputError("SPEC",
                       "a sweep spec is required: `slipwalk sweep SPEC.toml` (or "
                       "`slipwalk sweep merge SPEC.toml`)");
    }
    if (jobs < 0 || jobs > 4096) {
      throw InputError("--jobs",
                       "must be from 1 to 4096 (0: one per core), got " + std::to_string(jobs));
    }
    if (coordinator_jobs < -1 || coordinator_jobs > 4096) {
      throw InputError("--coordinator-jobs",
                       "must be from 0 to 4096, got " + std::to_string(coordinator_jobs));
    }
    if (max_points < -1) {
      throw InputError("--max-points", "must be non-negative");
    }
  }

  [[nodiscard]] sweeps::RunOptions run_options() const {
    sweeps::RunOptions options;
    options.data_dir = data;
    options.jobs = static_cast<unsigned>(jobs);
    options.resume = resume;
    options.timing = !no_timing;
    options.max_points = max_points;
    options.progress = &std::cerr;
    options.progress_interval_s = progress_interval_s;
    const bool sharded = shard_option != nullptr && shard_option->count() > 0;
    options.shard = sharded ? sweeps::parse_shard(shard, "--shard") : sweeps::Shard{};
    return options;
  }

  [[nodiscard]] sweeps::PreparedSweep prepare() const {
    return sweeps::prepare(sweeps::load_spec(spec, sweeps::variant_of(quick, full)),
                           sweeps::points::all_kinds());
  }

  /// Everything is checked before anything is written, the destination included.
  void check_outputs(const sweeps::PreparedSweep& sweep, const sweeps::Shard& s) const {
    const std::array<std::filesystem::path, 1> inputs{spec};
    const sweeps::SweepFiles files = sweeps::sweep_files(sweep.spec, data, s);
    for (const std::filesystem::path& out : {files.csv, files.partial}) {
      core::check_output_path(out, "--data (output " + out.string() + ")", inputs, true);
    }
  }

  static void print(const sweeps::RunSummary& s) {
    if (s.complete) {
      std::cout << s.csv.string() << ": " << s.points << " points (" << s.failed << " failed, "
                << budget_text(s.at_budget) << s.resumed << " resumed) in " << s.wall_s << " s on ";
      if (s.ranks > 1) {
        std::cout << s.ranks << " ranks\n";
      } else {
        std::cout << s.jobs << " thread" << (s.jobs == 1 ? "" : "s") << "\n";
      }
    } else {
      std::cout << s.partial.string() << ": " << (s.resumed + s.computed) << " of " << s.points
                << " points; continue with --resume\n";
    }
  }

  void run() const {
    check_options();
    if (mpi || sweeps::mpi::launched()) {
      run_mpi();
      return;
    }
    if (coordinator_jobs >= 0) {
      throw InputError("--coordinator-jobs", "applies to MPI runs only (under mpirun)");
    }
    const sweeps::RunOptions options = run_options();
    core::check_output_dir(data, "--data");
    const sweeps::PreparedSweep sweep = prepare();
    check_outputs(sweep, options.shard);
    print(sweeps::run(sweep, options));
  }

  void run_mpi() const {
    if (!sweeps::mpi::available()) {
      throw InputError(mpi ? "--mpi" : "MPI launcher",
                       "this slipwalk was built without MPI support; install Debian's "
                       "openmpi-bin and libopenmpi-dev (make deps) and rebuild, or run the sweep "
                       "as shards (--shard k/n, then `slipwalk sweep merge`)");
    }
    const sweeps::mpi::Session session;
    sweeps::mpi::Options options;
    options.coordinator_jobs = coordinator_jobs;
    const sweeps::mpi::Setup setup{
        [&] {
          options.run = run_options();
          core::check_output_dir(data, "--data");
          return prepare();
        },
        [&](const sweeps::PreparedSweep& sweep) { check_outputs(sweep, options.run.shard); }};
    // Rank 0 reports an error before any rank ends: a rank that exits non-zero makes the MPI
    // runtime end the job, and rank 0 with it, perhaps before it has printed.
    int code = 0;
    sweeps::RunSummary s;
    try {
      s = sweeps::mpi::run_sweep(session, setup, options);
    } catch (const sweeps::mpi::QuietExit& e) {
      code = e.code;
    } catch (const InputError& e) {
      code = 2;
      std::cerr << error_line(e.what()) << std::flush;
    } catch (const std::exception& e) {
      code = 1;
      std::cerr << error_line(e.what()) << std::flush;
    }
    session.barrier();
    if (code != 0) {
      throw sweeps::mpi::QuietExit{code};
    }
    if (session.rank() == 0) {
      print(s);
    }
  }
};

struct MergeCommand {
  std::string spec;
  bool quick = false;
  bool full = false;
  std::string data = default_data();
  long long shards = 0;
  bool keep_shards = false;

  void run() const {
    if (shards < 0 || shards > 1'000'000) {
      throw InputError("--shards", "must be from 1 to 1000000, got " + std::to_string(shards));
    }
    core::check_output_dir(data, "--data");
    const sweeps::PreparedSweep sweep = sweeps::prepare(
        sweeps::load_spec(spec, sweeps::variant_of(quick, full)), sweeps::points::all_kinds());
    const std::array<std::filesystem::path, 1> inputs{spec};
    const sweeps::SweepFiles files = sweeps::sweep_files(sweep.spec, data);
    core::check_output_path(files.csv, "--data (output " + files.csv.string() + ")", inputs, true);
    sweeps::MergeOptions options;
    options.data_dir = data;
    options.keep_shards = keep_shards;
    if (shards > 0) {
      options.shards = shards;
    }
    const sweeps::MergeSummary s = sweeps::merge_shards(sweep, options);
    std::cout << s.csv.string() << ": " << s.points << " points (" << s.failed << " failed"
              << (s.at_budget > 0 ? ", " + std::to_string(s.at_budget) + " at their budget" : "")
              << ") merged from " << s.shards << " shards\n";
  }
};

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto cmd = std::make_shared<SweepCommand>();
  auto* sub = app.add_subcommand(
      "sweep",
      "run a parameter sweep spec into <data>/<study>/ (on threads, as one shard of n, or over "
      "MPI ranks under mpirun); `sweep merge` joins the shards");
  sub->require_subcommand(0, 1);
  std::vector<CLI::Option*> own;
  own.push_back(sub->add_option("SPEC", cmd->spec, "sweep spec (TOML, see sweeps/README.md)"));
  own.push_back(sub->add_option("--jobs,-j", cmd->jobs,
                                "threads (per rank under MPI; default: one per core)"));
  own.push_back(sub->add_flag(
      "--resume", cmd->resume,
      "keep the points finished in <name>.partial.csv by an interrupted run (by any number of "
      "threads or ranks)"));
  auto* quick =
      sub->add_flag("--quick", cmd->quick, "apply the spec's [quick] overrides (smoke runs)");
  sub->add_flag("--full", cmd->full, "apply the spec's [full] overrides (the study's long version)")
      ->excludes(quick);
  sub->add_option("--data", cmd->data, "data folder (default <source>/data)");
  own.push_back(sub->add_flag("--no-timing", cmd->no_timing,
                              "write wall_s as 0, so that reruns give byte-identical files"));
  cmd->shard_option = sub->add_option(
      "--shard", cmd->shard,
      "run the k-th of n shards (k/n; the ids dealt in turn in a fixed shuffled order) "
      "into <name>.shard-k-of-n.csv; join them with `sweep merge`");
  own.push_back(cmd->shard_option);
  own.push_back(sub->add_flag("--mpi", cmd->mpi,
                              "run over MPI ranks (implied under mpirun or srun); an error if "
                              "this build has no MPI"));
  own.push_back(sub->add_option("--coordinator-jobs", cmd->coordinator_jobs,
                                "MPI: computing threads on rank 0, which also hands out the "
                                "points (default --jobs; 0: it only coordinates)"));
  own.push_back(sub->add_option("--max-points", cmd->max_points,
                                "stop after computing this many points (tests of --resume)")
                    ->group(""));  // hidden
  own.push_back(sub->add_option("--progress-interval", cmd->progress_interval_s,
                                "seconds between progress lines (tests use 0: every point)")
                    ->check(CLI::NonNegativeNumber)
                    ->group(""));  // hidden

  auto merge = std::make_shared<MergeCommand>();
  auto* mrg = sub->add_subcommand(
      "merge",
      "join the shards <name>.shard-k-of-n.csv of a spec into <name>.csv, the file a single run "
      "writes (the shard files are removed unless --keep-shards)");
  mrg->add_option("SPEC", merge->spec, "the sweep spec the shards ran")->required();
  auto* merge_quick = mrg->add_flag("--quick", merge->quick, "the shards ran with --quick");
  mrg->add_flag("--full", merge->full, "the shards ran with --full")->excludes(merge_quick);
  mrg->add_option("--data", merge->data, "data folder (default <source>/data)");
  mrg->add_option("--shards", merge->shards,
                  "the shard count n (default: the one count found in the data folder)");
  mrg->add_flag("--keep-shards", merge->keep_shards, "keep the shard files after the merge");
  // CLI11 runs the subcommand's callback before its parent's: the check comes first here.
  mrg->callback([merge, own, sub] {
    for (const CLI::Option* o : own) {
      if (o->count() > 0) {
        throw InputError(o->get_name(), "is an option of `slipwalk sweep`, not of `sweep merge`");
      }
    }
    for (const char* name : {"--quick", "--full", "--data"}) {
      if (sub->get_option(name)->count() > 0) {
        throw InputError(name, "give it after `merge`: `slipwalk sweep merge SPEC " +
                                   std::string(name) + " ...`");
      }
    }
    merge->run();
  });
  sub->callback([cmd, mrg] {
    if (!mrg->parsed()) {
      cmd->run();
    }
  });
}

}  // namespace slipwalk::cli
