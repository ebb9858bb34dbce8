// A plan's shaft angles as foot kinematics (planning/replay_feet.hpp): the planner's own
// execution agrees with the piecewise-linear law, the feet at each step's start are the toe at the
// recorded angles, q is continuous across steps (the wrap of φ at 1 → 0 included), q̇ is q's
// derivative (finite differences), the feet rest outside the plan, and a slowed plan walks the
// same feet at a slower pace.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "planning/goal.hpp"
#include "planning/plan_robot.hpp"
#include "planning/planner.hpp"
#include "planning/replay_feet.hpp"

namespace slipwalk::planning {
namespace {

/// Distance between two shaft angles on the circle of one turn.
double turn_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 1.0 - d);
}

/// A short plan of the straight goal (shared: planning is the costly part).
const PlanTrack& straight_track() {
  static const PlanTrack track = [] {
    const PlanRobot robot = bigant_plan_robot();
    PlanOptions options;
    options.steps = 60;
    Goal goal;
    goal.twist = {0.2, 0.0, 0.0};
    return plan_track(robot, options, goal, tripod_start(robot));
  }();
  return track;
}

/// A synthetic track of one leg pair that crosses φ = 1 → 0 forward and 0 → 1 backward.
PlanTrack wrapping_track(const PlanRobot& robot) {
  PlanTrack t;
  t.step_duration = 0.005;
  const int n = robot.legs(), s = 4;
  t.phi.resize(n, s);
  t.speed.resize(n, s);
  t.phi.col(0).setConstant(0.995);
  t.speed.setZero();
  t.speed.row(0).setConstant(2.0);   // 0.995 → 0.005 → 0.015 …: forward across 1 → 0
  t.speed.row(1).setConstant(-2.0);  // 0.005 → 0.995 → …: backward across 0 → 1
  t.phi(1, 0) = 0.005;
  for (int k = 0; k < s; ++k) {
    t.t.push_back(k * t.step_duration);
    t.pose.push_back({0.01 * k, 0.0, 0.0});
    if (k > 0) {
      for (int i = 0; i < n; ++i) {
        const double p = t.phi(i, k - 1) + t.speed(i, k - 1) * t.step_duration;
        t.phi(i, k) = p - std::floor(p);
      }
    }
  }
  t.end_pose = {0.04, 0.0, 0.0};
  t.end_phi = t.phi.col(s - 1) + t.speed.col(s - 1) * t.step_duration;
  t.end_phi = t.end_phi.array() - t.end_phi.array().floor();
  return t;
}

TEST(ReplayFeet, ThePlannersNextAnglesAreTheLinearLawAtTheStepsEnd) {
  const PlanTrack& track = straight_track();
  ASSERT_EQ(track.steps(), 60);
  EXPECT_NEAR(track.step_duration, 0.005, 1e-15);
  for (long long n = 0; n + 1 < track.steps(); ++n) {
    EXPECT_NEAR(track.t[n + 1] - track.t[n], track.step_duration, 1e-12);
    for (int i = 0; i < track.legs(); ++i) {
      const double predicted = track.phi(i, n) + track.speed(i, n) * track.step_duration;
      EXPECT_LT(turn_distance(predicted - std::floor(predicted), track.phi(i, n + 1)), 1e-12)
          << "step " << n << " leg " << i;
    }
  }
}

TEST(ReplayFeet, AtEveryStepStartTheFeetAreTheToeAtThePlannedAngles) {
  const PlanRobot robot = bigant_plan_robot();
  const PlanTrack& track = straight_track();
  const robots::Walker w = replay_walker(robot, track);
  Eigen::Matrix3Xd q(3, 6), qdot(3, 6);
  Eigen::Vector3d toe, dq;
  Eigen::VectorXd phase(6);
  for (long long n = 0; n < track.steps(); ++n) {
    w.feet(track.t[n], q, qdot);
    w.phase(track.t[n], phase);
    for (int i = 0; i < 6; ++i) {
      robot.toe(i, track.phi(i, n), toe, dq);
      EXPECT_LT((q.col(i) - toe).norm(), 1e-12) << "step " << n << " leg " << i;
      EXPECT_LT((qdot.col(i) - dq * track.speed(i, n)).norm(), 1e-12);
      EXPECT_LT(turn_distance(phase(i), track.phi(i, n)), 1e-12);
    }
  }
}

