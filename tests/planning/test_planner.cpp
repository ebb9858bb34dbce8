// The planner (planning/planner.hpp) against its own definition: deduplicated equals full
// enumeration over whole plans, thread counts do not change a plan, lookahead 1 is the greedy
// planner, executed substeps equal the evaluated ones, and the three goals of §5.5 are tracked.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "connection/trajectory.hpp"
#include "core/error.hpp"
#include "planning/cost.hpp"
#include "planning/planner.hpp"

namespace slipwalk::planning {
namespace {

struct Row {
  long long option;
  double cost;
  double x, y, theta;
};

std::vector<Row> run(const PlanOptions& options, const Goal& goal, const PlanRobot& robot) {
  std::vector<Row> rows;
  plan(robot, options, goal, tripod_start(robot), [&](const StepRecord& r) {
    rows.push_back(
        {r.choice.option, r.choice.cost, r.state.pose.x, r.state.pose.y, r.state.pose.theta});
  });
  return rows;
}

Goal straight() {
  Goal g;
  g.twist = {0.2, 0.0, 0.0};
  return g;
}

TEST(Planner, TheDeduplicatedPlannerChoosesTheOptionFullEnumerationChoosesAtEveryStep) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.steps = 40;
  const std::vector<Row> dedup = run(options, straight(), robot);
  options.deduplicate = false;
  const std::vector<Row> full = run(options, straight(), robot);
  ASSERT_EQ(dedup.size(), full.size());
  for (std::size_t k = 0; k < dedup.size(); ++k) {
    EXPECT_EQ(dedup[k].option, full[k].option) << "step " << k;
    EXPECT_EQ(dedup[k].cost, full[k].cost) << "step " << k;
    EXPECT_EQ(dedup[k].x, full[k].x) << "step " << k;
  }
}

Goal turn() {
  Goal g;
  g.twist = {0.0, 0.0, 0.2};
  return g;
}

Goal diagonal() {
  Goal g;
  g.twist = {0.05, 0.02, 0.0};
  return g;
}

TEST(Planner, OptionIndicesAndDigitsAreInverse) {
  std::array<int, 6> digits{};
  for (long long o = 0; o < 4096; o += 7) {
    option_digits(o, 6, 4, digits.data());
    EXPECT_EQ(option_index(digits.data(), 6, 4), o);
  }
  const std::array<int, 6> leg0_only = {3, 0, 0, 0, 0, 0};
  EXPECT_EQ(option_index(leg0_only.data(), 6, 4), 3);  // leg 0 is the least significant digit
}

TEST(Planner, StartsBigAntWithItsTwoTripodsOutOfPhaseAsSection55) {
  const PlanState s = tripod_start(bigant_plan_robot());
  const std::vector<double> thesis = {0.5, 0.0, 0.5, 0.0, 0.5, 0.0};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(s.phi(i), thesis[static_cast<std::size_t>(i)]);
  }
  // Eight legs: each side alternates, the sides out of phase.
  const PlanState e = tripod_start(bigant_plan_robot(8));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NE(e.phi(i), e.phi(i + 1));
  }
  EXPECT_NE(e.phi(0), e.phi(4));
}

TEST(Planner, PutsOneTripodDownAtTheStartSoOnlyItsThreeLegsChoose) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  PlanData data(robot, options);
  StepChoice choice;
  plan_step(robot, options, straight(), tripod_start(robot), data, choice);
  const std::vector<char> down = {0, 1, 0, 1, 0, 1};  // φ = 0 is mid-stance
  EXPECT_EQ(choice.chooses, down);
  EXPECT_EQ(choice.evaluated, 64);  // 4³ distinct motions, not 4⁶
  for (int i : {0, 2, 4}) {
    EXPECT_EQ(choice.speed(i), options.swing_speed);
  }
}

/// The feet of a plan's executed shaft angles: φ_i(t) = φ_i,n + φ̇_i,n (t − t_n) on step n.
struct ReplayedFeet {
  PlanRobot robot;
  std::vector<double> t0;
  std::vector<Eigen::VectorXd> phi;
  std::vector<Eigen::VectorXd> speed;
  double tau = 0.0;
  void operator()(double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) const {
    auto n = static_cast<std::size_t>(std::floor(t / tau + 0.5));
    n = std::min(n, phi.size() - 1);
    for (int i = 0; i < robot.legs(); ++i) {
      double p = phi[n](i) + speed[n](i) * (t - t0[n]);
      p -= std::floor(p);
      Eigen::Vector3d dq;
      robot.toe(i, p, q.col(i), dq);
      qdot.col(i) = dq * speed[n](i);
    }
  }
};

