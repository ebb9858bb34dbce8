// core/se2.hpp: the exponential map of a body twist, compose, inverse, log. Oracles: the closed
// form of a circular arc, exp(log) round trips, the one-parameter subgroup property
// exp(nξ) = exp(ξ)ⁿ (constant twists integrate exactly), the series/closed-form switch of sinc.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/se2.hpp"

namespace slipwalk::core {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_pose_near(const Pose2& a, const Pose2& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.theta, b.theta, tol);
}

TEST(Se2, ExpIsTheCircularArc) {
  // Moving forward at v with yaw rate ω for time T from the origin: a circle of radius v/ω
  // centred at (0, v/ω): x = (v/ω) sin(ωT), y = (v/ω)(1 − cos(ωT)).
  const double v = 0.7;
  const double w = 0.9;
  for (double T : {0.1, 1.0, 3.0, 7.0}) {
    const Pose2 p = exp(Eigen::Vector3d(v * T, 0.0, w * T));
    EXPECT_NEAR(p.x, v / w * std::sin(w * T), 1e-14);
    EXPECT_NEAR(p.y, v / w * (1.0 - std::cos(w * T)), 1e-14);
    EXPECT_EQ(p.theta, w * T);
  }
}

TEST(Se2, ZeroYawRateIsAStraightLine) {
  const Pose2 start{1.0, -2.0, 0.4};
  const Eigen::Vector3d twist(0.3, -0.2, 0.0);
  const Pose2 p = advance(start, twist, 5.0);
  // Straight along the body axes rotated by the start angle.
  EXPECT_NEAR(p.x, 1.0 + 5.0 * (0.3 * std::cos(0.4) + 0.2 * std::sin(0.4)), 1e-15);
  EXPECT_NEAR(p.y, -2.0 + 5.0 * (0.3 * std::sin(0.4) - 0.2 * std::cos(0.4)), 1e-15);
  EXPECT_EQ(p.theta, 0.4);
  const Pose2 q = exp(Eigen::Vector3d(2.0, 3.0, 0.0));
  EXPECT_EQ(q.x, 2.0);  // sinc(0) = 1 exactly, cos 0 = 1, sin 0 = 0
  EXPECT_EQ(q.y, 3.0);
}

TEST(Se2, ConstantTwistInNStepsIsOneStepOfNdt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d twist(U(rng), U(rng), 3.0 * U(rng));
    const Pose2 start{U(rng), U(rng), kPi * U(rng)};
    const int n = 1000;
    const double dt = 1e-3;
    Pose2 p = start;
    for (int i = 0; i < n; ++i) {
      p = advance(p, twist, dt);
    }
    const Pose2 once = advance(start, twist, n * dt);
    // 1000 compositions accumulate rounding ~ n·eps·(|θ| + path length) ≲ 1e-12; an integrator
    // that is not exact per step (forward Euler on the pose) is off by O(dt) ~ 1e-3 here.
    expect_pose_near(p, once, 1e-12);
  }
}

TEST(Se2, AFullCircleReturns) {
  const Eigen::Vector3d twist(0.5, 0.1, 2.0 * kPi);  // one turn per second
  const Pose2 start{0.3, 0.2, 1.0};
  const Pose2 once = advance(start, twist, 1.0);
  expect_pose_near(once, Pose2{start.x, start.y, start.theta + 2.0 * kPi}, 1e-15);
  Pose2 p = start;
  for (int i = 0; i < 360; ++i) {
    p = advance(p, twist, 1.0 / 360.0);
  }
  expect_pose_near(p, Pose2{start.x, start.y, start.theta + 2.0 * kPi}, 1e-13);
}

TEST(Se2, ExpLogRoundTrip) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    // |φ| < π: log(exp(ξ)) = ξ.
    const Eigen::Vector3d xi(2.0 * U(rng), 2.0 * U(rng), 0.999 * kPi * U(rng));
    const Eigen::Vector3d back = log(exp(xi));
    EXPECT_NEAR((back - xi).norm(), 0.0, 1e-14 * (1.0 + xi.norm()));
    // exp(log(p)) = p for any pose, as group elements (angle modulo 2π).
    const Pose2 p{3.0 * U(rng), 3.0 * U(rng), 10.0 * U(rng)};
    const Pose2 q = exp(log(p));
    EXPECT_NEAR(q.x, p.x, 1e-14);
    EXPECT_NEAR(q.y, p.y, 1e-14);
    EXPECT_NEAR(wrap_angle(q.theta - p.theta), 0.0, 1e-14);
  }
}

TEST(Se2, ComposeAndInverse) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Pose2 a{U(rng), U(rng), 4.0 * U(rng)};
    const Pose2 b{U(rng), U(rng), 4.0 * U(rng)};
    const Pose2 c{U(rng), U(rng), 4.0 * U(rng)};
    expect_pose_near(compose(a, inverse(a)), Pose2{}, 1e-15);
    expect_pose_near(compose(inverse(a), a), Pose2{}, 1e-15);
    expect_pose_near(compose(compose(a, b), c), compose(a, compose(b, c)), 1e-14);
    // A pose maps the body point (u, v) to R(θ)(u, v) + t; composing poses composes the maps.
    const Eigen::Vector2d u(U(rng), U(rng));
    auto apply = [](const Pose2& p, const Eigen::Vector2d& v) {
      return Eigen::Vector2d(p.x + std::cos(p.theta) * v(0) - std::sin(p.theta) * v(1),
                             p.y + std::sin(p.theta) * v(0) + std::cos(p.theta) * v(1));
    };
    EXPECT_NEAR((apply(compose(a, b), u) - apply(a, apply(b, u))).norm(), 0.0, 1e-14);
  }
}

TEST(Se2, SincSeriesIsContinuousAtTheSwitch) {
  // Just below and just above the switch the two formulas agree to rounding, and both agree with
  // long double sin(s)/s (which has no cancellation either).
  const double s0 = kSincSeriesBelow;
  for (double s : {std::nextafter(s0, 0.0), s0, std::nextafter(s0, 1.0), -s0,
                   std::nextafter(-s0, 0.0), 1e-3, 1e-6, 1e-9, 0.5 * s0, 2.0 * s0}) {
    const long double ref = std::sin(static_cast<long double>(s)) / static_cast<long double>(s);
    EXPECT_NEAR(sinc(s), static_cast<double>(ref), 2e-16) << s;
  }
  EXPECT_EQ(sinc(0.0), 1.0);
  EXPECT_NEAR(sinc(std::nextafter(s0, 0.0)), sinc(s0), 1e-16);
  // exp is continuous in φ through 0: the arc of a tiny yaw rate is the line plus O(φ).
  const Pose2 line = exp(Eigen::Vector3d(1.0, 0.0, 0.0));
  const Pose2 arc = exp(Eigen::Vector3d(1.0, 0.0, 1e-12));
  EXPECT_NEAR(arc.x, line.x, 1e-15);
  EXPECT_NEAR(arc.y, 0.5e-12, 1e-27);  // y = (1 − cos φ)/φ ≈ φ/2
}

TEST(Se2, WrapAngle) {
  EXPECT_EQ(wrap_angle(0.0), 0.0);
  EXPECT_NEAR(wrap_angle(3.0 * kPi), kPi, 1e-15);
  EXPECT_NEAR(wrap_angle(-kPi), kPi, 1e-15);
  EXPECT_NEAR(wrap_angle(7.0), 7.0 - 2.0 * kPi, 1e-15);
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = wrap_angle(a);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-14);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-14);
  }
}

}  // namespace
}  // namespace slipwalk::core
