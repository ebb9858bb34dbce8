// An N-leg disk robot for scaling studies (thesis §3.5.3 times the model on "a round disk with 3
// to 50 legs equally spaced on its circumference"; the gait here is ours). Leg j's hip is at angle
// α_j = 2πj/N on a rim of radius R; its foot runs a small ellipse in the vertical plane along x,
//   q_j = (R cos α_j + a cos ψ_j,  R sin α_j,  −H − b sin ψ_j),   ψ_j = 2π(f t + j g),
// lowest at ψ = π/2 where it moves backward (the robot walks toward +x). g = (√5 − 1)/2, the
// golden-ratio step, spreads the phases so that neighbours on the rim are far apart in phase and
// the feet down at any time are scattered around the rim for every N (a step of 1/N would put
// the down feet on one half of the rim and tip the robot).
// Sizes: a = min(0.1 R, 0.45 πR/N) (neighbouring ellipses never overlap: 2a < 2πR/N), b = a/2,
// H = 0.3 R. Mg = N newtons (mass linear in the legs, as for the Multipod, §3.5.2.1), μ = 1 and
// K = 1000 N/m: a static compression of a few millimetres against a lift of 2b. For even N two
// opposite feet are sometimes the only ones low enough to touch; the robot then stands on the
// line through them and the centre (spring support's "line" status), still balanced.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "robots/check.hpp"
#include "robots/robots.hpp"

namespace slipwalk::robots {

Walker disk_robot(const DiskGait& gait) {
  constexpr double kPi = std::numbers::pi;
  if (gait.legs < 3 || gait.legs > 1000) {
    throw core::InputError("disk_robot.legs",
                           "must be in [3, 1000], got " + std::to_string(gait.legs));
  }
  // Feet reach 1.1 R from the centre, inside contact::limits::kPosition.
  detail::require_in("disk_robot.radius", gait.radius, kDiskRadius);
  detail::require_in("disk_robot.frequency", gait.frequency, detail::kFrequency);

  const int n = gait.legs;
  const double r = gait.radius;
  const double a = std::min(0.1 * r, 0.45 * kPi * r / static_cast<double>(n));
  const double b = 0.5 * a;
  const double height = 0.3 * r;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);

  Walker w;
  w.name = "disk" + std::to_string(n);
  w.robot = contact::uniform_robot(n, 1000.0, 1.0, static_cast<double>(n));
  for (int j = 0; j < n; ++j) {
    w.leg_names.push_back("leg" + std::to_string(j));
  }
  w.period = 1.0 / gait.frequency;
  Eigen::Matrix2Xd hip(2, n);
  Eigen::VectorXd offset(n);
  for (int j = 0; j < n; ++j) {
    const double alpha = 2.0 * kPi * static_cast<double>(j) / static_cast<double>(n);
    hip.col(j) << r * std::cos(alpha), r * std::sin(alpha);
    const double s = static_cast<double>(j) * golden;
    offset(j) = s - std::floor(s);
  }
  const double f = gait.frequency;
  w.feet = [hip, offset, a, b, height, f](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    const double omega = 2.0 * kPi * f;
    for (int j = 0; j < hip.cols(); ++j) {
      const double psi = 2.0 * kPi * (f * t + offset(j));
      const double c = std::cos(psi);
      const double s = std::sin(psi);
      q.col(j) << hip(0, j) + a * c, hip(1, j), -height - b * s;
      qdot.col(j) << -a * omega * s, 0.0, -b * omega * c;
    }
  };
  w.phase = [offset, f](double t, Eigen::VectorXd& phase) {
    for (int j = 0; j < offset.size(); ++j) {
      const double s = f * t + offset(j);
      phase(j) = s - std::floor(s);
    }
  };
  return w;
}

}  // namespace slipwalk::robots
