#pragma once
// The spring-support model (thesis §3.3, Alg. 1): which feet touch the ground and what each
// carries. Every leg is a vertical spring of stiffness K_j on a "body plane" with roll slope α,
// pitch slope β and height z; F_z,j = −K_j h_j for h_j < 0 (eq. 3.7). The search starts at the
// height z* where vertical force balance holds with α = β = 0 (§3.3.1), then follows segments in
// (α, β, z) toward the balance of the current contact set (eq. 3.9), stopping at the first contact
// change on the way (eq. 3.10), and tilts the body under gravity when the contacts cannot balance
// the moment (fewer than three feet, eqs. 3.11 and 3.12, or all contacts on one line).
//
// Oracle: the result is the minimizer of the convex potential
//   U(α, β, z) = Σ_j ½ K_j min(h_j, 0)² + Mg z,
// whose stationarity conditions are exactly ΣF_z = Mg and M_x = M_y = 0. U strictly decreases
// along the search path; the choices made where the thesis is silent or misprinted (eq. 3.9's
// matrix, the order and signs of eqs. 3.11/3.12, ties, termination) are derived in
// spring_support.cpp.
//
// Routes: by default an active-set Newton method on U is tried first (support_newton.cpp); it
// either certifies the unique minimizer, which is then the end of Alg. 1's path too, or hands
// over to Alg. 1. SupportSummary::route says which ran.
//
// Contact convention: a foot is in contact when h_j < 0 by more than the rounding error of h_j
// itself; a foot with h_j = 0 (exactly touching) is reported as not in contact, and its load is
// zero either way (F_z is continuous in h_j).
#include <vector>

#include "contact/robot.hpp"

namespace slipwalk::contact {

/// One point of the search path (for Figs. 3.3, 3.4 and for tests).
struct SupportStep {
  double alpha;
  double beta;
  double z;
  int contacts;  ///< feet in the search's contact set after this step
  int changed;   ///< the leg whose contact changed at this step, −1 at the start and the end
};

struct SupportOptions {
  /// Safety limit on contact changes. 0: the number of cells of the arrangement of the N contact
  /// planes h_j = 0 in (α, β, z) space, 1 + N + C(N,2) + C(N,3), which bounds the search in
  /// general position (each cell is visited at most once, see spring_support.cpp). Reaching it
  /// gives SupportSummary::Status::kIterationLimit.
  int max_iterations = 0;
  std::vector<SupportStep>* path = nullptr;  ///< if set, every visited state is appended
  /// Try the active-set Newton route first (contact/support_newton.hpp): a few vectorized passes
  /// over the feet, certified or rejected, with Alg. 1 as the fallback. Same result where it
  /// certifies (the unique minimizer of U); ignored when `path` is set, since only Alg. 1 has a
  /// path. false: always Alg. 1.
  bool newton = true;
  /// Start the Newton route from the frame's previous balance (frame.alpha, beta, z, where
  /// frame.support.status says kBalanced) and its contact set, instead of a cold start (the
  /// all-feet cell, or from 20 legs the level body's balance): along a trajectory the feet move
  /// little from frame to frame, the contact set is usually the previous one, and one step
  /// certifies (two from the cold start where a foot is lifted). The certificate is the same, so
  /// the result is the same minimizer to rounding (not to the bit: another route to it); where the
  /// warm start does not certify, the cold start runs. Ignored with `path` or without `newton`.
  bool warm_start = false;
};

/// The default iteration limit for n legs (see SupportOptions::max_iterations).
[[nodiscard]] int default_support_iterations(int n);

/// "balanced", "line", "point", "unsupported", "iteration-limit", "non-finite".
[[nodiscard]] const char* status_name(SupportSummary::Status status);

/// Fills frame.alpha, beta, z, contact, Fz and frame.support from frame.q. Never throws on
/// degenerate input (it is recorded in frame.support); throws core::InputError only through
/// check_frame for malformed frames (the outputs are then unspecified). Does not allocate (except
/// to append to options.path, and a message for an unusual status).
void spring_support(const Robot& robot, Frame& frame, const SupportOptions& options = {});

/// Makes the next warm-started spring_support of this frame start cold: for a frame that begins
/// a new trajectory, whose last balance is another one's (frame.alpha, beta and z are NaN until
/// the next search writes them).
void forget_balance(Frame& frame);

}  // namespace slipwalk::contact
