#pragma once
// The "real" Multipod of thesis §5.3 (Fig. 5.4) as MuJoCo sees it, described without MuJoCo
// (built in every configuration): the robot whose motion trials the residual B is fitted to.
//
// Kinematics: exactly robots/multipod.hpp's reading of the robot (module layout, joint signs,
// geometry), as a chain of bodies from the head to the tail:
//
//   head stub —θ_y1,1— section 1 —θ_y2,1— connector 1 —θ_y1,2— section 2 — … — section M
//   —θ_y2,M— tail stub
//
// The free joint sits on section 1. Every yaw joint is a hinge about the vertical through its yaw
// axis, the roll joint θ_r,i a hinge about section i's long axis through its centre (the "leg
// pair" body carries both legs of module i). Hinge axes are chosen so that MuJoCo's qpos of each
// motor joint IS the template's angle with the template's sign (θ_y1,i: the section turned left of
// the connector in front of it; θ_y2,i: the section turned left of the connector behind it; θ_r,i
// > 0 lifts the left foot), so the measured joints go into robots::multipod_feet_from_joints as
// they are. The head's front yaw joint and the tail's rear one turn only a small stub (they move
// no foot, as in the template) but are driven and measured like the others.
//
// Motors: a MuJoCo position actuator (gain kp) on every yaw and roll joint, with joint damping d
// and a geared motor's armature. The target leads the gait by (d / kp) θ̇ (the trick of
// bigant_spec.hpp: with target θ + (d/kp) θ̇ the damping's steady lag cancels), so the joint
// follows the gait up to the load and the armature's inertia; see multipod_peer.hpp for the
// tracking error that remains.
//
// Legs: the leaf spring is a slide joint along the leg pair's vertical (it rolls with the pair)
// between the leg pair and the foot, stiffness K_k, rest at zero, damping leg_damping: a foot's
// vertical stiffness is K_k (the template's K, §3.5.2.1), in series with a contact much stiffer
// than it (solref time constant 5 ms). The foot is a sphere, Coulomb friction μ_k on an elliptic
// cone (condim 3); the floor is frictionless, so the contact's friction is the foot's
// (MuJoCo takes the larger of the two geoms').
//
// Asymmetries (§5.3: "mechanical asymmetry during installation, or individual differences in
// spring stiffness and friction coefficients among all legs"): per leg its stiffness K_k, its
// friction μ_k, a mounting yaw δ_k (the leg arm turned about the vertical through the roll axis:
// the foot moves along the section by −w sin δ_k for a left leg, +w sin δ_k for a right one, i.e.
// δ_k > 0 turns the arm counter-clockwise seen from above) and a length error e_k (the foot e_k
// lower than nominal: a longer leg, which carries more of the weight). The template never sees
// them (robots::multipod has uniform legs).
#include <cstdint>
#include <string>
#include <vector>

#include "robots/multipod.hpp"

namespace slipwalk::peers::mujoco {

/// Per-leg properties of the MuJoCo Multipod, legs k = 0..N−1 ordered [L1..LM, R1..RM] (1 = head
/// module), as robots::multipod orders them.
struct MultipodAsymmetry {
  std::vector<double> stiffness;  ///< (N) leg spring K_k, N/m (template: 1000); valid: > 0
  std::vector<double> mu;         ///< (N) foot friction μ_k (template: 1); valid: ≥ 0
  std::vector<double> mount_yaw;  ///< (N) rad, mounting yaw δ_k (above); valid: |δ| ≤ 0.5
  std::vector<double> foot_drop;  ///< (N) m, foot below nominal (a longer leg); valid: |e| ≤ 0.02

