// slipwalk plan PLAN.toml --out FILE.csv: a small plan writes the CSV of a direct
// planning::plan call, bit for bit, and its sidecar with the summary; bad plan files exit 2
// naming file:line:col and write nothing; a plan with no feasible option exits 1 and writes
// nothing; an --out that is an input is refused.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/csv.hpp"
#include "planning/plan_csv.hpp"
#include "planning/planner.hpp"

namespace slipwalk::testing {
namespace {

const char* const kSmall = R"([plan]
robot = "bigant"
steps = 20

[goal]
twist = [0.2, 0.0, 0.0]
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) {
    out.push_back(line);
  }
  return out;
}

TEST(CliPlan, WritesTheRowsOfADirectPlanCallBitForBitAndTheSummaryInItsSidecar) {
  const ScratchDir dir;
  write_text(dir / "plan.toml", kSmall);
  const auto r =
      run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / "out.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no --progress: quiet
  EXPECT_EQ(r.out, "");

  // The same plan, set up directly from planner.hpp's defaults (not through the file reader),
  // written by the same row table: the CSV's doubles round-trip (core::format_double), so equal
  // text is equal values, bit for bit.
  const planning::PlanRobot robot = planning::bigant_plan_robot();
  planning::PlanOptions options;
  options.steps = 20;
  planning::Goal goal;
  goal.twist = {0.2, 0.0, 0.0};
  std::ostringstream expected;
  core::CsvWriter csv(expected, planning::plan_columns(robot));
  std::vector<double> xs;
  const planning::PlanSummary summary = planning::plan(
      robot, options, goal, planning::tripod_start(robot), [&](const planning::StepRecord& s) {
        planning::write_plan_row(csv, options, s);
        xs.push_back(s.state.pose.x);
      });
  const std::string text = read_text(dir / "out.csv");
  EXPECT_EQ(text, expected.str());
  const std::vector<std::string> rows = lines_of(text);
  ASSERT_EQ(rows.size(), 21u);
  std::string header;
  for (const std::string& c : planning::plan_columns(robot)) {
    header.append(header.empty() ? "" : ",").append(c);
  }
  EXPECT_EQ(rows[0], header);
  // x (the third column) read back is the planner's value exactly.
  for (std::size_t k = 0; k < xs.size(); ++k) {
    std::stringstream cells(rows[k + 1]);
    std::string cell;
    for (int c = 0; c < 3; ++c) {
      std::getline(cells, cell, ',');
    }
    EXPECT_EQ(std::stod(cell), xs[k]) << "step " << k;
  }
  EXPECT_GT(xs.back(), 0.0);  // it walks toward the goal

  const auto sidecar = nlohmann::json::parse(read_text(dir / "out.json"));
  EXPECT_EQ(sidecar["command"], "plan");
  EXPECT_EQ(sidecar["robot"], "bigant");
  EXPECT_EQ(sidecar["csv"], "out.csv");
  EXPECT_EQ(sidecar["columns"], planning::plan_columns(robot));
  EXPECT_EQ(sidecar["summary"]["steps"], 20);
  EXPECT_EQ(sidecar["summary"]["mean_distance"].get<double>(), summary.mean_distance);
  EXPECT_EQ(sidecar["summary"]["final_distance"].get<double>(), summary.final_distance);
  EXPECT_EQ(sidecar["summary"]["evaluated"], summary.evaluated);
  EXPECT_EQ(sidecar["summary"]["end"]["pose"][0].get<double>(), summary.end.pose.x);
  EXPECT_EQ(sidecar["plan"]["plan"]["steps"], 20);
  EXPECT_EQ(sidecar["plan"]["goal"]["twist"][0], 0.2);
  EXPECT_GE(sidecar["wall_s"].get<double>(), 0.0);
  EXPECT_TRUE(sidecar.contains("provenance"));
  EXPECT_EQ(files_under(dir.path()),
            (std::vector<std::string>{"out.csv", "out.json", "plan.toml"}));
}

TEST(CliPlan, ProgressPrintsAboutTenLinesAndTheSummary) {
  const ScratchDir dir;
  write_text(dir / "plan.toml", kSmall);
  const auto r = run_slipwalk(
      {"plan", (dir / "plan.toml").string(), "--out", (dir / "out.csv").string(), "--progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 11u) << r.err;
  EXPECT_EQ(lines[0].rfind("slipwalk plan: 2/20 steps (t = 0.01 s;", 0), 0u) << lines[0];
  EXPECT_EQ(lines[9].rfind("slipwalk plan: 20/20 steps (t = 0.1 s;", 0), 0u) << lines[9];
  EXPECT_NE(lines[10].find("20 steps; tracking distance"), std::string::npos) << lines[10];
  EXPECT_NE(lines[10].find("options evaluated in"), std::string::npos) << lines[10];
}

TEST(CliPlan, WaypointGoalsAreReadBesideThePlanFile) {
  const ScratchDir dir;
  write_text(dir / "goal.csv", "t,x,y,theta\n0,0,0,0\n1,0.1,0,0\n");
  write_text(dir / "plan.toml", "[plan]\nsteps = 4\n[goal]\nwaypoints = \"goal.csv\"\n");
  const auto r =
      run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / "out.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines_of(read_text(dir / "out.csv")).size(), 5u);
  // The waypoint file is an input: --out may not replace it.
  const auto same =
      run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / "goal.csv").string()});
  EXPECT_EQ(same.exit_code, 2) << same.err;
  EXPECT_NE(same.err.find("--out"), std::string::npos) << same.err;
  EXPECT_EQ(read_text(dir / "goal.csv"), "t,x,y,theta\n0,0,0,0\n1,0.1,0,0\n");
}

