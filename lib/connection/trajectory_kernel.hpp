#pragma once
// The trajectory loop of connection::integrate (trajectory.hpp), as a template definition: the
// files that compose kernels (connection/trajectory.cpp for the law × filter bundles,
// scene/compose.cpp for every bundle a scene can name, the benchmarks) include it and instantiate
// the bundles they need. Every effect's call below is its policy's operator(); an "off" policy
// returns its argument, so a kernel without an effect has no code for it.
#include <string>

#include "connection/trajectory.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"

namespace slipwalk::connection {

namespace detail {

/// Counts this frame's numerical trouble; the message (allocated only on trouble) keeps the first.
void tally(const contact::Frame& f, double t, TrajectorySummary& s);

/// Checks the options, the sink, the feet and the data's sizes (once per run).
void check_run(const contact::Robot& robot, const FootKinematics& feet,
               const TrajectoryOptions& options, const TrajectoryData& data,
               const TrajectorySink& sink);

}  // namespace detail

template <class E>
TrajectorySummary integrate(const contact::Robot& robot, const FootKinematics& feet,
                            const TrajectoryOptions& options, E effects, TrajectoryData& data,
                            const TrajectorySink& sink) {
  detail::check_run(robot, feet, options, data, sink);
  contact::forget_balance(data.frame);  // the support's warm start begins with this run
  effects.filter.validate();
  effects.residual.validate(robot.legs());
  effects.noise.validate();
  effects.filter.reset();
  effects.noise.reset();
  effects.ground.validate();
  effects.ground.reset(robot);
  contact::Frame& f = data.frame;
  TrajectorySummary summary;
  core::Pose2 pose = options.start;
  long long n = 0;
  // The support checks every frame's feet (contact::check_frame, core::InputError); in a
  // trajectory they are the gait's output, not input, so a foot that is not finite is a state
  // that is not finite: the run stops there (no cost per step: nothing is thrown otherwise).
  try {
    for (; n <= options.steps; ++n) {
      const double t = options.t0 + static_cast<double>(n) * options.dt;
      // 1. The gait: the feet in the body frame at t.
      feet(t, f.q, f.qdot);
      f.theta = pose.theta;
      // 2. Which feet touch and what they carry (§3.3, Alg. 1), then 3. the friction law's
      // balance: v_model = f.v_body, F_xy (§3.4); both on the terrain's ground (§5.2; flat: just
      // the two calls, terrain_kernels.hpp).
      effects.ground(robot, f, pose, effects.law);
      // 4. The connection residual (§5.3.1), then the inertia filter (§3.5.2.2); identities if off.
      const Eigen::Vector3d& v = effects.filter(effects.residual(f.v_body, f.qdot));
      // 5. Each foot's velocity over the ground, u_k = v + ω S q_k + q̇_k (friction/solvers.hpp).
      for (int k = 0; k < f.legs(); ++k) {
        data.slip(0, k) = f.v_body(0) - f.v_body(2) * f.q(1, k) + f.qdot(0, k);
        data.slip(1, k) = f.v_body(1) + f.v_body(2) * f.q(0, k) + f.qdot(1, k);
      }
      // A pose or velocity that is no longer finite stays so: stop before the sink sees it.
      if (!detail::state_is_finite(pose, v)) {
        detail::stop_non_finite(n, t, summary);
        return summary;
      }
      detail::tally(f, t, summary);
      // 6. The measured pose (noise) and the sink.
      const core::Pose2& measured = effects.noise(pose);
      sink(TrajectoryStep{n, t, pose, measured, v, f.v_body, f, data.slip});
      summary.end = pose;
      // 7. Move: exact on SE(2) for v held over [t, t + dt).
      pose = core::advance(pose, v, options.dt);
    }
  } catch (const core::InputError& e) {
    detail::stop_non_finite(n, options.t0 + static_cast<double>(n) * options.dt, summary, e.what());
    return summary;
  }
  summary.frames = options.steps + 1;
  return summary;
}

}  // namespace slipwalk::connection
