#pragma once
// The multi-legged model of thesis ch. 3 (§3.2): a Robot (model: constants of the legs) and a
// Frame (data: one evaluation's inputs, outputs and scratch), in the Pinocchio/MuJoCo split of
// DESIGN.md. Algorithms are free functions f(const Robot&, Frame&, ...) in contact/, friction/ and
// connection/; none allocates once a Frame exists.
//
// Frames and conventions (DESIGN.md, frame format): body frame x forward, y left, z up; SI units.
// A foot below the body has q_z < 0. With roll slope α, pitch slope β and body height z, a foot's
// height above the ground is  h_j = −β q_x,j + α q_y,j + q_z,j + z  (eq. 3.6); h_j < 0 means the
// foot's spring is compressed and it is in contact.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "core/range.hpp"

namespace slipwalk::contact {

/// The admissible inputs of the model (validate(), check_frame(), the frame reader). They are
/// generous for any legged robot, and chosen so that every intermediate quantity of the spring
/// support (§3.3) and the friction solvers (§3.4) stays finite and normal in double precision:
///  - spring support (eqs. 3.6-3.9): the start z* = −(Σ K q_z + Mg)/Σ K (§3.3.1) and every later
///    height are at most |q| + Mg/K_min ≤ 1e3 + 1e7/1e-3 ≈ 1e10 m; a load K h ≤ 1e9 · 1e10 =
///    1e19 N, a moment q F ≤ 1e22 N m, U = ½ K h² ≤ 1e29 J, the Hessian Σ K a aᵀ over 1e5 legs
///    ≤ 1e14 N/m and its 3 × 3 determinants ≤ 1e42; the smallest compression Mg/Σ K ≥
///    1e-6/(1e5 · 1e9) = 1e-20 m is still normal, and the residuals divide by Mg ≥ 1e-6 N.
///  - friction (eqs. 3.12-3.19): a foot's weight c = μ F_z ≤ 1e2 · 1e19 = 1e21 N, its metric
///    ‖I + w wᵀ‖ ≤ 1 + 2e6, lever arms ≤ √2 · 1e3 m, slip speeds ≤ ~1e7 m/s, so the Coulomb
///    solver's squared residuals (c ‖W‖ ‖u‖)² ≤ ~1e80 and the cubes of its Hessian ≤ ~1e120.
///    μ is 0 (no friction) or at least 1e-6: a μ near the smallest doubles makes c subnormal and
///    1/c² (the Coulomb solver's scaling) infinite.
/// Values outside these ranges are refused as bad input (core::InputError) with the range named.
namespace limits {
inline constexpr int kMaxLegs = 100000;  ///< legs of one robot (a JSON frame of ~25 MB)
inline constexpr core::Range kStiffness = core::closed(1e-3, 1e9, "N/m");  ///< K_j
inline constexpr core::Range kFriction = core::closed(1e-6, 1e2);          ///< μ_j when not 0
inline constexpr core::Range kAnisotropy = core::closed(-1e3, 1e3);        ///< each w_j entry
inline constexpr core::Range kWeight = core::closed(1e-6, 1e7, "N");       ///< Mg
inline constexpr core::Range kPosition = core::closed(-1e3, 1e3, "m");     ///< each q entry
inline constexpr core::Range kVelocity = core::closed(-1e3, 1e3, "m/s");   ///< each q̇ entry
inline constexpr core::Range kYaw = core::closed(-1e6, 1e6, "rad");  ///< θ (sin/cos to ~1e-10)
}  // namespace limits

/// Constants of a legged robot. Every leg is a vertical spring with Coulomb-type friction.
struct Robot {
  Eigen::VectorXd K;   ///< (N) leg spring stiffness, N/m; valid: limits::kStiffness
  Eigen::VectorXd mu;  ///< (N) friction coefficient; valid: 0 or limits::kFriction
  Eigen::Matrix2Xd w;  ///< (2 x N) anisotropy: enhanced-traction direction × magnitude in the
                       ///< body frame (eq. 3.19, H ∝ I + w wᵀ); zero = isotropic; valid:
                       ///< limits::kAnisotropy
  double Mg = 1.0;     ///< N, total weight carried by the legs; valid: limits::kWeight

