#include "inchworm/mass_swap.hpp"

#include <string>

#include "core/error.hpp"

namespace slipwalk::inchworm {

namespace {
std::int8_t sign_or(double v, std::int8_t at_rest) {
  if (v > 0.0) {
    return 1;
  }
  if (v < 0.0) {
    return -1;
  }
  return at_rest;
}
}  // namespace

MassSwapSystem::MassSwapSystem(const Params& p)
    : p_(p),
      dm_(p.M - p.m),
      total_(2.0 * p.m + (p.M - p.m)),
      push_(p.alpha * p.F),
      body_friction_(p.mu * p.g * (2.0 * p.m + (p.M - p.m))),
      stroke_(p) {
  body_breaks_away_ = push_ > p.static_mu() * p.g * total_;
}

double MassSwapSystem::body_accel(std::int8_t body_slide, std::int8_t side) const {
  // 2m c̈ = −F_Δm − sgn(ċ) μ g (2m + Δm), F_Δm = side · α F (§2.5).
  if (body_slide == 0) {
    return 0.0;
  }
  return (-side * push_ - body_slide * body_friction_) / (2.0 * p_.m);
}

bool MassSwapSystem::pressed_into_start(std::int8_t body_slide, std::int8_t side) const {
  // Δm travels in direction `side`; free, it accelerates at side·P/Δm. It is pressed into the
  // end it left when the body accelerates faster in that direction.
  return side * (side * push_ / dm_ - body_accel(body_slide, side)) < 0.0;
}

events::ModeFlow<3, 3> MassSwapSystem::flow(Mode mode) const {
  events::ModeFlow<3, 3> f;
  int n = 0;
  if (mode.phase == kStroke) {
    const double aM = stroke_.accel_y(mode.slide_y);
    f.accel << stroke_.accel_x(mode.slide_x), aM, aM;  // Δm rides on y
    n = stroke_.add_guards(f, n, mode.slide_x, mode.slide_y, mode.side);
  } else {
    if (mode.held != 0) {
      // Δm held at its start: the three slide together under friction alone.
      const double a = -mode.slide_y * p_.mu * p_.g;
      f.accel << a, a, a;
    } else {
      const double a = body_accel(mode.slide_y, mode.side);
      f.accel << a, a, mode.side * push_ / dm_;
    }
    if (mode.slide_y != 0) {
      auto& g = f.guard[n++];
      g.wv(0) = -mode.slide_y;
      g.id = kBodyStops;
    }
    // Δm arrives at x: side·(z − x) rises to 0 from −(distance between the ends).
    auto& g = f.guard[n++];
    g.wp << -mode.side, 0.0, mode.side;
    g.id = kArrival;
  }
  f.n_guards = n;
  return f;
}

MassSwapSystem::Mode MassSwapSystem::stroke_mode(double v, std::int8_t side) const {
  Mode mode;
  mode.phase = kStroke;
  mode.slide_x = sign_or(v, stroke_.rest_x());
  mode.slide_y = sign_or(v, stroke_.rest_y());
  mode.side = side;
  return mode;
}

MassSwapSystem::Mode MassSwapSystem::swap_mode(double v, std::int8_t side) const {
  Mode mode;
  mode.phase = kSwap;
  mode.side = side;
  // At rest the body breaks away opposite to F_Δm (reaction −side·P) if static friction cannot
  // hold it.
  const std::int8_t at_rest = body_breaks_away_ ? static_cast<std::int8_t>(-side) : std::int8_t{0};
  mode.slide_y = sign_or(v, at_rest);
  mode.held = pressed_into_start(mode.slide_y, side) ? 1 : 0;
  return mode;
}

MassSwapSystem::Mode MassSwapSystem::reset(Mode mode, int guard_id, StateType& x) const {
  switch (guard_id) {
    case kSmallStops:
      x(3) = 0.0;
      mode.slide_x = stroke_.rest_x();
      return mode;
    case kLargeStops:
      x(4) = 0.0;
      x(5) = 0.0;
      mode.slide_y = stroke_.rest_y();
      return mode;
    case kLengthLimit: {
      // eq. 2.4 between x and y + Δm; then the swap starts from the common velocity.
      const double v = (p_.m * x(3) + p_.M * x(4)) / (p_.m + p_.M);
      x(3) = v;
      x(4) = v;
      x(5) = v;
      return swap_mode(v, mode.side);
    }
    case kBodyStops: {
      x(3) = 0.0;
      x(4) = 0.0;
      if (mode.held != 0) {
        x(5) = 0.0;  // Δm stopped with the body; at rest it is free to go
      }
      return swap_mode(0.0, mode.side);
    }
    case kArrival: {
      // Plastic collision of Δm with x; x becomes Δm's carrier y, the old y becomes x.
      const double v = com_velocity(x);
      const double x_old = x(0);
      x(0) = x(1);
      x(1) = x_old;
      x(2) = x_old;
      x(3) = v;
      x(4) = v;
      x(5) = v;
      return stroke_mode(v, static_cast<std::int8_t>(-mode.side));
    }
    default:
      throw core::ComputationError("MassSwapSystem: unknown guard id " + std::to_string(guard_id));
  }
}

MassSwapSystem::StateType MassSwapSystem::rest_state() const {
  StateType x = StateType::Zero();
  const double total = p_.m + p_.M;
  x(0) = p_.M / total * p_.L_min;
  x(1) = -p_.m / total * p_.L_min;
  x(2) = x(1);
  return x;
}

MassSwapSystem::Mode MassSwapSystem::initial_mode(const StateType& x) const {
  return stroke_mode(x(3), 1);
}

}  // namespace slipwalk::inchworm
