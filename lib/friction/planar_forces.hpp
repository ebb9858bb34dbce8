#pragma once
// The planar friction forces of the feet, and their sum, at a prescribed body velocity (thesis
// §3.4: eqs. 3.13, 3.14 and 3.19). The solvers of friction/solvers.hpp find the one velocity at
// which this sum vanishes; this evaluates it anywhere: force maps over a grid of body velocities
// (Fig. 3.2), the residual of a balance computed by another method, the error of one law
// against another (Fig. 3.15). Body frame and notation as in friction/balance.hpp:
//   u_k = v + ω S q_k + q̇_k,   S = [0 −1; 1 0],   G_k = I + w_k w_kᵀ,   c_k = μ_k F_z,k,
//   s_k = ‖W_k u_k‖ = √(u_kᵀ G_k u_k)   (W_k = G_k^{1/2}),
//   F_k = −c_k φ(s_k) G_k u_k  with φ = 1 (viscous-Coulomb), 1/s (Coulomb), (ε + s)/(ε + s²) (ε).
#include <Eigen/Core>
#include <limits>

#include "contact/robot.hpp"

namespace slipwalk::friction {

/// The friction laws of §3.4, each named after the solver that balances it.
enum class ForceLaw {
  kViscousCoulomb,  ///< eqs. 3.14 with ε → ∞ and 3.19, F = −c G u (solve_viscous_coulomb)
  kCoulomb,         ///< eq. 3.13 with eq. 3.19's ellipse, F = −c G u / s (solve_coulomb)
  kEpsilon,         ///< eq. 3.14, F = −c (ε + s)/(ε + s²) G u (solve_epsilon)
};

/// The planar force of foot k when it slides at u (body frame, m/s) under `law`; ε (m/s) is read
/// for ForceLaw::kEpsilon only: ε = +∞ is the viscous-Coulomb force, ε ≤ 0 or NaN throws
/// core::InputError. The Coulomb force of a foot with u = 0 is set-valued (any force in its
/// friction ellipse); this returns its centre, 0. Does not look at frame.contact.
[[nodiscard]] Eigen::Vector2d foot_force(const contact::Robot& robot, const contact::Frame& frame,
                                         int k, const Eigen::Vector2d& u, ForceLaw law,
                                         double epsilon = std::numeric_limits<double>::infinity());

/// Σ F_k and Σ (q_k × F_k)_z over the feet.
struct PlanarSum {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();  ///< N, body frame
  double moment = 0.0;                              ///< N m, about the body origin
};

/// Σ F_k and Σ (q_k × F_k)_z over the feet in contact (frame.contact, loads frame.Fz, e.g. from
/// contact::spring_support) when the body moves at v = (v_x, v_y) (m/s) and yaw rate ω (rad/s),
/// in the body frame, each foot's force by foot_force(). At the velocity a solver of
/// friction/solvers.hpp returns for the same law both vanish (Coulomb: unless a foot sticks,
/// whose force foot_force() does not know). Reads q, qdot, contact and Fz; writes nothing and
/// does not allocate.
[[nodiscard]] PlanarSum planar_forces(const contact::Robot& robot, const contact::Frame& frame,
                                      const Eigen::Vector2d& v, double omega, ForceLaw law,
                                      double epsilon = std::numeric_limits<double>::infinity());

}  // namespace slipwalk::friction
