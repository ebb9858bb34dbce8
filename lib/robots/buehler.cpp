#include "robots/buehler.hpp"

#include <cmath>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/range.hpp"

namespace slipwalk::robots {

namespace {

struct Unwrapped {
  double phi;
  double rate;
  bool stance;
};

/// Counts cycles from the touchdown before s: w = s + D/2 has its integer part at touchdowns.
Unwrapped unwrapped(const ClockShape& c, double s) {
  const double w = s + 0.5 * c.duty;
  const double n = std::floor(w);
  const double f = w - n;  // in [0, 1): time since touchdown, cycles
  if (f < c.duty) {
    const double tau = f / c.duty;
    if (c.cubic) {
      return {n + c.center - 0.5 * c.sweep + c.sweep * tau * tau * (3.0 - 2.0 * tau),
              6.0 * c.sweep * tau * (1.0 - tau) / c.duty, true};
    }
    return {n + c.center - 0.5 * c.sweep + c.sweep * tau, c.sweep / c.duty, true};
  }
  const double rho = (f - c.duty) / (1.0 - c.duty);
  return {n + c.center + 0.5 * c.sweep + (1.0 - c.sweep) * rho, (1.0 - c.sweep) / (1.0 - c.duty),
          false};
}

}  // namespace

void validate(const ClockShape& c, const char* where) {
  const std::string w(where);
  core::require_in(w + ".duty", c.duty, core::Range{0.0, 1.0, true, true, ""});
  core::require_in(w + ".sweep", c.sweep, core::Range{0.0, 1.0, false, true, "turns"});
  // The phase s + D/2 and its floor stay exact to ~1e-10 turns for |center| ≤ 1e6.
  core::require_in(w + ".center", c.center, core::closed(-1e6, 1e6, "turns"));
}

ClockState clock_at(const ClockShape& shape, double s) {
  const Unwrapped u = unwrapped(shape, s);
  return {u.phi - std::floor(u.phi), u.rate, u.stance};
}

double clock_unwrapped(const ClockShape& shape, double s) { return unwrapped(shape, s).phi; }

}  // namespace slipwalk::robots
