#pragma once
// The spring-support model (thesis §3.3, Alg. 1): which feet touch the ground and what each
// carries. Every leg is a vertical spring of stiffness K_j on a "body plane" with roll slope α,
// pitch slope β and height z; F_z,j = −K_j h_j for h_j < 0 (eq. 3.7). The search starts at the
// height z* where vertical force balance holds with α = β = 0 (§3.3.1), then follows segments in
// (α, β, z) toward the balance of the current contact set (eq. 3.9), stopping at the first contact
// change on the way (eq. 3.10), and tilts the body under gravity when fewer than three feet touch
// (eqs. 3.11, 3.12).
//
// Oracle: the result is the minimizer of the convex potential
//   U(α, β, z) = Σ_j ½ K_j min(h_j, 0)² + Mg z,
// whose stationarity conditions are exactly ΣF_z = Mg and M_x = M_y = 0.
#include <vector>

#include "contact/robot.hpp"

namespace slipwalk::contact {

/// One point of the search path (for Figs. 3.3, 3.4 and for tests).
struct SupportStep {
  double alpha;
  double beta;
  double z;
  int contacts;  ///< feet in contact after this step
  int changed;   ///< the leg whose contact changed at this step, −1 at the start and the end
};

struct SupportOptions {
  int max_iterations = 0;                    ///< 0: a bound proven sufficient for N legs (see .cpp)
  std::vector<SupportStep>* path = nullptr;  ///< if set, every visited state is appended
};

/// Fills frame.alpha, beta, z, contact, Fz and frame.support from frame.q. Never throws on
/// degenerate input (it is recorded in frame.support); throws core::InputError only through
/// check_frame for malformed frames.
void spring_support(const Robot& robot, Frame& frame, const SupportOptions& options = {});

}  // namespace slipwalk::contact
