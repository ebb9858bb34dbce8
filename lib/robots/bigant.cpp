#include "robots/bigant.hpp"

#include <cmath>
#include <numbers>

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

BigAntLegs bigant_legs() {
  BigAntLegs legs{
      bigant_linkage(), Eigen::Matrix3Xd(3, kBigAntLegs), {"HL", "ML", "FL", "HR", "MR", "FR"}};
  validate(legs.linkage);
  // Place each crank pivot so that the toe at mid-stance (φ = 0) is at its stance centre.
  const Eigen::Vector2d mid = four_bar_pose(legs.linkage, kBigAntCrankPhase).P;
  for (int j = 0; j < kBigAntLegs; ++j) {
    const double x = kBigAntLegSpacing * static_cast<double>(j % 3 - 1);  // hind, mid, front
    const double y = j < 3 ? kBigAntFootLateral : -kBigAntFootLateral;
    legs.pivot.col(j) = Eigen::Vector3d(x - mid.x(), y, 0.0);
  }
  return legs;
}

void bigant_toe(const BigAntLegs& legs, int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                Eigen::Ref<Eigen::Vector3d> dq_dphi) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const FourBarPose p = four_bar_pose(legs.linkage, kBigAntCrankPhase - kTwoPi * phi);
  // The linkage plane is the body xz-plane; dθ/dφ = −2π.
  q = legs.pivot.col(leg) + Eigen::Vector3d(p.P.x(), 0.0, p.P.y());
  dq_dphi = Eigen::Vector3d(-kTwoPi * p.dP.x(), 0.0, -kTwoPi * p.dP.y());
}

contact::Robot bigant_robot() {
  const double mg = kBigAntMass * kGravity;
  return contact::uniform_robot(kBigAntLegs, mg / (3.0 * kBigAntStaticSinkage), 1.0, mg);
}

}  // namespace slipwalk::robots
