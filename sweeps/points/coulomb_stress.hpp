#pragma once
// Random stress frames for the Coulomb solver (friction::solve_coulomb, thesis §3.4, eq. 3.13)
// and an oracle for its answers that shares no code with it. Used by the long run of the solver
// (point kind coulomb_long_run, coulomb_long_run.cpp) and by
// tests/friction/test_coulomb_stress.cpp.
//
// Frame `index` of stream `seed` is drawn from its own random stream (sweeps::Random(seed,
// index)), so any frame can be rebuilt alone from (seed, index), whatever the chunking of a run.
// A frame mixes independent choices:
//  * legs 3..50 (half of the frames 3..8), a layout of the feet (general position, all on one
//    line, nearly on one line, pairs of coincident feet, all at one point, equally spaced on a
//    circle — the thesis' disk robot of §3.5.3 —, mirror-symmetric about the x axis) at a size
//    of 1 cm .. 10 m;
//  * loads either through the spring-support search (contact::spring_support, §3.3: feet at
//    heights jittered around the body's static sinkage, some lifted) or set directly (a random
//    subset of feet in contact, F_z spread over six decades);
//  * foot velocities: general, the body at rest (all zero), some feet exactly zero, a rigid
//    motion of the feet (no foot slips: every u_k = 0 at the answer), along one direction (the
//    1-D flat minimum of §3.1.2 on a line of feet), mirror-symmetric; speeds 1e-4 .. 10 m/s;
//  * friction μ in [1e-6, 1e3] (one value or one per foot, some feet μ = 0), stiffness K in
//    [1e-3, 1e9] N/m, weight Mg in [0.1, 1e4] N, anisotropy w (eq. 3.19) on half of the robots
//    with ‖w‖ in [1e-3, 10].
// Every robot passes contact::validate; make_stress_frame throws core::InputError otherwise
// (a generator bug, counted by the long run).
#include <cstdint>
#include <string_view>

#include "contact/robot.hpp"

namespace slipwalk::sweeps::stress {

enum class Layout { kGeneral, kLine, kNearLine, kCoincident, kOnePoint, kCircle, kMirror };
enum class Motion { kGeneral, kRest, kSomeZero, kRigid, kAlongLine, kMirror };
enum class Loads { kSupport, kDirect };

inline constexpr int kLayouts = 7;
inline constexpr int kMotions = 6;

[[nodiscard]] std::string_view layout_name(Layout layout);
[[nodiscard]] std::string_view motion_name(Motion motion);

/// A generated frame: the robot, the frame with q, qdot, contact and Fz filled in, and what was
/// drawn.
struct StressFrame {
  contact::Robot robot;
  contact::Frame frame;
  Layout layout = Layout::kGeneral;
  Motion motion = Motion::kGeneral;
  Loads loads = Loads::kDirect;
};

/// Frame `index` of stream `seed` (see the file comment). Throws core::InputError if the robot
/// it drew fails contact::validate.
[[nodiscard]] StressFrame make_stress_frame(std::uint64_t seed, std::uint64_t index);

/// An independent check of a solved frame: the balanced forces in the friction ellipses prove a
/// lower bound on the dissipation, D(v') ≥ Σ_k F_k·(−q̇_k) for every v' (weak duality, §3.4), so
/// D(v) minus that bound, relative to max(D(v), D(0)), is the true optimality gap of the
/// reported body velocity. Computed per foot as c_k ‖W_k u_k‖ + F_k·u_k ≥ 0 (no cancellation
/// between feet) plus the work of the force and moment imbalance.
struct OracleCheck {
  bool finite = true;      ///< v_body, Fxy, certificate and residual are all finite
  double gap = 0.0;        ///< relative optimality gap proven by the reported forces
  double imbalance = 0.0;  ///< max(‖ΣF‖/F, |ΣM_z|/(F L)), F = Σ c_k √(1 + ‖w_k‖²)
  double outside = 0.0;  ///< max_k F_kᵀ G_k⁻¹ F_k / c_k² − 1 (≤ 0: every force in its ellipse)
  double idle_force = 0.0;  ///< max ‖F_k‖ / F over feet without friction (must be 0)
  double rounding = 0.0;    ///< the rounding of the gap's sums, relative like gap: 8 ε Σ_k c_k
                          ///< √(1 + ‖w_k‖²) (‖v_b‖ + |ω| ‖q_k‖ + ‖q̇_k‖) / max(D(v), D(0))
  double weight_decades = 0.0;  ///< log₁₀(max c_k / min c_k) over the feet with friction
  double dissipation = 0.0;     ///< D(v) at the reported body velocity
  double d0 = 0.0;              ///< D(0)
};

/// D(v) = Σ_k μ_k F_z,k ‖W_k u_k(v)‖ over the feet in contact, v = (v_x, v_y, ω) (eq. 3.13).
[[nodiscard]] double dissipation(const contact::Robot& robot, const contact::Frame& frame,
                                 const Eigen::Vector3d& v);

[[nodiscard]] OracleCheck check_coulomb(const contact::Robot& robot, const contact::Frame& frame);

}  // namespace slipwalk::sweeps::stress
