#pragma once
// BigANT in MuJoCo, driven along our gait (thesis §3.5.4, Fig. 3.14). Built only with
// MuJoCo (target slipwalk_peer_mujoco); the robot description is bigant_spec.hpp.
//
// Model / data as in peer.hpp: a BigAntModel (compiled mjModel and the indices we need) is built
// once, a BigAntData (mjData and our buffers) is reused; drive() allocates nothing per step.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/se2.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "robots/walker.hpp"

struct mjModel_;
struct mjData_;

namespace slipwalk::peers::mujoco {

/// The compiled BigANT model. Not copyable; loading is serialized with the disk robot's.
class BigAntModel {
 public:
  /// Throws core::InputError for an invalid spec, core::ComputationError if MuJoCo rejects it.
  explicit BigAntModel(BigAntPeerSpec spec);
  ~BigAntModel();
  BigAntModel(const BigAntModel&) = delete;
  BigAntModel& operator=(const BigAntModel&) = delete;

  [[nodiscard]] const mjModel_* mj() const { return model_; }
  [[nodiscard]] const BigAntPeerSpec& spec() const { return spec_; }
  [[nodiscard]] int legs() const { return spec_.legs(); }

  std::vector<int> qpos_leg;     ///< (N) qpos address of each leg's x slide; y, z follow
  std::vector<int> qvel_leg;     ///< (N) qvel address of each leg's x slide; y, z follow
  std::vector<int> leg_of_geom;  ///< (ngeom) leg index of a foot geom, −1 for other geoms
  std::vector<int> foot_geom;    ///< (N) geom id of each leg's foot

 private:
  BigAntPeerSpec spec_;
  mjModel_* model_ = nullptr;
};

/// Per-run data: MuJoCo's mjData and our buffers.
class BigAntData {
 public:
  explicit BigAntData(const BigAntModel& model);
  ~BigAntData();
  BigAntData(const BigAntData&) = delete;
  BigAntData& operator=(const BigAntData&) = delete;

  [[nodiscard]] mjData_* mj() { return data_; }
  [[nodiscard]] const mjData_* mj() const { return data_; }

  Eigen::Matrix3Xd q;        ///< (3 x N) feet from the gait, body frame, m
  Eigen::Matrix3Xd qdot;     ///< (3 x N) their velocities, m/s
  Eigen::Matrix3Xd targets;  ///< (3 x N) actuator targets (slide coordinates), m
  // ---- computed by read_legs ----------------------------------------------------------------
  Eigen::Matrix3Xd slides;    ///< (3 x N) slide coordinates: foot centre − nominal, body frame, m
  Eigen::VectorXd Fz;         ///< (N) normal force of the floor on each foot, N
  std::vector<char> contact;  ///< (N) 1 if MuJoCo has a contact at the foot
  /// (2 x N) planar force of the floor on each foot (Σ over its contacts of mj_contactForce
  /// rotated from the contact frame to the world), in the chassis' yaw frame, N — the columns
  /// Fx_L, Fy_L of a scene run (scene/run_writer.hpp)
  Eigen::Matrix2Xd Fxy;
  /// (2 x N) planar velocity of each foot's centre over the floor (mj_objectVelocity of the foot
  /// geom, world axes) in the chassis' yaw frame, m/s: the slip velocity while it has contact
  Eigen::Matrix2Xd slip;

