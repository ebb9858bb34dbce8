// robots::four_bar_pose: the closed-form loop closure of a crank-rocker (robots/four_bar.hpp).
// Oracles: the two link-length constraints at every crank angle, the vector loop through the
// coupler and rocker angles, hand-computed poses of Hoekens' straight-line linkage, the toe's
// rigid placement on the coupler, and the analytic derivative against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "robots/bigant.hpp"
#include "robots/four_bar.hpp"

namespace slipwalk::robots {
namespace {

constexpr double kPi = std::numbers::pi;

/// Hoekens' linkage: crank 1, ground 2, coupler and rocker 2.5, toe on the coupler extended to 5.
FourBar hoekens(int branch) {
  FourBar f;
  f.crank = 1.0;
  f.coupler = 2.5;
  f.rocker = 2.5;
  f.rocker_pivot = {2.0, 0.0};
  f.toe_distance = 5.0;
  f.toe_angle = 0.0;
  f.branch = branch;
  return f;
}

std::vector<FourBar> linkages() {
  FourBar mirrored = bigant_linkage();
  mirrored.branch = -1;  // the other assembly of the same links
  return {bigant_linkage(), hoekens(1), hoekens(-1), mirrored};
}

TEST(FourBar, TheLinkagesUnderTestAreValidCrankRockers) {
  for (const FourBar& f : linkages()) {
    EXPECT_NO_THROW(validate(f));
  }
}

TEST(FourBar, LoopClosureHoldsAtEveryCrankAngle) {
  for (const FourBar& f : linkages()) {
    const double scale = f.coupler + f.rocker;  // lengths are checked relative to the linkage
    for (int k = 0; k < 3600; ++k) {
      const double theta = 2.0 * kPi * k / 3600.0 - kPi;
      const FourBarPose p = four_bar_pose(f, theta);
      EXPECT_NEAR(p.A.norm(), f.crank, 1e-12 * scale);
      EXPECT_NEAR((p.B - p.A).norm(), f.coupler, 1e-12 * scale) << "theta " << theta;
      EXPECT_NEAR((p.B - f.rocker_pivot).norm(), f.rocker, 1e-12 * scale) << "theta " << theta;
      // The vector loop O₂A + AB = O₂O₄ + O₄B through the reported angles.
      const Eigen::Vector2d lhs =
          p.A + f.coupler * Eigen::Vector2d(std::cos(p.coupler_angle), std::sin(p.coupler_angle));
      const Eigen::Vector2d rhs =
          f.rocker_pivot +
          f.rocker * Eigen::Vector2d(std::cos(p.rocker_angle), std::sin(p.rocker_angle));
      EXPECT_LT((lhs - rhs).norm(), 1e-12 * scale);
      // The toe is rigid on the coupler: |P − A| = e at angle γ from AB.
      EXPECT_NEAR((p.P - p.A).norm(), f.toe_distance, 1e-12 * scale);
      const Eigen::Vector2d ab = p.B - p.A;
      const Eigen::Vector2d ap = p.P - p.A;
      EXPECT_NEAR(std::atan2(ab.x() * ap.y() - ab.y() * ap.x(), ab.dot(ap)), f.toe_angle, 1e-12);
      // The branch: B on the σ side of the ray A → O₄, never on it (no toggle).
      const Eigen::Vector2d ao = f.rocker_pivot - p.A;
      EXPECT_GT(f.branch * (ao.x() * ab.y() - ao.y() * ab.x()), 0.0);
      EXPECT_GT(std::abs(p.transmission_sin), 0.1);
    }
  }
}

TEST(FourBar, HoekensPosesComputedByHand) {
  // θ = 90°: A = (0, 1), B = (2, 2.5), P = 2B − A = (4, 4); θ = 180°: A = (−1, 0), B = (0.5, 2),
  // P = (2, 4); θ = 270°: B = (0, 1.5), P = (0, 4) — three points of its straight line v = 4.
  const FourBar f = hoekens(1);
  const FourBarPose p90 = four_bar_pose(f, kPi / 2);
  EXPECT_LT((p90.B - Eigen::Vector2d(2.0, 2.5)).norm(), 1e-14);
  EXPECT_LT((p90.P - Eigen::Vector2d(4.0, 4.0)).norm(), 1e-14);
  const FourBarPose p180 = four_bar_pose(f, kPi);
  EXPECT_LT((p180.B - Eigen::Vector2d(0.5, 2.0)).norm(), 1e-14);
  EXPECT_LT((p180.P - Eigen::Vector2d(2.0, 4.0)).norm(), 1e-14);
  const FourBarPose p270 = four_bar_pose(f, 1.5 * kPi);
  EXPECT_LT((p270.P - Eigen::Vector2d(0.0, 4.0)).norm(), 1e-13);
  // The other branch is the mirror image in the ground line.
  const FourBarPose m = four_bar_pose(hoekens(-1), -kPi / 2);
  EXPECT_LT((m.P - Eigen::Vector2d(4.0, -4.0)).norm(), 1e-14);
  // Between 90° and 270° the toe stays within 1 % of the crank of that line (Hoekens' design).
  for (int k = 0; k <= 180; ++k) {
    const double theta = kPi / 2 + kPi * k / 180.0;
    EXPECT_NEAR(four_bar_pose(f, theta).P.y(), 4.0, 0.01);
  }
}

TEST(FourBar, DerivativesMatchCentralDifferences) {
  const double h = 1e-6;
  for (const FourBar& f : linkages()) {
    for (int k = 0; k < 360; ++k) {
      const double theta = 2.0 * kPi * (k + 0.37) / 360.0;
      const FourBarPose p = four_bar_pose(f, theta);
      const FourBarPose lo = four_bar_pose(f, theta - h);
      const FourBarPose hi = four_bar_pose(f, theta + h);
      const Eigen::Vector2d dA = (hi.A - lo.A) / (2 * h);
      const Eigen::Vector2d dB = (hi.B - lo.B) / (2 * h);
      const Eigen::Vector2d dP = (hi.P - lo.P) / (2 * h);
      const double scale = f.toe_distance + f.coupler;  // m per radian, the size of dP
      EXPECT_LT((dA - p.dA).norm(), 1e-6 * scale);
      EXPECT_LT((dB - p.dB).norm(), 1e-6 * scale) << "theta " << theta;
      EXPECT_LT((dP - p.dP).norm(), 1e-6 * scale) << "theta " << theta;
      // And the differentiated constraints hold exactly.
      EXPECT_NEAR((p.B - p.A).dot(p.dB - p.dA), 0.0, 1e-12 * scale * scale);
      EXPECT_NEAR((p.B - f.rocker_pivot).dot(p.dB), 0.0, 1e-12 * scale * scale);
    }
  }
}

TEST(FourBar, ValidationNamesTheField) {
  auto where = [](const FourBar& f) {
    try {
      validate(f);
    } catch (const core::InputError& e) {
      return e.where();
    }
    return std::string("(no error)");
  };
  FourBar f = bigant_linkage();
  f.crank = -0.07;
  EXPECT_EQ(where(f), "four_bar.crank");
  f = bigant_linkage();
  f.rocker = std::nan("");
  EXPECT_EQ(where(f), "four_bar.rocker");
  f = bigant_linkage();
  f.branch = 0;
  EXPECT_EQ(where(f), "four_bar.branch");
  f = bigant_linkage();
  f.crank = 0.09;  // a + d > b + c: the crank cannot turn fully
  EXPECT_EQ(where(f), "four_bar");
  f = hoekens(1);
  f.rocker_pivot = {1.2, 0.0};  // d − a < |b − c| fails only when b ≠ c
  f.rocker = 1.5;
  EXPECT_EQ(where(f), "four_bar");
}

}  // namespace
}  // namespace slipwalk::robots
