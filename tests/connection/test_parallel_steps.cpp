// The steps of a motion computed in parallel (connection/parallel_steps.hpp, thesis §3.5.3): each
// increment is exp(v dt) of connection::evaluate's body velocity for that step's frame, and the
// increments are the same to the bit on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "connection/local_connection.hpp"
#include "connection/parallel_steps.hpp"
#include "core/error.hpp"
#include "core/worker_pool.hpp"
#include "sweeps/engine/random.hpp"

namespace slipwalk::connection {
namespace {

/// A hexapod batch: feet jittered around x ∈ {−0.3, 0, 0.3}, y = ±0.2, some lifted.
StepBatch hexapod_batch(long long steps) {
  sweeps::Random rng(11, 0);
  StepBatch b;
  b.q.resize(3, 6 * steps);
  b.qdot.resize(3, 6 * steps);
  b.dt = 0.02;
  for (long long c = 0; c < 6 * steps; ++c) {
    const long long k = c % 6;
    b.q.col(c) << 0.3 * static_cast<double>(k / 2 - 1) + rng.uniform(-0.02, 0.02),
        (k % 2 == 0 ? 0.2 : -0.2) + rng.uniform(-0.02, 0.02),
        -0.1 + (rng.uniform() < 0.3 ? rng.uniform(0.0, 0.03) : 0.0);
    b.qdot.col(c) << rng.normal(), rng.normal(), 0.0;
  }
  return b;
}

TEST(ParallelSteps, IncrementsAreTheModelsBodyVelocities) {
  const contact::Robot robot = contact::uniform_robot(6, 8000.0, 1.0, 80.0);
  const StepBatch batch = hexapod_batch(200);
  core::WorkerPool pool(2);
  StepBatchData data(robot, 2, 200);
  step_increments(robot, batch, FrictionLaw::kViscousCoulomb, pool, 16, data);
  contact::Frame f(robot);
  for (long long k = 0; k < 200; ++k) {
    f.q = batch.q.middleCols(6 * k, 6);
    f.qdot = batch.qdot.middleCols(6 * k, 6);
    evaluate(robot, f, FrictionLaw::kViscousCoulomb);
    const core::Pose2 e = core::exp(f.v_body * batch.dt);
    const core::Pose2& p = data.increments[static_cast<std::size_t>(k)];
    ASSERT_EQ(p.x, e.x) << "step " << k;
    ASSERT_EQ(p.y, e.y);
    ASSERT_EQ(p.theta, e.theta);
  }
}

TEST(ParallelSteps, SameBitsOnAnyNumberOfThreads) {
  const contact::Robot robot = contact::uniform_robot(6, 8000.0, 1.0, 80.0);
  const StepBatch batch = hexapod_batch(1000);
  StepBatchData one(robot, 1, 1000);
  core::WorkerPool pool1(1);
  step_increments(robot, batch, FrictionLaw::kViscousCoulomb, pool1, 7, one);
  for (int threads : {2, 4}) {
    core::WorkerPool pool(threads);
    StepBatchData many(robot, threads, 1000);
    step_increments(robot, batch, FrictionLaw::kViscousCoulomb, pool, 7, many);
    for (std::size_t k = 0; k < 1000; ++k) {
      ASSERT_EQ(one.increments[k].x, many.increments[k].x);
      ASSERT_EQ(one.increments[k].y, many.increments[k].y);
      ASSERT_EQ(one.increments[k].theta, many.increments[k].theta);
    }
  }
}

TEST(ParallelSteps, BadSizesThrow) {
  const contact::Robot robot = contact::uniform_robot(6, 8000.0, 1.0, 80.0);
  StepBatch batch = hexapod_batch(10);
  core::WorkerPool pool(2);
  StepBatchData small(robot, 1, 10);  // one frame, two threads
  EXPECT_THROW(step_increments(robot, batch, FrictionLaw::kViscousCoulomb, pool, 4, small),
               core::InputError);
  batch.q.conservativeResize(3, 59);
  StepBatchData data(robot, 2, 10);
  EXPECT_THROW(step_increments(robot, batch, FrictionLaw::kViscousCoulomb, pool, 4, data),
               core::InputError);
}

}  // namespace
}  // namespace slipwalk::connection
