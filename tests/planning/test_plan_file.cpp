// planning::parse_plan_file: every key of the format read into its field, a file with only a goal
// planning exactly as planner.hpp's defaults, the waypoint CSV, and every error class naming
// file:line:col (unknown key with a suggestion, wrong type, out of range, the cross-field
// checks, a parameter of a choice not made, TOML syntax, the waypoint file's cells).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "planning/plan_file.hpp"

namespace slipwalk::planning {
namespace {

using testing::ScratchDir;
using testing::write_text;

const char* const kEvery = R"([plan]
robot = "bigant"
law = "coulomb"
tol = 1e-9
max_iterations = 200
horizon = 0.04
substeps = 10
execute = 3
speeds = [-1, 0, 1]
swing_speed = 1.5
contact = "stance_window"
stance_half_width = 0.2
rotation_length = 0.25
steps = 7
lookahead = 2
beam = 3
deduplicate = false
threads = 2

[goal]
twist = [0.1, 0.02, 0.3]
start = [1, 2, 0.5]

[start]
t = 0.5
pose = [0.1, -0.2, 0.3]
phi = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
)";

const char* const kMinimal = R"([goal]
twist = [0.2, 0.0, 0.0]
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

/// Parses `text` (as plan.toml) expecting an InputError at `line:col` whose message contains
/// `part`.
void expect_error(const std::string& text, const std::string& at, const std::string& part) {
  try {
    (void)parse_plan_file(text, "plan.toml");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "plan.toml:" + at) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(PlanFile, ReadsEveryKeyIntoItsField) {
  const PlanFile f = parse_plan_file(kEvery, "plan.toml");
  EXPECT_EQ(f.path, "plan.toml");
  EXPECT_EQ(f.robot.name, "bigant");
  EXPECT_EQ(f.robot.legs(), 6);
  const PlanOptions& o = f.options;
  EXPECT_EQ(o.law, connection::FrictionLaw::kCoulomb);
  EXPECT_EQ(o.coulomb.tol, 1e-9);
  EXPECT_EQ(o.coulomb.max_iterations, 200);
  EXPECT_EQ(o.horizon, 0.04);
  EXPECT_EQ(o.substeps, 10);
  EXPECT_EQ(o.execute, 3);
  EXPECT_EQ(o.speeds, (std::vector<double>{-1.0, 0.0, 1.0}));
  EXPECT_EQ(o.swing_speed, 1.5);
  EXPECT_EQ(o.contact, ContactRule::kStanceWindow);
  EXPECT_EQ(f.robot.stance_half_width, 0.2);
  EXPECT_EQ(o.rotation_length, 0.25);
  EXPECT_EQ(o.steps, 7);
  EXPECT_EQ(o.lookahead, 2);
  EXPECT_EQ(o.beam, 3);
  EXPECT_FALSE(o.deduplicate);
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(f.goal.twist, Eigen::Vector3d(0.1, 0.02, 0.3));
  EXPECT_EQ(f.goal.start.x, 1.0);
  EXPECT_EQ(f.goal.start.y, 2.0);
  EXPECT_EQ(f.goal.start.theta, 0.5);
  EXPECT_TRUE(f.goal.times.empty());
  EXPECT_TRUE(f.goal_file.empty());
  EXPECT_EQ(f.start.t, 0.5);
  EXPECT_EQ(f.start.pose.x, 0.1);
  EXPECT_EQ(f.start.pose.y, -0.2);
  EXPECT_EQ(f.start.pose.theta, 0.3);
  ASSERT_EQ(f.start.phi.size(), 6);
  const std::vector<double> phi = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(f.start.phi(i), phi[static_cast<std::size_t>(i)]) << i;
  }
  // The sidecar's JSON holds what was read.
  const nlohmann::json j = to_json(f);
  EXPECT_EQ(j["plan"]["law"], "coulomb");
  EXPECT_EQ(j["plan"]["contact"], "stance_window");
  EXPECT_EQ(j["plan"]["stance_half_width"], 0.2);
  EXPECT_EQ(j["goal"]["twist"][2], 0.3);
  EXPECT_EQ(j["start"]["phi"].size(), 6u);
}

TEST(PlanFile, AFileWithOnlyAGoalHasThePlannersDefaults) {
  const PlanFile f = parse_plan_file(kMinimal, "plan.toml");
  const PlanOptions d;
  const PlanOptions& o = f.options;
  EXPECT_EQ(o.horizon, d.horizon);
  EXPECT_EQ(o.substeps, d.substeps);
  EXPECT_EQ(o.execute, d.execute);
  EXPECT_EQ(o.speeds, d.speeds);
  EXPECT_EQ(o.swing_speed, d.swing_speed);
  EXPECT_EQ(o.contact, d.contact);
  EXPECT_EQ(o.rotation_length, d.rotation_length);
  EXPECT_EQ(o.law, d.law);
  EXPECT_EQ(o.coulomb.tol, d.coulomb.tol);
  EXPECT_EQ(o.coulomb.max_iterations, d.coulomb.max_iterations);
  EXPECT_EQ(o.steps, d.steps);
  EXPECT_EQ(o.lookahead, d.lookahead);
  EXPECT_EQ(o.beam, d.beam);
  EXPECT_EQ(o.deduplicate, d.deduplicate);
  EXPECT_EQ(o.threads, d.threads);
  const PlanRobot bigant = bigant_plan_robot();
  EXPECT_EQ(f.robot.name, bigant.name);
  EXPECT_EQ(f.robot.leg_names, bigant.leg_names);
  EXPECT_EQ(f.robot.stance_half_width, bigant.stance_half_width);
  const PlanState start = tripod_start(bigant);
  EXPECT_EQ(f.start.t, start.t);
  EXPECT_EQ(f.start.phi, start.phi);
  EXPECT_EQ(f.start.pose.x, 0.0);
  EXPECT_EQ(f.start.pose.theta, 0.0);
  // The twist starts from the start pose (the thesis' goals).
  const PlanFile moved =
      parse_plan_file(std::string(kMinimal) + "[start]\npose = [1, -2, 0.5]\n", "plan.toml");
  EXPECT_EQ(moved.goal.start.x, 1.0);
  EXPECT_EQ(moved.goal.start.y, -2.0);
  EXPECT_EQ(moved.goal.start.theta, 0.5);
}

TEST(PlanFile, BigAntLikeRobotsAreNamedByTheirLegs) {
  const PlanFile eight =
      parse_plan_file(std::string("[plan]\nrobot = \"bigant8\"\n") + kMinimal, "plan.toml");
  EXPECT_EQ(eight.robot.name, "bigant8");
  EXPECT_EQ(eight.robot.legs(), 8);
  EXPECT_EQ(eight.start.phi, tripod_start(bigant_plan_robot(8)).phi);
  EXPECT_EQ(parse_plan_file(std::string("[plan]\nrobot = \"bigant6\"\n") + kMinimal, "plan.toml")
                .robot.name,
            "bigant");
  for (const char* bad :
       {"bigant7", "bigant0", "bigant08", "bigant42", "bigantx", "bigant+8", "ant", "bigant 8"}) {
    expect_error(std::string("[plan]\nrobot = \"") + bad + "\"\n" + kMinimal, "2:9",
                 "unknown robot");
  }
}

TEST(PlanFile, UnknownKeysAndTablesAreRefusedAtTheirPlace) {
  expect_error(replace(kEvery, "horizon = 0.04", "horizn = 0.04"), "6:1",
               "did you mean 'horizon'?");
  expect_error(replace(kEvery, "[goal]", "[gaol]"), "20:2", "did you mean [goal]?");
  expect_error(std::string("steps = 3\n") + kMinimal, "1:1", "it belongs in [plan]");
  expect_error(replace(kEvery, "t = 0.5", "pose_x = 0.5"), "25:1", "unknown key 'pose_x'");
  expect_error(replace(kEvery, "threads = 2", "twist = [0, 0, 0]"), "18:1", "it belongs in [goal]");
  expect_error("plan = 3\n" + std::string(kMinimal), "1:1", "expected a table [plan]");
}

TEST(PlanFile, WrongTypesAreRefusedAtTheValue) {
  expect_error(replace(kEvery, "substeps = 10", "substeps = 10.0"), "7:12",
               "expected an integer, got a float");
  expect_error(replace(kEvery, "horizon = 0.04", "horizon = \"short\""), "6:11",
               "expected a number, got a string");
  expect_error(replace(kEvery, "deduplicate = false", "deduplicate = 0"), "17:15",
               "expected a boolean");
  expect_error(replace(kEvery, "speeds = [-1, 0, 1]", "speeds = 1"), "9:10", "an array");
  expect_error(replace(kEvery, "speeds = [-1, 0, 1]", "speeds = [-1, \"0\", 1]"), "9:15",
               "expected a number, got a string");
  expect_error(replace(kEvery, "robot = \"bigant\"", "robot = 6"), "2:9", "expected a string");
  expect_error(replace(kEvery, "law = \"coulomb\"", "law = \"colomb\""), "3:7",
               "did you mean 'coulomb'?");
  expect_error(replace(kEvery, "contact = \"stance_window\"", "contact = \"touching\""), "11:11",
               "unknown value 'touching'");
  expect_error(replace(kEvery, "twist = [0.1, 0.02, 0.3]", "twist = [0.1, 0.02]"), "21:9",
               "a twist [vx, vy, omega]");
  expect_error(replace(kEvery, "pose = [0.1, -0.2, 0.3]", "pose = 0.1"), "26:8",
               "a pose [x, y, theta]");
  expect_error(replace(kEvery, "horizon = 0.04", "horizon = nan"), "6:11", "got nan");
}

TEST(PlanFile, ValuesOutOfRangeNameTheRangeAndItsUnit) {
  expect_error(replace(kEvery, "horizon = 0.04", "horizon = 0"), "6:11", "(0, 10] s");
  expect_error(replace(kEvery, "substeps = 10", "substeps = 0"), "7:12", "[1, 10000]");
  expect_error(replace(kEvery, "speeds = [-1, 0, 1]", "speeds = [-1, 0, 101]"), "9:18",
               "[-100, 100] turns/s");
  expect_error(replace(kEvery, "speeds = [-1, 0, 1]", "speeds = []"), "9:10",
               "the number of speeds must be in [1, 64]");
  expect_error(replace(kEvery, "swing_speed = 1.5", "swing_speed = -200"), "10:15", "turns/s");
  expect_error(replace(kEvery, "stance_half_width = 0.2", "stance_half_width = 0.5"), "12:21",
               "(0, 0.5) turns");
  expect_error(replace(kEvery, "rotation_length = 0.25", "rotation_length = -1"), "13:19", "m/rad");
  expect_error(replace(kEvery, "steps = 7", "steps = -1"), "14:9", "[0, 100000000]");
  expect_error(replace(kEvery, "lookahead = 2", "lookahead = 17"), "15:13", "[1, 16]");
  expect_error(replace(kEvery, "beam = 3", "beam = 0"), "16:8", "[1, 64]");
  expect_error(replace(kEvery, "threads = 2", "threads = 1000"), "18:11", "[1, 256]");
  expect_error(replace(kEvery, "tol = 1e-9", "tol = 0"), "4:7", "[1e-15, 1]");
  expect_error(replace(kEvery, "max_iterations = 200", "max_iterations = 0"), "5:18",
               "[1, 1000000]");
  expect_error(replace(kEvery, "twist = [0.1, 0.02, 0.3]", "twist = [0.1, 0.02, 2000]"), "21:21",
               "rad/s");
  expect_error(replace(kEvery, "twist = [0.1, 0.02, 0.3]", "twist = [1e4, 0.02, 0.3]"), "21:10",
               "m/s");
  expect_error(replace(kEvery, "start = [1, 2, 0.5]", "start = [1, 2e3, 0.5]"), "22:13", " m,");
  expect_error(replace(kEvery, "pose = [0.1, -0.2, 0.3]", "pose = [0.1, -0.2, 1e7]"), "26:20",
               "rad");
  expect_error(replace(kEvery, "t = 0.5", "t = 1e10"), "25:5", "s,");
  expect_error(replace(kEvery, "phi = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]",
                       "phi = [0.1, 0.2, 0.3, 0.4, 1.0, 0.6]"),
               "27:28", "[0, 1) turns");
}

TEST(PlanFile, CrossFieldErrorsNameTheKeyThatBreaksThem) {
  // execute > substeps, at execute; a substeps below the default execute, at substeps.
  expect_error(replace(kEvery, "execute = 3", "execute = 11"), "8:11",
               "must be at most substeps = 10");
  expect_error(std::string("[plan]\nsubsteps = 1\n") + kMinimal, "2:12",
               "must be at least execute = 2");
  // M^N > 2^24, at speeds (or the robot when the speeds are the default).
  expect_error(std::string("[plan]\nrobot = \"bigant14\"\nspeeds = [-1, 0, 1, 2]\n") + kMinimal,
               "3:10", "4 speeds on 14 legs");
  expect_error(std::string("[plan]\nrobot = \"bigant14\"\n") + kMinimal, "2:9",
               "4 speeds on 14 legs");
  // A phi count that is not the robot's legs.
  expect_error(replace(kEvery, "robot = \"bigant\"", "robot = \"bigant8\""), "27:7",
               "the robot has 8 legs, got 6");
  // A CSV past 4 GB, at steps.
  expect_error(replace(kEvery, "steps = 7", "steps = 99000000"), "14:9", "GB of CSV");
  // A parameter of a choice not made.
  expect_error(replace(kEvery, "law = \"coulomb\"", "law = \"viscous\""), "4:7",
               "a parameter of the coulomb law");
  expect_error(replace(kEvery, "contact = \"stance_window\"", "contact = \"all\""), "12:21",
               "a parameter of the stance_window rule");
}

TEST(PlanFile, TheGoalIsATwistOrWaypointsAndRequired) {
  expect_error("[plan]\nsteps = 3\n", "1:1", "missing required table [goal]");
  expect_error("[goal]\n", "1:1", "missing required key 'twist' (or 'waypoints')");
  expect_error(replace(kEvery, "start = [1, 2, 0.5]", "waypoints = \"goal.csv\""), "22:13",
               "give twist or waypoints, not both");
  expect_error("[goal]\nwaypoints = 3\n", "2:13", "expected a string");
  expect_error("[goal]\nwaypoints = \"missing.csv\"\n", "2:13", "cannot read");
  expect_error("[goal]\nwaypoints = \"g.csv\"\nstart = [0, 0, 0]\n", "3:9",
               "a parameter of a twist goal");
}

TEST(PlanFile, SyntaxErrorsNameTheirPlace) {
  try {
    (void)parse_plan_file("[plan]\nsteps = = 3\n", "plan.toml");
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where().rfind("plan.toml:2:", 0), 0u) << e.what();
  }
}