TEST(CliPlan, BadPlanFilesExitTwoNamingTheirPlaceAndWriteNothing) {
  struct Case {
    std::string text;
    std::string where;
    std::string what;
  };
  const std::vector<Case> cases = {
      {replace(kSmall, "steps = 20", "stesp = 20"), "plan.toml:3:1", "did you mean 'steps'?"},
      {replace(kSmall, "steps = 20", "steps = 2.5"), "plan.toml:3:9", "expected an integer"},
      {replace(kSmall, "steps = 20", "execute = 30"), "plan.toml:3:11",
       "must be at most substeps = 20"},
      {replace(kSmall, "0.2, 0.0, 0.0", "0.2, 0.0"), "plan.toml:6:9", "a twist"},
      {replace(kSmall, "robot = \"bigant\"", "robot = \"bigant16\""), "plan.toml:2:9",
       "4 speeds on 16 legs"},
      {std::string(kSmall) + "[start]\nphi = [0.5, 0, 0.5]\n", "plan.toml:8:7",
       "the robot has 6 legs, got 3"},
      {replace(kSmall, "[goal]", "[goal"), "plan.toml:5:", "plan.toml"},
      {replace(kSmall, "twist = [0.2, 0.0, 0.0]", "waypoints = \"goal.csv\""), "goal.csv:2:3",
       "'x' is not a finite number"},
  };
  for (const Case& c : cases) {
    const ScratchDir dir;
    write_text(dir / "plan.toml", c.text);
    write_text(dir / "goal.csv", "0,0,0,0\n1,x,0,0\n");
    const auto r =
        run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / "out.csv").string()});
    EXPECT_EQ(r.exit_code, 2) << c.text << r.err;
    EXPECT_NE(r.err.find("slipwalk: error: " + (dir / c.where).string()), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(c.what), std::string::npos) << r.err;
    EXPECT_EQ(files_under(dir.path()), (std::vector<std::string>{"goal.csv", "plan.toml"}))
        << c.text;
  }
  // A missing plan file.
  const ScratchDir dir;
  const auto r =
      run_slipwalk({"plan", (dir / "none.toml").string(), "--out", (dir / "out.csv").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.toml"), std::string::npos) << r.err;
  EXPECT_TRUE(files_under(dir.path()).empty());
}

TEST(CliPlan, AnOutputThatIsTheInputOrItsOwnSidecarIsRefused) {
  const ScratchDir dir;
  write_text(dir / "plan.toml", kSmall);
  for (const char* out : {"plan.toml", "out.json"}) {
    const auto r =
        run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / out).string()});
    EXPECT_EQ(r.exit_code, 2) << out;
    EXPECT_NE(r.err.find("slipwalk: error: --out"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(dir / "plan.toml"), kSmall);
    EXPECT_EQ(files_under(dir.path()), (std::vector<std::string>{"plan.toml"})) << out;
  }
  // A plan file named p.json: --out p.csv would overwrite it with its sidecar.
  write_text(dir / "p.json", kSmall);
  const auto r =
      run_slipwalk({"plan", (dir / "p.json").string(), "--out", (dir / "p.csv").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("slipwalk: error: --out (its sidecar"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir / "p.json"), kSmall);
}

TEST(CliPlan, APlanWithNoFeasibleOptionExitsOneAndWritesNothing) {
  // Two legs, one per side at the body's middle: the spring support has no balance away from
  // their line, so every option tips the robot.
  const ScratchDir dir;
  write_text(dir / "plan.toml", replace(kSmall, "\"bigant\"", "\"bigant2\""));
  const auto r =
      run_slipwalk({"plan", (dir / "plan.toml").string(), "--out", (dir / "out.csv").string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("slipwalk: error: " + (dir / "plan.toml").string() + ": "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("no option is feasible"), std::string::npos) << r.err;
  EXPECT_EQ(files_under(dir.path()), (std::vector<std::string>{"plan.toml"}));
}

TEST(CliPlan, HelpNamesThePlanFileAndTheOutput) {
  const auto r = run_slipwalk({"plan", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("§5.4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PLAN"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("plan_file.hpp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--out"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--progress"), std::string::npos) << r.out;
  const auto top = run_slipwalk({"--help"});
  EXPECT_NE(top.out.find("plan"), std::string::npos) << top.out;
  const auto missing = run_slipwalk({"plan"});
  EXPECT_EQ(missing.exit_code, 2);
}

}  // namespace
}  // namespace slipwalk::testing
