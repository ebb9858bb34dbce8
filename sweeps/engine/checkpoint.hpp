#pragma once
// What a sweep leaves on disk, in one place: where its files go (a whole run or one shard of
// it), the spec's fingerprint, a finished point as text, the checkpoint that --resume reads and
// the sorted result CSV with its provenance sidecar. The threaded runner, the MPI coordinator
// and `slipwalk sweep merge` all write through here, which is why their CSVs are the same bytes.
//
// The checkpoint `<stem>.partial.csv`: the CSV header, `#spec,<fingerprint>`, `#timing,<0|1>`
// (whether timing columns hold times: a resume keeps the setting), then per finished point its
// rows and a `#done,<id>,<outcome>,<message>` line (0 done, 1 failed, 2 at its budget). A point
// counts only once its #done line is complete, so a run killed in the middle of a write loses at
// most that point. The format does not depend on who wrote it: a threaded run resumes an MPI run's
// checkpoint and the other way round.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {

struct PreparedSweep;

/// The k-th of n deterministic shards of a sweep (`--shard k/n`, 1 ≤ k ≤ n). The points are dealt
/// round-robin in a fixed pseudo-random order of their ids (shard_members), so shards differ in
/// size by at most one point and none is made of one value of an axis: dealt in id order, a grid
/// whose last axis has n values (say a cheap and a costly method) would give each shard one of
/// them. The default is the whole sweep, not a shard; a shard 1/1 is a shard (its own files,
/// merged like any), so that a job array of one task works.
struct Shard {
  long long index = 1;
  long long count = 1;
  bool split = false;  ///< a shard (its own files); false: the whole sweep
  [[nodiscard]] bool whole() const { return !split; }
  /// "k/n"
  [[nodiscard]] std::string text() const;
};

/// Which of the ids 0 … points − 1 the shard holds: the ids are ordered by SplitMix64 of the id
/// (random.hpp; the same on every platform) and dealt to shards 1, 2, …, n, 1, 2, … in that
/// order. Every id for the whole sweep.
[[nodiscard]] std::vector<char> shard_members(std::size_t points, const Shard& shard);

/// Parses "k/n" (1 ≤ k ≤ n ≤ 1,000,000); throws core::InputError naming `option`.
[[nodiscard]] Shard parse_shard(const std::string& text, const std::string& option);

/// The files of a run: `<data>/<study>/<stem>.csv`, `.json` and `.partial.csv`, where the stem is
/// the spec's name, or `<name>.shard-k-of-n` for a shard.
struct SweepFiles {
  std::filesystem::path csv;
  std::filesystem::path sidecar;
  std::filesystem::path partial;
};
[[nodiscard]] SweepFiles sweep_files(const Spec& spec, const std::filesystem::path& data,
                                     const Shard& shard = {});

/// The CSV header: the kind's column names joined by commas.
[[nodiscard]] std::string header_line(const PreparedSweep& sweep);

/// FNV-1a over the kind, the columns and every point of the whole sweep (not of a shard): a
/// checkpoint is only resumed, and a shard only merged, by the spec (after quick overrides) that
/// wrote it.
[[nodiscard]] std::string fingerprint(const PreparedSweep& sweep);

/// One finished point as the files hold it.
struct Finished {
  std::string rows;  ///< CSV text, one line per row, each starting with the point's id
  bool failed = false;
  bool at_budget = false;  ///< stopped at a budget its spec sets (PointResult::at_budget)
  std::string message;     ///< one line
  double seconds = 0.0;    ///< wall time of its computation (this run only; not in any file)
};

/// The finished points of a run, by id.
using FinishedPoints = std::map<long long, Finished>;

/// Computes one point of `sweep`: its rows as CSV text (timing columns written as 0 unless
/// `timing`), its outcome (a stop at a budget is a failure unless the spec expects it) and its
/// wall time. A point of a timed kind holds the process-wide timed-point lock while it runs
/// (point_kind.hpp). Throws what the kind throws.
[[nodiscard]] Finished compute_point(const PreparedSweep& sweep, const Point& point, bool timing);

/// The checkpoint of a run in progress: opened fresh or resumed, then appended to.
class Checkpoint {
 public:
  /// Reads `path` when `resume` and it exists (throws core::InputError for a checkpoint of
  /// another spec, other columns or the other timing setting), then rewrites it with what it
  /// kept.
  Checkpoint(std::filesystem::path path, const std::string& header, const std::string& print,
             bool timing, long long points, bool resume);
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;
  ~Checkpoint() = default;

  /// The points finished so far, resumed ones included.
  [[nodiscard]] const FinishedPoints& done() const { return done_; }
  [[nodiscard]] long long resumed() const { return resumed_; }
  /// Appends finished points, one write and flush for all of them; throws
  /// core::ComputationError when the write fails.
  void append(std::vector<std::pair<long long, Finished>>& points);
  /// Removes the file and the folder the run created when nothing was ever finished in it.
  void discard_if_empty();
  /// Removes the file (after the result is written).
  void remove();
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  FinishedPoints done_;
  long long resumed_ = 0;
  bool folder_existed_ = true;
  std::ofstream out_;
};

/// Writes the finished result: the CSV (header, then every point's rows by id) and its sidecar,
/// `sidecar` as given with "csv" set, both atomically, the CSV renamed last.
void write_result(const SweepFiles& files, const std::string& header, const FinishedPoints& points,
                  nlohmann::json sidecar);

/// The sidecar fields every result shares: the spec, the kind's columns, the points (of the
/// shard), the failed points, this build's provenance and the date.
[[nodiscard]] nlohmann::json result_sidecar(const PreparedSweep& sweep, const Shard& shard,
                                            const FinishedPoints& points, bool timing);

/// Order statistics of the points' computation times, for the sidecar: count, sum, mean, median,
/// p90 and max in seconds (what a cluster run's scaling is judged by).
[[nodiscard]] nlohmann::json point_seconds_json(std::vector<double> seconds);

}  // namespace slipwalk::sweeps
