#pragma once
// MuJoCo as the peer simulator (thesis §3.5.3–3.5.4). Built only with the CMake option
// SLIPWALK_MUJOCO and Debian's libmujoco-dev (target slipwalk_peer_mujoco, which defines
// SLIPWALK_HAVE_MUJOCO for its users).
//
// The robot (legs, joints, MJCF, kinematics) is described in legged_spec.hpp, which is built
// without MuJoCo too; this part compiles it with MuJoCo, sets our configurations, steps and reads
// back the body's motion and the feet's contact forces.
//
// Model / data as in MuJoCo itself: a PeerModel (the compiled mjModel and the indices we need) is
// built once; a PeerData (an mjData and our buffers) is reused for every step, and nothing of
// ours allocates after it exists.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "peers/mujoco/legged_spec.hpp"

struct mjModel_;
struct mjData_;

namespace slipwalk::peers::mujoco {

/// The compiled model and the indices into it. Not copyable; loading is serialized (MuJoCo 2.2's
/// XML loader keeps global state).
class PeerModel {
 public:
  /// Compiles the spec's MJCF from memory. Throws core::InputError for an invalid spec and
  /// core::ComputationError with MuJoCo's message if it does not compile.
  explicit PeerModel(PeerSpec spec);
  ~PeerModel();
  PeerModel(const PeerModel&) = delete;
  PeerModel& operator=(const PeerModel&) = delete;

  [[nodiscard]] const mjModel_* mj() const { return model_; }
  [[nodiscard]] const PeerSpec& spec() const { return spec_; }
  [[nodiscard]] int legs() const { return static_cast<int>(spec_.legs.size()); }

  std::vector<int> qpos_slide;    ///< (N) qpos address of each leg's slide; yaw, pitch follow it
  std::vector<int> qvel_slide;    ///< (N) qvel address of each slide; yaw, pitch follow it
  std::vector<int> ctrl_slide;    ///< (N) actuator index of each slide; yaw, pitch follow it
  std::vector<int> foot_of_geom;  ///< (ngeom) leg index of a foot geom, −1 for other geoms
  int body_id = -1;               ///< the free-floating body

 private:
  PeerSpec spec_;
  mjModel_* model_ = nullptr;
};

/// The body's state: pose (small-angle slopes as in eq. 3.6) and planar velocity.
struct BodyState {
  double x = 0.0;      ///< m, world
  double y = 0.0;      ///< m, world
  double z = 0.0;      ///< m, height of the body frame's origin above the foot-centre plane
  double theta = 0.0;  ///< rad, yaw
  double alpha = 0.0;  ///< roll (rad; eq. 3.6's α)
  double beta = 0.0;   ///< pitch (rad; eq. 3.6's β)
  Eigen::Vector3d v_body = Eigen::Vector3d::Zero();  ///< (v_x, v_y, ω_z), body frame
};

/// Per-step data: MuJoCo's mjData plus our buffers (a saved state to rewind to).
class PeerData {
 public:
  explicit PeerData(const PeerModel& model);
  ~PeerData();
  PeerData(const PeerData&) = delete;
  PeerData& operator=(const PeerData&) = delete;

  [[nodiscard]] mjData_* mj() { return data_; }
  [[nodiscard]] const mjData_* mj() const { return data_; }

  // ---- computed by read_feet --------------------------------------------------------------
  Eigen::Matrix3Xd q;         ///< (3 x N) foot centres in the body frame (forward kinematics), m
  std::vector<char> contact;  ///< (N) 1 if MuJoCo has a contact at the foot
  Eigen::VectorXd Fz;         ///< (N) vertical (world z) force of the floor on the foot, N
  Eigen::Matrix2Xd Fxy;       ///< (2 x N) planar force on the foot, yaw-aligned body frame, N

 private:
  friend void checkpoint(const PeerModel&, PeerData&);
  friend void rewind(const PeerModel&, PeerData&);
  mjData_* data_ = nullptr;
  std::vector<double> saved_;  ///< qpos, qvel, ctrl, qacc_warmstart of the checkpoint
};

/// Puts the robot into our model's configuration: body pose and velocity, each leg's joints (and
/// the position actuators' targets) from the foot positions q and velocities qdot (3 x N, body
/// frame). Clears the solver's warm start. Returns the number of feet out of their leg's reach
/// (those keep their previous joints). Does not allocate.
int set_state(const PeerModel& model, PeerData& data, const BodyState& body,
              const Eigen::Matrix3Xd& q, const Eigen::Matrix3Xd& qdot);

/// The warm start a running simulation would have: mj_forward at the current state and its
/// accelerations as the constraint solver's starting point of the next mj_step.
void warm_start(const PeerModel& model, PeerData& data);

/// Saves qpos, qvel, ctrl and the warm start; rewind restores them (time to 0), so one state can
/// be stepped many times (timing). No allocation.
void checkpoint(const PeerModel& model, PeerData& data);
void rewind(const PeerModel& model, PeerData& data);

/// One mj_step.
void step(const PeerModel& model, PeerData& data);

/// mj_forward: positions, contacts and accelerations at the current state, no time step.
void forward(const PeerModel& model, PeerData& data);

/// The body's pose and velocity now.
[[nodiscard]] BodyState body_state(const PeerModel& model, const PeerData& data);

/// Fills data.q (forward kinematics of MuJoCo's own joint state, in the body frame), data.contact,
/// data.Fz and data.Fxy from MuJoCo's contacts (mj_contactForce). Needs positions and contacts
/// computed (after mj_step or mj_forward). Returns the number of contacts MuJoCo found.
int read_feet(const PeerModel& model, PeerData& data);

/// Constraint solver iterations of the last step.
[[nodiscard]] int solver_iterations(const PeerData& data);

/// MuJoCo's version string ("2.2.2").
[[nodiscard]] std::string version();

}  // namespace slipwalk::peers::mujoco
