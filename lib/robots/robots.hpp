#pragma once
// The built-in robots and gaits of thesis §3.5 and §5.5. Each factory validates its
// options (core::InputError naming the option on a bad value) and returns a Walker.
#include <numbers>

#include "core/range.hpp"
#include "robots/walker.hpp"

namespace slipwalk::robots {

/// Which linkage the legs carry (a model choice a scene names: [robot] linkage = "stairs").
/// kStandard is the linkage of robots/bigant.hpp, whose return lifts the toe 42 mm. kStairs is a
/// leg for §5.2.2's stairs (riser 0.12 m; numbers and design in bigant.cpp, checks in
/// tests/robots/test_bigant_stairs.cpp): the same 145 mm stance stroke over the same 0.35-turn
/// sweep and the same stance centres, but a return that lifts the toe 0.195 m above the stance
/// line, rising steeply after lift-off and coming down steeply to touchdown. The thesis gives no
/// link lengths; its BigANT climbs 0.12 m risers (Fig. 5.3), which the standard leg cannot in the
/// quasi-static model (no riser walls): its returning toes pass stair edges below the next tread
/// and stand on it.
enum class BigAntLinkage { kStandard, kStairs };

/// BigANT (§3.5.1, §4.1): hexapod, 73 cm chassis, 8.18 kg, legs [HL, ML, FL, HR, MR, FR], each a
/// 1-DoF four-bar crank driven by a shaft angle φ ∈ [0, 1) (robots/bigant.hpp).
/// Alternating tripod driven by a Buehler clock (§3.5.1.4, robots/buehler.hpp): slow stance, fast
/// return. Tripods {HL, FL, MR} and {ML, HR, FR} run half a cycle apart; at t = 0 the first is in
/// mid-stance (φ = 0) and the second in mid-return (φ = 0.5).
/// Steering: steer s > 0 turns left (counter-clockwise, ω > 0): the left legs sweep Σ(1 − s) of
/// shaft during stance and the right legs Σ; s < 0 shortens the right side's sweep by |s| instead.
/// Stance still lasts duty/frequency and stays centred on the flat bottom of the toe path, so the
/// inner side takes shorter, slower strokes (s = ±1: the inner feet stand still in stance).
struct TripodGait {
  double frequency = 0.1;  ///< Hz, cycles per second; valid: > 0
  double steer = 0.0;      ///< in [−1, 1]: shortens the stance sweep of one side (turning)
  double duty = 0.55;      ///< fraction of the cycle in stance; valid: [0.5, 1) (one tripod is
                           ///< always down; above 0.5 both are down around the switch)
  double sweep = 0.35;     ///< Σ, shaft turns per stance; valid: (0, 0.6]; 0.35 is the flat
                           ///< bottom of the toe path, more reaches into its round corners
  BigAntLinkage linkage = BigAntLinkage::kStandard;  ///< the legs (above)
};
[[nodiscard]] Walker bigant_tripod(const TripodGait& gait = {});

/// Metachronal slipping gait (§3.5.1.5): each foot down 2/3 of a cycle, four feet down at any
/// time, shaft angle cubic in time during stance. Mid-stance times, in cycles after HL's:
/// HL 0, ML 1/3, FL 2/3 (a wave from hind to front on each side), HR 1/2, MR 5/6, FR 1/6 (the
/// opposite side half a cycle later). Sorted, the offsets are the six multiples of 1/6 and
/// alternate sides (HL, FR, ML, HR, FL, MR); a leg is in return for 1/3 of a cycle, so at any time
/// exactly two legs with consecutive offsets are up, one per side: four feet down, two per side.
/// The default sweep reaches past the flat bottom (0.35 turn) into the round corners of the toe
/// path, so that the slow ends of the cubic stance are the touchdown and lift-off themselves: a
/// foot then really touches the ground for about 2/3 of the cycle (0.69) and spring support finds
/// four feet down 90 % of the time (five at the hand-overs). With the flat sweep 0.35 each foot
/// stays on the ground well into its fast return and five feet are down 38 % of the time.
struct MetachronalGait {
  double frequency = 0.1;  ///< Hz; valid: > 0
  double sweep = 0.53;     ///< Σ, shaft turns per stance; valid: (0, 0.6]
  BigAntLinkage linkage = BigAntLinkage::kStandard;  ///< the legs (above)
};
[[nodiscard]] Walker bigant_metachronal(const MetachronalGait& gait = {});

/// Multipod (§3.5.2.1, §5.3.2): N/2 segments, yaw and roll joints, leaf-spring legs; undulation
/// gait θ_y = θ_y,0 cos(2πft + iΔφ), θ_r = θ_r,0 sin(2πft + iΔφ); Mg = N, K = 1, μ = 1 (Mg in
/// newtons, K in N/mm).
/// Kinematics, body frame and stiffness units: robots/multipod.hpp.
struct UndulationGait {
  int legs = 6;                    ///< N ∈ {6, 8, 10, 12}
  double dphi = std::numbers::pi;  ///< Δφ, rad; thesis range [0.2π, 1.8π]
  double frequency = 0.6;          ///< f, Hz; thesis {0.3, 0.6, 1.2, 2.4}
  double roll_amplitude = 5.0 * std::numbers::pi / 36.0;  ///< θ_r,0; valid: [0, π/2)
  double yaw_amplitude = std::numbers::pi / 9.0;          ///< θ_y1,0 = θ_y2,0; valid: [0, π/4]
  double stiffness = 1000.0;  ///< K, N/m: the thesis' K = 1 read with lengths in mm (see
                              ///< robots/multipod.hpp); valid: > 0
};
[[nodiscard]] Walker multipod(const UndulationGait& gait = {});

/// Quadruped (Spirit-like trot, §3.5.2.2; robots/quadruped.cpp): ≈ 12 kg, hips at x = ±0.22 m,
/// feet at y = ±0.15 m, 0.30 m below the body; legs [HL, FL, HR, FR]; the diagonal pairs
/// {FL, HR} and {HL, FR} alternate, each foot on a straight stance line (backward at constant
/// speed) and a raised half-sine swing. At t = 0 {FL, HR} are in mid-stance.
struct TrotGait {
  double frequency = 1.0;      ///< Hz; valid: > 0
  double duty = 0.55;          ///< stance fraction; valid: [0.5, 1): slightly above 1/2 so the
                               ///< pairs overlap briefly instead of switching at one instant
  double stride = 0.15;        ///< m, stance stroke length; valid: > 0, ≤ 0.3
  double swing_height = 0.06;  ///< m, toe lift at mid-swing; valid: > 0, ≤ 0.2
};
[[nodiscard]] Walker quadruped_trot(const TrotGait& gait = {});

/// An N-leg disk robot (legs equally spaced on a rim) for scaling studies, with a simple gait
/// (each foot on a small ellipse, phases spread around the rim; robots/disk.cpp).
/// The disk robot's rim radius: its feet reach 1.1 R from the centre, inside
/// contact::limits::kPosition, and at 1 cm the feet are still apart in double precision.
inline constexpr core::Range kDiskRadius = core::closed(1e-2, 1e2, "m");

struct DiskGait {
  int legs = 6;            ///< N ≥ 3 (≤ 1000)
  double radius = 0.3;     ///< m, rim radius; valid: kDiskRadius
  double frequency = 1.0;  ///< Hz; valid: > 0
};
[[nodiscard]] Walker disk_robot(const DiskGait& gait = {});

}  // namespace slipwalk::robots
