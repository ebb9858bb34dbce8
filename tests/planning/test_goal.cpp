// Targets of a plan (planning/goal.hpp): the held twist is the SE(2) exponential (a straight
// line, a circle, a turn in place), waypoints interpolate linearly and hold at their ends, and
// bad goals are refused with the field named.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "planning/goal.hpp"

namespace slipwalk::planning {
namespace {

TEST(Goal, AStraightTwistMovesAlongTheStartHeadingAtItsSpeed) {
  Goal g;
  g.start = {1.0, 2.0, M_PI / 2.0};
  g.twist = {0.2, 0.0, 0.0};
  const core::Pose2 p = target_at(g, 5.0);
  EXPECT_NEAR(p.x, 1.0, 1e-15);
  EXPECT_NEAR(p.y, 3.0, 1e-15);
  EXPECT_EQ(p.theta, M_PI / 2.0);
}

TEST(Goal, ATurnInPlaceStaysAtTheStartAndTurnsAtItsRate) {
  Goal g;
  g.twist = {0.0, 0.0, 0.2};
  for (double t : {0.0, 1.0, 7.5, 40.0}) {
    const core::Pose2 p = target_at(g, t);
    EXPECT_EQ(p.x, 0.0);
    EXPECT_EQ(p.y, 0.0);
    EXPECT_NEAR(p.theta, 0.2 * t, 1e-15);
  }
}

TEST(Goal, ATwistWithSpeedAndTurnFollowsACircleOfRadiusVOverOmega) {
  Goal g;
  g.twist = {0.2, 0.0, 0.4};  // radius 0.5 m about (0, 0.5)
  for (double t : {0.3, 2.0, 9.0}) {
    const core::Pose2 p = target_at(g, t);
    EXPECT_NEAR(std::hypot(p.x, p.y - 0.5), 0.5, 1e-14);
    EXPECT_NEAR(p.theta, 0.4 * t, 1e-15);
  }
}

TEST(Goal, TheDiagonalGoalKeepsItsHeading) {
  Goal g;
  g.twist = {0.05, 0.02, 0.0};
  const core::Pose2 p = target_at(g, 10.0);
  EXPECT_NEAR(p.x, 0.5, 1e-15);
  EXPECT_NEAR(p.y, 0.2, 1e-15);
  EXPECT_EQ(p.theta, 0.0);
}

TEST(Goal, WaypointsInterpolateLinearlyAndHoldBeyondTheirEnds) {
  Goal g;
  g.times = {1.0, 3.0};
  g.waypoints = {{0.0, 0.0, 0.0}, {2.0, -4.0, 1.0}};
  validate(g);
  const core::Pose2 mid = target_at(g, 2.0);
  EXPECT_DOUBLE_EQ(mid.x, 1.0);
  EXPECT_DOUBLE_EQ(mid.y, -2.0);
  EXPECT_DOUBLE_EQ(mid.theta, 0.5);
  EXPECT_EQ(target_at(g, 0.0).x, 0.0);
  EXPECT_EQ(target_at(g, 99.0).y, -4.0);
}

TEST(Goal, TheThesisGoalsAreTheCaptionsOfFigures59To511AndOtherNamesAreRefused) {
  EXPECT_EQ(thesis_goal("straight").twist, Eigen::Vector3d(0.2, 0.0, 0.0));
  EXPECT_EQ(thesis_goal("turn").twist, Eigen::Vector3d(0.0, 0.0, 0.2));
  EXPECT_EQ(thesis_goal("diagonal").twist, Eigen::Vector3d(0.05, 0.02, 0.0));
  EXPECT_TRUE(thesis_goal("turn").times.empty());
  EXPECT_THROW((void)thesis_goal("sideways"), core::InputError);
}

void expect_refused(const Goal& g, const std::string& where) {
  try {
    validate(g);
    ADD_FAILURE() << "accepted; expected an error at " << where;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), where) << e.what();
  }
}

TEST(Goal, RefusesNonFiniteValuesAndWaypointsThatDoNotIncrease) {
  Goal g;
  g.twist(2) = NAN;
  expect_refused(g, "goal.twist[2]");
  Goal w;
  w.times = {0.0, 1.0, 1.0};
  w.waypoints = {{}, {}, {}};
  expect_refused(w, "goal.waypoints[2].t");
  Goal one;
  one.times = {0.0};
  one.waypoints = {{}};
  expect_refused(one, "goal.waypoints");
  Goal mismatch;
  mismatch.times = {0.0, 1.0};
  mismatch.waypoints = {{}};
  expect_refused(mismatch, "goal.waypoints");
}

}  // namespace
}  // namespace slipwalk::planning
