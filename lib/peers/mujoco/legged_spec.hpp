#pragma once
// The legged robots the MuJoCo peer simulates, described without MuJoCo (this part is built in
// every configuration, so the sweeps draw the same configurations with or without the peer):
// leg geometry and joint ranges, the disk robot of §3.5.3, the MJCF text, and each leg's inverse
// and forward kinematics.
//
// A leg is a vertical slide (s), a hip yaw (ψ) about the vertical and a hip pitch (φ) about the
// horizontal axis across the leg, then a rod of length ℓ ending in a spherical foot whose centre
// is the foot point q of our model (ch. 3), in the body frame:
//   q = hip + s e_z + ℓ sin φ e_r(a + ψ) − ℓ cos φ e_z,   e_r(β) = (cos β, sin β, 0),
// with a the leg's outward direction (φ > 0 swings the foot outward). The floor plane lies one
// foot radius below z = 0, so a foot touches exactly when its centre is below z = 0, which is our
// h_j < 0 (eq. 3.6) with the body at height z and slopes α (roll) and β (pitch).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/robot.hpp"

namespace slipwalk::peers::mujoco {

/// One leg: where its hip is and how far it may move (the joint ranges keep the workspaces of
/// neighbouring legs apart, as in §3.5.3).
struct LegSpec {
  Eigen::Vector3d hip = Eigen::Vector3d::Zero();  ///< m, body frame (the slide's zero)
  double direction = 0.0;    ///< rad, the leg's outward direction a in the body's xy plane
  double length = 0.1;       ///< m, ℓ: pitch joint to foot centre; valid: > 0
  double yaw_range = 0.5;    ///< rad, |ψ| ≤ yaw_range; valid: (0, π/2)
  double pitch_min = 0.05;   ///< rad, φ ≥ pitch_min > 0 (keeps the yaw well defined)
  double pitch_max = 1.2;    ///< rad, φ ≤ pitch_max < π/2
  double slide_range = 0.1;  ///< m, |s| ≤ slide_range
  double mu = 1.0;           ///< foot–floor friction coefficient; valid: ≥ 0
};

/// What the MJCF describes. Defaults are MuJoCo 2.2's (Newton solver, 100 iterations, default
/// solref/solimp) unless stated.
struct PeerSpec {
  std::vector<LegSpec> legs;
  double total_mass = 8.18;     ///< kg, body + legs (the weight the feet carry is g times this)
  double link_mass = 0.01;      ///< kg, each of a leg's three moving links (near massless legs)
  double body_radius = 0.3;     ///< m, the disk's radius (inertia and the drawn geometry)
  double foot_radius = 0.005;   ///< m
  double gravity = 9.81;        ///< m/s²
  double timestep = 0.002;      ///< s, MuJoCo's default
  int iterations = 100;         ///< constraint solver iterations (Newton)
  double tolerance = 1e-8;      ///< constraint solver tolerance
  double kp_slide = 1e4;        ///< N/m, the position actuator of each slide
  double kp_hinge = 100.0;      ///< N·m/rad, the position actuators of the hips
  double joint_damping = 10.0;  ///< per leg joint, as in §3.5.4
};

/// A disk of robot.legs() legs equally spaced on a rim of `radius` (thesis §3.5.3): hip k at angle
/// 2πk/N, its foot nominally `reach` further out and `height` below the body; yaw ranges keep the
/// feet's workspaces apart; μ from robot.mu; total mass robot.Mg / g.
[[nodiscard]] PeerSpec disk_spec(const contact::Robot& robot, double radius = 0.3,
                                 double reach = 0.05, double height = 0.1);

/// The MJCF text of a spec. Throws core::InputError("peer spec", ...) for invalid fields.
[[nodiscard]] std::string mjcf(const PeerSpec& spec);

/// Joint coordinates of one leg.
struct LegJoints {
  double slide = 0.0;  ///< m
  double yaw = 0.0;    ///< rad
  double pitch = 0.0;  ///< rad
};

/// Inverse kinematics: the joints that put the foot centre at q (body frame) and their rates for
/// the foot velocity qdot. Returns false (joints unchanged) when q is outside the leg's reach
/// (horizontal distance from the hip not in (0, ℓ)); the joint ranges are not checked.
bool leg_inverse(const LegSpec& leg, const Eigen::Vector3d& q, const Eigen::Vector3d& qdot,
                 LegJoints& joints, LegJoints& rates);
/// Forward kinematics: the foot centre in the body frame.
[[nodiscard]] Eigen::Vector3d leg_forward(const LegSpec& leg, const LegJoints& joints);

/// A point of the leg's workspace (inside its joint ranges, shrunk by 5 %): u_reach, u_yaw in
/// [0, 1] sweep the horizontal distance from the hip and the yaw; z is the foot centre's height
/// in the body frame (not range-checked: the slide is long).
[[nodiscard]] Eigen::Vector3d workspace_point(const LegSpec& leg, double u_reach, double u_yaw,
                                              double z);

}  // namespace slipwalk::peers::mujoco