TEST(PlanFile, ReadsWaypointsRelativeToThePlanFile) {
  const ScratchDir dir;
  std::filesystem::create_directories(dir / "goals");
  write_text(dir / "goals" / "path.csv",
             "\xEF\xBB\xBFt, x, y, theta\r\n# a comment\r\n0, 0, 0, 0\r\n\r\n0.5,0.1,0,0 # half "
             "way\r\n1.5, 0.2, -0.1, 7.5\r\n");
  write_text(dir / "plan.toml", "[goal]\nwaypoints = \"goals/path.csv\"\n");
  const PlanFile f = read_plan_file(dir / "plan.toml");
  EXPECT_EQ(f.goal_file, (dir / "goals" / "path.csv").string());
  EXPECT_EQ(f.goal.times, (std::vector<double>{0.0, 0.5, 1.5}));
  ASSERT_EQ(f.goal.waypoints.size(), 3u);
  EXPECT_EQ(f.goal.waypoints[1].x, 0.1);
  EXPECT_EQ(f.goal.waypoints[2].y, -0.1);
  EXPECT_EQ(f.goal.waypoints[2].theta, 7.5);  // unwrapped
  // The target between waypoints is their linear interpolation (goal.hpp).
  EXPECT_DOUBLE_EQ(target_at(f.goal, 1.0).x, 0.15);
  EXPECT_EQ(to_json(f)["goal"]["rows"], 3);
}

