#pragma once
// The study pipeline as a library call (`slipwalk reproduce` is a thin adapter of it):
//
//   ReproduceOptions options;
//   options.studies_dir = "studies";
//   options.kinds = points::all_kinds();           // sweeps/points/families.hpp
//   const ReproduceSummary summary = reproduce(options);
//   std::cout << summary.brief_report() << "\n";
//
// Stages: check the options; read and check every study file and sweep spec (nothing is written
// before all of them have passed); run each study's jobs (job.hpp: traces, scene runs, sweeps, in
// that order); build the report with the Python builder. Bad input throws core::InputError before
// any file is written; a job that throws stops the pipeline; failed sweep points are counted,
// not fatal (the summary lists them by study and kind, and `slipwalk reproduce` exits 1 after
// writing everything else); points that stop at a budget their spec sets on purpose are counted
// apart and are no failure; a failing report builder is recorded in the summary.
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "sweeps/engine/job.hpp"
#include "sweeps/engine/point_kind.hpp"

namespace slipwalk::sweeps {

struct ReproduceOptions {
  std::filesystem::path studies_dir = "studies";  ///< folders holding a study.toml
  /// The studies to run, folder names under studies_dir; empty (default): every study there.
  std::vector<std::string> names;
  std::filesystem::path data_dir = "data";  ///< outputs: <data_dir>/<study>/<name>.{csv,json}
  bool quick = false;  ///< the specs' [quick] overrides and scenes' quick_duration: a smoke run
  bool full = false;   ///< the specs' [full] overrides: each study's long version (not with quick)
  /// true (default): an interrupted sweep continues from its checkpoint. false (`--fresh`):
  /// checkpoints are discarded (and keep_finished is ignored).
  bool resume = true;
  /// true (`--keep-finished`): a job whose CSV and sidecar exist and were written by this build
  /// (the git commit configured into it) for the same inputs is not rerun and counts its points
  /// as resumed. Off by default: a code change that is not yet committed and configured would
  /// leave stale results in place.
  bool keep_finished = false;
  /// Sweeps whose failed points are known, as "study/name" (`--expect-failures`): an open
  /// defect that is being fixed elsewhere. Their failures are still counted and listed, marked
  /// expected; only the others make ReproduceSummary::unexpected_failed_points() non-zero. Each
  /// must name a sweep of the studies run.
  std::vector<std::string> expected_failures;
  int jobs = 0;        ///< threads per sweep, 1 to 4096; 0 (default): one per core
  bool report = true;  ///< run the report builder after the studies
  std::filesystem::path report_dir = "reports/out";   ///< the builder's --out
  std::filesystem::path python = "/usr/bin/python3";  ///< the interpreter of the builder
  /// The builder: `<python> <builder> --data DATA --out REPORT [--quick]`; when the file does
  /// not exist the report is skipped (ReportOutcome::kNoBuilder).
  std::filesystem::path report_builder = "reports/site/build_report.py";
  std::span<const PointKind> kinds;  ///< the point kinds sweeps may name (required)
  std::ostream* log = nullptr;       ///< a line per study and per job as they finish; null: none
  std::ostream* progress = nullptr;  ///< sweep progress lines and warnings; null: none

  /// The first problem with these options, or none: quick and full together, a --jobs out of
  /// range, no point kinds, a studies folder that does not exist, a named study without a
  /// study.toml. Its `where` names the option (`--full`, `--jobs`, `--studies`, `STUDY`).
  [[nodiscard]] std::optional<core::InputError> validate() const;
};

enum class ReportOutcome {
  kOff,        ///< options.report was false
  kNoBuilder,  ///< the builder script does not exist: skipped
  kBuilt,      ///< the builder exited with status 0
  kFailed,     ///< it could not start or exited non-zero (report_message says which)
};

struct ReproduceSummary {
  struct StudyRun {
    std::string id;
    std::string title;
  };
  std::vector<StudyRun> studies;               ///< in the order run
  std::vector<JobSummary> jobs;                ///< every job, in the order run
  std::vector<std::string> expected_failures;  ///< ReproduceOptions::expected_failures
  ReportOutcome report = ReportOutcome::kOff;
  std::string report_message;  ///< why the report was skipped or failed; empty when built or off
  double report_seconds = 0.0;
  double seconds = 0.0;  ///< the whole call

  [[nodiscard]] long long failed_points() const;  ///< over every sweep job
  /// Failed points of the sweeps not named in expected_failures: what makes the run fail.
  [[nodiscard]] long long unexpected_failed_points() const;
  [[nodiscard]] long long budget_points() const;  ///< stopped at their specs' budgets: not failed
  [[nodiscard]] long long resumed_points() const;
  [[nodiscard]] long long points() const;
  /// One line: `reproduce: done in 61.2 s; 0 sweep points failed (recorded in the sidecars)`,
  /// with `, 36 stopped at a budget their study sets` where there are any.
  [[nodiscard]] std::string brief_report() const;
  /// The failed points by study and kind, a line per sweep with any:
  /// `  stability/coulomb_long_run (kind coulomb_long_run): 100 of 100 points failed (SIDECAR:
  /// failed_points)`, with `, expected` for a sweep named in expected_failures, after a heading
  /// line; and a line per expected sweep that did not fail. Empty when neither.
  [[nodiscard]] std::string failures_report() const;
};

/// Runs the pipeline (above). Throws options.validate()'s error, core::InputError for a bad
/// study or spec (before anything is written), and what a job throws.
ReproduceSummary reproduce(const ReproduceOptions& options);

}  // namespace slipwalk::sweeps
