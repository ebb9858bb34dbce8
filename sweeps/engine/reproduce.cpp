#include "sweeps/engine/reproduce.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>  // environ

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>

#include "sweeps/engine/spec.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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

/// A study read and checked, with its sweeps expanded: nothing of it has been written yet.
struct LoadedStudy {
  Study study;
  std::vector<PreparedSweep> sweeps;
};

/// Stage 1: the study folders, each read and checked whole.
std::vector<LoadedStudy> load_studies(const ReproduceOptions& options) {
  std::vector<fs::path> dirs;
  if (options.names.empty()) {
    dirs = find_studies(options.studies_dir);
  } else {
    for (const auto& name : options.names) {
      dirs.push_back(options.studies_dir / name);
    }
  }
  std::vector<LoadedStudy> loaded;
  for (const auto& dir : dirs) {
    LoadedStudy l{load_study(dir), {}};
    for (const auto& spec : l.study.sweeps) {
      l.sweeps.push_back(
          prepare(load_spec(spec, variant_of(options.quick, options.full)), options.kinds));
    }
    loaded.push_back(std::move(l));
  }
  return loaded;
}

/// Every sweep named by --expect-failures is one of the studies' sweeps.
void check_expected_failures(const ReproduceOptions& options,
                             const std::vector<LoadedStudy>& loaded) {
  for (const std::string& name : options.expected_failures) {
    bool found = false;
    for (const auto& l : loaded) {
      for (const auto& sweep : l.sweeps) {
        found = found || sweep.spec.study + "/" + sweep.spec.name == name;
      }
    }
    if (!found) {
      throw core::InputError("--expect-failures",
                             "no sweep '" + name + "' (study/name) among the studies run");
    }
  }
}

/// Stage 2: a study's jobs, in the order they run: traces, scene runs, sweeps.
std::vector<Job> jobs_of(const LoadedStudy& l) {
  std::vector<Job> jobs;
  for (const auto& trace : l.study.traces) {
    jobs.emplace_back(TraceRun{&l.study, &trace});
  }
  for (const auto& scene : l.study.scenes) {
    jobs.emplace_back(SceneRun{&l.study, &scene});
  }
  for (const auto& sweep : l.sweeps) {
    jobs.emplace_back(SweepRun{&sweep});
  }
  return jobs;
}

/// Stage 3: the report builder, its outcome into `summary`.
void build_report(const ReproduceOptions& options, ReproduceSummary& summary) {
  if (!options.report) {
    summary.report = ReportOutcome::kOff;
    return;
  }
  const std::string builder = options.report_builder.string();
  if (!fs::is_regular_file(options.report_builder)) {
    summary.report = ReportOutcome::kNoBuilder;
    summary.report_message = builder + " does not exist yet; the report is skipped";
    if (options.progress != nullptr) {
      *options.progress << "slipwalk: warning: " << summary.report_message << std::endl;
    }
    return;
  }
  std::vector<std::string> args = {options.python.string(),   builder, "--data",
                                   options.data_dir.string(), "--out", options.report_dir.string()};
  if (options.quick) {
    args.emplace_back("--quick");
  }
  const auto start = Clock::now();
  if (options.log != nullptr) {
    *options.log << "== report -> " << options.report_dir.string() << std::endl;
  }
  const int status = run_program(args);
  summary.report_seconds = seconds_since(start);
  if (status != 0) {
    summary.report = ReportOutcome::kFailed;
    summary.report_message = "the report builder (" + builder + ") failed" +
                             (status < 0 ? ": cannot run " + options.python.string()
                                         : " with exit status " + std::to_string(status));
    return;
  }
  summary.report = ReportOutcome::kBuilt;
  if (options.log != nullptr) {
    *options.log << "  report built (" << seconds_text(summary.report_seconds) << ")" << std::endl;
  }
}

}  // namespace

std::optional<core::InputError> ReproduceOptions::validate() const {
  if (quick && full) {
    return core::InputError("--full", "cannot be combined with --quick (one size per run)");
  }
  if (jobs < 0 || jobs > 4096) {
    return core::InputError(
        "--jobs", "must be from 1 to 4096 (0: one per core), got " + std::to_string(jobs));
  }
  if (kinds.empty()) {
    return core::InputError("kinds", "no point kinds given (sweeps/points/families.hpp)");
  }
  if (names.empty() && !fs::is_directory(studies_dir)) {
    std::string what = "'";
    what.append(studies_dir.string()).append("' is not a folder");
    return core::InputError("--studies", what);
  }
  if (names.empty() && find_studies(studies_dir).empty()) {
    std::string what = "'";
    what.append(studies_dir.string()).append("' holds no study (no <folder>/study.toml)");
    return core::InputError("--studies", what);
  }
  for (const auto& name : names) {
    const fs::path file = studies_dir / name / "study.toml";
    if (!fs::is_regular_file(file)) {
      return core::InputError("STUDY", "no study '" + name + "' (no " + file.string() + ")");
    }
  }
  return std::nullopt;
}

