#include "core/worker_pool.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace slipwalk::core {

WorkerPool::WorkerPool(int threads) {
  if (threads < 1) {
    throw InputError("threads", "must be at least 1, got " + std::to_string(threads));
  }
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int w = 1; w < threads; ++w) {
    workers_.emplace_back([this, w] { work(w); });
  }
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& t : workers_) {
    t.join();
  }
}

// Claims tasks one at a time. The claim is under the mutex: tasks here are blocks of hundreds of
// model evaluations, so two uncontended locks per task are noise. A worker touches task_ only
// after claiming a task of the current run, and run() returns only when every claimed task has
// finished, so a late worker never sees a stale task.
void WorkerPool::drain(int worker) {
  for (;;) {
    int i = 0;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (next_ >= tasks_) {
        return;
      }
      i = next_++;
    }
    bool failed = false;
    try {
      (*task_)(i, worker);
    } catch (...) {
      failed = true;
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) {
        error_ = std::current_exception();
      }
    }
    bool all_done = false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ++done_;
      if (failed) {  // the tasks nobody claimed yet are skipped
        done_ += tasks_ - next_;
        next_ = tasks_;
      }
      all_done = done_ == tasks_;
    }
    if (all_done) {
      done_cv_.notify_all();
    }
  }
}

void WorkerPool::work(int worker) {
  long long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) {
        return;
      }
      seen = generation_;
    }
    drain(worker);
  }
}

void WorkerPool::run(int n, const Task& task) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    tasks_ = std::max(n, 0);
    next_ = 0;
    done_ = 0;
    error_ = nullptr;
    ++generation_;
  }
  if (!workers_.empty()) {
    start_.notify_all();
  }
  drain(0);
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [&] { return done_ == tasks_; });
    task_ = nullptr;
    error = error_;
  }
  if (error) {
    std::rethrow_exception(error);
  }
}

}  // namespace slipwalk::core
