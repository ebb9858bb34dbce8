#pragma once
// The realistic-swap inchworm of thesis §2.5 ("dm" model) as a hybrid system (see
// events/hybrid_system.hpp). Three bodies: two end masses m and the moving mass Δm = M − m.
//
// Stroke phase: Δm rides locked on one end mass, which is then "M" (y); the other end mass is x.
//   The stroke is exactly the instant-swap stroke (eqs. 2.1–2.2, actuator +F on x, −F on y) and
//   ends in a plastic collision of x with y+Δm at the length limit (eq. 2.4).
// Swap phase: the end masses move as one body of mass 2m at fixed distance (the m–m body); Δm is
//   pushed from y toward x by F_Δm = αF (§2.5.1), the body feels −F_Δm; friction acts on the body
//   with the whole normal load (2m + Δm)g (Δm rides on the mechanism, not on the ground). The
//   body is stuck while at rest and |F_Δm| ≤ μ_s g(2m + Δm), else it slides (§2.5 eqs.). When Δm
//   arrives at x, a plastic collision gives all three one velocity; Δm's new carrier becomes y and
//   the next stroke runs the other way.
// Details the thesis leaves open, chosen here (and stated in the report):
//   - Δm starts the swap at the end mass it rode on, with that mass's velocity (after the
//     stroke's collision: the common velocity);
//   - the body's static friction uses μ_s like the end masses; a body pushed out of its friction
//     cone slides (backward after an extension stroke, forward after a contraction stroke) with
//     dynamic friction, and stops and sticks again when its velocity reaches zero;
//   - Δm moves on a rail between the end masses: if its free motion would press it into the end
//     it just left, it is held there and the three slide together until the body stops ("held"
//     mode). That happens after a contraction stroke when αF < μ g Δm, i.e. only for α < Δm/m
//     (F > μ m g), = 0.5 with the thesis' masses.
#include <cstdint>

#include "events/hybrid_system.hpp"
#include "inchworm/params.hpp"
#include "inchworm/stroke_dynamics.hpp"

namespace slipwalk::inchworm {

class MassSwapSystem {
 public:
  static constexpr int kBodies = 3;
  static constexpr int kMaxGuards = 3;
  using StateType = events::State<kBodies>;

  enum GuardId : int {
    kSmallStops = StrokeDynamics::kSmallStops,    ///< stroke: x's velocity reaches zero
    kLargeStops = StrokeDynamics::kLargeStops,    ///< stroke: y's (and Δm's) reaches zero
    kLengthLimit = StrokeDynamics::kLengthLimit,  ///< stroke ends: x − y at L_max or −L_min
    kBodyStops = 3,                               ///< swap: the m–m body's velocity reaches zero
    kArrival = 4,                                 ///< swap: Δm reaches x; the next stroke starts
  };
  /// The event that closes a half cycle (stroke + swap).
  static constexpr int kHalfCycleEnd = kArrival;

  enum Phase : std::int8_t { kStroke = 0, kSwap = 1 };

  /// stroke: slide_x, slide_y are the end masses' friction modes (+1 forward, −1 back, 0 stuck);
  /// swap: slide_y is the m–m body's; held = Δm pressed against the end it left.
  /// side = sgn(x − y): +1 in an extension stroke and the swap after it.
  struct Mode {
    std::int8_t phase = kStroke;
    std::int8_t slide_x = 0;
    std::int8_t slide_y = 0;
    std::int8_t side = 1;
    std::int8_t held = 0;
    friend bool operator==(const Mode&, const Mode&) = default;
  };

  /// Bits of mode_flags(): what a half cycle did, for regime classification.
  enum Flags : unsigned {
    kLargeMassSlidBack = 1U << 0U,  ///< y was driven backward in the stroke (two masses moving)
    kSwapStopped = 1U << 1U,        ///< the m–m body came to rest and stuck during the swap
  };

  explicit MassSwapSystem(const Params& p);

  [[nodiscard]] events::ModeFlow<kBodies, kMaxGuards> flow(Mode mode) const;
  [[nodiscard]] Mode reset(Mode mode, int guard_id, StateType& x) const;

  [[nodiscard]] StateType rest_state() const;
  [[nodiscard]] Mode initial_mode(const StateType& x) const;
  [[nodiscard]] double com(const StateType& x) const {
    return (p_.m * (x(0) + x(1)) + dm_ * x(2)) / total_;
  }
  [[nodiscard]] double com_velocity(const StateType& x) const {
    return (p_.m * (x(3) + x(4)) + dm_ * x(5)) / total_;
  }
  /// What being in `mode` says about the half cycle (Flags): a stroke mode with y sliding back
  /// while driven back (F > μMg, so it accelerates backward) is two masses moving (§2.3.1); a
  /// swap mode with the body stuck is a stop during the swap (§2.5.2).
  [[nodiscard]] unsigned mode_flags(Mode mode) const {
    unsigned f = 0;
    if (mode.phase == kStroke && mode.slide_y < 0 && stroke_.drives_y_back()) {
      f |= kLargeMassSlidBack;
    }
    if (mode.phase == kSwap && mode.slide_y == 0) {
      f |= kSwapStopped;
    }
    return f;
  }
  [[nodiscard]] const Params& params() const { return p_; }

 private:
  [[nodiscard]] Mode stroke_mode(double v, std::int8_t side) const;
  [[nodiscard]] Mode swap_mode(double v, std::int8_t side) const;
  /// Would Δm, free, accelerate into the end it left (side: its direction of travel)?
  [[nodiscard]] bool pressed_into_start(std::int8_t body_slide, std::int8_t side) const;
  [[nodiscard]] double body_accel(std::int8_t body_slide, std::int8_t side) const;

  Params p_;
  double dm_;              ///< Δm
  double total_;           ///< 2m + Δm
  double push_;            ///< P = α F
  double body_friction_;   ///< μ g (2m + Δm)
  StrokeDynamics stroke_;  ///< the stroke phase
  bool body_breaks_away_;  ///< swap: α F > μ_s g (2m + Δm), the body cannot stay at rest
};

}  // namespace slipwalk::inchworm
