// slipwalk reproduce [--quick] [--jobs N] [--data DIR] [--report DIR] [--studies DIR] [--fresh]
// [STUDY...]: every study's traces, scene runs and sweeps, then the report (sweeps/README.md).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>  // environ

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "sweeps/cli/commands.hpp"
#include "core/error.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"
#include "sweeps/engine/study.hpp"

namespace slipwalk::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string seconds(double s) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f s", s);
  return buffer;
}

/// Runs argv[0] with arguments, no shell; returns its exit status (-1: could not start).
int run_program(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const auto& a : args) {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) {
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      return -1;
    }
  }
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status);
  }
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

struct ReproduceCommand {
  const std::string source = SLIPWALK_SOURCE_DIR;
  bool quick = false;
  bool fresh = false;
  bool no_report = false;
  int jobs = 0;
  std::string data = source + "/data";
  std::string report = source + "/reports/out";
  std::string studies = source + "/studies";
  std::vector<std::string> names;

  void run() const {
    const auto start = Clock::now();
    if (jobs < 0 || jobs > 4096) {
      throw core::InputError(
          "--jobs", "must be from 1 to 4096 (0: one per core), got " + std::to_string(jobs));
    }
    // The studies to run: every folder with a study.toml, or the ones named.
    std::vector<fs::path> dirs;
    if (names.empty()) {
      if (!fs::is_directory(studies)) {
        throw core::InputError("--studies", "'" + studies + "' is not a folder");
      }
      dirs = sweeps::find_studies(studies);
    } else {
      for (const auto& name : names) {
        const fs::path dir = fs::path(studies) / name;
        if (!fs::is_regular_file(dir / "study.toml")) {
          throw core::InputError(
              "STUDY", "no study '" + name + "' (no " + (dir / "study.toml").string() + ")");
        }
        dirs.push_back(dir);
      }
    }
    // Everything is read and checked before anything is written.
    struct Loaded {
      sweeps::Study study;
      std::vector<sweeps::PreparedSweep> sweeps;
    };
    std::vector<Loaded> loaded;
    for (const auto& dir : dirs) {
      Loaded l{sweeps::load_study(dir), {}};
      for (const auto& spec : l.study.sweeps) {
        l.sweeps.push_back(sweeps::prepare(sweeps::load_spec(spec, quick), sweeps::points::all_kinds()));
      }
      loaded.push_back(std::move(l));
    }

    sweeps::RunOptions options;
    options.data_dir = data;
    options.jobs = static_cast<unsigned>(jobs);
    options.resume = !fresh;
    options.progress = &std::cerr;
    long long failed = 0;
    for (const auto& l : loaded) {
      std::cout << "== " << l.study.id << ": " << l.study.title << (quick ? " (quick)" : "")
                << std::endl;
      for (const auto& trace : l.study.traces) {
        const auto t0 = Clock::now();
        const fs::path csv = sweeps::write_trace_job(l.study, trace, data);
        std::cout << "  trace " << trace.name << " -> " << csv.string() << " ("
                  << seconds(since(t0)) << ")" << std::endl;
      }
      for (const auto& scene : l.study.scenes) {
        const auto t0 = Clock::now();
        const fs::path csv = sweeps::write_scene_job(l.study, scene, data, quick);
        std::cout << "  scene " << scene.name << " -> " << csv.string() << " ("
                  << seconds(since(t0)) << ")" << std::endl;
      }
      for (const auto& sweep : l.sweeps) {
        const auto t0 = Clock::now();
        const sweeps::RunSummary s = sweeps::run(sweep, options);
        failed += s.failed;
        std::cout << "  sweep " << sweep.spec.name << ": " << s.points << " points (" << s.failed
                  << " failed, " << s.resumed << " resumed) -> " << s.csv.string() << " ("
                  << seconds(since(t0)) << ")" << std::endl;
      }
    }

    // The report.
    const fs::path builder = fs::path(source) / "reports" / "build_report.py";
    if (no_report) {
      std::cout << "== report skipped (--no-report)" << std::endl;
    } else if (!fs::is_regular_file(builder)) {
      std::cerr << "slipwalk: warning: " << builder.string()
                << " does not exist yet; the report is skipped" << std::endl;
    } else {
      std::vector<std::string> args = {SLIPWALK_PYTHON, builder.string(), "--data", data, "--out",
                                       report};
      if (quick) {
        args.emplace_back("--quick");
      }
      const auto t0 = Clock::now();
      std::cout << "== report -> " << report << std::endl;
      const int status = run_program(args);
      if (status != 0) {
        throw core::ComputationError("the report builder (" + builder.string() + ") failed" +
                                     (status < 0 ? std::string(": cannot run ") + SLIPWALK_PYTHON
                                                 : " with exit status " + std::to_string(status)));
      }
      std::cout << "  report built (" << seconds(since(t0)) << ")" << std::endl;
    }
    std::cout << "reproduce: done in " << seconds(since(start)) << "; " << failed
              << " sweep points failed (recorded in the sidecars)" << std::endl;
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
  sub->add_flag("--no-report", cmd->no_report, "run the studies only, not the report builder");
  sub->add_option("--jobs,-j", cmd->jobs, "threads per sweep (default: one per core)");
  sub->add_option("--data", cmd->data, "data folder (default <source>/data)");
  sub->add_option("--report", cmd->report, "report folder (default <source>/reports/out)");
  sub->add_option("--studies", cmd->studies, "studies folder (default <source>/studies)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
