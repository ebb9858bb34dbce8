#pragma once
// Trajectories (thesis §3.5): a gait moves the feet in the body frame; at every step the model of
// ch. 3 gives the body velocity (spring support §3.3, then the friction law's balance §3.4, as in
// connection::evaluate), and the pose integrates it on SE(2) exactly for the twist held over the
// step: pose_{n+1} = pose_n · exp(v_n dt) (core/se2.hpp).
//
// The simulator is composed once from exactly the effects a run needs (DESIGN.md): the friction
// law and the inertia filter are template parameters of integrate(), so a run without the filter
// never tests for it. The kernels instantiated here (trajectory.cpp) are the four combinations of
// {ViscousCoulombKernel, CoulombKernel} × {NoFilter, IirFilter}; scene::compose picks one at load.
//
// Per step a sink receives the time, the pose, the body velocity and per leg the contact, F_z, the
// planar force and the slip velocity, all in the body frame (x forward, y left): the model is
// written in the body frame, and the world frame is one rotation by pose.theta away.
#include <Eigen/Core>
#include <functional>
#include <string>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "core/se2.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::connection {

/// The gait: writes the feet's positions q (3 × N, m) and velocities q̇ (3 × N, m/s) in the body
/// frame at time t without allocating. The same type as robots::FootKinematics (robots/walker.hpp),
/// spelled here so that connection/ does not depend on robots/.
using FootKinematics = std::function<void(double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot)>;

// ---- friction laws (one per kernel; §3.4) ----------------------------------------------------

/// Viscous-Coulomb friction: the balance is one 3 × 3 solve (eq. 3.20).
struct ViscousCoulombKernel {
  static constexpr FrictionLaw kLaw = FrictionLaw::kViscousCoulomb;
  void operator()(const contact::Robot& robot, contact::Frame& frame) const {
    friction::solve_viscous_coulomb(robot, frame);
  }
};

/// Classical Coulomb friction (eq. 3.13), a certified convex program.
struct CoulombKernel {
  static constexpr FrictionLaw kLaw = FrictionLaw::kCoulomb;
  friction::CoulombOptions options;  ///< tol: the relative duality gap to reach
  void operator()(const contact::Robot& robot, contact::Frame& frame) const {
    friction::solve_coulomb(robot, frame, options);
  }
};

// ---- body-velocity filters --------------------------------------------------------------------

/// No filter: the body moves with the model's velocity.
struct NoFilter {
  void validate() const {}
  void reset() {}
  const Eigen::Vector3d& operator()(const Eigen::Vector3d& x) { return x; }
};

/// The first-order IIR lowpass of §3.5.2.2, a simple model of the body's inertia:
/// y_n = γ y_{n−1} + (1 − γ) x_n, starting from rest (y_{−1} = 0), applied to (v_x, v_y, ω).
/// γ is per step: the thesis chose 0.15 at its motion-capture frame rate, so the same γ at
/// another dt is another time constant (τ = −dt / ln γ).
struct IirFilter {
  double gamma = 0.15;                          ///< valid: [0, 1)
  Eigen::Vector3d y = Eigen::Vector3d::Zero();  ///< the filter's state, y_{n−1}

  void validate() const;  ///< throws core::InputError("filter.gamma", ...) outside [0, 1)
  void reset() { y.setZero(); }
  const Eigen::Vector3d& operator()(const Eigen::Vector3d& x) {
    y = gamma * y + (1.0 - gamma) * x;
    return y;
  }
};

// ---- options, data, output --------------------------------------------------------------------

struct TrajectoryOptions {
  double dt = 0.01;        ///< s, the step; valid: > 0, finite
  long long steps = 0;     ///< steps taken; steps + 1 frames t_0 … t_steps are evaluated and
                           ///< reported; valid: ≥ 0
  double t0 = 0.0;         ///< s, the time of the first frame; t_n = t0 + n·dt (not accumulated)
  core::Pose2 start = {};  ///< the pose at t0
};

/// Throws core::InputError naming "trajectory.dt" etc. for out-of-range options.
void validate(const TrajectoryOptions& options);

/// Buffers of a run (sized once from the robot; nothing is allocated per step).
struct TrajectoryData {
  explicit TrajectoryData(const contact::Robot& robot)
      : frame(robot), slip(Eigen::Matrix2Xd::Zero(2, robot.legs())) {}
  contact::Frame frame;   ///< the current frame: q, q̇, contact, F_z, F_xy, v_body, summaries
  Eigen::Matrix2Xd slip;  ///< (2 x N) u_k = v + ω S q_k + q̇_k, body frame, m/s
};

/// What one step hands to the sink; the references are valid during the call only.
struct TrajectoryStep {
  long long n;                     ///< step index, 0 … steps
  double t;                        ///< s
  const core::Pose2& pose;         ///< the pose at t (world frame)
  const Eigen::Vector3d& v_body;   ///< (v_x, v_y, ω) that moves the pose over [t, t + dt): the
                                   ///< filtered velocity when the filter is on, else v_model
  const Eigen::Vector3d& v_model;  ///< the friction balance's velocity at t (body frame)
  const contact::Frame& frame;     ///< q, q̇, contact, F_z, F_xy (body frame), support, friction
  const Eigen::Matrix2Xd& slip;    ///< (2 x N) each foot's planar velocity over the ground, body
                                   ///< frame, from v_model (so F_xy is the friction law of it);
                                   ///< the slip velocity for feet in contact
};

using TrajectorySink = std::function<void(const TrajectoryStep&)>;

/// How a run went. Numerical trouble is counted, not thrown: one bad frame should not lose a run.
struct TrajectorySummary {
  long long frames = 0;              ///< frames evaluated (steps + 1)
  core::Pose2 end = {};              ///< the pose at the last frame
  long long unsupported = 0;         ///< frames the spring support could not balance
                                     ///< (kUnsupported, kIterationLimit)
  long long not_converged = 0;       ///< frames whose friction solve did not converge
  long long not_unique = 0;          ///< frames with a continuum of balancing body velocities
  double max_friction_residual = 0;  ///< the largest friction.residual over the frames
  std::string message;               ///< the first problem ("t = 1.5: ..."), empty if none
};

/// Runs the trajectory: for n = 0 … steps at t_n, feet(t_n) → data.frame.q, q̇; spring support;
/// the law's balance → v_model; filter → v_body; slip; sink(step); pose ← pose · exp(v_body dt).
/// Throws core::InputError for bad options or a frame whose sizes do not match the robot.
template <class Law, class Filter>
TrajectorySummary integrate(const contact::Robot& robot, const FootKinematics& feet,
                            const TrajectoryOptions& options, const Law& law, Filter filter,
                            TrajectoryData& data, const TrajectorySink& sink);

extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&, const ViscousCoulombKernel&,
                                            NoFilter, TrajectoryData&, const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&, const ViscousCoulombKernel&,
                                            IirFilter, TrajectoryData&, const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&, const CoulombKernel&,
                                            NoFilter, TrajectoryData&, const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&, const CoulombKernel&,
                                            IirFilter, TrajectoryData&, const TrajectorySink&);

}  // namespace slipwalk::connection
