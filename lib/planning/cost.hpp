#pragma once
// The planner's cost (thesis §5.4.4): "a geodesic norm of translational and rotational
// distances" between an option's pose and the target pose. The thesis does not say which metric;
// we take the left-invariant Riemannian metric ds² = dx² + dy² + ρ² dθ² on SE(2) (world-frame
// coordinates x, y, θ). Its geodesics are straight lines in (x, y) traversed while θ turns
// uniformly, so the geodesic distance is in closed form:
//   d(a, b) = √(‖t_b − t_a‖² + ρ² wrap(θ_b − θ_a)²),
// wrap to (−π, π]: the shorter way round. ρ (m/rad) says how many metres of position error one
// radian of heading error is worth. The distance is a metric (a product of the Euclidean plane
// and the circle): symmetric, zero only for equal poses, with the triangle inequality; and
// invariant under a common rigid motion c of both poses, d(c·a, c·b) = d(a, b), since c rotates
// both translations alike and adds the same angle to both headings (tests/planning/test_cost.cpp).
#include <cmath>

#include "core/se2.hpp"

namespace slipwalk::planning {

/// The default ρ: 0.3 m per radian, BigANT's fore-aft spacing between legs, so that turning the
/// body by one radian about its centre moves the front and hind toes about as far as ρ.
inline constexpr double kDefaultRotationLength = 0.3;

/// d(a, b) above, with ρ = rotation_length (m/rad, ≥ 0).
[[nodiscard]] inline double se2_distance(const core::Pose2& a, const core::Pose2& b,
                                         double rotation_length) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double dtheta = rotation_length * core::wrap_angle(b.theta - a.theta);
  return std::sqrt(dx * dx + dy * dy + dtheta * dtheta);
}

}  // namespace slipwalk::planning
