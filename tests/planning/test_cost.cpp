// The planner's cost (planning/cost.hpp) is a proper distance on SE(2): checked on random poses
// against the metric axioms and the invariance it claims, and against the closed form of its
// geodesic (a straight line in the plane traversed while the heading turns uniformly: the
// length of a finely sampled geodesic equals the distance).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/se2.hpp"
#include "planning/cost.hpp"

namespace slipwalk::planning {
namespace {

constexpr double kRho = kDefaultRotationLength;

core::Pose2 random_pose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> xy(-3.0, 3.0);
  std::uniform_real_distribution<double> angle(-10.0, 10.0);  // unwrapped, several turns
  return {xy(rng), xy(rng), angle(rng)};
}

TEST(Se2Distance, IsZeroExactlyBetweenEqualPosesAndPositiveOtherwise) {
  std::mt19937_64 rng(1);
  for (int k = 0; k < 1000; ++k) {
    const core::Pose2 a = random_pose(rng);
    EXPECT_EQ(se2_distance(a, a, kRho), 0.0);
    core::Pose2 b = a;
    b.x += 1e-9;
    EXPECT_GT(se2_distance(a, b, kRho), 0.0);
  }
}

TEST(Se2Distance, CountsHeadingsThatDifferByFullTurnsAsTheSame) {
  const core::Pose2 a{0.1, -0.2, 0.3};
  const core::Pose2 b{0.1, -0.2, 0.3 + 4.0 * std::numbers::pi};
  EXPECT_NEAR(se2_distance(a, b, kRho), 0.0, 1e-15);
  // And takes the shorter way round: 350° apart is 10°.
  const core::Pose2 c{0.0, 0.0, 350.0 * std::numbers::pi / 180.0};
  EXPECT_NEAR(se2_distance({}, c, 1.0), 10.0 * std::numbers::pi / 180.0, 1e-14);
}

TEST(Se2Distance, IsSymmetric) {
  std::mt19937_64 rng(2);
  for (int k = 0; k < 1000; ++k) {
    const core::Pose2 a = random_pose(rng);
    const core::Pose2 b = random_pose(rng);
    EXPECT_NEAR(se2_distance(a, b, kRho), se2_distance(b, a, kRho), 1e-14);
  }
}

TEST(Se2Distance, SatisfiesTheTriangleInequality) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 1000; ++k) {
    const core::Pose2 a = random_pose(rng);
    const core::Pose2 b = random_pose(rng);
    const core::Pose2 c = random_pose(rng);
    EXPECT_LE(se2_distance(a, c, kRho),
              se2_distance(a, b, kRho) + se2_distance(b, c, kRho) + 1e-13);
  }
}

TEST(Se2Distance, IsInvariantUnderACommonRigidMotionOfBothPoses) {
  std::mt19937_64 rng(4);
  for (int k = 0; k < 1000; ++k) {
    const core::Pose2 a = random_pose(rng);
    const core::Pose2 b = random_pose(rng);
    const core::Pose2 g = random_pose(rng);
    EXPECT_NEAR(se2_distance(core::compose(g, a), core::compose(g, b), kRho),
                se2_distance(a, b, kRho), 1e-12);
  }
}

TEST(Se2Distance, EqualsTheLengthOfItsGeodesicUnderTheMetricDx2Dy2Rho2Dtheta2) {
  // The geodesic from a to b: (x, y) on the segment, θ turning by wrap(θ_b − θ_a), both
  // uniformly; its length by summing the metric over a fine polygon.
  std::mt19937_64 rng(5);
  for (int k = 0; k < 50; ++k) {
    const core::Pose2 a = random_pose(rng);
    const core::Pose2 b = random_pose(rng);
    const double turn = core::wrap_angle(b.theta - a.theta);
    constexpr int kPieces = 1000;
    double length = 0.0;
    for (int i = 0; i < kPieces; ++i) {
      const double dx = (b.x - a.x) / kPieces;
      const double dy = (b.y - a.y) / kPieces;
      const double dth = turn / kPieces;
      length += std::sqrt(dx * dx + dy * dy + kRho * kRho * dth * dth);
    }
    EXPECT_NEAR(se2_distance(a, b, kRho), length, 1e-12 * (1.0 + length));
  }
}

TEST(Se2Distance, WeighsOneRadianOfHeadingAsRhoMetres) {
  const core::Pose2 turned{0.0, 0.0, 1.0};
  EXPECT_DOUBLE_EQ(se2_distance({}, turned, 0.3), 0.3);
  EXPECT_DOUBLE_EQ(se2_distance({}, turned, 0.0), 0.0);
  const core::Pose2 moved{0.3, 0.4, 0.0};
  EXPECT_DOUBLE_EQ(se2_distance({}, moved, 123.0), 0.5);
}

}  // namespace
}  // namespace slipwalk::planning
