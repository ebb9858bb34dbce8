// The planning point kinds (sweeps/points/planning.cpp) against the planner they wrap: plan_run's
// rows are the plan CSV of planning::write_plan_row, cell for cell, plus the state after the last
// step; plan_summary's numbers are the planner's own summary and agree with plan_run's rows;
// threads do not change a plan; foot_path is the toe of the leg it names, with the figure's five
// points marked. Bad keys name themselves.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "planning/plan_csv.hpp"
#include "planning/planner.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {
namespace {

double num(const PointKind& f, const Cells& row, const std::string& name) {
  const Cell& c = row.at(test_support::column(f, name));
  if (const auto* d = std::get_if<double>(&c)) {
    return *d;
  }
  if (const auto* i = std::get_if<long long>(&c)) {
    return static_cast<double>(*i);
  }
  return std::stod(std::get<std::string>(c));
}

PointResult run(const std::string& kind, const std::string& body) {
  const PointKind& f = test_support::point_kind(kind);
  const std::vector<Point> pts = test_support::points_of(kind, body);
  EXPECT_EQ(pts.size(), 1u);
  f.check(pts.at(0));
  return f.run(pts.at(0));
}

void expect_input_error(const std::string& kind, const std::string& body, const std::string& key) {
  const std::vector<Point> pts = test_support::points_of(kind, body);
  try {
    test_support::point_kind(kind).check(pts.at(0));
    ADD_FAILURE() << "accepted: " << body;
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(PlanningPoints, BadKeysAndValuesNameTheKey) {
  expect_input_error("plan_run", "[params]\ngoal = \"north\"\n", "goal");
  expect_input_error("plan_run", "[params]\ngoal = \"straight\"\nvx = 0.1\n", "vx");
  expect_input_error("plan_run", "[params]\nsteps = 0\n", "steps");
  expect_input_error("plan_summary", "[params]\nlookahead = 0\n", "lookahead");
  expect_input_error("plan_summary", "[params]\nlaw = \"ice\"\n", "law");
  expect_input_error("plan_summary", "[params]\nspeed = 1.0\n", "speed");
  expect_input_error("foot_path", "[params]\nsamples = 12\n", "samples");
  expect_input_error("foot_path", "[params]\nleg = \"XX\"\n", "leg");
}

TEST(PlanningPoints, PlanRunRowsAreThePlanCsvOfThePlannerPlusTheEndState) {
  const PointKind& f = test_support::point_kind("plan_run");
  const PointResult r = run("plan_run", "[params]\ngoal = \"diagonal\"\nsteps = 12\n");
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_EQ(r.rows.size(), 13u);

  // The planner run directly, written by plan_csv.
  const planning::PlanRobot robot = planning::bigant_plan_robot();
  planning::PlanOptions options;
  options.steps = 12;
  planning::Goal goal;
  goal.twist = {0.05, 0.02, 0.0};
  std::ostringstream text;
  core::CsvWriter writer(text, planning::plan_columns(robot));
  const planning::PlanSummary s = planning::plan(
      robot, options, goal, planning::tripod_start(robot),
      [&](const planning::StepRecord& rec) { planning::write_plan_row(writer, options, rec); });
  std::istringstream lines(text.str());
  std::string line;
  std::getline(lines, line);  // the header
  const std::size_t first = test_support::column(f, "step");
  for (std::size_t k = 0; k < 12; ++k) {
    ASSERT_TRUE(std::getline(lines, line));
    std::string joined;
    for (std::size_t j = 0; j < planning::plan_columns(robot).size(); ++j) {
      joined += (j ? "," : "") + std::get<std::string>(r.rows[k].at(first + j));
    }
    EXPECT_EQ(joined, line) << "step " << k;
  }
  const Cells& end = r.rows.back();
  EXPECT_EQ(num(f, end, "step"), 12.0);
  EXPECT_EQ(num(f, end, "x"), s.end.pose.x);
  EXPECT_EQ(num(f, end, "y"), s.end.pose.y);
  EXPECT_EQ(num(f, end, "t"), s.end.t);
  EXPECT_EQ(num(f, end, "distance"), s.final_distance);
  EXPECT_EQ(num(f, end, "option"), -1.0);
  EXPECT_TRUE(std::isnan(num(f, end, "speed_HL")));
}

TEST(PlanningPoints, SummaryIsThePlannersAndAgreesWithThePlanRows) {
  const std::string body = "[params]\ngoal = \"turn\"\nsteps = 10\n";
  const PointKind& fr = test_support::point_kind("plan_run");
  const PointKind& fs = test_support::point_kind("plan_summary");
  const PointResult rows = run("plan_run", body);
  const PointResult sum = run("plan_summary", body);
  ASSERT_EQ(sum.rows.size(), 1u);
  const Cells& s = sum.rows[0];
  double mean = 0.0;
  double radius = 0.0;
  double evaluated = 0.0;
  double speed_mr = 0.0;
  for (std::size_t k = 0; k < 10; ++k) {
    mean += num(fr, rows.rows[k], "distance");
    evaluated += num(fr, rows.rows[k], "evaluated");
    speed_mr += num(fr, rows.rows[k], "speed_MR");
  }
  for (const Cells& row : rows.rows) {
    radius = std::max(radius, std::hypot(num(fr, row, "x"), num(fr, row, "y")));
  }
  EXPECT_NEAR(num(fs, s, "mean_distance"), mean / 10.0, 1e-15);
  EXPECT_EQ(num(fs, s, "final_distance"), num(fr, rows.rows.back(), "distance"));
  EXPECT_EQ(num(fs, s, "max_radius"), radius);
  EXPECT_DOUBLE_EQ(num(fs, s, "evaluated_per_step"), evaluated / 10.0);
  EXPECT_DOUBLE_EQ(num(fs, s, "mean_speed_MR"), speed_mr / 10.0);
  EXPECT_DOUBLE_EQ(num(fs, s, "duration"), 10 * 2 * 0.05 / 20);  // T_f h per step
  EXPECT_DOUBLE_EQ(num(fs, s, "goal_turn"), 0.2 * num(fs, s, "duration"));
}

TEST(PlanningPoints, ThreadsDoNotChangeAPlan) {
  const PointKind& f = test_support::point_kind("plan_run");
  const std::string body = "[params]\ngoal = \"straight\"\nsteps = 8\nlookahead = 2\nbeam = 3\n";
  const PointResult one = run("plan_run", body + "threads = 1\n");
  const PointResult two = run("plan_run", body + "threads = 2\n");
  EXPECT_EQ(test_support::first_value_difference(f, one, two), "");
}

TEST(PlanningPoints, FootPathIsTheLegsToeWithTheFigurePointsMarked) {
  const PointKind& f = test_support::point_kind("foot_path");
  const PointResult r = run("foot_path", "[params]\nsamples = 50\nleg = \"MR\"\n");
  ASSERT_EQ(r.rows.size(), 50u);
  const planning::PlanRobot robot = planning::bigant_plan_robot();
  std::vector<double> marked;
  for (const Cells& row : r.rows) {
    const double phi = num(f, row, "phi");
    Eigen::Vector3d q;
    Eigen::Vector3d dq;
    robot.toe(4, phi, q, dq);  // MR
    EXPECT_EQ(num(f, row, "x"), q(0));
    EXPECT_EQ(num(f, row, "z"), q(2));
    EXPECT_EQ(num(f, row, "in_window"),
              std::min(phi, 1.0 - phi) <= robot.stance_half_width ? 1.0 : 0.0);
    if (num(f, row, "marked") == 1.0) {
      marked.push_back(phi);
    }
  }
  EXPECT_EQ(marked, (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8}));
}

}  // namespace
}  // namespace slipwalk::sweeps
