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

namespace {

void check_leg_count(int legs) {
  if (legs < 2 || legs > kBigAntMaxLegs || legs % 2 != 0) {
    throw core::InputError("legs", "a BigANT-like robot has an even number of legs in [2, " +
                                       std::to_string(kBigAntMaxLegs) + "], got " +
                                       std::to_string(legs));
  }
}

}  // namespace

BigAntLegs bigant_legs(int legs) {
  check_leg_count(legs);
  const int side = legs / 2;
  BigAntLegs out{bigant_linkage(), Eigen::Matrix3Xd(3, legs), {}};
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
  const Eigen::Vector2d mid = four_bar_pose(out.linkage, kBigAntCrankPhase).P;
  for (int j = 0; j < legs; ++j) {
    const double x = kBigAntLegSpacing * (static_cast<double>(j % side) -
                                          0.5 * static_cast<double>(side - 1));  // hind → front
    const double y = j < side ? kBigAntFootLateral : -kBigAntFootLateral;
    out.pivot.col(j) = Eigen::Vector3d(x - mid.x(), y, 0.0);
  }
  return out;
}

void bigant_toe(const BigAntLegs& legs, int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                Eigen::Ref<Eigen::Vector3d> dq_dphi) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const FourBarPose p = four_bar_pose(legs.linkage, kBigAntCrankPhase - kTwoPi * phi);
  // The linkage plane is the body xz-plane; dθ/dφ = −2π.
  q = legs.pivot.col(leg) + Eigen::Vector3d(p.P.x(), 0.0, p.P.y());
  dq_dphi = Eigen::Vector3d(-kTwoPi * p.dP.x(), 0.0, -kTwoPi * p.dP.y());
}

contact::Robot bigant_robot() { return bigant_robot(kBigAntLegs); }

contact::Robot bigant_robot(int legs) {
  check_leg_count(legs);
  const double n = static_cast<double>(legs);
  const double mg = kBigAntMass * kGravity * (n / kBigAntLegs);  // × 1.0 exactly for BigANT
  return contact::uniform_robot(legs, mg / (0.5 * n * kBigAntStaticSinkage), 1.0, mg);
}

}  // namespace slipwalk::robots
