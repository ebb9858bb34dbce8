#pragma once
// Friction at the feet and the planar force/moment balance that gives the body velocity (thesis
// §3.4). All solvers work in the body frame: with body velocity v_b = (v_x, v_y) and yaw rate ω,
// foot k slides at  u_k = v_b + ω S q_xy,k + q̇_xy,k  (eq. 3.5 rotated by R_θᵀ, S = [0 −1; 1 0]);
// the planar force is F_k = H_k u_k and balance means Σ F_k = 0 and Σ M_z,k = Σ (q_xy,k × F_k)_z
// = Σ q_xy,kᵀ Sᵀ F_k = 0 (eqs. 3.16–3.18). They read frame.q, frame.qdot, frame.contact and
// frame.Fz (from contact::spring_support) and write frame.v_body, frame.Fxy and frame.friction. No
// allocation.
#include "contact/robot.hpp"

namespace slipwalk::friction {

/// Viscous-Coulomb ansatz with anisotropy (eqs. 3.14 with ε → ∞, 3.19): H_k = −μ_k F_z,k (I +
/// w_k w_kᵀ); the balance is a 3×3 linear solve (exact).
void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame);

struct EpsilonOptions {
  double tol = 1e-12;  ///< relative change of the body velocity at which iteration stops
  int max_iterations = 200;
};

/// The ε-family of eq. 3.14, H_k = −μ_k F_z,k (ε + ‖u_k‖)/(ε + ‖u_k‖²) (times (I + w wᵀ)):
/// ε → ∞ viscous-Coulomb, ε → 0 Coulomb. Nonlinear in v; solved iteratively from the
/// viscous-Coulomb solution.
void solve_epsilon(const contact::Robot& robot, contact::Frame& frame, double epsilon,
                   const EpsilonOptions& options = {});

struct CoulombOptions {
  double tol = 1e-10;  ///< target of the optimality certificate (relative duality gap)
  int max_iterations = 500;
};

/// Classical Coulomb friction, F_k = −μ_k F_z,k u_k/‖u_k‖ (eq. 3.13): the balance is the
/// optimality condition of minimizing the total dissipation D(v) = Σ μ_k F_z,k ‖u_k(v)‖ over
/// v = (v_x, v_y, ω), a convex problem; feet with u_k = 0 carry any force in their friction disk.
/// Always terminates; frame.friction reports the certificate and whether the minimizer is unique.
void solve_coulomb(const contact::Robot& robot, contact::Frame& frame,
                   const CoulombOptions& options = {});

}  // namespace slipwalk::friction
