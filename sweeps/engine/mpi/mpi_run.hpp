#pragma once
// A sweep across MPI ranks: `mpirun -np R slipwalk sweep SPEC.toml`. Rank 0 is the coordinator
// (coordinator.hpp): it owns the checkpoint and the result, hands the points out one request at a
// time — dynamically, since a point's cost varies a thousandfold within one sweep — and computes
// on its own threads too; every other rank computes on its threads (`--jobs`) and asks for more
// as its queue empties. The CSV is the same bytes as a threaded run's (rows by id, formatted where
// they are computed by the same code), the checkpoint is the same format, so a run killed on R
// ranks resumes on any number of ranks or threads.
//
// A rank holds at most its threads plus its threads' part of half the points not yet handed out
// (guided self-scheduling), so that a rank asking for many cheap points cannot hoard the costly
// ones, and at the end every rank holds no more than it is computing.
//
// Messages (all non-blocking sends, so that no two ranks can wait on each other):
//   rank r -> 0, tag kResults: the points r finished since its last message (index, outcome,
//     rows, message, seconds), how many more points it wants, and whether it is its last;
//   rank 0 -> r, tag kWork: point indices to compute; an empty list means stop.
// Only the main thread of a rank calls MPI (MPI_THREAD_FUNNELED); the computing threads meet it
// through a queue and an outbox.
//
// A rank that dies ends the job: the MPI runtime stops the other ranks with SIGTERM, and rank 0
// says what its checkpoint kept and exits 1 (core::set_signal_farewell). The checkpoint holds
// every point rank 0 had received.
//
// Built when CMake finds MPI (mpi_run.cpp); without it (no_mpi.cpp) available() is false and
// every other call throws core::InputError saying so.
#include <exception>
#include <functional>
#include <memory>
#include <string>

#include "sweeps/engine/runner.hpp"

namespace slipwalk::sweeps::mpi {

/// Whether this build has MPI support.
[[nodiscard]] bool available();

/// Whether this process was started by an MPI launcher (mpirun, mpiexec, srun): its environment
/// names a world size or rank (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE).
[[nodiscard]] bool launched();
/// This process's rank as its launcher's environment says it (OMPI_COMM_WORLD_RANK, PMIX_RANK,
/// PMI_RANK), before MPI is initialised; -1 when none says it.
[[nodiscard]] int launched_rank();

/// A process's part in an MPI job: MPI_Init_thread (funneled) on construction, MPI_Finalize on
/// destruction. Throws core::InputError when MPI is unavailable or gives no funneled threading.
class Session {
 public:
  Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  /// Waits until every rank has come here.
  void barrier() const;

 private:
  int rank_ = 0;
  int size_ = 1;
};

/// Thrown on the ranks other than 0 when the run fails: rank 0 reports the error, the others end
/// with the same exit code and say nothing, so that an error is printed once.
struct QuietExit {
  int code = 1;
};

/// What is set up before the run, on every rank (`prepare`: read and check the spec) and on rank
/// 0 only (`check_outputs`: the outputs are writable). Collective: when any rank fails, rank 0
/// throws the first failing rank's error (prefixed with its rank when not 0) and the others throw
/// QuietExit with the same exit code (2 for core::InputError, else 1). Every rank must read the
/// same points (the spec's fingerprint is compared).
struct Setup {
  std::function<PreparedSweep()> prepare;
  std::function<void(const PreparedSweep&)> check_outputs;
};

struct Options {
  RunOptions run;             ///< as a threaded run (jobs: threads per rank); only rank 0 writes
  int coordinator_jobs = -1;  ///< rank 0's computing threads (-1: run.jobs; 0: it only coordinates)
};

/// Collective: sets up (above) and runs the sweep over the session's ranks. On rank 0 returns the
/// summary (ranks, jobs set); on the others a summary with complete = false and nothing else.
/// Throws core::ComputationError on rank 0 when a point throws (the checkpoint kept), QuietExit
/// on the others.
RunSummary run_sweep(const Session& session, const Setup& setup, const Options& options);

}  // namespace slipwalk::sweeps::mpi
