#pragma once
// Planar rigid motions SE(2) for trajectories (thesis §3.5: the body velocity of the local
// connection is a body-frame twist; integrating it gives the robot's pose in the world).
//
// A Pose2 (x, y, θ) maps body coordinates p to world coordinates R(θ) p + (x, y). Composition is
// a·b = (t_a + R(θ_a) t_b, θ_a + θ_b). The angle is kept unwrapped (compose adds angles), so a
// trajectory's yaw is continuous and counts full turns; as group elements, poses whose angles
// differ by 2π are the same, and log() wraps.
//
// The exponential map of a body twist ξ = (a, b, φ) = (v_x, v_y, ω)·dt held constant over dt: the
// body moves along a circular arc of length ‖(a, b)‖ turning by φ; the chord of that arc is
//   t = sinc(φ/2) R(φ/2) (a, b),   sinc(s) = sin(s)/s,
// (the usual V(φ) = [sin φ/φ, −(1 − cos φ)/φ; (1 − cos φ)/φ, sin φ/φ] written with half angles:
// sin φ/φ = sinc(φ/2) cos(φ/2), (1 − cos φ)/φ = sinc(φ/2) sin(φ/2)). This form has no
// cancellation (1 − cos φ is never formed) and its only removable singularity, sinc at 0, is
// evaluated by its Taylor series for small arguments. Hence the integration is exact per step for
// a twist held over the step: n steps of dt give one step of n·dt to rounding.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace slipwalk::core {

struct Pose2 {
  double x = 0.0;      ///< m, world frame
  double y = 0.0;      ///< m, world frame
  double theta = 0.0;  ///< rad, yaw; unwrapped (see above)

  [[nodiscard]] Eigen::Vector2d translation() const { return {x, y}; }
};

/// Below this |s| sinc(s) is its Taylor series 1 − s²/6 + s⁴/120 − s⁶/5040; the first omitted
/// term, s⁸/362880 ≤ 3e-22, is far below the rounding of 1. Above it sin(s)/s has the relative
/// accuracy of sin (no cancellation), so the switch is seamless (tests/core/test_se2.cpp).
inline constexpr double kSincSeriesBelow = 1e-2;

/// sin(s)/s, 1 at s = 0.
[[nodiscard]] inline double sinc(double s) {
  if (std::abs(s) < kSincSeriesBelow) {
    const double s2 = s * s;
    return 1.0 - s2 / 6.0 * (1.0 - s2 / 20.0 * (1.0 - s2 / 42.0));
  }
  return std::sin(s) / s;
}

/// The angle wrapped to (−π, π].
[[nodiscard]] inline double wrap_angle(double angle) {
  double r = std::remainder(angle, 2.0 * std::numbers::pi);  // in [−π, π]
  if (r <= -std::numbers::pi) {
    r += 2.0 * std::numbers::pi;
  }
  return r;
}

/// A shaft angle in turns wrapped to [0, 1): x − ⌊x⌋, where for x just below an integer the
/// difference can round up to 1.0 exactly (the same angle as 0).
[[nodiscard]] inline double wrap_turns(double x) {
  const double w = x - std::floor(x);
  return w >= 1.0 ? 0.0 : w;
}

/// a·b: first a, then b expressed in a's body frame.
[[nodiscard]] inline Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, a.theta + b.theta};
}

/// a⁻¹, so that compose(a, inverse(a)) is the identity (angle exactly 0).
[[nodiscard]] inline Pose2 inverse(const Pose2& a) {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {-(c * a.x + s * a.y), s * a.x - c * a.y, -a.theta};
}

/// exp of the body twist ξ = (a, b, φ) (a twist times a duration): the pose reached from the
/// identity moving with that twist held constant for the duration. The angle is φ itself (not
/// wrapped), so a twist of φ = 2π returns a pose with θ = 2π at the start point.
[[nodiscard]] inline Pose2 exp(const Eigen::Vector3d& xi) {
  const double h = 0.5 * xi(2);
  const double k = sinc(h);
  const double c = std::cos(h);
  const double s = std::sin(h);
  return {k * (c * xi(0) - s * xi(1)), k * (s * xi(0) + c * xi(1)), xi(2)};
}

/// log: the twist ξ with exp(ξ) = p as group elements, with φ = wrap_angle(θ) ∈ (−π, π] (the
/// shortest turn). Inverse of exp for |φ| ≤ π: (a, b) = R(−φ/2) t / sinc(φ/2), sinc(φ/2) ≥ 2/π.
[[nodiscard]] inline Eigen::Vector3d log(const Pose2& p) {
  const double phi = wrap_angle(p.theta);
  const double h = 0.5 * phi;
  const double k = 1.0 / sinc(h);
  const double c = std::cos(h);
  const double s = std::sin(h);
  return {k * (c * p.x + s * p.y), k * (-s * p.x + c * p.y), phi};
}

/// pose · exp(twist · dt): one step of a body twist held constant over dt (exact).
[[nodiscard]] inline Pose2 advance(const Pose2& pose, const Eigen::Vector3d& twist, double dt) {
  return compose(pose, exp(twist * dt));
}

}  // namespace slipwalk::core
