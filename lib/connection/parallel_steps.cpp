#include "connection/parallel_steps.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace slipwalk::connection {

StepBatchData::StepBatchData(const contact::Robot& robot, int threads, long long steps)
    : workers(static_cast<std::size_t>(std::max(threads, 1)), StepWorker(robot)),
      increments(static_cast<std::size_t>(std::max(steps, 0LL))) {}

long long StepBatchData::unsupported() const {
  long long n = 0;
  for (const StepWorker& w : workers) {
    n += w.unsupported;
  }
  return n;
}

void step_increments(const contact::Robot& robot, const StepBatch& batch, FrictionLaw law,
                     core::WorkerPool& pool, int blocks, StepBatchData& data) {
  const int n = robot.legs();
  if (batch.q.cols() != batch.qdot.cols() || batch.q.cols() % n != 0) {
    throw core::InputError("step batch",
                           "q and qdot need N·steps columns each (N = " + std::to_string(n) + ")");
  }
  const long long steps = batch.steps(n);
  if (static_cast<long long>(data.increments.size()) < steps ||
      static_cast<int>(data.workers.size()) < pool.threads()) {
    throw core::InputError("step batch", "data sized for fewer steps or threads than needed");
  }
  for (StepWorker& w : data.workers) {
    w.unsupported = 0;
  }
  if (steps == 0) {
    return;
  }
  const long long b = std::clamp<long long>(blocks, 1, steps);
  pool.run(static_cast<int>(b), [&](int i, int worker) {
    StepWorker& w = data.workers[static_cast<std::size_t>(worker)];
    contact::Frame& f = w.frame;
    const long long lo = i * steps / b, hi = (i + 1) * steps / b;
    for (long long k = lo; k < hi; ++k) {
      f.q = batch.q.middleCols(k * n, n);
      f.qdot = batch.qdot.middleCols(k * n, n);
      evaluate(robot, f, law);
      if (f.support.status == contact::SupportSummary::Status::kUnsupported ||
          f.support.status == contact::SupportSummary::Status::kIterationLimit ||
          f.support.status == contact::SupportSummary::Status::kNonFinite) {
        ++w.unsupported;
      }
      data.increments[static_cast<std::size_t>(k)] = core::exp(f.v_body * batch.dt);
    }
  });
}

}  // namespace slipwalk::connection
