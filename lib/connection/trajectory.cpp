// Trajectory integration (thesis §3.5): the per-step pipeline of connection::evaluate without the
// local connection A (a trajectory reports v_body and forces, not A; the friction solvers do not
// read A), with the effects fixed at compile time (trajectory.hpp; the loop is in
// trajectory_kernel.hpp). Here: the checks, the tally and the law × filter instantiations.
#include "connection/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "connection/trajectory_kernel.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::connection {

namespace detail {

void tally(const contact::Frame& f, double t, TrajectorySummary& s) {
  using Status = contact::SupportSummary::Status;
  const bool unsupported = f.support.status == Status::kUnsupported ||
                           f.support.status == Status::kIterationLimit ||
                           f.support.status == Status::kNonFinite;
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

void stop_non_finite(long long n, double t, TrajectorySummary& s, std::string_view what) {
  s.non_finite_step = n;
  s.frames = n;
  s.non_finite = "t = " + core::format_double(t) + " s (step " + std::to_string(n) + "): ";
  s.non_finite.append(what).append("; the run stopped there");
}

void check_run(const contact::Robot& robot, const FootKinematics& feet,
               const TrajectoryOptions& options, const TrajectoryData& data,
               const TrajectorySink& sink) {
  validate(options);
  if (!feet || !sink) {
    throw core::InputError("trajectory", "the foot kinematics and the sink must be set");
  }
  if (data.frame.legs() != robot.legs() || data.slip.cols() != robot.legs()) {
    throw core::InputError("trajectory", "the data's sizes do not match the robot's legs");
  }
}

}  // namespace detail

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

void LinearResidual::validate(int legs) const {
  if (B.cols() != 2 * static_cast<Eigen::Index>(legs)) {
    throw core::InputError("residual.B", "has " + std::to_string(B.cols()) +
                                             " columns; the robot's " + std::to_string(legs) +
                                             " legs need " + std::to_string(2 * legs));
  }
  if (!B.allFinite()) {
    throw core::InputError("residual.B", "has an entry that is not a finite number");
  }
}

void PoseNoise::validate() const {
  if (!(sigma_xy >= 0.0) || !(sigma_theta >= 0.0) || !std::isfinite(sigma_xy) ||
      !std::isfinite(sigma_theta)) {
    throw core::InputError("noise.sigma", "must be finite and >= 0, got " +
                                              core::format_double(sigma_xy) + " and " +
                                              core::format_double(sigma_theta));
  }
}

template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&,
                                     Effects<ViscousCoulombKernel, NoFilter>, TrajectoryData&,
                                     const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&,
                                     Effects<ViscousCoulombKernel, IirFilter>, TrajectoryData&,
                                     const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, Effects<CoulombKernel, NoFilter>,
                                     TrajectoryData&, const TrajectorySink&);
template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                     const TrajectoryOptions&, Effects<CoulombKernel, IirFilter>,
                                     TrajectoryData&, const TrajectorySink&);

}  // namespace slipwalk::connection
