// A motion plan replayed on MuJoCo's BigANT (plan_replay.hpp).
#include "peers/mujoco/plan_replay.hpp"

#include <Eigen/Core>
#include <cmath>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "peers/mujoco/bigant_spec.hpp"

namespace slipwalk::peers::mujoco {

PlanReplay replay_plan(const planning::PlanRobot& robot, const planning::PlanTrack& track,
                       const PlanReplayOptions& o) {
  const robots::Walker walker = planning::replay_walker(robot, track);  // validates
  const double tau = track.step_duration;
  const double per_step = tau / o.timestep;
  if (!(o.timestep > 0.0) || !std::isfinite(o.timestep) ||
      std::abs(per_step - std::round(per_step)) > 1e-9 * per_step || std::round(per_step) < 1.0) {
    throw core::InputError("plan replay", "the timestep must divide the plan's step duration");
  }
  BigAntPeerSpec spec = bigant_peer_spec(walker);
  spec.timestep = o.timestep;
  spec.kp_xy = o.kp_xy;
  spec.kp_z = o.kp_z;
  spec.damping = o.damping;
  spec.solref_timeconst = o.solref_timeconst;
  spec.solref_dampratio = o.solref_dampratio;
  spec.iterations = o.iterations;
  const BigAntModel model(spec);
  BigAntData data(model);

  // bigant_drive starts its clock at 0: the plan's clock runs from t_0.
  const double t0 = track.t.front();
  const robots::FootKinematics feet = [&walker, t0](double t, Eigen::Matrix3Xd& q,
                                                    Eigen::Matrix3Xd& qdot) {
    walker.feet(t + t0, q, qdot);
  };
  // The chassis where our spring support puts the first feet with legs as stiff as kp_z.
  contact::Robot stand = walker.robot;
  stand.K.setConstant(o.kp_z);
  contact::Frame f(stand);
  Eigen::Matrix3Xd qdot(3, stand.legs());
  feet(0.0, f.q, qdot);
  contact::spring_support(stand, f);

  BigAntDriveOptions drive;
  drive.duration = tau * static_cast<double>(track.steps());
  drive.settle = o.settle;
  drive.sample = tau;
  drive.lead = o.lead;
  PlanReplay out;
  const auto samples = static_cast<std::size_t>(track.steps() + 1);
  out.t.reserve(samples);
  out.plan.reserve(samples);
  out.mujoco.reserve(samples);
  const core::Pose2 start = track.pose.front();
  out.drive =
      bigant_drive(model, data, feet, f.z, f.alpha, f.beta, drive, [&](const BigAntSample& s) {
        const long long n = std::llround(s.t / tau);
        if (n < 0 || n > track.steps()) {
          return;
        }
        const bool end = n == track.steps();
        out.t.push_back(end ? track.end_time() : track.t[static_cast<std::size_t>(n)]);
        out.plan.push_back(end ? track.end_pose : track.pose[static_cast<std::size_t>(n)]);
        // compose adds the angles: the yaw stays unwrapped.
        out.mujoco.push_back(core::compose(start, s.pose));
      });
  return out;
}

}  // namespace slipwalk::peers::mujoco