 private:
  mjData_* data_ = nullptr;
};

/// Chassis level at height z (the foot-centre plane is z = 0), roll α and pitch β (small angles as
/// in eq. 3.6), yaw 0 at the origin, at rest; every slide at its target and the targets set.
void bigant_place(const BigAntModel& model, BigAntData& data, double z, double alpha, double beta,
                  const Eigen::Matrix3Xd& targets);

/// The chassis' planar pose from qpos (θ = yaw of the free joint's quaternion, in (−π, π]).
[[nodiscard]] core::Pose2 bigant_pose(const BigAntData& data);
/// The chassis origin's height above the foot-centre plane, m.
[[nodiscard]] double bigant_height(const BigAntData& data);
/// The chassis origin in MuJoCo's world frame (on a slope: the plane's coordinates), m.
[[nodiscard]] Eigen::Vector3d bigant_position(const BigAntData& data);
/// (roll, pitch) of the chassis, rad: pitch nose-up positive, the angle of its x axis above the
/// world's x-y plane (on a slope: above the plane; eq. 3.6's −β to first order); roll left side
/// up, the angle of its y axis above that plane (eq. 3.6's α to first order).
[[nodiscard]] Eigen::Vector2d bigant_tilt(const BigAntData& data);

/// Feet's contacts whose normal leans more than 10° from the world's z axis (|n_z| < cos 10°): on
/// stairs a foot on a tread's edge or against a riser (bigant_spec.hpp), which our model's stairs
/// do not have (a toe is on a tread or above it); none on flat ground or the slope's plane. Needs
/// contacts computed (after mj_forward or mj_step).
[[nodiscard]] int bigant_edge_contacts(const BigAntModel& model, const BigAntData& data);

/// data.slides from qpos; data.Fz, data.contact, data.Fxy from MuJoCo's contacts and data.slip
/// from its body velocities (need contacts and cvel computed: after mj_forward, or after mj_step
/// for the state the step started from).
void bigant_read_legs(const BigAntModel& model, BigAntData& data);

struct BigAntDriveOptions {
  double duration = 40.0;  ///< s of gait after settling; valid: > 0
  double settle = 1.0;     ///< s the feet are held at the gait's t = 0 first; valid: ≥ 0
  double sample = 0.1;     ///< s between samples (rounded to whole steps); valid: > 0
  bool lead = false;       ///< targets lead by (damping / kp) q̇ (bigant_targets)
};

/// One sample: the pose relative to the settled pose (so both start at the origin, as ours).
struct BigAntSample {
  double t = 0.0;       ///< s since the gait started
  core::Pose2 pose;     ///< θ unwrapped
  double z = 0.0;       ///< m, chassis height
  int contacts = 0;     ///< feet in contact
  double Fz_sum = 0.0;  ///< N, Σ normal forces
};

/// Tracking of the gait's foot positions by the slides, over every step of the gait.
struct BigAntTracking {
  long long steps = 0;
  Eigen::Matrix3Xd sum_sq;         ///< (3 x N) Σ over steps of (slide − (q − nominal))², m²
  Eigen::VectorXd swing_z_sum_sq;  ///< (N) the z part over the steps the foot had no contact
  Eigen::VectorXd swing_steps;     ///< (N) those steps
  /// RMSE per axis over all feet and steps, m.
  [[nodiscard]] Eigen::Vector3d rmse() const;
  /// RMSE per axis and foot, m (3 x N).
  [[nodiscard]] Eigen::Matrix3Xd rmse_per_foot() const;
  /// z RMSE while a foot swings (no contact), over all feet, m: the true z tracking error; in
  /// stance the z error is the leg spring's deflection F_z / kp_z, our model's compression too.
  [[nodiscard]] double swing_z_rmse() const;
};

struct BigAntDriveSummary {
  BigAntTracking tracking;
  core::Pose2 settled;         ///< the world pose after settling (subtracted from the samples)
  core::Pose2 end;             ///< the last sample's relative pose
  double mean_contacts = 0.0;  ///< feet in contact, mean over steps
  double max_Fz_error = 0.0;   ///< max over steps of |ΣF_z − Mg| / Mg
  long long edge_steps = 0;    ///< steps with a foot on an edge or a riser (bigant_edge_contacts)
};

using BigAntSink = std::function<void(const BigAntSample&)>;

/// Runs the gait in MuJoCo: places the robot with feet(0) (chassis at z, α, β), holds those
/// targets for options.settle, then for every step n sets the targets from feet(n h) and steps,
/// calling sink every options.sample s (from t = 0 to duration). Throws core::InputError for bad
/// options.
BigAntDriveSummary bigant_drive(const BigAntModel& model, BigAntData& data,
                                const robots::FootKinematics& feet, double z, double alpha,
                                double beta, const BigAntDriveOptions& options,
                                const BigAntSink& sink);

}  // namespace slipwalk::peers::mujoco