long long ReproduceSummary::failed_points() const {
  long long n = 0;
  for (const auto& j : jobs) {
    n += j.kind == "sweep" ? j.failed : 0;
  }
  return n;
}

namespace {
std::string sweep_id(const JobSummary& j) { return j.study + "/" + j.name; }
}  // namespace

long long ReproduceSummary::unexpected_failed_points() const {
  long long n = 0;
  for (const auto& j : jobs) {
    const bool expected = std::find(expected_failures.begin(), expected_failures.end(),
                                    sweep_id(j)) != expected_failures.end();
    n += j.kind == "sweep" && !expected ? j.failed : 0;
  }
  return n;
}

long long ReproduceSummary::budget_points() const {
  long long n = 0;
  for (const auto& j : jobs) {
    n += j.kind == "sweep" ? j.at_budget : 0;
  }
  return n;
}

long long ReproduceSummary::resumed_points() const {
  long long n = 0;
  for (const auto& j : jobs) {
    n += j.resumed;
  }
  return n;
}

long long ReproduceSummary::points() const {
  long long n = 0;
  for (const auto& j : jobs) {
    n += j.points;
  }
  return n;
}

std::string ReproduceSummary::brief_report() const {
  std::string out = "reproduce: done in " + seconds_text(seconds) + "; " +
                    std::to_string(failed_points()) + " sweep points failed";
  if (const long long budget = budget_points(); budget > 0) {
    out += ", " + std::to_string(budget) + " stopped at a budget their study sets";
  }
  return out + " (recorded in the sidecars)";
}

std::string ReproduceSummary::failures_report() const {
  std::string out;
  std::string held;  // expected failures that did not happen
  for (const auto& j : jobs) {
    if (j.kind != "sweep") {
      continue;
    }
    const bool expected = std::find(expected_failures.begin(), expected_failures.end(),
                                    sweep_id(j)) != expected_failures.end();
    if (j.failed > 0) {
      out += "  " + sweep_id(j) + " (kind " + j.point_kind + "): " + std::to_string(j.failed) +
             " of " + std::to_string(j.points) + " points failed" +
             (expected ? ", expected (--expect-failures)" : "") + " (" +
             fs::path(j.csv).replace_extension(".json").string() + ": failed_points)\n";
    } else if (expected) {
      held += "reproduce: " + sweep_id(j) +
              " was expected to fail (--expect-failures) and did not: drop it from the list\n";
    }
  }
  return (out.empty() ? out : "reproduce: failed points, by study and kind:\n" + out) + held;
}

ReproduceSummary reproduce(const ReproduceOptions& options) {
  const auto start = Clock::now();
  if (auto error = options.validate()) {
    throw *error;
  }
  // Everything is read and checked before anything is written.
  const std::vector<LoadedStudy> loaded = load_studies(options);
  check_expected_failures(options, loaded);

  JobContext context;
  context.sweep.data_dir = options.data_dir;
  context.sweep.jobs = static_cast<unsigned>(options.jobs);
  context.sweep.resume = options.resume;
  context.sweep.progress = options.progress;
  context.quick = options.quick;
  context.keep_finished = options.resume && options.keep_finished;

  ReproduceSummary summary;
  summary.expected_failures = options.expected_failures;
  for (const auto& l : loaded) {
    summary.studies.push_back({l.study.id, l.study.title});
    if (options.log != nullptr) {
      *options.log << "== " << l.study.id << ": " << l.study.title
                   << (options.quick ? " (quick)" : "") << (options.full ? " (full)" : "")
                   << std::endl;
    }
    for (const Job& job : jobs_of(l)) {
      summary.jobs.push_back(run_job(job, context));
      const JobSummary& done = summary.jobs.back();
      if (!done.warning.empty() && options.progress != nullptr) {
        *options.progress << "slipwalk: warning: " << done.warning << "\n";
      }
      if (options.log != nullptr) {
        *options.log << done.line() << std::endl;
      }
    }
  }
  build_report(options, summary);
  summary.seconds = seconds_since(start);
  return summary;
}

}  // namespace slipwalk::sweeps
