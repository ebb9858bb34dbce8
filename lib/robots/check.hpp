#pragma once
// Ranges of the robot factories' options, checked with core::require_in so that each message
// names the option ("multipod.frequency") and states the allowed interval with its unit. Bounds
// that are not the physics' own (a duty below 1) keep the derived quantities finite and normal:
// a frequency f gives the period 1/f and phases f t, so f stays in [1e-6, 1e3] Hz (1/f ≤ 1e6 s,
// f t far from overflow over any run); lengths stay within contact::limits::kPosition.
#include <numbers>

#include "contact/robot.hpp"
#include "core/range.hpp"

namespace slipwalk::robots::detail {

using core::require_in;

/// A gait's cycle frequency.
inline constexpr core::Range kFrequency = core::closed(1e-6, 1e3, "Hz");
/// A stance fraction: at least half the cycle (one tripod or diagonal pair always down), below 1
/// (the legs need a swing).
inline constexpr core::Range kDuty = core::Range{0.5, 1.0, false, true, ""};
/// A phase offset or a fixed angle: |x| ≤ 1e3 rad keeps sin/cos accurate to ~1e-13.
inline constexpr core::Range kAngle = core::closed(-1e3, 1e3, "rad");

}  // namespace slipwalk::robots::detail
