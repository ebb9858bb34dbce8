#include "events/exact_backend.hpp"

namespace slipwalk::events {

double first_rising_root(double c0, double c1, double c2) {
  const double never = std::numeric_limits<double>::infinity();
  if (c0 >= 0.0) {
    // Already on or above the guard: fire now only if rising; otherwise wait for it to come back
    // down and rise again, which a quadratic does only if it first dips below zero (c2 > 0).
    if (c0 == 0.0 && c1 > 0.0) {
      return 0.0;
    }
    if (c0 > 0.0 && c1 > 0.0) {
      return 0.0;  // inconsistent start above a rising guard: fire at once rather than miss it
    }
  }
  if (c2 == 0.0) {
    if (c1 <= 0.0) {
      return never;
    }
    const double tau = -c0 / c1;
    return tau >= 0.0 ? tau : never;
  }
  const double disc = c1 * c1 - 4.0 * c2 * c0;
  if (disc <= 0.0) {
    return never;  // no crossing (a tangency is not a rise through zero)
  }
  // Stable roots: q = -(c1 + sgn(c1) sqrt(disc)) / 2, roots q/c2 and c0/q.
  const double sq = std::sqrt(disc);
  const double q = -0.5 * (c1 + std::copysign(sq, c1));
  double r1 = q / c2;
  double r2 = q != 0.0 ? c0 / q : r1;
  if (r1 > r2) {
    std::swap(r1, r2);
  }
  // The rising crossing of a quadratic: the larger root if c2 > 0, the smaller if c2 < 0.
  const double rising = c2 > 0.0 ? r2 : r1;
  return rising >= 0.0 ? rising : never;
}

}  // namespace slipwalk::events
