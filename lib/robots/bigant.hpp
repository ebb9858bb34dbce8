#pragma once
// BigANT (thesis §3.5.1, §4.1): a hexapod with a 73 cm chassis, 8.18 kg, six identical 1-DoF
// four-bar legs, each driven by one motor shaft φ (turns). Legs in the thesis' order
// [HL, ML, FL, HR, MR, FR] (§5.5). Body frame: x forward, y left, z up, origin at the chassis
// centroid (§4.1.1: "close to the centroid of the robot chassis"), which the model takes as the
// CoM.
//
// The leg linkage. The thesis gives no link lengths (Fig. 4.1(C)/(D) and Fig. 5.8 show only a
// drawing and the toe path), so we chose a crank-rocker whose coupler point traces a BigANT-like
// closed path in the body xz-plane: a flat-ish stance stroke at the bottom and a raised return.
// The lengths came from a shape optimization (scale-free: stance height variation / stroke, with
// lift ≥ 0.28 stroke, a compact leg, a transmission angle ≥ 29° and a stance toe speed that varies
// by < 1.7×), rounded to millimetres; with the crank pivot O₂ at the origin of the leg's xz-plane:
//   crank a = 70 mm, rocker pivot O₄ = (−143, 220) mm (ground link d = 262.4 mm),
//   coupler b = 208 mm, rocker c = 135 mm, toe e = 192 mm from the crank pin at γ = 1.136 rad
//   (65.1°) from the coupler, branch σ = +1; crank angle θ = θ₀ − 2πφ, θ₀ = −0.979 rad.
// Grashof: a + d = 332.4 < b + c = 343 and d − a = 192.4 > |b − c| = 73 (a crank-rocker).
// What the path is (tests/robots/test_bigant.cpp checks each number):
//   - stance sweep φ ∈ [−0.175, 0.175] (0.35 turn, centred on φ = 0): the toe moves backward by
//     a 145 mm stroke, 124.5 mm below the crank pivot, its height varying by 3.3 mm;
//   - the return lifts the toe 42 mm above the stance line; 0.05 turn past either end of the
//     sweep the toe is ≥ 6 mm up, 0.1 turn past ≥ 13 mm (the corners of a coupler curve are round);
//   - φ = 0 is mid-stance and φ = 0.5 mid-return, so §5.5's standing pose [0.5, 0, 0.5, 0, 0.5, 0]
//     has one tripod down and the other up.
// Placement: the stance centres (toe at φ = 0) lie at x = −0.30, 0, +0.30 m (hind, mid, front;
// 60 cm of a 73 cm chassis) and y = ±0.20 m; the crank pivots at the chassis plane z = 0.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "robots/four_bar.hpp"
#include "robots/robots.hpp"

namespace slipwalk::robots {

inline constexpr int kBigAntLegs = 6;
inline constexpr double kBigAntMass = 8.18;           ///< kg (§4.1.1)
inline constexpr double kGravity = 9.81;              ///< m/s²
inline constexpr double kBigAntStanceSweep = 0.35;    ///< turns of φ on the flat bottom
inline constexpr double kBigAntMaxSweep = 0.6;        ///< the most a gait may sweep in stance
inline constexpr double kBigAntStaticSinkage = 0.01;  ///< m, mean spring compression standing
                                                      ///< on one tripod (sets K, below)
inline constexpr double kBigAntLegSpacing = 0.30;     ///< m, fore-aft between stance centres
inline constexpr double kBigAntFootLateral = 0.20;    ///< m, |y| of the toes

/// The leg linkage described above (in m and rad), and the crank angle at φ = 0.
[[nodiscard]] FourBar bigant_linkage();
inline constexpr double kBigAntCrankPhase = -0.979;  ///< θ₀, rad: θ = θ₀ − 2πφ

// BigAntLinkage (robots.hpp): which linkage the legs carry, the one above or the stairs leg.

/// The stairs leg's linkage (m, rad); its crank phase and sense are in bigant.cpp's table.
[[nodiscard]] FourBar bigant_stairs_linkage();

/// The legs: linkage and where each crank pivot sits in the body frame.
struct BigAntLegs {
  FourBar linkage;                 ///< shared by all legs
  Eigen::Matrix3Xd pivot;          ///< (3 × N) crank pivot O₂ of each leg, body frame, m
  std::vector<std::string> names;  ///< HL, ML, FL, HR, MR, FR; L1 … Ln, R1 … Rn (hind to front)
  double crank_phase = kBigAntCrankPhase;  ///< θ₀ of the linkage, rad
  double crank_sense = -1.0;  ///< θ = θ₀ + crank_sense · 2πφ: −1 turns the crank clockwise in
                              ///< the body's xz-plane (standard), +1 counter-clockwise (stairs)
};

/// The most legs a BigANT-like chassis may have (planning's growth study goes to 12).
inline constexpr int kBigAntMaxLegs = 40;

/// BigANT's six legs, or a BigANT-like robot with an even number `legs` ∈ [2, kBigAntMaxLegs]
/// of the same legs (either linkage, placed so that φ = 0 puts the toes at the same stance
/// centres): legs/2 per side, hind to front, kBigAntLegSpacing apart and centred on the
/// body origin, left side first (for 6 legs exactly BigANT's placement and order). Throws
/// core::InputError("legs", ...) for another count.
[[nodiscard]] BigAntLegs bigant_legs(int legs = kBigAntLegs,
                                     BigAntLinkage linkage = BigAntLinkage::kStandard);

/// Toe of `leg` at shaft angle φ (turns): position q (m, body frame) and dq/dφ (m per turn),
/// from the closed-form loop closure and its derivative (robots/four_bar.hpp). No allocation.
void bigant_toe(const BigAntLegs& legs, int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                Eigen::Ref<Eigen::Vector3d> dq_dphi);

/// The contact::Robot of BigANT: Mg = 8.18 kg · 9.81 m/s² = 80.25 N, μ = 1 (the thesis' naive
/// isotropic value, §3.5.1.4), no anisotropy, and K = Mg / (3 · 1 cm) = 2675 N/m on every leg, so
/// that standing on one tripod compresses the legs by 1 cm on average: small against the 42 mm
/// lift of the return (the swing tripod stays off the ground) but large against the 3.3 mm height
/// variation of the stance line (all stance feet keep carrying load). The thesis' naive K = 10
/// with Mg = 1 (§3.5.1.4) would be a 3.3 cm compression in metres.
[[nodiscard]] contact::Robot bigant_robot();

/// A BigANT-like robot with `legs` legs (bigant_legs(legs)): the weight grows with the chassis,
/// Mg = 80.25 N · legs/6, and K = Mg / (legs/2 · 1 cm), so one "tripod" (half the legs) standing
/// compresses by 1 cm as on BigANT. bigant_robot(6) is bigant_robot().
[[nodiscard]] contact::Robot bigant_robot(int legs);

}  // namespace slipwalk::robots
