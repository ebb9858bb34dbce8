#pragma once
// BigANT as MuJoCo sees it in thesis §3.5.4 (Fig. 3.14), described without MuJoCo (built in every
// configuration): a plate chassis on a free joint carrying the robot's mass, and per leg a foot
// sphere moved relative to the chassis by three slide joints along the chassis' x, y and z axes,
// each driven by a position actuator (kp 100 N/m in x and y, 1000 N/m in z, joint damping 10
// N·s/m); Newton solver, 100 iterations; friction μ from our robot.
//
// The slides' zeros sit at each foot's nominal point (its mean over one gait cycle, body frame),
// so a slide's coordinate is the foot centre's offset from that point and the actuator target for
// our foot position q is q − nominal. The floor lies one foot radius below z = 0, so a foot
// touches when its centre is below z = 0, as in the disk robot of legged_spec.hpp.
//
// Why z stiffness matters: our model's leg is a spring of stiffness K whose rest point is q (ch. 3,
// eq. 3.6: F_z = −K h). MuJoCo's z slide with target q_z is the same spring with K = kp_z (the
// contact itself is far stiffer), so the like-for-like comparison runs our model with K = kp_z
// (the peer_bigant sweep point does so by default).
//
// Terrain (thesis §5.2), one place for both: a slope keeps the floor plane and tilts gravity by σ
// toward −ψ (downhill), so MuJoCo's world frame is the plane's and the pose is in the plane's
// coordinates exactly as ours (terrain.hpp); tilting the plane instead would put the pose in the
// world and need the change of coordinates at every sample. Stairs replace the plane by one box
// per tread: tread i covers s ∈ [i·tread, (i+1)·tread) along ψ, its top at i·riser less the foot
// radius (a foot centre at the tread's height touches, as on the flat floor), every box down to
// one common base below the lowest tread. Unlike ours, MuJoCo's risers are walls.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "robots/walker.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::peers::mujoco {

/// What the BigANT MJCF describes. Defaults are §3.5.4's where it gives them.
struct BigAntPeerSpec {
  std::vector<std::string> leg_names;  ///< (N) HL, ML, FL, HR, MR, FR
  Eigen::Matrix3Xd nominal;            ///< (3 x N) each slide's zero, body frame, m
  std::vector<double> mu;              ///< (N) foot–floor friction; valid: ≥ 0
  double total_mass = 8.18;            ///< kg, chassis + legs
  /// kg·m², the chassis' principal inertia: §3.5.4's diaginertia '130000 430000 300000' with
  /// mass '818' read in units of 10 g and cm (818 → 8.18 kg, 130000 → 0.13 kg·m²).
  Eigen::Vector3d chassis_inertia = Eigen::Vector3d(0.13, 0.43, 0.30);
  Eigen::Vector3d chassis_half_size = Eigen::Vector3d(0.365, 0.2, 0.01);  ///< m, drawn box
  double link_mass = 0.02;         ///< kg, each of a leg's three slide links (near massless)
  double foot_radius = 0.005;      ///< m
  double gravity = 9.81;           ///< m/s²
  double timestep = 0.002;         ///< s, MuJoCo's default
  int iterations = 100;            ///< Newton iterations (§3.5.4)
  double tolerance = 1e-8;         ///< constraint solver tolerance
  double kp_xy = 100.0;            ///< N/m, x and y position actuators (§3.5.4)
  double kp_z = 1000.0;            ///< N/m, z position actuator (§3.5.4)
  double damping = 10.0;           ///< N·s/m, every slide joint (§3.5.4)
  double solref_timeconst = 0.02;  ///< s, contact solref[0] (MuJoCo's default)
  double solref_dampratio = 1.0;   ///< contact solref[1] (MuJoCo's default)
  bool elliptic = false;           ///< friction cone: elliptic, or pyramidal (MuJoCo's default)
  int noslip_iterations = 0;  ///< MuJoCo's no-slip post-solver iterations (0: off, the default;
                              ///< > 0 removes the soft contacts' creep in stick)
  terrain::Terrain terrain;   ///< flat (default), slope (gravity tilted) or stairs (tread boxes)
  /// m, stairs only: the range of s = p·(cos ψ, sin ψ) the treads cover (whole treads around it);
  /// valid: finite, first < second, at most kMaxStairBoxes treads
  Eigen::Vector2d stairs_extent = Eigen::Vector2d(-1.5, 3.0);
  double stairs_half_width = 2.0;  ///< m, stairs only: each tread's half width across ψ; > 0
  double stairs_depth = 0.5;       ///< m, stairs only: the boxes' base below the lowest tread; > 0

  [[nodiscard]] int legs() const { return static_cast<int>(nominal.cols()); }
};

/// The most tread boxes a stairs spec may ask for.
inline constexpr int kMaxStairBoxes = 1000;

/// The spec for a BigANT walker: leg names and μ from walker.robot, nominal points the mean of
/// walker.feet over one period (`samples` evenly spaced times), mass Mg / g. Throws
/// core::InputError for a walker without feet.
[[nodiscard]] BigAntPeerSpec bigant_peer_spec(const robots::Walker& walker, int samples = 256);

/// The MJCF text. Throws core::InputError("bigant peer spec", ...) for invalid fields.
[[nodiscard]] std::string bigant_mjcf(const BigAntPeerSpec& spec);

/// Gravity in MuJoCo's world frame (m/s²): (0, 0, −g) on flat ground and stairs; on a slope, in
/// the plane's coordinates, −g (sin σ cos ψ, sin σ sin ψ, cos σ) (eq. 5.1: Mg cos σ along the
/// normal, Mg sin σ downhill).
[[nodiscard]] Eigen::Vector3d bigant_gravity(const BigAntPeerSpec& spec);

/// The index range [first, last] of the treads of a stairs spec (i with [i·tread, (i+1)·tread)
/// meeting stairs_extent).
[[nodiscard]] Eigen::Vector2i bigant_treads(const BigAntPeerSpec& spec, const terrain::Stairs& s);

/// The actuator targets (slide coordinates, 3 x N) for feet q: q − nominal, plus a lead
/// (damping / kp) q̇ per axis when `lead` is set. The lead cancels the joint damping's steady lag
/// of an unloaded foot: with target r, kp (r − s) = c ṡ holds for s = q when r = q + (c / kp) q̇.
void bigant_targets(const BigAntPeerSpec& spec, const Eigen::Matrix3Xd& q,
                    const Eigen::Matrix3Xd& qdot, bool lead, Eigen::Matrix3Xd& targets);

}  // namespace slipwalk::peers::mujoco
