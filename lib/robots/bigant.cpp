#include "robots/bigant.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace slipwalk::robots {

FourBar bigant_linkage() {
  FourBar f;
  f.crank = 0.070;
  f.coupler = 0.208;
  f.rocker = 0.135;
  f.rocker_pivot = {-0.143, 0.220};
  f.toe_distance = 0.192;
  f.toe_angle = 1.136;
  f.branch = 1;
  return f;
}

// The stairs leg (robots.hpp: BigAntLinkage::kStairs). The thesis gives no link lengths; this
// crank-rocker came from a shape optimization (differential evolution over the link lengths and
// the coupler point, scale-free, then scaled to the standard leg's 145 mm stroke and rounded to
// 0.1 mm) that asks, over the standard leg's 0.35-turn stance sweep, for a flat stance moving
// backward, a transmission angle ≥ 25°, and a return that fits §5.2.2's stairs (tread 0.3 m,
// riser 0.12 m). Its model of the swing: the toe's world path with the body pitched by the
// stairs' slope and moving on at its stance speed while the toe returns (duty 0.55), for every
// position of the lift-off point on its tread (120 positions). Asked: the toe stays 1 cm or more
// above the upper tread wherever it passes an edge (the last 15 % of the return excluded), and
// once it meets a tread it moves forward by at most 1 cm more (it comes down steeply, so a toe
// landing on a tread above the body's stance line does not push the body back). With the crank
// pivot O₂ at the origin of the leg's xz-plane:
//   crank a = 98.3 mm, rocker pivot O₄ = (−505.7, 96.4) mm (ground link d = 514.8 mm),
//   coupler b = 146.9 mm, rocker c = 522.3 mm, toe e = 266.3 mm from the crank pin at 0.1173 rad
//   from the coupler, branch σ = −1; θ = θ₀ + 2πφ (the crank turns counter-clockwise; with this
//   linkage that runs the toe backward below and forward above, as the standard leg's does),
//   θ₀ = −1.685 rad.
// Grashof: a + d = 613.1 < b + c = 669.2 and d − a = 416.5 > |b − c| = 375.4 (a crank-rocker).
// The path (tests/robots/test_bigant_stairs.cpp): a 145 mm stance stroke, its height varying by
// 3.6 mm, the stance toe speed varying by 2.4× (standard: 1.65×); the return lifts the toe 195 mm
// above the stance line (standard: 42 mm), steeply at lift-off and at touchdown; transmission
// angle ≥ 38°; in the design's model of the swing the toe clears every edge by ≥ 2.4 cm and moves
// on at most 1.1 cm after meeting a tread. The coupler curve lies above this linkage's pivots (the
// mechanism would stand under its toe path): only the toe path enters the model, so the crank
// pivots are put 0.38 m below the chassis plane, which puts the stance line 0.21 m below it and
// the whole path below it (a real leg would need another mechanism, e.g. a six-bar, for the same
// path).
FourBar bigant_stairs_linkage() {
  FourBar f;
  f.crank = 0.0983;
  f.coupler = 0.1469;
  f.rocker = 0.5223;
  f.rocker_pivot = {-0.5057, 0.0964};
  f.toe_distance = 0.2663;
  f.toe_angle = 0.1173;
  f.branch = -1;
  return f;
}

namespace {

constexpr double kStairsCrankPhase = -1.685;  // θ₀, rad
constexpr double kStairsCrankSense = 1.0;     // θ = θ₀ + 2πφ
constexpr double kStairsPivotZ = -0.38;       // m, the crank pivots below the chassis plane

/// The linkages a BigANT leg may carry, in the order of BigAntLinkage.
struct LinkageEntry {
  FourBar (*linkage)();
  double crank_phase;  ///< θ₀, rad
  double crank_sense;  ///< θ = θ₀ + crank_sense · 2πφ
  double pivot_z;      ///< m, the crank pivots' height in the body frame
};
constexpr LinkageEntry kLinkages[] = {
    {&bigant_linkage, kBigAntCrankPhase, -1.0, 0.0},
    {&bigant_stairs_linkage, kStairsCrankPhase, kStairsCrankSense, kStairsPivotZ},
};

void check_leg_count(int legs) {
  if (legs < 2 || legs > kBigAntMaxLegs || legs % 2 != 0) {
    throw core::InputError("legs", "a BigANT-like robot has an even number of legs in [2, " +
                                       std::to_string(kBigAntMaxLegs) + "], got " +
                                       std::to_string(legs));
  }
}

}  // namespace

BigAntLegs bigant_legs(int legs, BigAntLinkage linkage) {
  check_leg_count(legs);
  const int side = legs / 2;
  const LinkageEntry& entry = kLinkages[static_cast<std::size_t>(linkage)];
  BigAntLegs out{
      entry.linkage(), Eigen::Matrix3Xd(3, legs), {}, entry.crank_phase, entry.crank_sense};
  validate(out.linkage);
  if (legs == kBigAntLegs) {
    out.names = {"HL", "ML", "FL", "HR", "MR", "FR"};
  } else {
    for (int j = 0; j < legs; ++j) {
      std::string name(1, j < side ? 'L' : 'R');
      name.append(std::to_string(j % side + 1));
      out.names.push_back(std::move(name));
    }
  }
  // Place each crank pivot so that the toe at mid-stance (φ = 0) is at its stance centre.
  const Eigen::Vector2d mid = four_bar_pose(out.linkage, out.crank_phase).P;
  for (int j = 0; j < legs; ++j) {
    const double x = kBigAntLegSpacing * (static_cast<double>(j % side) -
                                          0.5 * static_cast<double>(side - 1));  // hind → front
    const double y = j < side ? kBigAntFootLateral : -kBigAntFootLateral;
    out.pivot.col(j) = Eigen::Vector3d(x - mid.x(), y, entry.pivot_z);
  }
  return out;
}

void bigant_toe(const BigAntLegs& legs, int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                Eigen::Ref<Eigen::Vector3d> dq_dphi) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double rate = legs.crank_sense * kTwoPi;  // dθ/dφ
  const FourBarPose p = four_bar_pose(legs.linkage, legs.crank_phase + rate * phi);
  // The linkage plane is the body xz-plane.
  q = legs.pivot.col(leg) + Eigen::Vector3d(p.P.x(), 0.0, p.P.y());
  dq_dphi = Eigen::Vector3d(rate * p.dP.x(), 0.0, rate * p.dP.y());
}

contact::Robot bigant_robot() { return bigant_robot(kBigAntLegs); }

contact::Robot bigant_robot(int legs) {
  check_leg_count(legs);
  const double n = static_cast<double>(legs);
  const double mg = kBigAntMass * kGravity * (n / kBigAntLegs);  // × 1.0 exactly for BigANT
  return contact::uniform_robot(legs, mg / (0.5 * n * kBigAntStaticSinkage), 1.0, mg);
}

}  // namespace slipwalk::robots
