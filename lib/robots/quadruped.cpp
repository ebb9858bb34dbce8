// A Spirit-like trotting quadruped (thesis §3.5.2.2; the gait and dimensions are ours, the thesis
// used measured foot positions): see TrotGait in robots.hpp. The model is quasi-static, so the
// trot has no flight phase: a diagonal pair carries the body, and with duty > 1/2 both pairs share
// it briefly around each switch.
#include <cmath>
#include <numbers>
#include <string>

#include "robots/check.hpp"
#include "robots/robots.hpp"

namespace slipwalk::robots {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMass = 12.0;         // kg (Spirit 40 is about 12 kg)
constexpr double kG = 9.81;            // m/s², gravity
constexpr double kHipX = 0.22;         // m, hips fore and aft of the centre (0.5 m body)
constexpr double kFootY = 0.15;        // m, feet to the side (0.3 m body)
constexpr double kStanceDepth = 0.30;  // m, feet below the body in stance
constexpr double kSinkage = 0.01;      // m, spring compression on one diagonal pair

/// Foot of a leg at cycle phase s (s = 0: mid-stance): offset from its stance centre (x, z) and
/// its derivative with respect to s (per cycle).
struct Swing {
  double x, z, dx, dz;
};

Swing trot_foot(const TrotGait& g, double s) {
  const double w = s + 0.5 * g.duty;
  const double f = w - std::floor(w);  // since touchdown, cycles
  if (f < g.duty) {
    // Stance: a straight line backward at constant speed.
    const double tau = f / g.duty;
    return {g.stride * (0.5 - tau), 0.0, -g.stride / g.duty, 0.0};
  }
  // Swing: forward along a half cosine, lifted along a half sine.
  const double sigma = (f - g.duty) / (1.0 - g.duty);
  const double ds = 1.0 / (1.0 - g.duty);
  return {g.stride * (0.5 * (1.0 - std::cos(kPi * sigma)) - 0.5),
          g.swing_height * std::sin(kPi * sigma), g.stride * 0.5 * kPi * std::sin(kPi * sigma) * ds,
          g.swing_height * kPi * std::cos(kPi * sigma) * ds};
}

}  // namespace

Walker quadruped_trot(const TrotGait& gait) {
  detail::require_in("quadruped_trot.frequency", gait.frequency, detail::kFrequency);
  detail::require_in("quadruped_trot.duty", gait.duty, detail::kDuty);
  detail::require_in("quadruped_trot.stride", gait.stride, core::positive_up_to(0.3, "m"));
  detail::require_in("quadruped_trot.swing_height", gait.swing_height,
                     core::positive_up_to(0.2, "m"));

  const double mg = kMass * kG;
  Walker w;
  w.name = "quadruped_trot";
  w.robot = contact::uniform_robot(4, mg / (2.0 * kSinkage), 1.0, mg);
  w.leg_names = {"HL", "FL", "HR", "FR"};
  w.period = 1.0 / gait.frequency;
  // [HL, FL, HR, FR]: stance centres, and mid-stance times ({FL, HR} at 0, {HL, FR} at 1/2).
  const Eigen::Matrix<double, 2, 4> centre{{-kHipX, kHipX, -kHipX, kHipX},
                                           {kFootY, kFootY, -kFootY, -kFootY}};
  const Eigen::Vector4d offset(0.5, 0.0, 0.0, 0.5);
  w.feet = [gait, centre, offset](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    for (int j = 0; j < 4; ++j) {
      const Swing s = trot_foot(gait, gait.frequency * t - offset(j));
      q.col(j) << centre(0, j) + s.x, centre(1, j), s.z - kStanceDepth;
      qdot.col(j) << s.dx * gait.frequency, 0.0, s.dz * gait.frequency;
    }
  };
  w.phase = [gait, offset](double t, Eigen::VectorXd& phase) {
    for (int j = 0; j < 4; ++j) {
      const double s = gait.frequency * t - offset(j);
      phase(j) = s - std::floor(s);
    }
  };
  return w;
}

}  // namespace slipwalk::robots