TEST(Planner, ExecutesExactlyTheTrajectoryTheModelGivesForTheChosenShaftSpeeds) {
  // An independent route: the executed shaft angles, replayed as a gait through the trajectory
  // integrator of ch. 3 (connection::integrate) at the substep h, reach the plan's poses.
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.steps = 60;
  options.execute = 1;  // one substep per step: the integrator's dt is the step
  ReplayedFeet feet{robot, {}, {}, {}, options.horizon / options.substeps};
  std::vector<core::Pose2> poses;
  plan(robot, options, diagonal(), tripod_start(robot), [&](const StepRecord& r) {
    feet.t0.push_back(r.state.t);
    feet.phi.push_back(r.state.phi);
    feet.speed.push_back(r.choice.speed);
    poses.push_back(r.state.pose);
  });
  connection::TrajectoryOptions run;
  run.dt = feet.tau;
  run.steps = options.steps - 1;
  connection::TrajectoryData data(robot.robot);
  std::vector<core::Pose2> replayed;
  const auto summary = connection::integrate(
      robot.robot, std::cref(feet), run, connection::ViscousCoulombKernel{}, connection::NoFilter{},
      data, [&](const connection::TrajectoryStep& s) { replayed.push_back(s.pose); });
  ASSERT_EQ(summary.non_finite_step, -1) << summary.non_finite;
  ASSERT_EQ(replayed.size(), poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR(replayed[k].x, poses[k].x, 1e-12) << "step " << k;
    EXPECT_NEAR(replayed[k].y, poses[k].y, 1e-12) << "step " << k;
    EXPECT_NEAR(replayed[k].theta, poses[k].theta, 1e-12) << "step " << k;
  }
}

TEST(Planner, ABeamIsIgnoredWithoutLookAheadSoHorizonOneIsTheGreedyPlanner) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.steps = 30;
  const std::vector<Row> greedy = run(options, turn(), robot);
  options.beam = 16;
  const std::vector<Row> beam = run(options, turn(), robot);
  ASSERT_EQ(greedy.size(), beam.size());
  for (std::size_t k = 0; k < greedy.size(); ++k) {
    EXPECT_EQ(greedy[k].option, beam[k].option);
    EXPECT_EQ(greedy[k].cost, beam[k].cost);
  }
}

TEST(Planner, LooksAheadSeveralStepsWithABeamAndCountsTheLevelsItSearched) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.lookahead = 2;
  options.beam = 4;
  PlanData data(robot, options);
  StepChoice choice;
  plan_step(robot, options, straight(), tripod_start(robot), data, choice);
  // Level 1: the 64 motions of the root; level 2: the distinct motions of four kept nodes.
  EXPECT_GT(choice.evaluated, 64 + 4 * 8);
  EXPECT_GE(choice.option, 0);
  // The cost sums both levels' distances, so it is at least the best one-level cost.
  PlanOptions greedy;
  PlanData greedy_data(robot, greedy);
  StepChoice one;
  plan_step(robot, greedy, straight(), tripod_start(robot), greedy_data, one);
  EXPECT_GE(choice.cost, one.cost);
}

TEST(Planner, TracksTheThreeGoalsOfSection55) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.steps = 300;  // 1.5 s
  const PlanSummary s = plan(robot, options, straight(), tripod_start(robot), {});
  EXPECT_NEAR(s.end.pose.x, 0.3, 0.05);  // 0.2 m/s for 1.5 s
  EXPECT_LT(s.mean_distance, 0.02);
  const PlanSummary t = plan(robot, options, turn(), tripod_start(robot), {});
  EXPECT_NEAR(t.end.pose.theta, 0.3, 0.1);                 // 0.2 rad/s for 1.5 s
  EXPECT_LT(std::hypot(t.end.pose.x, t.end.pose.y), 0.1);  // "less than 0.1 m" (Fig. 5.10)
  const PlanSummary d = plan(robot, options, diagonal(), tripod_start(robot), {});
  EXPECT_GT(d.end.pose.x, 0.0);
  EXPECT_GT(d.end.pose.y, 0.0);
  EXPECT_LT(d.mean_distance, 0.02);
}

void expect_refused(const PlanRobot& robot, const PlanOptions& options, const std::string& where) {
  try {
    validate(robot, options);
    ADD_FAILURE() << "accepted; expected an error at " << where;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), where) << e.what();
  }
}

TEST(Planner, RefusesOptionsOutOfRangeNamingTheOption) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions o;
  o.execute = 21;
  expect_refused(robot, o, "plan.execute");
  o = {};
  o.speeds = {0.0, NAN};
  expect_refused(robot, o, "plan.speeds[1]");
  o = {};
  o.horizon = 0.0;
  expect_refused(robot, o, "plan.horizon");
  o = {};
  o.speeds = {-2.0, -1.0, 0.0, 1.0, 2.0};  // 5¹² > 2²⁴ options
  expect_refused(bigant_plan_robot(12), o, "plan.speeds");
  o = {};
  o.threads = 0;
  expect_refused(robot, o, "plan.threads");
}

TEST(Planner, RefusesAStartWithShaftAnglesOutsideOneTurn) {
  const PlanRobot robot = bigant_plan_robot();
  PlanState start = tripod_start(robot);
  start.phi(3) = 1.0;
  PlanOptions options;
  options.steps = 1;
  EXPECT_THROW(plan(robot, options, straight(), start, {}), core::InputError);
}

}  // namespace
}  // namespace slipwalk::planning
