#pragma once
// A job of a study: it runs and yields a CSV, its provenance sidecar and a JobSummary. The kinds
// are the entries of the `Job` variant — an inchworm trace, a scene run, a sweep — and run_job
// dispatches on it; a new kind is one more entry and its overload in job.cpp.
#include <filesystem>
#include <string>
#include <variant>

#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/study.hpp"

namespace slipwalk::sweeps {

/// What one job did.
struct JobSummary {
  std::string study;          ///< the study it belongs to (its id)
  std::string name;           ///< the output stem: <data>/<folder>/<name>.csv
  std::string kind;           ///< "trace" | "scene" | "sweep"
  std::filesystem::path csv;  ///< the result
  long long points = 0;       ///< sweep: its points; trace and scene: 1
  long long failed = 0;       ///< points whose solve failed (sweeps; recorded in the sidecar)
  long long resumed = 0;      ///< points kept from an earlier run instead of computed
  double seconds = 0.0;       ///< wall time of this run of the job
  std::string warning;        ///< empty, or what went wrong short of failing (a scene's bad frames)
  std::string point_kind;     ///< sweep: the spec's point kind; empty for traces and scenes
  long long at_budget = 0;    ///< sweep: points that stopped at a budget the spec sets (not failed)

  /// The job's line in the log of `slipwalk reproduce`, e.g.
  /// `  sweep fig2_3: 320 points (0 failed, 0 resumed) -> data/ch2/fig2_3.csv (1.2 s)`, with
  /// `, 19 at their budget` after the failures where there are any.
  [[nodiscard]] std::string line() const;
};

/// How jobs run: shared by every job of one pipeline call.
struct JobContext {
  RunOptions sweep;    ///< data_dir (every job's outputs), jobs, resume, progress (sweeps)
  bool quick = false;  ///< scene runs take their quick_duration (sweeps are prepared quick)
  /// Keep a job whose CSV and sidecar exist and were written by this build (git commit) for the
  /// same inputs: it is not rerun and its summary counts its points as resumed. Independent of
  /// sweep.resume, which continues interrupted sweeps from their checkpoints.
  bool keep_finished = false;
};

/// The job kinds: each refers to its entry in a loaded study (which must outlive the job).
struct TraceRun {
  const Study* study;
  const TraceJob* job;
};
struct SceneRun {
  const Study* study;
  const SceneJob* job;
};
struct SweepRun {
  const PreparedSweep* sweep;
};
using Job = std::variant<TraceRun, SceneRun, SweepRun>;

/// Runs one job into <data>/<folder>/<name>.csv and its sidecar <name>.json, both atomically.
/// Throws what the job throws (core::ComputationError for a point kind that throws).
JobSummary run_job(const Job& job, const JobContext& context);

/// The trace job alone: <data>/<study>/<name>.csv (inchworm::write_trace) and its sidecar.
JobSummary write_trace_job(const Study& study, const TraceJob& job,
                           const std::filesystem::path& data_dir);

/// The scene job alone (quick: its quick_duration, when given): the `slipwalk run` columns and
/// sidecar (scene/run_writer.hpp). Unsupported or unconverged frames go to `warning`.
JobSummary write_scene_job(const Study& study, const SceneJob& job,
                           const std::filesystem::path& data_dir, bool quick);

}  // namespace slipwalk::sweeps
