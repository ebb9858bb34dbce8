// A plan replayed on MuJoCo's BigANT (peers/mujoco/plan_replay.hpp, the plan_replay point kind):
// a short plan of each straight-line goal moves MuJoCo's body in the goal's direction, the turn
// turns it the goal's way, both start at the plan's start pose and are sampled at the plan's
// step times. Without MuJoCo the point kind still plans and says why MuJoCo's columns are empty;
// the tests that need MuJoCo are skipped, saying so.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include "core/error.hpp"
#include "planning/goal.hpp"
#include "planning/plan_robot.hpp"
#include "planning/planner.hpp"
#include "planning/replay_feet.hpp"
#include "support/point_rows.hpp"
#include "support/skip_without_mujoco.hpp"
#include "sweeps/engine/point_kind.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/plan_replay.hpp"
#endif

namespace slipwalk::peers::mujoco {
namespace {

#ifdef SLIPWALK_HAVE_MUJOCO
planning::PlanTrack short_plan(const Eigen::Vector3d& twist, long long steps) {
  const planning::PlanRobot robot = planning::bigant_plan_robot();
  planning::PlanOptions options;
  options.steps = steps;
  planning::Goal goal;
  goal.twist = twist;
  return planning::plan_track(robot, options, goal, planning::tripod_start(robot));
}

/// MuJoCo's feet close to the plan's (Fig. 3.14's robot with stiff x/y slides and the lead), a
/// short settle.
PlanReplayOptions stiff() {
  PlanReplayOptions o;
  o.settle = 0.3;
  o.kp_xy = 2675.0;
  o.lead = true;
  return o;
}
#endif

TEST(PlanReplay, AStraightPlanMovesMujocosBodyForwardFromThePlansStart) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const planning::PlanTrack track = short_plan({0.2, 0.0, 0.0}, 100);
  const PlanReplay r = replay_plan(planning::bigant_plan_robot(), track, stiff());
  ASSERT_EQ(r.t.size(), 101U);
  ASSERT_EQ(r.mujoco.size(), 101U);
  for (long long n = 0; n < track.steps(); ++n) {
    EXPECT_EQ(r.t[n], track.t[n]);
    EXPECT_EQ(r.plan[n].x, track.pose[n].x);
  }
  EXPECT_NEAR(r.t.back(), track.end_time(), 1e-12);
  // Both start at the plan's start pose (MuJoCo relative to its settled pose).
  EXPECT_NEAR(r.mujoco.front().x, 0.0, 1e-12);
  EXPECT_NEAR(r.mujoco.front().theta, 0.0, 1e-12);
  // The plan walks ≈ 0.1 m forward in 0.5 s; MuJoCo's body goes forward, more than sideways.
  const core::Pose2& end = r.mujoco.back();
  EXPECT_GT(r.plan.back().x, 0.05);
  EXPECT_GT(end.x, 0.25 * r.plan.back().x);
  EXPECT_GT(end.x, 3.0 * std::abs(end.y));
  // Its slides follow the planned feet within a centimetre.
  EXPECT_LT(r.drive.tracking.rmse().head<2>().maxCoeff(), 0.01);
#endif
}

TEST(PlanReplay, ATurnPlanTurnsMujocosBodyTheGoalsWay) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const planning::PlanTrack track = short_plan({0.0, 0.0, 0.2}, 200);
  const PlanReplay r = replay_plan(planning::bigant_plan_robot(), track, stiff());
  EXPECT_GT(r.plan.back().theta, 0.05);
  EXPECT_GT(r.mujoco.back().theta, 0.25 * r.plan.back().theta);
#endif
}

TEST(PlanReplay, ATimestepThatDoesNotDivideTheStepIsRefused) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const planning::PlanTrack track = short_plan({0.2, 0.0, 0.0}, 2);
  PlanReplayOptions o = stiff();
  o.timestep = 0.002;  // 5 ms / 2 ms is not whole
  EXPECT_THROW((void)replay_plan(planning::bigant_plan_robot(), track, o), core::InputError);
#endif
}

TEST(PlanReplay, ThePointKindGivesOneRowPerStepTimeAndSaysWhenMujocoIsMissing) {
  const sweeps::PointKind& kind = test_support::point_kind("plan_replay");
  const auto points = test_support::points_of(
      "plan_replay", "[params]\nsteps = 20\nsettle = 0.2\ngoal = \"diagonal\"\n");
  ASSERT_EQ(points.size(), 1U);
  const sweeps::PointResult res = kind.run(points.front());
  ASSERT_EQ(res.rows.size(), 21U);
  const std::size_t xm = test_support::column(kind, "x_mujoco");
  const std::size_t msg = test_support::column(kind, "message");
  const double x_mujoco = std::get<double>(res.rows.back()[xm]);
#ifdef SLIPWALK_HAVE_MUJOCO
  EXPECT_TRUE(std::isfinite(x_mujoco));
  EXPECT_EQ(std::get<std::string>(res.rows.back()[msg]), "");
#else
  EXPECT_TRUE(std::isnan(x_mujoco));
  EXPECT_NE(std::get<std::string>(res.rows.back()[msg]).find("without MuJoCo"), std::string::npos);
#endif
}

}  // namespace
}  // namespace slipwalk::peers::mujoco
