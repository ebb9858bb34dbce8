#pragma once
// The admissible range of every number a scene file holds (scene.hpp has the format), checked
// where the value is read so that the error names its file:line:col, its range and its unit. The
// robot factories and the trajectory kernel check again (robots/check.hpp, connection/), but a
// scene never reaches them with a value they would refuse.
//
// Why these bounds: every length of a walking robot of this model is between a micrometre and a
// kilometre, and every stiffness, mass and rate is bounded the same way, so that the products the
// model forms (K·q for the support's loads, §3.3; μ·F_z and the 3 × 3 balance of eq. 3.20; ω·q
// for the slip, eq. 3.5; 2π f·stride for the foot speeds) stay finite and normal in double
// precision: the largest such product is about 1e9 N/m · 1e3 m · 1e3 = 1e15, the smallest
// positive one about 1e-6 · 1e-6 · 1e-3 = 1e-15, both far from 1e±308.
#include <numbers>

#include "contact/robot.hpp"
#include "core/range.hpp"
#include "robots/check.hpp"
#include "robots/robots.hpp"

namespace slipwalk::scene::ranges {

using core::closed;
using core::Range;

/// A coordinate of a hip in the body frame.
inline constexpr Range kCoordinate = contact::limits::kPosition;
/// A length that must be positive (stride, height, radius, tread).
inline constexpr Range kLength = closed(1e-6, 1e3, "m");
/// A length that may be zero (lift, swing height of the trot is positive: kLength; riser,
/// com_height).
inline constexpr Range kLengthOrZero = closed(0.0, 1e3, "m");
/// A gait's frequency: one cycle per 11.6 days to a kHz.
inline constexpr Range kFrequency = robots::detail::kFrequency;
/// A leg's spring stiffness K (§3.3).
inline constexpr Range kStiffness = contact::limits::kStiffness;
/// A robot's mass (Mg = mass · 9.81 m/s² is carried by the legs).
inline constexpr Range kMass = closed(1e-6, 1e6, "kg");
/// A friction coefficient μ (eq. 3.9): 0 (no friction) or in contact::limits::kFriction; the
/// reader checks the gap between 0 and the lower bound (leg_table.cpp).
inline constexpr Range kFrictionCoefficient = closed(0.0, contact::limits::kFriction.hi);
/// A phase in cycles: [0, 1).
inline constexpr Range kPhase = Range{0.0, 1.0, false, true, "cycles"};
/// The run's duration and its step: at most kMaxSteps steps (scene.hpp) of at least a
/// nanosecond each.
inline constexpr Range kDuration = closed(1e-9, 1e9, "s");
inline constexpr Range kStep = closed(1e-9, 1e3, "s");
/// Tripod steering, [-1, 1] (robots/robots.hpp).
inline constexpr Range kSteer = closed(-1.0, 1.0);
/// Stance duty factor of the tripod and the trot: [0.5, 1) (robots/robots.hpp).
inline constexpr Range kDuty = Range{0.5, 1.0, false, true, ""};
/// BigANT's shaft turns per stance Σ: (0, 0.6] (robots/robots.hpp, the four-bar's reach).
inline constexpr Range kSweep = Range{0.0, 0.6, true, false, "turns"};
/// The Multipod's phase lag between sections Δφ (§3.5.2.1); any lag is one of [-2π, 2π].
inline constexpr Range kPhaseLag = closed(-2.0 * std::numbers::pi, 2.0 * std::numbers::pi, "rad");
/// The Multipod's roll and yaw amplitudes (robots/robots.hpp: [0, π/2) and [0, π/4]).
inline constexpr Range kRollAmplitude = Range{0.0, std::numbers::pi / 2.0, false, true, "rad"};
inline constexpr Range kYawAmplitude = closed(0.0, std::numbers::pi / 4.0, "rad");
/// The trot's stride and swing height (robots/robots.hpp).
inline constexpr Range kTrotStride = closed(1e-6, 0.3, "m");
inline constexpr Range kTrotSwingHeight = closed(1e-6, 0.2, "m");
/// The disk robot's rim radius.
inline constexpr Range kRadius = robots::kDiskRadius;
/// The inertia filter's γ per step (§3.5.2.2): [0, 1).
inline constexpr Range kFilterGamma = Range{0.0, 1.0, false, true, ""};
/// The Coulomb solver's relative duality gap: below 1e-15 it is rounding.
inline constexpr Range kCoulombTolerance = closed(1e-15, 1.0);
/// An anisotropy vector's component (eq. 3.19, H ∝ I + w wᵀ: w wᵀ up to 1e6).
inline constexpr Range kAnisotropy = contact::limits::kAnisotropy;
/// An entry of the residual B (§5.3.1): v_body += B q̇.
inline constexpr Range kResidualEntry = closed(-1e3, 1e3);
/// Measurement noise (motion capture, §3.5.1).
inline constexpr Range kNoiseXY = closed(0.0, 1e3, "m");
inline constexpr Range kNoiseTheta = closed(0.0, 1e3, "rad");
/// A slope's angle (§5.2.1): [0, 90) degrees; at 90 the plane is a wall.
inline constexpr Range kSlopeAngle = Range{0.0, 90.0, false, true, "degrees"};
/// A heading of the slope or the stairs.
inline constexpr Range kHeading = closed(-360.0, 360.0, "degrees");

}  // namespace slipwalk::scene::ranges
