#pragma once
// The steps of a motion computed in parallel (thesis §3.5.3, Fig. 3.13 b). The model has no
// inertia: the body velocity at a step depends only on that step's foot positions and velocities
// (eq. 3.20), so the steps of a planned motion are independent. Here each step's frame is run
// through connection::evaluate (spring support, local connection, the friction law's balance) and
// turned into the SE(2) increment exp(v_body dt), on the pool's threads over fixed blocks of
// steps; the poses then follow by composing the increments, sequentially (as the thesis did) or
// by the parallel prefix product of core/se2_scan.hpp.
//
// Deterministic: every step's increment is computed by the same code from the same inputs
// whichever thread runs it, so the increments (and the sequential product) are identical to the
// bit for any thread count.
#include <Eigen/Core>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "core/se2.hpp"
#include "core/worker_pool.hpp"

namespace slipwalk::connection {

/// The inputs of a batch of steps: step k's feet are columns [k·N, (k+1)·N).
struct StepBatch {
  Eigen::Matrix3Xd q;     ///< (3 x N·steps) foot positions, body frame, m
  Eigen::Matrix3Xd qdot;  ///< (3 x N·steps) foot velocities, body frame, m/s
  double dt = 0.01;       ///< s, each step's duration

  [[nodiscard]] long long steps(int legs) const { return q.cols() / legs; }
};

/// One worker's scratch, on cache lines of its own (workers write theirs at every step; sharing a
/// line with another worker's would make the cores fight over it).
struct alignas(64) StepWorker {
  explicit StepWorker(const contact::Robot& robot) : frame(robot) {}
  contact::Frame frame;
  long long unsupported = 0;  ///< frames the support could not balance, this run
};

/// Buffers of one batch (sized once: one worker's scratch per thread, one increment per step).
struct StepBatchData {
  StepBatchData(const contact::Robot& robot, int threads, long long steps);
  std::vector<StepWorker> workers;      ///< (threads)
  std::vector<core::Pose2> increments;  ///< (steps) exp(v_body,k dt)

  /// Σ over the workers: the frames of the last run the support could not balance.
  [[nodiscard]] long long unsupported() const;
};

/// Fills data.increments (and counts unsupported frames) for every step of the batch, over
/// `blocks` fixed blocks of steps on the pool's threads. Throws core::InputError if the batch's
/// size is not a multiple of the robot's legs or the data was sized for fewer threads or steps.
void step_increments(const contact::Robot& robot, const StepBatch& batch, FrictionLaw law,
                     core::WorkerPool& pool, int blocks, StepBatchData& data);

}  // namespace slipwalk::connection
