#pragma once
// Trajectories (thesis §3.5): a gait moves the feet in the body frame; at every step the model of
// ch. 3 gives the body velocity (spring support §3.3, then the friction law's balance §3.4, as in
// connection::evaluate), and the pose integrates it on SE(2) exactly for the twist held over the
// step: pose_{n+1} = pose_n · exp(v_n dt) (core/se2.hpp).
//
// The simulator is composed once from exactly the effects a run needs (DESIGN.md): every effect
// is a policy type of an Effects bundle, the template parameter of integrate(): the friction law
// ({ViscousCoulombKernel, CoulombKernel}; anisotropy is the robot's w, read by both), the inertia
// filter ({NoFilter, IirFilter}), the connection residual B of §5.3.1 ({NoResidual,
// LinearResidual}) and the measurement noise ({NoNoise, PoseNoise}). Each effect's "off" type is
// an identity returning its argument by reference: no branch, no allocation, nothing left after
// inlining. The loop itself is in trajectory_kernel.hpp; trajectory.cpp instantiates the four
// law × filter bundles declared extern below, and scene/compose.cpp instantiates the bundles a
// scene can name through one std::visit over the effects' variants (a new effect is one more
// policy member of Effects and one more variant there).
//
// Per step a sink receives the time, the pose, the body velocity and per leg the contact, F_z, the
// planar force and the slip velocity, all in the body frame (x forward, y left): the model is
// written in the body frame, and the world frame is one rotation by pose.theta away.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <string_view>

#include "connection/local_connection.hpp"
#include "connection/terrain_kernels.hpp"
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

// ---- connection residual (§5.3.1) ------------------------------------------------------------

/// No residual: the body moves with the friction balance's velocity.
struct NoResidual {
  void validate(int /*legs*/) const {}
  const Eigen::Vector3d& operator()(const Eigen::Vector3d& v, const Eigen::Matrix3Xd& /*qdot*/) {
    return v;
  }
};

/// The data-driven residual of §5.3.1: g̊ = (A(q) + B) q̇ with a constant B ∈ R^{3 × 2N}, i.e.
/// B · vec(q̇_xy) (columns 2k, 2k + 1 multiply foot k's q̇_x, q̇_y, the ordering of A in eq. 3.20)
/// is added to the balance's body velocity (v_x, v_y, ω) before the filter. The feet's slip and
/// forces stay those of the balance (B models what the balance misses, not another friction law).
struct LinearResidual {
  Eigen::Matrix<double, 3, Eigen::Dynamic> B;           ///< (3 x 2N)
  Eigen::Vector3d corrected = Eigen::Vector3d::Zero();  ///< scratch, the returned velocity

  void validate(int legs) const;  ///< throws core::InputError("residual.B", ...) for a wrong size
                                  ///< or a non-finite entry
  const Eigen::Vector3d& operator()(const Eigen::Vector3d& v, const Eigen::Matrix3Xd& qdot) {
    corrected = v;
    for (Eigen::Index k = 0; k < qdot.cols(); ++k) {
      corrected += B.col(2 * k) * qdot(0, k) + B.col(2 * k + 1) * qdot(1, k);
    }
    return corrected;
  }
};

// ---- measurement noise ------------------------------------------------------------------------

/// No noise: the measured pose is the pose.
struct NoNoise {
  void validate() const {}
  void reset() {}
  const core::Pose2& operator()(const core::Pose2& pose) { return pose; }
};

/// Motion-capture-like measurement noise (the thesis measures the pose by motion capture, §3.5.1,
/// and derives velocities from it): the reported pose is (x + σ_xy n₁, y + σ_xy n₂,
/// θ + σ_θ n₃) with independent standard normal n per frame; the simulated motion is untouched.
/// Deterministic for a seed on every platform: std::mt19937_64 is fully specified and the
/// normals are Box–Muller written out (the standard distributions are implementation-defined).
struct PoseNoise {
  double sigma_xy = 0.0;     ///< m, ≥ 0
  double sigma_theta = 0.0;  ///< rad, ≥ 0
  std::uint64_t seed = 0;
  std::mt19937_64 engine{0};
  core::Pose2 measured = {};
  double spare = 0.0;  ///< Box–Muller's second normal
  bool has_spare = false;

