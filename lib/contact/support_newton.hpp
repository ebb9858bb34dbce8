#pragma once
// Internal to contact/: the fast route of the spring-support search (spring_support.hpp), an
// active-set (semismooth) Newton method on the convex potential U of spring_support.cpp. Each
// step is one vectorized pass over the feet; the answer is certified or rejected, never guessed.
#include "contact/robot.hpp"

namespace slipwalk::contact::detail {

// The certificate's constants, shared with the batched route (support_batch.cpp).
inline constexpr int kMaxSteps = 12;
inline constexpr double kDefiniteTol = 1e-10;  // λ_min(H̃) / tr(H̃) below this: leave it to the path
inline constexpr double kPolished = 1e-14;     // balance residual that needs no refinement
inline constexpr double kRoundingCap = 1e-10;  // a stalled refinement is accepted only below this
// A foot this many times the heights' rounding error or closer to its plane at the end may carry
// nothing at the balance and hold a tilt (a see-saw on a line of contacts with one foot exactly
// touching): the contact set is then not strictly complementary, the minimizer may not be unique,
// and the path search decides.
inline constexpr double kNearPlane = 1e3;

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
