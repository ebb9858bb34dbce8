#pragma once
// Internal to contact/: the fast route of the spring-support search (spring_support.hpp), an
// active-set (semismooth) Newton method on the convex potential U of spring_support.cpp. Each
// step is one vectorized pass over the feet; the answer is certified or rejected, never guessed.
#include "contact/robot.hpp"

namespace slipwalk::contact::detail {

/// Tries the Newton route. Returns true when it certified the global minimizer of U: the contact
/// set read off the feet's heights did not change over the last step, ∇U = 0 to rounding on that
/// set, and the cell's Hessian is safely nonsingular (three or more contacts off a line), so the
/// minimizer is unique and equals the end of Alg. 1's path; it certifies only feet within
/// limits::kPosition (tested on its first pass: the caller's check_frame need not test q first).
/// Then frame.alpha, beta, z, contact, Fz and support.residual, iterations, newton_steps, route are
/// written (status kBalanced). Returns false otherwise (a cell with fewer than three contacts off a
/// line, a cycling contact set, too many steps, a foot at its plane at the end):
/// frame.support.newton_steps says how far it got; contact and Fz may be written, and all outputs
/// are the path search's to write. Uses frame.support_newton as scratch; does not allocate.
bool support_by_newton(const Robot& robot, Frame& frame);

/// The same from the state v0 = (α, β, z) of a previous balance (SupportOptions::warm_start): the
/// start cell is the feet below its plane there. Where that start does not certify, the cold
/// start above follows (support.newton_steps counts both).
bool support_by_newton_warm(const Robot& robot, Frame& frame, const Eigen::Vector3d& v0);

}  // namespace slipwalk::contact::detail
