#include "inchworm/instant_swap.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace slipwalk::inchworm {

InstantSwapSystem::InstantSwapSystem(const Params& p) : p_(p), stroke_(p) {}

events::ModeFlow<2, 3> InstantSwapSystem::flow(Mode mode) const {
  events::ModeFlow<2, 3> f;
  f.accel << stroke_.accel_x(mode.slide_m), stroke_.accel_y(mode.slide_M);
  f.n_guards = stroke_.add_guards(f, 0, mode.slide_m, mode.slide_M, mode.side);
  return f;
}

InstantSwapSystem::Mode InstantSwapSystem::reset(Mode mode, int guard_id, StateType& x) const {
  switch (guard_id) {
    case kSmallStops:
      x(2) = 0.0;  // snap: the guard located v = 0 up to round-off
      mode.slide_m = stroke_.rest_x();
      return mode;
    case kLargeStops:
      x(3) = 0.0;
      mode.slide_M = stroke_.rest_y();
      return mode;
    case kLengthLimit: {
      // eq. 2.4: perfectly plastic collision, then the masses swap positions (§2.2.1).
      const double v = com_velocity(x);
      const double x_pos = x(0);
      x(0) = x(1);
      x(1) = x_pos;
      x(2) = v;
      x(3) = v;
      return mode_of(x, static_cast<std::int8_t>(-mode.side));
    }
    default:
      throw core::ComputationError("InstantSwapSystem: unknown guard id " +
                                   std::to_string(guard_id));
  }
}

InstantSwapSystem::Mode InstantSwapSystem::mode_of(const StateType& x, std::int8_t side) const {
  auto direction = [](double v, std::int8_t at_rest) -> std::int8_t {
    if (v > 0.0) {
      return 1;
    }
    if (v < 0.0) {
      return -1;
    }
    return at_rest;
  };
  return {direction(x(2), stroke_.rest_x()), direction(x(3), stroke_.rest_y()), side};
}

InstantSwapSystem::StateType InstantSwapSystem::rest_state() const {
  StateType x;
  // x − y = L_min with the CoM at the origin.
  const double total = p_.m + p_.M;
  x << p_.M / total * p_.L_min, -p_.m / total * p_.L_min, 0.0, 0.0;
  return x;
}

}  // namespace slipwalk::inchworm
