#pragma once
// The coordinator of a sweep run: it owns the checkpoint, hands the points out one at a time in
// id order (dynamically: the next point goes to whichever worker asks first, since a point's cost
// varies a thousandfold within one sweep), collects the finished ones, prints the progress line
// and writes the result. Its workers are the threads of this process (runner.cpp) and, under MPI,
// the other ranks (engine/mpi/): every one of them takes and gives through the same calls, under
// one lock, so that the checkpoint and the result do not depend on who computed what.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sweeps/engine/checkpoint.hpp"
#include "sweeps/engine/runner.hpp"

namespace slipwalk::sweeps {

class Coordinator {
 public:
  /// Opens the checkpoint (resumed or fresh; throws core::InputError for another spec's) and
  /// lists the points still to compute: those of `options.shard` not in the checkpoint, at most
  /// `options.max_points` of them.
  Coordinator(const PreparedSweep& sweep, const RunOptions& options);

  /// Who computes, for the progress line ("2 threads", "3 ranks × 2 threads").
  void describe_workers(std::string workers);

  /// The next point to compute (an index into sweep.points); waits while a point of a timed kind
  /// is in flight elsewhere (timed points run one at a time, across ranks too). None when every
  /// point has been handed out or the run is stopping.
  [[nodiscard]] std::optional<std::size_t> take();
  /// Up to `most` points without waiting (a remote rank's request).
  [[nodiscard]] std::vector<std::size_t> take_now(std::size_t most);
  /// Records finished points: appended to the checkpoint in one write, then the progress line.
  void give(std::vector<std::pair<std::size_t, Finished>>& finished);
  /// A point threw: the first such error is kept, nothing more is handed out.
  void fail(std::size_t index, const std::string& error);

  /// Nothing left to hand out (all handed out, or stopping).
  [[nodiscard]] bool exhausted() const;
  /// A point threw or the checkpoint could not be written: the run is ending.
  [[nodiscard]] bool stopping() const;
  [[nodiscard]] const std::filesystem::path& checkpoint_path() const { return files_.partial; }
  [[nodiscard]] std::size_t in_flight() const;
  [[nodiscard]] std::size_t pending() const;

  /// After every worker has stopped: throws core::ComputationError when a point threw (the
  /// checkpoint kept when it holds anything); writes the result and removes the checkpoint when
  /// every point of the shard is done, with `extra` merged into the sidecar.
  RunSummary finish(const nlohmann::json& extra);

 private:
  [[nodiscard]] bool can_take() const;  // under mutex_
  std::optional<std::size_t> take_locked();
  void progress_locked();

  const PreparedSweep& sweep_;
  RunOptions options_;
  std::string workers_;
  std::string label_;
  std::string header_;
  SweepFiles files_;
  Checkpoint checkpoint_;
  std::vector<std::size_t> pending_;  // indices into sweep_.points, in id order
  std::size_t next_ = 0;              // pending_[next_] is handed out next
  long long total_ = 0;               // points of the shard
  std::size_t in_flight_ = 0;
  std::size_t cap_;  // points in flight at once (1 for a timed kind)
  bool stopping_ = false;
  std::string error_;
  long long computed_ = 0;
  std::vector<double> seconds_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_progress_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
};

/// Runs `threads` threads that take points from `coordinator`, compute them and give them back,
/// until it hands out no more; a point that throws is reported through fail(). Returns when every
/// thread has stopped.
void compute_on_threads(Coordinator& coordinator, const PreparedSweep& sweep, unsigned threads,
                        bool timing);

}  // namespace slipwalk::sweeps