TEST(PlanFile, WaypointErrorsNameTheirCell) {
  const auto expect_csv_error = [](const std::string& text, const std::string& at,
                                   const std::string& part) {
    Goal g;
    try {
      parse_waypoints(text, "goal.csv", g);
      ADD_FAILURE() << "no error for:\n" << text;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), "goal.csv:" + at) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_csv_error("0,0,0,0\n1, 0.1, abc, 0\n", "2:9", "y: 'abc' is not a finite number");
  expect_csv_error("0,0,0,0\n1,0,0,inf\n", "2:7", "theta: 'inf'");
  expect_csv_error("0,0,0,0\n1,0,,0\n", "2:5", "y: ''");
  expect_csv_error("0,0,0,0\n1,0,0\n", "2", "the row has 3");
  expect_csv_error("0,0,0,0\n1,0,0,0,5\n", "2", "the row has 5");
  expect_csv_error("0,0,0,0\n1,0,0,0\n1,1,0,0\n", "3:1", "times must increase strictly");
  expect_csv_error("0,0,0,0\n1,2000,0,0\n", "2:3", "[-1000, 1000] m");
  expect_csv_error("# only\n0,0,0,0\n", "2", "at least 2 rows");
  expect_csv_error("", "1", "at least 2 rows");
  expect_csv_error("t,x,y,theta\n", "1", "the file has 0");
  // A header is only the first row.
  expect_csv_error("0,0,0,0\nt,x,y,theta\n", "2:1", "t: 't'");
}

TEST(PlanFile, TheExamplePlansReadAsTheThesisGoals) {
  const std::filesystem::path plans =
      std::filesystem::path(SLIPWALK_SOURCE_DIR) / "studies/ch5_planning/plans";
  const PlanFile straight = read_plan_file(plans / "straight.toml");
  const PlanFile turn = read_plan_file(plans / "turn_in_place.toml");
  const PlanFile diagonal = read_plan_file(plans / "diagonal.toml");
  EXPECT_EQ(straight.goal.twist, Eigen::Vector3d(0.2, 0.0, 0.0));
  EXPECT_EQ(turn.goal.twist, Eigen::Vector3d(0.0, 0.0, 0.2));
  EXPECT_EQ(diagonal.goal.twist, Eigen::Vector3d(0.05, 0.02, 0.0));
  for (const PlanFile* f : {&straight, &turn, &diagonal}) {
    EXPECT_EQ(f->options.steps, 300) << f->path;
    EXPECT_EQ(f->start.phi, tripod_start(f->robot).phi) << f->path;
    EXPECT_EQ(f->options.speeds, PlanOptions{}.speeds) << f->path;
  }
}

}  // namespace
}  // namespace slipwalk::planning
