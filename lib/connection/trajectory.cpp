// Trajectory integration (thesis §3.5): the per-step pipeline of connection::evaluate without the
// local connection A (a trajectory reports v_body and forces, not A; the friction solvers do not
// read A), with the friction law and the filter fixed at compile time (trajectory.hpp).
#include "connection/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "contact/spring_support.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::connection {

namespace {

/// Counts this frame's numerical trouble; the message (allocated only on trouble) keeps the first.
void tally(const contact::Frame& f, double t, TrajectorySummary& s) {
  using Status = contact::SupportSummary::Status;
  const bool unsupported =
      f.support.status == Status::kUnsupported || f.support.status == Status::kIterationLimit;
  s.unsupported += unsupported ? 1 : 0;
  s.not_converged += f.friction.converged ? 0 : 1;
  s.not_unique += f.friction.unique ? 0 : 1;
  s.max_friction_residual = std::max(s.max_friction_residual, f.friction.residual);
  if (s.message.empty() && (unsupported || !f.friction.converged)) {
    s.message.append("t = ").append(core::format_double(t)).append(": ");
    if (unsupported) {
      s.message.append("spring support: ").append(contact::status_name(f.support.status));
    } else {
      s.message.append("friction did not converge: ").append(f.friction.message);
    }
  }
}

}  // namespace

void IirFilter::validate() const {
  if (!(gamma >= 0.0 && gamma < 1.0)) {
    throw core::InputError("filter.gamma", "must be in [0, 1), got " + core::format_double(gamma));
  }
}

void validate(const TrajectoryOptions& options) {
  if (!(options.dt > 0.0) || !std::isfinite(options.dt)) {
    throw core::InputError("trajectory.dt",
                           "must be positive and finite, got " + core::format_double(options.dt));
  }
  if (options.steps < 0) {
    throw core::InputError("trajectory.steps",
                           "must be >= 0, got " + std::to_string(options.steps));
  }
  const core::Pose2& p = options.start;
  if (!std::isfinite(options.t0) || !std::isfinite(p.x) || !std::isfinite(p.y) ||
      !std::isfinite(p.theta)) {
    throw core::InputError("trajectory.start", "t0 and the start pose must be finite");
  }
}

template <class Law, class Filter>
TrajectorySummary integrate(const contact::Robot& robot, const FootKinematics& feet,
                            const TrajectoryOptions& options, const Law& law, Filter filter,
                            TrajectoryData& data, const TrajectorySink& sink) {
  validate(options);
  filter.validate();
  if (!feet || !sink) {
    throw core::InputError("trajectory", "the foot kinematics and the sink must be set");
  }
  if (data.frame.legs() != robot.legs() || data.slip.cols() != robot.legs()) {
    throw core::InputError("trajectory", "the data's sizes do not match the robot's legs");
  }
  filter.reset();
  contact::Frame& f = data.frame;
  TrajectorySummary summary;
  core::Pose2 pose = options.start;
  for (long long n = 0; n <= options.steps; ++n) {
    const double t = options.t0 + static_cast<double>(n) * options.dt;
    // 1. The gait: the feet in the body frame at t.
    feet(t, f.q, f.qdot);
    f.theta = pose.theta;
    // 2. Which feet touch and what they carry (§3.3, Alg. 1).
    contact::spring_support(robot, f);
    // 3. The friction law's balance: v_model = f.v_body, F_xy (§3.4).
    law(robot, f);
    // 4. The inertia filter (§3.5.2.2) or the identity.
    const Eigen::Vector3d& v = filter(f.v_body);
    // 5. Each foot's velocity over the ground, u_k = v + ω S q_k + q̇_k (friction/solvers.hpp).
    for (int k = 0; k < f.legs(); ++k) {
      data.slip(0, k) = f.v_body(0) - f.v_body(2) * f.q(1, k) + f.qdot(0, k);
      data.slip(1, k) = f.v_body(1) + f.v_body(2) * f.q(0, k) + f.qdot(1, k);
    }
    tally(f, t, summary);
    sink(TrajectoryStep{n, t, pose, v, f.v_body, f, data.slip});
    summary.end = pose;
    // 6. Move: exact on SE(2) for v held over [t, t + dt).
    pose = core::advance(pose, v, options.dt);
  }
  summary.frames = options.steps + 1;
  return summary;
}

template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, const ViscousCoulombKernel&,
                                     NoFilter, TrajectoryData&, const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, const ViscousCoulombKernel&,
                                     IirFilter, TrajectoryData&, const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, const CoulombKernel&, NoFilter,
                                     TrajectoryData&, const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, const CoulombKernel&, IirFilter,
                                     TrajectoryData&, const TrajectorySink&);

}  // namespace slipwalk::connection
