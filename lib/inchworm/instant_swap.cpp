#include "inchworm/instant_swap.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace slipwalk::inchworm {

InstantSwapSystem::InstantSwapSystem(const Params& p) : p_(p) {
  const double fm = p.mu * p.m * p.g;  // dynamic friction magnitude on m
  const double fM = p.mu * p.M * p.g;  // on M
  // Differences are formed before dividing so that F close to μmg keeps its digits (Sterbenz).
  accel_m_[0] = (p.F + fm) / p.m;
  accel_m_[1] = 0.0;
  accel_m_[2] = (p.F - fm) / p.m;
  accel_M_[0] = -(p.F - fM) / p.M;
  accel_M_[1] = 0.0;
  accel_M_[2] = -(p.F + fM) / p.M;
  rest_m_ = p.F > p.static_mu() * p.m * p.g ? 1 : 0;
  rest_M_ = p.F > p.static_mu() * p.M * p.g ? -1 : 0;
}

events::ModeFlow<2, 3> InstantSwapSystem::flow(Mode mode) const {
  events::ModeFlow<2, 3> f;
  f.accel << accel_m_[mode.slide_m + 1], accel_M_[mode.slide_M + 1];
  int n = 0;
  // A sliding mass's guard: its velocity reaches zero (g = −v·slide rises through 0).
  if (mode.slide_m != 0) {
    auto& g = f.guard[n++];
    g.wv(0) = -mode.slide_m;
    g.id = kSmallStops;
  }
  if (mode.slide_M != 0) {
    auto& g = f.guard[n++];
    g.wv(1) = -mode.slide_M;
    g.id = kLargeStops;
  }
  // The length limit: x − y rises to L_max (extension) or to −L_min (contraction).
  auto& g = f.guard[n++];
  g.wp << 1.0, -1.0;
  g.w0 = mode.side > 0 ? -p_.L_max : p_.L_min;
  g.id = kLengthLimit;
  f.n_guards = n;
  return f;
}

InstantSwapSystem::Mode InstantSwapSystem::reset(Mode mode, int guard_id, StateType& x) const {
  switch (guard_id) {
    case kSmallStops:
      x(2) = 0.0;  // snap: the guard located v = 0 up to round-off
      mode.slide_m = rest_m_;
      return mode;
    case kLargeStops:
      x(3) = 0.0;
      mode.slide_M = rest_M_;
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
  return {direction(x(2), rest_m_), direction(x(3), rest_M_), side};
}

InstantSwapSystem::StateType InstantSwapSystem::rest_state() const {
  StateType x;
  // x − y = L_min with the CoM at the origin.
  const double total = p_.m + p_.M;
  x << p_.M / total * p_.L_min, -p_.m / total * p_.L_min, 0.0, 0.0;
  return x;
}

}  // namespace slipwalk::inchworm
