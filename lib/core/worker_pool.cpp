#include "core/worker_pool.hpp"

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
// model evaluations, so one uncontended lock per task is noise.
void WorkerPool::drain(int worker) {
  for (;;) {
    int i = 0;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (next_ >= tasks_ || error_) {
        return;
      }
      i = next_++;
    }
    try {
      (*task_)(i, worker);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) {
        error_ = std::current_exception();
      }
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
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      --busy_;
    }
    done_.notify_one();
  }
}

void WorkerPool::run(int n, const Task& task) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    tasks_ = n;
    next_ = 0;
    error_ = nullptr;
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  start_.notify_all();
  drain(0);
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    task_ = nullptr;
    error = error_;
  }
  if (error) {
    std::rethrow_exception(error);
  }
}

}  // namespace slipwalk::core