  [[nodiscard]] int legs() const { return static_cast<int>(K.size()); }
  /// Whether every foot's w is zero (G = I: the friction passes' isotropic kernels apply).
  [[nodiscard]] bool isotropic() const;
};

/// A robot with n legs, all with stiffness K, friction μ, isotropic.
[[nodiscard]] Robot uniform_robot(int n, double K = 1.0, double mu = 1.0, double Mg = 1.0);

/// Throws core::InputError ("K[3]: must be in [0.001, 1000000000] N/m, got -1") for sizes that
/// disagree, more than limits::kMaxLegs legs, values out of the ranges of `limits` and
/// non-numbers.
void validate(const Robot& robot);

/// Throws core::InputError(where, ...) unless μ is 0 or in limits::kFriction.
void require_friction(const std::string& where, double mu);

/// What the spring-support search did (§3.3, Alg. 1; contact/spring_support.hpp).
struct SupportSummary {
  enum class Status {
    kBalanced,        ///< force and moment balance with ≥ 3 contacts not on one line; the state
                      ///< is the unique balance of its contact set
    kLine,            ///< balanced on contacts along one line (two feet, or more in a row) with
                      ///< the CoM on that line: z and loads are determined, the tilt about the
                      ///< line is not; reported is the least |(α, β)| that keeps the other feet
                      ///< off the ground
    kPoint,           ///< balanced on contacts at one point under the CoM (e.g. one foot): z and
                      ///< loads determined, tilt moved toward zero as far as the other feet allow
    kUnsupported,     ///< no balance exists: the CoM is outside the support polygon of all feet
                      ///< and the robot tips over (U is unbounded below). The state is where the
                      ///< unbounded tilt starts: vertical balance holds there, moment balance not
    kIterationLimit,  ///< safety stop after SupportOptions::max_iterations contact changes (not
                      ///< reached in general position; see contact/spring_support.cpp)
    kNonFinite,       ///< the search ended on a state or loads that are not finite (inputs
                      ///< outside the ranges of `limits`): no result, never a balance
  };
  /// Which algorithm produced the state (contact/spring_support.hpp).
  enum class Route {
    kNewton,  ///< the active-set Newton route on U, certified (consistent contact set, U's
              ///< gradient zero to rounding, nonsingular cell)
    kPath,    ///< Alg. 1's path-following search (asked for, or the Newton route did not certify)
  };
  Status status = Status::kBalanced;
  Route route = Route::kPath;
  int iterations = 0;     ///< contact changes: along Alg. 1's path (kPath), or summed over the
                          ///< Newton route's successive contact sets (kNewton)
  int newton_steps = 0;   ///< Newton steps the Newton route took (also when it then fell back)
  double residual = 0.0;  ///< max(|ΣF_z − Mg|/Mg, |M_x|/(Mg·L), |M_y|/(Mg·L)) at the end, with
                          ///< L = max_j |q_xy,j| the robot's horizontal size
  std::string message;    ///< empty unless something noteworthy happened
};

/// What a friction solve did (§3.4).
struct FrictionSummary {
  /// Coulomb (friction::solve_coulomb, solve_coulomb_loaded): which of the solver's routes gave
  /// the answer (friction/coulomb.cpp); the other laws leave it as it is.
  enum class Route {
    kDirect,    ///< no Newton step: no friction, nothing moves, or the viscous start certified
    kFastPath,  ///< Newton with the kink model (the fast path)
    kPath,      ///< the smoothing path, the fast path not tried (a foot at rest at the start,
                ///< fast_path = false, or a load near its holding limit with no balanced
                ///< dual inside the disks yet)
    kFallback,  ///< the smoothing path after the fast path stalled (a restart from the start)
  };
  bool converged = true;  ///< false when the solve failed, also whenever v_body, the forces or
                          ///< the residual came out non-finite (checked at the end of every solve)
  Route route = Route::kDirect;
  int iterations = 0;     ///< 0 for the direct (viscous-Coulomb) solve
  double residual = 0.0;  ///< planar balance residual max(‖ΣF‖/F, |ΣM_z|/(F L)), F = the size
                          ///< of the cancelling terms (Coulomb: Σ μF_z‖W‖; viscous: Σ μF_z‖G‖
                          ///< (‖q̇‖ + ‖J x‖)), L = the largest lever arm of a foot in contact
  double certificate = 0.0;  ///< Coulomb: relative duality gap (D(v) − dual)/max(D(v), D(0)) of
                             ///< balanced forces in the friction disks; 0 otherwise
  bool unique = true;        ///< false when the balance has a continuum of body velocities
                             ///< (< 2 distinct contact points, or a flat minimum of D)
  int static_feet = 0;       ///< Coulomb: feet in contact that do not slip (u_k = 0)
  double dissipation = 0.0;  ///< −Σ F_k·u_k, the power the feet dissipate (Coulomb: W; the
                             ///< viscous laws: in their own units, F = −μF_z u)
  std::string message;       ///< empty unless something noteworthy happened
};

/// Per-foot quantities as rows: one column per foot, padded with zero columns to a count N̄ of
/// feet that is a multiple of four, so that a pass over the feet handles four feet per step (one
/// AVX register, two SSE2 registers; core/lanes.hpp) with no remainder (a struct of arrays).
using FootRow = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor>;
template <int kRows>
using FootRows = Eigen::Matrix<double, kRows, Eigen::Dynamic, Eigen::RowMajor>;

/// One 64-bit flag per foot, a pass's lane mask (core::Lanes<4>::M) stored as it is.
using FootFlags = Eigen::Matrix<std::int64_t, 1, Eigen::Dynamic, Eigen::RowMajor>;

/// N rounded up to a multiple of four: the column count of FootRow and FootRows.
[[nodiscard]] constexpr int padded_feet(int legs) { return (legs + 3) / 4 * 4; }
/// N rounded up to even: the column count of the Coulomb solver's rows (CoulombScratch), whose
/// passes take two feet per step (Eigen::Array2d) and pad with at most one foot.
[[nodiscard]] constexpr int padded_pairs(int legs) { return (legs + 1) / 2 * 2; }

/// Scratch of the spring-support Newton route (contact/support_newton.cpp, §3.3): the feet's
/// coordinates in the plane of (α, β, z) and their contact flags, each (1 x N̄). The padding
/// foot sits far above the ground with K = 0.
struct SupportNewtonScratch {
  explicit SupportNewtonScratch(int legs);
  FootRow qy;        ///< q_y,j, m: the coefficient of α in the height h_j (eq. 3.6)
  FootRow minus_qx;  ///< −q_x,j, m: the coefficient of β in h_j
  FootRow qz;        ///< q_z,j, m
  FootRow K;         ///< K_j, N/m
  FootFlags on;      ///< all ones (−1) where foot j was in contact (h_j < 0) at the last pass,
                     ///< else 0: the pass's lane mask as it is

