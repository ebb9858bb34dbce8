#pragma once
// The built-in robots and gaits of thesis §3.5 and §5.5 (issue 6). Each factory validates its
// options (core::InputError naming the option on a bad value) and returns a Walker.
#include <numbers>

#include "robots/walker.hpp"

namespace slipwalk::robots {

/// BigANT (§3.5.1, §4.1): hexapod, 73 cm chassis, 8.18 kg, legs [HL, ML, FL, HR, MR, FR], each a
/// 1-DoF four-bar crank driven by a shaft angle φ ∈ [0, 1) (robots/bigant.hpp).
/// Alternating tripod driven by a Buehler clock (§3.5.1.4): slow stance, fast return.
struct TripodGait {
  double frequency = 0.1;  ///< Hz, cycles per second; valid: > 0
  double steer = 0.0;      ///< in [−1, 1]: shortens the stance sweep of one side (turning)
};
[[nodiscard]] Walker bigant_tripod(const TripodGait& gait = {});

/// Metachronal slipping gait (§3.5.1.5): each foot down 2/3 of a cycle, four feet down at any
/// time, shaft angle cubic in time during stance.
struct MetachronalGait {
  double frequency = 0.1;  ///< Hz; valid: > 0
};
[[nodiscard]] Walker bigant_metachronal(const MetachronalGait& gait = {});

/// Multipod (§3.5.2.1, §5.3.2): N/2 segments, yaw and roll joints, leaf-spring legs; undulation
/// gait θ_y = θ_y,0 cos(2πft + iΔφ), θ_r = θ_r,0 sin(2πft + iΔφ); Mg = N, K = 1, μ = 1.
struct UndulationGait {
  int legs = 6;                                     ///< N ∈ {6, 8, 10, 12}
  double dphi = std::numbers::pi;                   ///< Δφ, rad; thesis range [0.2π, 1.8π]
  double frequency = 0.6;                           ///< f, Hz; thesis {0.3, 0.6, 1.2, 2.4}
  double roll_amplitude = 5.0 * std::numbers::pi / 36.0;  ///< θ_r,0
  double yaw_amplitude = std::numbers::pi / 9.0;          ///< θ_y1,0 = θ_y2,0
};
[[nodiscard]] Walker multipod(const UndulationGait& gait = {});

/// Quadruped (Spirit-like trot, §3.5.2.2).
struct TrotGait {
  double frequency = 1.0;  ///< Hz; valid: > 0
};
[[nodiscard]] Walker quadruped_trot(const TrotGait& gait = {});

/// An N-leg disk robot (legs equally spaced on a rim) for scaling studies, with a simple gait
/// (each foot on a small ellipse, phases spread around the rim).
struct DiskGait {
  int legs = 6;            ///< N ≥ 3
  double radius = 0.3;     ///< m, rim radius
  double frequency = 1.0;  ///< Hz
};
[[nodiscard]] Walker disk_robot(const DiskGait& gait = {});

}  // namespace slipwalk::robots
