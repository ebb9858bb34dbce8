#pragma once
// A fixed pool of threads for data-parallel loops inside one computation (thesis §3.5.3: the
// body velocities of an inertia-free model are independent per time step, so a batch of steps
// can be spread over M threads). The sweep engine parallelizes over points; this pool is for
// the inside of one point, where starting threads per call would cost more than the work.
//
// run(n, task) calls task(i, worker) for i = 0 … n−1 and returns when all are done. Tasks are
// claimed in order from a shared counter, so which worker runs which task varies; results are
// deterministic when each task writes only its own outputs (and uses `worker` only to pick its
// scratch space). The calling thread takes part as worker 0, so a pool of one thread runs
// everything inline. run() returns as soon as every task has finished, without waiting for
// workers that were never scheduled: on a busy machine a sleeping worker may wake milliseconds
// late, and then the caller has simply done its share.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace slipwalk::core {

class WorkerPool {
 public:
  using Task = std::function<void(int task, int worker)>;

  /// threads ≥ 1 (the caller counts as one); throws core::InputError("threads", ...) otherwise.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  [[nodiscard]] int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Runs task(i, worker) for i in [0, n); worker ∈ [0, threads()). The first exception a task
  /// throws is rethrown here after all tasks have stopped. Not reentrant.
  void run(int n, const Task& task);

 private:
  void work(int worker);
  void drain(int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_cv_;
  const Task* task_ = nullptr;
  int tasks_ = 0;
  int next_ = 0;              ///< the next unclaimed task (under mutex_)
  int done_ = 0;              ///< tasks finished (or skipped after an error) in this run
  long long generation_ = 0;  ///< counts run() calls; workers wake on a new one
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace slipwalk::core
