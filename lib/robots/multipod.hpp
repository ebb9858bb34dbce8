#pragma once
// The Multipod (thesis §3.5.2.1, §5.3.2, Fig. 5.4): n = N/2 modules in a row, each carrying a
// contralateral pair of leaf-spring legs. The thesis says each pair has "two DoF – yaw and roll"
// (§3.5.2.1) and that the modules are "configured in yaw-roll-yaw" with three motors (§5.3.2), but
// gives no drawing we can read, so this is our reading, chosen so every joint of the gait formula
// has a place (read the joint signs and module layout as assumptions, not as the robot's):
//
//   module i (i = 0 at the head):  front yaw joint θ_y1,i — leg section with the roll joint
//   θ_r,i at its centre — rear yaw joint θ_y2,i;  consecutive modules are joined by a rigid
//   connector from θ_y2,i to θ_y1,i+1.
//
// The spine stays in the ground plane (yaw joints only). Each yaw angle is the leg section's
// heading relative to the connector on that side of it (θ > 0: the section turned to the left,
// counter-clockwise), so with θ_y1 = θ_y2, as the gait commands, the section turns in place
// relative to the spine while the connectors on either side stay parallel: this is the pair's yaw
// DoF of §3.5.2.1 (the spine jogs sideways by the turned section). The roll joint turns the leg
// pair about the section's long axis, lifting one foot and lowering the other (θ_r > 0 lifts the
// left foot). With these signs the gait walks forward (+x) over the whole thesis range of Δφ.
// Reading the two yaw joints as bending the spine the same way instead (angles measured front
// minus rear at both) doubles the bend between modules and cancels it at Δφ = π (the spine only
// shears sideways): in our runs that robot hardly walks (no motion at Δφ = π, at most 0.4 of
// this reading's speed elsewhere, backward for some Δφ), unlike the robot of Fig. 3.11.
// The legs are rigid in the kinematics: the leaf spring's flexing is the model's vertical spring
// K (§3.5.2.1 extrapolates the unloaded foot position).
// The head module's front yaw joint and the tail's rear one join nothing and move no foot.
//
// Gait (§5.3.2), phase ψ_i = 2πft + iΔφ:  θ_y1,i = θ_y2,i = θ_y,0 cos ψ_i,  θ_r,i = θ_r,0 sin ψ_i.
//
// Body frame: the mean frame of the sections — origin at the centroid of the n section centres,
// heading the mean of the n section headings (x along it, z up). With it the section centres sum
// to zero and their headings average zero at every instant, so the body frame does not wobble
// with any one module; the first segment's frame would put all the undulation into the body's
// motion instead.
//
// Units. The thesis uses Mg = N, K = 1, μ = 1 (§3.5.2.1); only Mg/K, a length, matters to the
// model. With lengths in metres that is a static compression of about N/(N/2 · 1) = 2 m, far
// larger than the robot, so every foot would always touch; with motion-capture millimetres it is
// 2 mm, small against the roll's lift. We take the latter: K = 1 N/mm = 1000 N/m, Mg = N newtons.
//
// Geometry (our estimate of a Multipod module; the thesis gives none): leg section 0.07 m between
// its yaw axes, connector 0.05 m (module pitch 0.12 m), each foot 0.12 m to the side of and
// 0.08 m below the roll axis. Legs ordered [L1 … Ln, R1 … Rn], 1 = the head module.
#include <Eigen/Core>

#include "robots/robots.hpp"

namespace slipwalk::robots {

struct MultipodGeometry {
  double section = 0.07;       ///< m, between a module's two yaw axes
  double connector = 0.05;     ///< m, from a module's rear yaw axis to the next one's front axis
  double foot_lateral = 0.12;  ///< m, foot to the side of the roll axis (legs straight)
  double foot_depth = 0.08;    ///< m, foot below the roll axis (legs straight)
};

/// Throws core::InputError("multipod.legs", ...) etc. for a gait out of range (robots.hpp).
void validate(const UndulationGait& gait);

/// The Multipod's shape: its joint angles, one column per module i (head first), rows
/// (θ_y1,i, θ_r,i, θ_y2,i) in rad — what the motors' encoders read. Size 3 × N/2.
using MultipodJoints = Eigen::Matrix3Xd;

/// The gait's joint angles at time t and their rates (rad/s), §5.3.2: θ_y1,i = θ_y2,i =
/// θ_y,0 cos ψ_i, θ_r,i = θ_r,0 sin ψ_i, ψ_i = 2πft + iΔφ. Sizes must be 3 × gait.legs/2.
void multipod_gait_joints(const UndulationGait& gait, double t, Eigen::Ref<MultipodJoints> joints,
                          Eigen::Ref<MultipodJoints> rates);

/// Feet of the Multipod in the mean body frame for any joint angles and rates: q (3 × N, m) and
/// q̇ = dq/dt (3 × N, m/s), analytic (joint rates through the chain, then the moving body frame:
/// q̇ = R(−ψ̄)(ṗ − c̄̇) − ψ̄̇ S q_xy). N = 2 · joints.cols(); q, qdot must be 3 × N; no
/// allocation. θ_y1,i and θ_y2,i may differ (a measured robot's do).
void multipod_feet_from_joints(const MultipodGeometry& geometry,
                               const Eigen::Ref<const MultipodJoints>& joints,
                               const Eigen::Ref<const MultipodJoints>& rates, Eigen::Matrix3Xd& q,
                               Eigen::Matrix3Xd& qdot);

/// The same along the gait at time t (multipod_gait_joints, then multipod_feet_from_joints).
/// Sizes must be 3 × gait.legs; no allocation.
void multipod_feet(const MultipodGeometry& geometry, const UndulationGait& gait, double t,
                   Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot);

}  // namespace slipwalk::robots
