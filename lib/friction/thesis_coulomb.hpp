#pragma once
// The thesis' own Coulomb solver (§3.5.1.3), as a peer to time ours against, not as a solver to
// use: "scipy.optimize.root with the LM algorithm, hot-starting with the solution of the previous
// time-step ... a sequence of smooth approximations to the solution starting from ε = 1e-5
// (eqn. 3.14), using each solution as an initial condition for another solution with smaller ε
// until the relative change in L2-norm of two consecutive solutions differed less than 1e-3".
// scipy's root(method="lm") is MINPACK's lmdif (Levenberg–Marquardt with a forward-difference
// Jacobian, ftol = xtol = 1.49012e-8); Eigen's unsupported NonLinearOptimization module is a
// port of the same MINPACK code, used here with its default tolerances, which are MINPACK's.
// The unknowns are (v_x, v_y, ω) and the residuals the ε-law's force and moment sums
// (friction/planar_forces.hpp), as a root finder on the balance sees them. The thesis does not
// say by what factor ε shrinks: a parameter. Unlike the solvers of friction/solvers.hpp this
// allocates (MINPACK's work arrays, as scipy's would) and certifies nothing.
#include <Eigen/Core>

#include "contact/robot.hpp"

namespace slipwalk::friction {

struct ThesisCoulombOptions {
  double eps_start = 1e-5;  ///< m/s, the first ε (§3.5.1.3)
  double eps_factor = 0.1;  ///< each next ε = eps_factor × the last (not stated); in (0, 1)
  double rel_change = 1e-3;  ///< stop when ‖v_j − v_{j−1}‖ ≤ rel_change ‖v_j‖ (§3.5.1.3)
  int max_eps_steps = 30;  ///< ε values at most; converged = false when reached
};

/// One ε solve of eq. 3.14's balance by MINPACK's Levenberg–Marquardt from `start` = (v_x, v_y,
/// ω); writes frame.v_body, frame.Fxy and frame.friction (iterations: function evaluations;
/// converged: MINPACK's own success; residual as the other solvers define it).
void solve_epsilon_thesis(const contact::Robot& robot, contact::Frame& frame, double epsilon,
                          const Eigen::Vector3d& start);

/// The sequence of ε solves of §3.5.1.3 from `start`, each from the last; frame.friction.
/// iterations counts the ε values solved.
void solve_coulomb_thesis(const contact::Robot& robot, contact::Frame& frame,
                          const Eigen::Vector3d& start, const ThesisCoulombOptions& options = {});

}  // namespace slipwalk::friction
