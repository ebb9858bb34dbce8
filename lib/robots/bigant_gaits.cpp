// BigANT's two gaits (thesis §3.5.1.4, §3.5.1.5): every leg runs a clock (robots/buehler.hpp)
// from time to shaft angle, and the leg linkage (robots/bigant.hpp) from shaft angle to toe.
// Toe velocity by the chain rule, q̇ = dq/dφ · dφ/ds · f (s = f t − offset, cycles), all analytic.
#include <algorithm>
#include <array>
#include <string>

#include "robots/bigant.hpp"
#include "robots/buehler.hpp"
#include "robots/check.hpp"
#include "robots/robots.hpp"

namespace slipwalk::robots {

namespace {

using Shapes = std::array<ClockShape, kBigAntLegs>;
using Offsets = std::array<double, kBigAntLegs>;  // mid-stance times of the legs, cycles

/// A walker whose leg j sits at cycle phase s_j = f t − offset_j of its clock.
Walker bigant_walker(std::string name, const Shapes& shapes, const Offsets& offsets, double f,
                     BigAntLinkage linkage) {
  BigAntLegs legs = bigant_legs(kBigAntLegs, linkage);
  Walker w;
  w.name = std::move(name);
  w.robot = bigant_robot();
  w.leg_names = legs.names;
  w.period = 1.0 / f;
  w.feet = [legs, shapes, offsets, f](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    Eigen::Vector3d dq_dphi;
    for (int j = 0; j < kBigAntLegs; ++j) {
      const auto k = static_cast<std::size_t>(j);
      const ClockState c = clock_at(shapes[k], f * t - offsets[k]);
      bigant_toe(legs, j, c.phi, q.col(j), dq_dphi);
      qdot.col(j) = dq_dphi * (c.rate * f);  // dφ/dt = dφ/ds · f
    }
  };
  w.phase = [shapes, offsets, f](double t, Eigen::VectorXd& phase) {
    for (int j = 0; j < kBigAntLegs; ++j) {
      const auto k = static_cast<std::size_t>(j);
      phase(j) = clock_at(shapes[k], f * t - offsets[k]).phi;
    }
  };
  return w;
}

void check_sweep(const std::string& where, double sweep) {
  detail::require_in(where, sweep, core::positive_up_to(kBigAntMaxSweep, "turns"));
}

}  // namespace

Walker bigant_tripod(const TripodGait& gait) {
  detail::require_in("bigant_tripod.frequency", gait.frequency, detail::kFrequency);
  detail::require_in("bigant_tripod.steer", gait.steer, core::closed(-1.0, 1.0));
  detail::require_in("bigant_tripod.duty", gait.duty, detail::kDuty);
  check_sweep("bigant_tripod.sweep", gait.sweep);

  // Steering shortens the inner side's sweep (robots.hpp); HL, ML, FL are the left legs.
  const double left = gait.sweep * (1.0 - std::max(gait.steer, 0.0));
  const double right = gait.sweep * (1.0 - std::max(-gait.steer, 0.0));
  Shapes shapes;
  for (int j = 0; j < kBigAntLegs; ++j) {
    shapes[static_cast<std::size_t>(j)] = {gait.duty, j < 3 ? left : right, 0.0, false};
  }
  // Tripod {HL, FL, MR} at offset 0, {ML, HR, FR} half a cycle later.
  const Offsets offsets = {0.0, 0.5, 0.0, 0.5, 0.0, 0.5};
  return bigant_walker("bigant_tripod", shapes, offsets, gait.frequency, gait.linkage);
}

Walker bigant_metachronal(const MetachronalGait& gait) {
  detail::require_in("bigant_metachronal.frequency", gait.frequency, detail::kFrequency);
  check_sweep("bigant_metachronal.sweep", gait.sweep);
  Shapes shapes;
  shapes.fill({2.0 / 3.0, gait.sweep, 0.0, true});
  // [HL, ML, FL, HR, MR, FR]: a hind-to-front wave per side, the right side half a cycle later
  // (the derivation of "four down, two per side" is in robots.hpp).
  const Offsets offsets = {0.0, 1.0 / 3.0, 2.0 / 3.0, 0.5, 5.0 / 6.0, 1.0 / 6.0};
  return bigant_walker("bigant_metachronal", shapes, offsets, gait.frequency, gait.linkage);
}

}  // namespace slipwalk::robots
