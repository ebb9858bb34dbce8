#pragma once
// A motion plan (thesis §5.4–5.5) replayed open-loop on MuJoCo's BigANT (bigant_peer.hpp): the
// feet follow the plan's shaft angles (planning/replay_feet.hpp) through MuJoCo's position
// actuators, from the plan's start pose, and MuJoCo's body pose is recorded at the plan's step
// times. The planner predicts the motion with the quasi-static model of ch. 3; MuJoCo adds what
// that model leaves out (inertia, soft contacts, Coulomb friction with stick, actuators that
// lag), so the gap between the two poses is how much of the plan survives a full dynamics
// simulator. Built only with MuJoCo (target slipwalk_peer_mujoco).
#include <vector>

#include "core/se2.hpp"
#include "peers/mujoco/bigant_peer.hpp"
#include "planning/plan_robot.hpp"
#include "planning/replay_feet.hpp"

namespace slipwalk::peers::mujoco {

/// MuJoCo's robot for a replay. Defaults are Fig. 3.14's base peer (studies/ch3_peer/
/// fig3_14.toml): §3.5.4's xy gain and damping, the z actuator as stiff as our BigANT's leg
/// spring (kp_z = K = 2675 N/m) and a contact stiff against it (solref 5 ms).
struct PlanReplayOptions {
  double settle = 1.0;              ///< s the feet are held at the plan's first pose; ≥ 0
  double timestep = 0.001;          ///< s, MuJoCo's; must divide the plan's step duration τ
  double kp_xy = 100.0;             ///< N/m
  double kp_z = 2675.0;             ///< N/m
  double damping = 10.0;            ///< N·s/m, every slide
  double solref_timeconst = 0.005;  ///< s
  double solref_dampratio = 1.0;
  int iterations = 100;
  bool lead = false;  ///< targets lead by (damping / kp) q̇ (bigant_targets)
};

/// The two poses at the plan's step times t_0 … t_{S−1} and its end t_S (S + 1 samples).
struct PlanReplay {
  std::vector<double> t;          ///< s
  std::vector<core::Pose2> plan;  ///< the plan's pose (θ unwrapped)
  /// MuJoCo's chassis pose relative to its settled pose, carried onto the plan's start pose (θ
  /// unwrapped): both start at the same pose.
  std::vector<core::Pose2> mujoco;
  BigAntDriveSummary drive;  ///< MuJoCo's tracking of the feet, contacts, load
};

/// Replays `track` (of `robot`, a BigANT-like PlanRobot) on MuJoCo. The chassis starts at the
/// height and tilt our spring support gives the first feet with legs as stiff as kp_z. Throws
/// core::InputError for a bad track or options (a timestep that does not divide τ), and
/// core::ComputationError if MuJoCo rejects the model.
[[nodiscard]] PlanReplay replay_plan(const planning::PlanRobot& robot,
                                     const planning::PlanTrack& track,
                                     const PlanReplayOptions& options);

}  // namespace slipwalk::peers::mujoco