TEST(ReplayFeet, TheFeetAreContinuousAcrossStepsAndQdotIsTheirDerivative) {
  const PlanRobot robot = bigant_plan_robot();
  const PlanTrack& track = straight_track();
  const robots::Walker w = replay_walker(robot, track);
  Eigen::Matrix3Xd q0(3, 6), q1(3, 6), qa(3, 6), qb(3, 6), qdot(3, 6), unused(3, 6);
  const double d = 1e-7;
  for (long long n = 1; n < track.steps(); ++n) {
    // Across the boundary: |Δq| ≤ |q̇| 2d with |q̇| a few m/s at most; a jump would be mm.
    w.feet(track.t[n] - d, q0, unused);
    w.feet(track.t[n] + d, q1, unused);
    EXPECT_LT((q1 - q0).cwiseAbs().maxCoeff(), 1e-5) << "step " << n;
    // Inside the step: central differences.
    const double mid = track.t[n] + 0.5 * track.step_duration;
    w.feet(mid, q0, qdot);
    w.feet(mid - d, qa, unused);
    w.feet(mid + d, qb, unused);
    EXPECT_LT(((qb - qa) / (2.0 * d) - qdot).cwiseAbs().maxCoeff(), 1e-5) << "step " << n;
  }
}

TEST(ReplayFeet, TheWrapOfTheShaftAngleLeavesTheFeetContinuous) {
  const PlanRobot robot = bigant_plan_robot();
  const PlanTrack track = wrapping_track(robot);
  const robots::Walker w = replay_walker(robot, track);
  Eigen::Matrix3Xd q0(3, 6), q1(3, 6), qdot(3, 6), unused(3, 6);
  Eigen::VectorXd phase(6);
  // Leg 0 crosses 1 → 0 inside step 0 (at t = 2.5 ms), leg 1 crosses 0 → 1 there too.
  const double cross = 0.0025, d = 1e-8;
  w.feet(cross - d, q0, unused);
  w.feet(cross + d, q1, qdot);
  EXPECT_LT((q1 - q0).cwiseAbs().maxCoeff(), 1e-6);
  w.phase(cross + 1e-4, phase);
  EXPECT_NEAR(phase(0), 2.0 * 1e-4, 1e-12);
  EXPECT_NEAR(phase(1), 1.0 - 2.0 * 1e-4, 1e-12);
  for (long long n = 0; n < track.steps(); ++n) {
    for (int i = 0; i < 6; ++i) {
      EXPECT_GE(track.phi(i, n), 0.0);
      EXPECT_LT(track.phi(i, n), 1.0);
    }
  }
}

TEST(ReplayFeet, TheFeetRestBeforeThePlanAndAfterItsEnd) {
  const PlanRobot robot = bigant_plan_robot();
  const PlanTrack& track = straight_track();
  const robots::Walker w = replay_walker(robot, track);
  EXPECT_NEAR(w.period, 60 * 0.005, 1e-12);
  Eigen::Matrix3Xd q(3, 6), qdot(3, 6), first(3, 6), unused(3, 6);
  Eigen::Vector3d toe, dq;
  w.feet(track.t[0], first, unused);
  w.feet(track.t[0] - 1.0, q, qdot);
  EXPECT_EQ(qdot.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((q - first).cwiseAbs().maxCoeff(), 1e-15);
  w.feet(track.end_time() + 1.0, q, qdot);
  EXPECT_EQ(qdot.cwiseAbs().maxCoeff(), 0.0);
  for (int i = 0; i < 6; ++i) {
    robot.toe(i, track.end_phi(i), toe, dq);
    EXPECT_LT((q.col(i) - toe).norm(), 1e-12);
  }
  // And the end is where the last step's law arrives.
  w.feet(track.end_time() - 1e-9, first, unused);
  EXPECT_LT((q - first).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(ReplayFeet, ASlowedPlanWalksTheSameFeetAtTheSlowerPace) {
  const PlanRobot robot = bigant_plan_robot();
  const PlanTrack& track = straight_track();
  const PlanTrack slow = slowed(track, 4.0);
  EXPECT_NEAR(slow.end_time(), 4.0 * track.end_time(), 1e-12);
  const robots::Walker fast = replay_walker(robot, track);
  const robots::Walker w = replay_walker(robot, slow);
  Eigen::Matrix3Xd q(3, 6), qdot(3, 6), qs(3, 6), qdots(3, 6);
  for (double t : {0.0013, 0.1, 0.2222, 0.29}) {
    fast.feet(t, q, qdot);
    w.feet(4.0 * t, qs, qdots);
    EXPECT_LT((qs - q).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((4.0 * qdots - qdot).cwiseAbs().maxCoeff(), 1e-12);
  }
  EXPECT_THROW((void)slowed(track, 0.5), core::InputError);
}

TEST(ReplayFeet, ABadTrackIsRefusedNamingTheTrack) {
  const PlanRobot robot = bigant_plan_robot();
  EXPECT_THROW((void)replay_walker(robot, PlanTrack{}), core::InputError);
  PlanTrack t = wrapping_track(robot);
  t.t[2] = t.t[1];
  EXPECT_THROW((void)replay_walker(robot, t), core::InputError);
  t = wrapping_track(robot);
  t.speed.resize(5, 4);
  EXPECT_THROW((void)replay_walker(robot, t), core::InputError);
}

}  // namespace
}  // namespace slipwalk::planning
