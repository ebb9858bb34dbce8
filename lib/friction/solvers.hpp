#pragma once
// Friction at the feet and the planar force/moment balance that gives the body velocity (thesis
// §3.4). All solvers work in the body frame: with body velocity v_b = (v_x, v_y) and yaw rate ω,
// foot k slides at  u_k = v_b + ω S q_xy,k + q̇_xy,k  (eq. 3.5 rotated by R_θᵀ, S = [0 −1; 1 0]);
// the planar force is F_k = H_k u_k and balance means Σ F_k = 0 and Σ M_z,k = Σ (q_xy,k × F_k)_z
// = Σ q_xy,kᵀ Sᵀ F_k = 0 (eqs. 3.16–3.18). They read frame.q, frame.qdot, frame.contact and
// frame.Fz (from contact::spring_support) and write frame.v_body, frame.Fxy and frame.friction. No
// allocation (a message string is written only for degenerate or failed solves). The derivation
// of the balance and where it corrects the thesis' printed matrices: friction/balance.hpp.
//
// Degenerate contact sets never give NaN: with no foot carrying friction v_body = 0; with all
// contacts at one point the rotation about it is undetermined and the least-norm solution in
// (v_x, v_y, L ω) (L the largest lever arm) is returned; both set friction.unique = false and say
// so in friction.message.
#include "contact/robot.hpp"

namespace slipwalk::friction {

/// Viscous-Coulomb ansatz with anisotropy (eqs. 3.14 with ε → ∞, 3.19): H_k = −μ_k F_z,k (I +
/// w_k w_kᵀ); the balance is a 3×3 linear solve (exact).
void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame);

/// solve_viscous_coulomb with an external planar wrench on the body, `load` = (F_x, F_y, M_z) in
/// the body frame (N, N, N m; M_z about the body origin), e.g. gravity's component along a slope
/// (terrain/terrain.hpp): the balance Σ F_k + f = 0, Σ M_z,k + M_z = 0 is M x = f − b, so the
/// body velocity is affine in q̇, v_body = A q̇ + M⁻¹ f (A of eq. 3.20 unchanged). With no foot
/// carrying friction, or all contacts at one point and a moment they cannot feel, no balance
/// exists: friction.converged = false and the message starts with "sliding".
void solve_viscous_coulomb_loaded(const contact::Robot& robot, contact::Frame& frame,
                                  const Eigen::Vector3d& load);

struct EpsilonOptions {
  double tol = 1e-12;  ///< stop after two Newton steps in a row change the scaled body velocity
                       ///< by less than tol · (‖v‖ + max ‖q̇_k‖), or when the balance holds to
                       ///< rounding; valid: > 0
  int max_iterations = 200;  ///< Newton steps; converged = false when reached
};

/// The ε-family of eq. 3.14, H_k = −μ_k F_z,k (ε + s_k)/(ε + s_k²) (I + w_k w_kᵀ) with
/// s_k = ‖W_k u_k‖, W_k = (I + w_k w_kᵀ)^{1/2} (= ‖u_k‖ for isotropic feet, as printed): ε → ∞
/// gives viscous-Coulomb, ε → 0 Coulomb (solve_coulomb's law, anisotropy included). Nonlinear in
/// v: Newton's method on the potential whose gradient is the balance, from the viscous-Coulomb
/// solution (see epsilon.cpp; the law is not convex for s_k > 1 + √(1 + ε), which the message
/// flags). ε = +∞ is solve_viscous_coulomb exactly; ε ≤ 0 or NaN throws core::InputError.
void solve_epsilon(const contact::Robot& robot, contact::Frame& frame, double epsilon,
                   const EpsilonOptions& options = {});

struct CoulombOptions {
  double tol = 1e-10;        ///< target of the certificate, the relative duality gap; valid: > 0
  int max_iterations = 500;  ///< Newton steps (fast path, smoothing path and polish together)
  bool fast_path = true;     ///< try Newton with the kink model first (friction/coulomb.cpp);
                             ///< false: the smoothing path alone (a reference for tests)
  bool warm_start = false;   ///< along a trajectory: start from what the previous solve left
                             ///< in the frame, v_body (if the dissipation is no higher there
                             ///< than at rest; else, NaN or absurd, the viscous start) and its
                             ///< static feet (work_idx; held if they certify) instead of the
                             ///< viscous-Coulomb velocity. Safe for any frame contents: the
                             ///< certificate does not depend on the start, which only costs
                             ///< iterations. false: independent frames, today's behaviour.
};

/// Classical Coulomb friction, F_k = −μ_k F_z,k u_k/‖u_k‖ (eq. 3.13; anisotropic: the friction
/// ellipse {F : Fᵀ G_k⁻¹ F ≤ (μ_k F_z,k)²} of eq. 3.19's G_k, F_k = −μ_k F_z,k G_k u_k/‖W_k u_k‖).
/// The balance is the optimality condition of minimizing the dissipation
/// D(v) = Σ μ_k F_z,k ‖W_k u_k(v)‖ over v = (v_x, v_y, ω), a convex, nonsmooth problem; feet with
/// u_k = 0 (static friction) carry any balancing force in their friction ellipse.
/// Always terminates (options.max_iterations); frame.Fxy are dual-feasible forces (balanced to
/// rounding, inside the ellipses) and friction.certificate is the relative duality gap
/// (D(v) − Σ F_k·(−q̇_k)) / max(D(v), D(0)) they prove; converged ⇔ certificate ≤ tol.
/// friction.unique is false when D is flat at the optimum (a continuum of velocities balances,
/// e.g. the even-N 1-D example of §3.1.2); friction.static_feet counts the feet that do not slip.
/// Algorithm and tolerances: friction/coulomb.cpp.
void solve_coulomb(const contact::Robot& robot, contact::Frame& frame,
                   const CoulombOptions& options = {});

/// Coulomb friction with an external planar wrench `load` = (F_x, F_y, M_z) on the body (body
/// frame, M_z about the origin; see solve_viscous_coulomb_loaded): minimizes the convex
///   Φ(v) = Σ μ_k F_z,k ‖W_k u_k(v)‖ − fᵀ v
/// (dissipation minus the load's power). Φ is bounded below iff f lies in the set of wrenches the
/// friction ellipses can hold, {Σ J_kᵀ F_k : F_k in ellipse k}; otherwise there is no
/// quasi-static balance and the robot slides: the solver returns v_body = 0, Fxy = 0,
/// converged = false, a message starting with "sliding", and friction.certificate = the
/// recession slope Σ μ_k F_z,k ‖W_k J_k d‖ − fᵀ d < 0 of a unit direction d that proves it.
/// Otherwise as solve_coulomb: Fxy balance the load to rounding and lie in their ellipses, and
/// certificate is the relative duality gap (D(v) − fᵀv − Σ F_k·(−q̇_k)) / max(D(v), D(0)). One
/// algorithm for both: solve_coulomb's, with the load's linear term in every pass and its
/// certificates anchored at a balanced point inside the ellipses (friction/coulomb.cpp, "The
/// load"). A load of exactly zero is solve_coulomb itself, bit for bit.
void solve_coulomb_loaded(const contact::Robot& robot, contact::Frame& frame,
                          const Eigen::Vector3d& load, const CoulombOptions& options = {});

}  // namespace slipwalk::friction