  /// Whether every row has the same count of columns, a multiple of four, at least `legs`.
  [[nodiscard]] bool holds(int legs) const {
    const Eigen::Index n = qy.cols();
    return n >= legs && n % 4 == 0 && minus_qx.cols() == n && qz.cols() == n && K.cols() == n &&
           on.cols() == n;
  }
};

/// Scratch of the Coulomb solver (friction::solve_coulomb, friction/coulomb_solver.hpp): the
/// per-foot constants of the dissipation D(y) = Σ_k ‖B_k y + d_k‖ in the scaled coordinates
/// y = (v_x, v_y, L ω) of friction/balance.hpp, and the solver's per-foot state. Each member is
/// (rows x N̄), N̄ = padded_pairs(N); a foot without friction and the padding foot have zero
/// columns.
struct CoulombScratch {
  explicit CoulombScratch(int legs);
  FootRows<6> B;        ///< B_k = c_k W_k J̃_k (2 x 3), N, column-major down the rows:
                        ///< B₀₀ B₁₀ B₀₁ B₁₁ B₀₂ B₁₂
  FootRows<2> d;        ///< d_k = c_k W_k q̇_k, N m/s
  FootRow active;       ///< 1.0 for a foot with friction (c_k > 0), else 0.0: the feet a full
                        ///< pass visits
  FootRow sliding;      ///< 1.0 for a foot the current active set lets slide, else 0.0: the feet
                        ///< a polish pass visits
  FootRow r2;           ///< ‖r_k‖² = ‖B_k y + d_k‖² at the last pass's y, (N m/s)²
  FootRow weight;       ///< c_k = μ_k F_z,k, N
  FootRow inv_weight2;  ///< 1 / c_k², N⁻²

