#pragma once
// Runs a sweep: checks every point, computes the points on N threads, checkpoints each finished
// point to `<name>.partial.csv`, and on completion writes `<data>/<study>/<name>.csv` (rows sorted
// by id: the same bytes whatever the thread count, wall_s aside) and the provenance sidecar
// `<name>.json`, both atomically. A run may be one shard of the sweep (`--shard k/n`, its own
// files, merged by merge_shards in shards.hpp); across MPI ranks it is engine/mpi/mpi_run.hpp.
// See sweeps/README.md.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "sweeps/engine/checkpoint.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {

struct RunOptions {
  std::filesystem::path data_dir = "data";  ///< outputs go to <data_dir>/<study>/<name>.*
  unsigned jobs = 0;                        ///< threads; 0 = std::thread::hardware_concurrency()
  bool resume = false;  ///< keep the points finished in <name>.partial.csv (else discard it)
  bool timing = true;   ///< false: wall_s and cpu_s cells are written as 0 (identical reruns)
  /// Stop after computing this many points in this run (< 0: no limit), leaving the partial
  /// file for --resume: how the tests interrupt a sweep.
  long long max_points = -1;
  std::ostream* progress = nullptr;  ///< progress lines; null: silent
  double progress_interval_s = 1.0;  ///< at most one progress line per this many seconds
  Shard shard;                       ///< the shard to run ({1, 1}: the whole sweep)
};

struct RunSummary {
  std::filesystem::path csv;      ///< the result (written only when complete)
  std::filesystem::path sidecar;  ///< its provenance
  std::filesystem::path partial;  ///< the checkpoint (removed when complete)
  long long points = 0;           ///< in the spec (in the shard, for a shard)
  long long resumed = 0;          ///< taken from the checkpoint
  long long computed = 0;         ///< in this run
  long long failed = 0;           ///< points whose solve failed (all runs)
  long long at_budget = 0;        ///< points that stopped at a budget the spec sets (all runs)
  bool complete = false;          ///< false when max_points stopped the run
  unsigned jobs = 1;              ///< threads (per rank)
  unsigned ranks = 1;             ///< MPI ranks
  double wall_s = 0.0;            ///< this run
};

/// A spec whose points are expanded and checked: nothing has been written yet.
struct PreparedSweep {
  Spec spec;
  const PointKind* kind = nullptr;
  std::vector<Point> points;
};

/// Expands and checks every point against its kind, one of `kinds` (sweeps/points/families.hpp
/// lists them all). Throws core::InputError for a bad spec (unknown kind, a key the kind does
/// not take, a value out of range at any point).
[[nodiscard]] PreparedSweep prepare(Spec spec, std::span<const PointKind> kinds);

/// Runs a prepared sweep. Points of a timed kind run one at a time across every sweep of the
/// process, whatever `jobs` says (point_kind.hpp). Throws core::InputError when --resume finds a
/// checkpoint written for another spec, core::ComputationError when a point kind throws (the
/// checkpoint is kept).
RunSummary run(const PreparedSweep& sweep, const RunOptions& options);

/// Paths of a sweep's outputs.
[[nodiscard]] std::filesystem::path csv_path(const Spec& spec, const std::filesystem::path& data);
[[nodiscard]] std::filesystem::path partial_path(const Spec& spec,
                                                 const std::filesystem::path& data);

/// An ISO 8601 UTC time stamp (sidecars).
[[nodiscard]] std::string utc_now();

}  // namespace slipwalk::sweeps