  void validate() const;  ///< throws core::InputError("noise.sigma", ...) for σ < 0 or NaN
  void reset() {
    engine.seed(seed);
    has_spare = false;
  }
  double normal() {
    if (has_spare) {
      has_spare = false;
      return spare;
    }
    constexpr double kUnit = 0x1.0p-53;
    const double u1 = 1.0 - static_cast<double>(engine() >> 11) * kUnit;  // (0, 1]
    const double u2 = static_cast<double>(engine() >> 11) * kUnit;
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 2.0 * std::numbers::pi * u2;
    spare = r * std::sin(a);
    has_spare = true;
    return r * std::cos(a);
  }
  const core::Pose2& operator()(const core::Pose2& pose) {
    measured.x = pose.x + sigma_xy * normal();
    measured.y = pose.y + sigma_xy * normal();
    measured.theta = pose.theta + sigma_theta * normal();
    return measured;
  }
};

// ---- the bundle -------------------------------------------------------------------------------

/// The effects of one kernel, one policy each; a default member is the effect switched off.
template <class Law, class Filter = NoFilter, class Residual = NoResidual, class Noise = NoNoise,
          class Ground = FlatGround>
struct Effects {
  Law law;
  Filter filter;
  Residual residual;
  Noise noise;
  Ground ground;  ///< the terrain (§5.2): FlatGround, SlopeGround, StairsGround
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
  const core::Pose2& measured;     ///< the pose as measured: pose + noise with PoseNoise, else
                                   ///< the same object as pose
  const Eigen::Vector3d& v_body;   ///< (v_x, v_y, ω) that moves the pose over [t, t + dt):
                                   ///< filter(v_model + B q̇); v_model itself when both are off
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
                                     ///< (kUnsupported, kIterationLimit, kNonFinite)
  long long not_converged = 0;       ///< frames whose friction solve did not converge
  long long not_unique = 0;          ///< frames with a continuum of balancing body velocities
  double max_friction_residual = 0;  ///< the largest friction.residual over the frames
  std::string message;               ///< the first problem ("t = 1.5: ..."), empty if none
  /// The step whose pose or body velocity was not finite, -1 if none. Such a state cannot turn
  /// finite again, so the run stopped there: that frame was not handed to the sink, `frames`
  /// counts the frames before it, and `non_finite` says where ("t = 1.5 s (step 150): ...").
  /// Callers treat it as a failed run (a scene run exits 1), never as a result.
  long long non_finite_step = -1;
  std::string non_finite;
};

namespace detail {
/// True when the pose and the velocity that moves it are all finite: one sum and one compare
/// per step (NaN and ±inf propagate through the sum; finite values of the model's ranges cannot
/// overflow it).
[[nodiscard]] inline bool state_is_finite(const core::Pose2& pose, const Eigen::Vector3d& v) {
  return std::isfinite(pose.x + pose.y + pose.theta + v(0) + v(1) + v(2));
}
/// Records the stop at step n, time t in `summary`; `what` says which state.
void stop_non_finite(long long n, double t, TrajectorySummary& summary,
                     std::string_view what = "the pose or the body velocity is not finite");
}  // namespace detail

/// Runs the trajectory: for n = 0 … steps at t_n, feet(t_n) → data.frame.q, q̇; spring support;
/// the law's balance → v_model; residual → v_model + B q̇; filter → v_body; slip (from v_model);
/// noise → measured pose; sink(step); pose ← pose · exp(v_body dt). Stops early when the pose or
/// v_body is not finite (summary.non_finite_step). Defined in trajectory_kernel.hpp. Throws
/// core::InputError for bad options, effects or data sizes.
template <class E>
TrajectorySummary integrate(const contact::Robot& robot, const FootKinematics& feet,
                            const TrajectoryOptions& options, E effects, TrajectoryData& data,
                            const TrajectorySink& sink);

/// The law × filter kernels (no residual, no noise), instantiated in trajectory.cpp.
template <class Law, class Filter>
TrajectorySummary integrate(const contact::Robot& robot, const FootKinematics& feet,
                            const TrajectoryOptions& options, const Law& law, Filter filter,
                            TrajectoryData& data, const TrajectorySink& sink) {
  Effects<Law, Filter> effects{};  // every other effect off
  effects.law = law;
  effects.filter = filter;
  return integrate(robot, feet, options, effects, data, sink);
}

extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&,
                                            Effects<ViscousCoulombKernel, NoFilter>,
                                            TrajectoryData&, const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&,
                                            Effects<ViscousCoulombKernel, IirFilter>,
                                            TrajectoryData&, const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&,
                                            Effects<CoulombKernel, NoFilter>, TrajectoryData&,
                                            const TrajectorySink&);
extern template TrajectorySummary integrate(const contact::Robot&, const FootKinematics&,
                                            const TrajectoryOptions&,
                                            Effects<CoulombKernel, IirFilter>, TrajectoryData&,
                                            const TrajectorySink&);

}  // namespace slipwalk::connection