  /// Whether the members have the column count of a frame with `legs` feet.
  [[nodiscard]] bool fits(int legs) const { return B.cols() == padded_pairs(legs); }
};

/// Scratch of the viscous balance (friction/viscous_system.hpp, thesis eq. 3.20): the feet's
/// planar inputs and weights as rows, written by the assembly pass so that the passes after it
/// (the forces, the columns of A) read them contiguously, the forces four feet at a time. Each row
/// (1 x N̄); the padding foot has a zero column (c = 0: it adds exact zeros to every sum).
struct ViscousScratch {
  explicit ViscousScratch(int legs);
  enum Row : int {
    kQx = 0,  ///< q_x,k, m
    kQy,      ///< q_y,k, m
    kQdx,     ///< q̇_x,k, m/s
    kQdy,     ///< q̇_y,k, m/s
    kC,       ///< c_k = μ_k F_z,k, N (0 for a foot in the air or without friction)
    kRows
  };
  FootRows<kRows> rows;

  /// Whether the rows have the column count of a frame with `legs` feet.
  [[nodiscard]] bool fits(int legs) const { return rows.cols() == padded_feet(legs); }
};

/// One evaluation of the model: inputs, outputs ("computed by ..."), scratch.
struct Frame {
  explicit Frame(const Robot& robot);

  // ---- inputs -------------------------------------------------------------------------------
  Eigen::Matrix3Xd q;     ///< (3 x N) foot positions in the body frame, m
  Eigen::Matrix3Xd qdot;  ///< (3 x N) foot velocities in the body frame, m/s (z unused)
  double theta = 0.0;     ///< yaw, rad (world-frame outputs rotate by it)

  // ---- computed by contact::spring_support (§3.3) -------------------------------------------
  double alpha = 0.0;         ///< roll slope (eq. 3.6)
  double beta = 0.0;          ///< pitch slope (eq. 3.6)
  double z = 0.0;             ///< body height, m (eq. 3.6)
  std::vector<char> contact;  ///< (N) 1 if the foot is on the ground (h_j < 0; h_j = 0 is not)
  Eigen::VectorXd Fz;         ///< (N) normal loads, N (eq. 3.7); 0 for feet in the air
  SupportSummary support;

  // ---- computed by friction:: solvers and connection::local_connection (§3.4) ---------------
  Eigen::Vector3d v_body = Eigen::Vector3d::Zero();  ///< (v_x, v_y, ω_z): R_θᵀ ṗ_xy,0 and θ̇
  Eigen::Matrix2Xd Fxy;  ///< (2 x N) planar foot forces in the body frame, N
  Eigen::MatrixXd A;     ///< (3 x 2N) local connection, eq. 3.20: v_body = A · vec(q̇_xy)
  FrictionSummary friction;

  // ---- scratch (sized once here; algorithms may use it freely) ------------------------------
  Eigen::VectorXd work_n;     ///< (N) friction/: c_k or the α_k of W_k (friction/balance.hpp)
  Eigen::Matrix2Xd work_2n;   ///< (2 x N) friction/: the Coulomb duals λ_k, or ‖W_k u_k‖
  std::vector<int> work_idx;  ///< (N) friction/: the Coulomb feet's states, static marks
  SupportNewtonScratch support_newton;  ///< contact::spring_support's Newton route
  ViscousScratch viscous;               ///< friction::ViscousSystem (isotropic robots)
  CoulombScratch coulomb;               ///< friction::solve_coulomb

  [[nodiscard]] int legs() const { return static_cast<int>(q.cols()); }
};

/// The height of foot j above the ground at (alpha, beta, z), eq. 3.6.
[[nodiscard]] inline double foot_height(const Frame& f, int j, double alpha, double beta,
                                        double z) {
  return -beta * f.q(0, j) + alpha * f.q(1, j) + f.q(2, j) + z;
}

/// Throws core::InputError if the frame's sizes do not match the robot or an input is outside
/// limits::kPosition, kVelocity or kYaw (non-finite included). One vectorized test per matrix.
void check_frame(const Robot& robot, const Frame& frame);

/// check_frame without the range test of q: for a caller whose first pass over q tests that range
/// on the way and calls check_frame where it fails (the spring support's Newton route, which
/// certifies only feet within limits::kPosition).
void check_frame_except_positions(const Robot& robot, const Frame& frame);

}  // namespace slipwalk::contact
