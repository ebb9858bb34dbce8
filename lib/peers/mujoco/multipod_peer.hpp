#pragma once
// The "real" Multipod of thesis §5.3 in MuJoCo: compile, drive along the §5.3.2 gait, record a
// motion trial (residual/trial.hpp) as motion capture and the motors' encoders would. Built only
// with MuJoCo (target slipwalk_peer_mujoco); the robot is described in multipod_spec.hpp.
//
// Model / data as in bigant_peer.hpp: a MultipodModel (compiled mjModel and the indices we need)
// is built once (loading is serialized), a MultipodData (mjData and our buffers) is reused;
// stepping allocates nothing (the trial's arrays are sized once per trial).
//
// Tracking (defaults of multipod_spec.hpp: kp = 200 N·m/rad, damping 1 N·m·s/rad, armature
// 0.001 kg·m², targets leading by (d/kp) θ̇): the measured joints follow the gait within about
// 0.01 rad RMS (the roll joints, which carry the feet's loads, lag most; see the tests' bound).
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"
#include "peers/mujoco/multipod_spec.hpp"
#include "residual/trial.hpp"
#include "robots/robots.hpp"

struct mjModel_;
struct mjData_;

namespace slipwalk::peers::mujoco {

/// The compiled Multipod. Not copyable.
class MultipodModel {
 public:
  /// Throws core::InputError for an invalid spec, core::ComputationError if MuJoCo rejects it.
  explicit MultipodModel(MultipodPeerSpec spec);
  ~MultipodModel();
  MultipodModel(const MultipodModel&) = delete;
  MultipodModel& operator=(const MultipodModel&) = delete;

  [[nodiscard]] const mjModel_* mj() const { return model_; }
  [[nodiscard]] const MultipodPeerSpec& spec() const { return spec_; }
  [[nodiscard]] int legs() const { return spec_.legs; }
  [[nodiscard]] int modules() const { return spec_.modules(); }

  std::vector<int> section_body;  ///< (M) body id of each section, head first
  /// (3M) qpos address of module i's θ_y1, θ_r, θ_y2 at 3i, 3i+1, 3i+2 (the trial's columns;
  /// the actuators are in the same order)
  std::vector<int> qpos_joint;
  std::vector<int> qpos_spring;  ///< (N) qpos address of each leg's spring slide (its
                                 ///< compression, m: > 0 when the foot pushes up)
  std::vector<int> foot_geom;    ///< (N) geom id of each leg's foot
  std::vector<int> leg_of_geom;  ///< (ngeom) leg index of a foot geom, −1 for other geoms

 private:
  MultipodPeerSpec spec_;
  mjModel_* model_ = nullptr;
};

/// Per-run data: MuJoCo's mjData and our buffers.
class MultipodData {
 public:
  explicit MultipodData(const MultipodModel& model);
  ~MultipodData();
  MultipodData(const MultipodData&) = delete;
  MultipodData& operator=(const MultipodData&) = delete;

  [[nodiscard]] mjData_* mj() { return data_; }
  [[nodiscard]] const mjData_* mj() const { return data_; }

  robots::MultipodJoints joints;  ///< (3 × M) the gait's joint angles at the step, rad
  robots::MultipodJoints rates;   ///< (3 × M) their rates, rad/s
  Eigen::VectorXd Fz;  ///< (N) normal force of the floor on each foot, N (multipod_loads)

 private:
  mjData_* data_ = nullptr;
};

/// Places the robot at rest with the motor joints at `joints` (3 × M) and the targets there,
/// section 1 at the origin heading +x, level, lowered so the lowest foot just touches the floor;
/// springs at rest.
void multipod_place(const MultipodModel& model, MultipodData& data,
                    const Eigen::Ref<const robots::MultipodJoints>& joints);

/// The body pose in the world from the section bodies' poses (needs MuJoCo's kinematics of the
/// current qpos: after mj_forward or mj_kinematics): the mean frame of robots/multipod.hpp, origin
/// the centroid of the section centres (x, y), heading the mean of the section headings (each
/// the heading of its long axis projected on the floor), θ in (−π, π] about section 1's.
[[nodiscard]] core::Pose2 multipod_pose(const MultipodModel& model, const MultipodData& data);

/// The motor joints' angles (qpos, the trial's sign convention), module i in column i.
void multipod_measured_joints(const MultipodModel& model, const MultipodData& data,
                              Eigen::Ref<robots::MultipodJoints> joints);

/// data.Fz from MuJoCo's contacts (after mj_forward): the floor's normal force on each foot.
void multipod_loads(const MultipodModel& model, MultipodData& data);

/// Simulates `seconds` with the targets held (whole steps, rounded).
void multipod_hold(const MultipodModel& model, MultipodData& data, double seconds);

struct TrialOptions {
  double cycles = 8.0;         ///< gait cycles recorded (thesis: 8–10); valid: > 0, ≤ 1000
  double sample_rate = 125.0;  ///< Hz, motion capture (thesis); 1/(rate · timestep) must be whole
  double settle = 0.5;  ///< s, standing in the gait's t = 0 pose before recording; valid: ≥ 0
};

/// Runs the §5.3.2 gait (robots::multipod_gait_joints as the motors' targets, leading by
/// (d/kp) θ̇) and records, at sample_rate from t = 0 to cycles / f (the samples that fall in it),
/// the body pose (multipod_pose, θ unwrapped) and the measured joints, in the trial's columns.
/// First: multipod_place in the gait's t = 0 pose, then `settle` s of standing. t = 0 is the start
/// of recording; the gait's phase is 2πf t + iΔφ from there. The label says "MuJoCo Multipod,
/// f = …, Δφ = …π". Throws core::InputError ("multipod.*" for the gait, "trial.*" for the
/// options) for a bad gait, a gait whose legs differ from the model's, or bad options;
/// core::ComputationError when the simulation blows up (a non-finite state or a section turned
/// over).
[[nodiscard]] residual::MotionTrial record_trial(const MultipodModel& model, MultipodData& data,
                                                 const robots::UndulationGait& gait,
                                                 const TrialOptions& options);

}  // namespace slipwalk::peers::mujoco
