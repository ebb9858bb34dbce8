#pragma once
// The instant-swap inchworm of thesis §2.2 as a hybrid system (see events/hybrid_system.hpp).
//
// Bodies: 0 = m at x, 1 = M at y. The actuator force on m is F_t sgn(x−y) = +F and on M is −F
// in every stroke (eqs. 2.1–2.2 with F_t = F sgn(x−y), §2.3): extension from x−y = L_min to
// L_max, then contraction from x−y = −L_max to −L_min. Each stroke ends in a plastic collision
// (eq. 2.4) followed by the instantaneous swap of the two masses.
// Friction (eq. 2.3) is a mode per mass: sliding forward, sliding backward or stuck. A stuck
// mass stays stuck while |applied force| ≤ μ_s N; the applied force is constant within a stroke,
// so a mass leaves the stuck mode only at a collision.
#include <cstdint>

#include "events/hybrid_system.hpp"
#include "inchworm/params.hpp"
#include "inchworm/stroke_dynamics.hpp"

namespace slipwalk::inchworm {

class InstantSwapSystem {
 public:
  static constexpr int kBodies = 2;
  static constexpr int kMaxGuards = 3;
  using StateType = events::State<kBodies>;

  /// Guard ids passed to reset().
  /// Guard ids passed to reset(): those of the stroke.
  enum GuardId : int {
    kSmallStops = StrokeDynamics::kSmallStops,    ///< m's velocity reaches zero
    kLargeStops = StrokeDynamics::kLargeStops,    ///< M's velocity reaches zero
    kLengthLimit = StrokeDynamics::kLengthLimit,  ///< x−y reaches L_max or −L_min
  };

  /// The event that closes a half cycle (one stroke with its swap).
  static constexpr int kHalfCycleEnd = kLengthLimit;

  /// Bits of mode_flags(): what a half cycle did, for regime classification.
  enum Flags : unsigned {
    kLargeMassSlidBack = 1U << 0U,  ///< M driven backward (regime II, two masses moving)
  };

  /// slide: +1 sliding forward, −1 backward, 0 stuck. side = sgn(x − y): +1 extension stroke.
  struct Mode {
    std::int8_t slide_m = 0;
    std::int8_t slide_M = 0;
    std::int8_t side = 1;
    friend bool operator==(const Mode&, const Mode&) = default;
  };

  explicit InstantSwapSystem(const Params& p);

  [[nodiscard]] events::ModeFlow<kBodies, kMaxGuards> flow(Mode mode) const;
  [[nodiscard]] Mode reset(Mode mode, int guard_id, StateType& x) const;

  /// The mode of a state: sliding masses by their velocity; masses at rest by static friction.
  [[nodiscard]] Mode mode_of(const StateType& x, std::int8_t side) const;
  [[nodiscard]] Mode initial_mode(const StateType& x) const { return mode_of(x, 1); }
  /// What being in `mode` says about the half cycle: M sliding back while driven back
  /// (F > μMg) is regime II, two masses moving (§2.3.1).
  [[nodiscard]] unsigned mode_flags(Mode mode) const {
    return mode.slide_M < 0 && stroke_.drives_y_back() ? kLargeMassSlidBack : 0U;
  }
  /// Both masses at rest, x − y = L_min, CoM at 0: the start of every thesis run (§2.3).
  [[nodiscard]] StateType rest_state() const;
  [[nodiscard]] double com(const StateType& x) const {
    return (p_.m * x(0) + p_.M * x(1)) / (p_.m + p_.M);
  }
  [[nodiscard]] double com_velocity(const StateType& x) const {
    return (p_.m * x(2) + p_.M * x(3)) / (p_.m + p_.M);
  }
  [[nodiscard]] const Params& params() const { return p_; }

 private:
  Params p_;
  StrokeDynamics stroke_;
};

}  // namespace slipwalk::inchworm
