// The hand-written flat isotropic viscous kernel (reference_kernel.hpp).
#include "scene/reference_kernel.hpp"

#include "connection/terrain_kernels.hpp"
#include "connection/trajectory_kernel.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::scene {

connection::TrajectorySummary run_flat_viscous(const robots::Walker& walker,
                                               const connection::TrajectoryOptions& options,
                                               connection::TrajectoryData& data,
                                               const connection::TrajectorySink& sink) {
  const contact::Robot& robot = walker.robot;
  connection::detail::check_run(robot, walker.feet, options, data, sink);
  contact::forget_balance(data.frame);
  contact::Frame& f = data.frame;
  connection::TrajectorySummary summary;
  core::Pose2 pose = options.start;
  long long n = 0;
  try {  // as in connection::integrate: a frame that is not finite stops the run
    for (; n <= options.steps; ++n) {
      const double t = options.t0 + static_cast<double>(n) * options.dt;
      walker.feet(t, f.q, f.qdot);
      f.theta = pose.theta;
      contact::spring_support(robot, f, connection::kTrajectorySupport);
      friction::solve_viscous_coulomb(robot, f);
      for (int k = 0; k < f.legs(); ++k) {
        data.slip(0, k) = f.v_body(0) - f.v_body(2) * f.q(1, k) + f.qdot(0, k);
        data.slip(1, k) = f.v_body(1) + f.v_body(2) * f.q(0, k) + f.qdot(1, k);
      }
      if (!connection::detail::state_is_finite(pose, f.v_body)) {
        connection::detail::stop_non_finite(n, t, summary);
        return summary;
      }
      connection::detail::tally(f, t, summary);
      sink(connection::TrajectoryStep{n, t, pose, pose, f.v_body, f.v_body, f, data.slip});
      summary.end = pose;
      pose = core::advance(pose, f.v_body, options.dt);
    }
  } catch (const core::InputError& e) {
    connection::detail::stop_non_finite(n, options.t0 + static_cast<double>(n) * options.dt,
                                        summary, e.what());
    return summary;
  }
  summary.frames = options.steps + 1;
  return summary;
}

}  // namespace slipwalk::scene