  [[nodiscard]] int legs() const { return static_cast<int>(stiffness.size()); }
};

/// Default spreads (standard deviations at scale 1). Their size is a guess at a hand-built robot:
/// a leaf spring's stiffness goes with the cube of its thickness, so a few percent in thickness is
/// ~10–15 % in K; rubber foot pads on one floor differ in μ by similar amounts; a leg mounted 3°
/// off and a millimetre longer than its neighbours is what assembly by hand leaves. The feet sink
/// only Mg/(N K) = 1 mm under the robot's weight, so the length error is the strongest of the four
/// (a leg a millimetre short carries almost nothing standing, a long one twice its share), then the
/// mounting yaw; in our runs μ and K at these spreads change the walk little (the quasi-static
/// robot's slipping depends on the ratios μ_k F_k, which the stance feet share). With them the
/// robot turns and drifts sideways at Δφ = π where the symmetric one walks straight — by a few
/// percent of its forward speed at 0.3 Hz, more at 0.6–2.4 Hz — and the template, fed the
/// measured joints, misses it (Fig. 3.11's side drift).
inline constexpr double kStiffnessSpread = 0.15;  ///< relative (K_k = K ρ(0.15 z), ρ below)
inline constexpr double kFrictionSpread = 0.15;   ///< relative (μ_k = μ ρ(0.15 z))
inline constexpr double kMountYawSpread = 0.06;   ///< rad (3.4°)
inline constexpr double kFootDropSpread = 1e-3;   ///< m
/// Largest scale: keeps |δ_k| ≤ 2 · 0.06 · 2√3 ≈ 0.42 rad (z is bounded by 2√3, below).
inline constexpr double kMaxAsymmetryScale = 2.0;

/// The relative factor of a stiffness or friction: ρ(x) = 1 + x for x ≥ 0, 1 / (1 − x) below,
/// positive for every x and symmetric in the logarithm to first order (ρ(−x) ≈ 1/ρ(x)).
[[nodiscard]] double asymmetry_ratio(double x);

/// The nominal (symmetric) legs: K = 1000 N/m, μ = 1, no mounting error.
[[nodiscard]] MultipodAsymmetry symmetric_legs(int legs);

/// The nominal legs, then each property of each leg drawn with z of zero mean and unit variance,
/// z = √3 (u1 + u2 + u3 + u4 − 2), u uniform on [0, 1) from the top 53 bits of
/// std::mt19937_64(seed) (a sum of four uniforms: bell-shaped, bounded by ±2√3, and only IEEE
/// arithmetic, so the draw is the same on every platform, unlike std::normal_distribution):
/// K_k = 1000 ρ(scale · 0.15 z), μ_k = ρ(scale · 0.15 z), δ_k = scale · 0.06 z,
/// e_k = scale · 0.001 z. Draw order: all stiffnesses (legs in order), then all μ, all mounting
/// yaws, all foot drops. scale = 0 gives symmetric_legs exactly. Throws
/// core::InputError("multipod.legs" or "asymmetry.scale", ...) for legs not in {6, 8, 10, 12} or
/// scale outside [0, 2].
[[nodiscard]] MultipodAsymmetry draw_asymmetry(int legs, std::uint64_t seed, double scale);

/// What the MuJoCo Multipod's MJCF describes. Masses: total weight Mg = N newtons (the template's,
/// robots/multipod.cpp), split over the bodies below; the sections take what the others leave.
struct MultipodPeerSpec {
  int legs = 8;                                     ///< N ∈ {6, 8, 10, 12} (M = N/2 modules)
  robots::MultipodGeometry geometry;                ///< m, as the template's
  MultipodAsymmetry asymmetry = symmetric_legs(8);  ///< (N) per-leg properties
  double weight = 8.0;         ///< N, Mg: the template's N newtons; valid: > the parts below
  double gravity = 9.81;       ///< m/s²
  double timestep = 0.001;     ///< s; valid: (0, 0.002] (the contact's 5 ms needs 2 steps)
  int iterations = 50;         ///< Newton solver iterations; valid: ≥ 1
  double tolerance = 1e-10;    ///< solver tolerance; valid: > 0
  double kp = 200.0;           ///< N·m/rad, every motor's position gain; valid: > 0
  double joint_damping = 1.0;  ///< N·m·s/rad, every motor joint; valid: ≥ 0
  double torque_limit = 0.0;   ///< N·m, each motor's most torque (0: unlimited); valid: ≥ 0
  double armature = 0.001;    ///< kg·m², every motor joint (a geared servo's rotor); valid: ≥ 0
  double leg_damping = 15.0;  ///< N·s/m, each leg spring; valid: ≥ 0
  double foot_radius = 0.01;  ///< m; valid: > 0, < foot_depth
  double foot_mass = 0.01;    ///< kg, each foot (below the spring); valid: > 0
  double leg_pair_mass = 0.04;      ///< kg, each module's leg pair (above the springs); valid: > 0
  double connector_mass = 0.02;     ///< kg, each connector; valid: > 0
  double stub_mass = 0.01;          ///< kg, the head and tail stubs; valid: > 0
  double solref_timeconst = 0.005;  ///< s, contact stiffness (≥ 2 timesteps); valid: > 0
  double solref_dampratio = 1.0;    ///< contact damping ratio; valid: > 0

  [[nodiscard]] int modules() const { return legs / 2; }
  /// kg, each section: what the weight leaves after the other bodies.
  [[nodiscard]] double section_mass() const;
};

/// The spec of an N-leg robot with the asymmetry draw_asymmetry(legs, seed, scale), weight N
/// newtons and the defaults above.
[[nodiscard]] MultipodPeerSpec multipod_peer_spec(int legs, std::uint64_t seed, double scale);

/// Throws core::InputError naming the field ("multipod peer spec.kp", "... .asymmetry.mu[3]")
/// for an invalid spec.
void validate(const MultipodPeerSpec& spec);

/// The MJCF text (validates first). Names: bodies section<i>, connector<i>, legs<i>, head, tail,
/// foot bodies and geoms <leg>_foot (leg = L1..LM, R1..RM); joints root (free), yaw1_<i>, roll_<i>,
/// yaw2_<i>, <leg>_spring; actuators in the trial's column order (yaw1_1, roll_1, yaw2_1, …).
[[nodiscard]] std::string multipod_mjcf(const MultipodPeerSpec& spec);

/// Leg k's name: L1..LM for k < M, R1..RM after.
[[nodiscard]] std::string multipod_leg_name(int legs, int k);

/// The foot centre of leg k in its section's frame with every joint at zero and the spring at
/// rest (x along the section, y left, z up, origin on the roll axis at the section centre), m:
/// the template's (0, ±w, −h) moved by the leg's mounting yaw and foot drop.
[[nodiscard]] Eigen::Vector3d multipod_foot_mount(const MultipodPeerSpec& spec, int k);

}  // namespace slipwalk::peers::mujoco
