// Leg-table robots in scenes (scene/leg_table.hpp) and every scene file the project ships.
// Oracles: the foot path's q̇ is the derivative of q (central differences); a tripod of the table
// whose stance feet move as one rigid body carries the body exactly opposite (no slip: v = −q̇,
// ω = 0); every leg-table error names file:line:col; every scene under studies/ parses, composes
// and runs a few steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {
namespace {

std::string leg(const std::string& name, double x, double y, double phase) {
  return "[[robot.leg]]\nname = \"" + name + "\"\nhip = [" + std::to_string(x) + ", " +
         std::to_string(y) + ", 0.0]\nK = 2675.0\nmu = 0.8\nphase = " + std::to_string(phase) +
         "\n";
}

/// A hexapod leg table walking an alternating tripod; `extra` goes into [robot] before the legs.
std::string hexapod(const std::string& extra = "", const std::string& gait_extra = "") {
  return "[robot]\nname = \"legs\"\nmass = 8.18\n" + extra + leg("HL", -0.3, 0.2, 0.0) +
         leg("ML", 0.0, 0.2, 0.5) + leg("FL", 0.3, 0.2, 0.0) + leg("HR", -0.3, -0.2, 0.5) +
         leg("MR", 0.0, -0.2, 0.0) + leg("FR", 0.3, -0.2, 0.5) +
         "[gait]\nkind = \"foot_path\"\nfrequency = 0.5\nstride = 0.1\nheight = 0.1\nlift = "
         "0.03\n" +
         gait_extra + "[run]\nduration = 2.0\ndt = 0.01\n[friction]\nlaw = \"viscous\"\n";
}

int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

void expect_error(const std::string& text, int line, int col, const std::string& part) {
  try {
    (void)parse_scene(text, "s.toml");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "s.toml:" + std::to_string(line) + ":" + std::to_string(col)) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(SceneLegs, ReadsTheTable) {
  const Scene s = parse_scene(hexapod(), "s.toml");
  EXPECT_EQ(s.robot, "legs");
  ASSERT_TRUE(std::holds_alternative<LegTableGait>(s.gait));
  EXPECT_STREQ(gait_kind(s.gait), "foot_path");
  const Simulator sim = compose(s);
  EXPECT_EQ(sim.walker.legs(), 6);
  EXPECT_EQ(sim.walker.leg_names[2], "FL");
  EXPECT_EQ(sim.walker.robot.K(3), 2675.0);
  EXPECT_EQ(sim.walker.robot.mu(5), 0.8);
  EXPECT_DOUBLE_EQ(sim.walker.robot.Mg, 8.18 * 9.81);
  EXPECT_EQ(sim.walker.period, 2.0);
  const auto json = to_json(s);
  EXPECT_EQ(json["gait"]["legs"][2]["name"], "FL");
  EXPECT_EQ(json["gait"]["legs"][1]["phase"], 0.5);
}

TEST(SceneLegs, FootVelocitiesAreTheDerivative) {
  const Simulator sim = compose(parse_scene(hexapod(), "s.toml"));
  Eigen::Matrix3Xd q(3, 6), qd(3, 6), qp(3, 6), qm(3, 6), unused(3, 6);
  const double h = 1e-6;
  for (double t : {0.13, 0.61, 1.37, 1.93}) {
    sim.walker.feet(t, q, qd);
    sim.walker.feet(t + h, qp, unused);
    sim.walker.feet(t - h, qm, unused);
    const Eigen::Matrix3Xd fd = (qp - qm) / (2.0 * h);
    EXPECT_LE((fd - qd).cwiseAbs().maxCoeff(), 1e-7) << t;
  }
}

TEST(SceneLegs, RigidTripodCarriesTheBodyWithoutSlip) {
  // While exactly one tripod is down its three feet have the same q̇ = (q̇_x, 0): the only
  // balance without slip is v = −q̇, ω = 0, and viscous-Coulomb finds it (it is the zero of
  // every foot's force).
  const Simulator sim = compose(parse_scene(hexapod(), "s.toml"));
  int checked = 0;
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    int down = 0;
    for (char c : s.frame.contact) {
      down += c != 0 ? 1 : 0;
    }
    if (down != 3) {
      return;
    }
    int k = 0;
    while (s.frame.contact[static_cast<std::size_t>(k)] == 0) {
      ++k;
    }
    EXPECT_NEAR(s.v_body(0), -s.frame.qdot(0, k), 1e-12) << s.t;
    EXPECT_NEAR(s.v_body(1), 0.0, 1e-12) << s.t;
    EXPECT_NEAR(s.v_body(2), 0.0, 1e-12) << s.t;
    ++checked;
  });
  EXPECT_GT(checked, 100);  // of 201 frames; near touchdown both tripods are down
}

TEST(SceneLegs, Errors) {
  const std::string good = hexapod();
  auto at = [&](const std::string& text, const std::string& needle, int col, int lines = 0) {
    return std::pair<int, int>{line_of(text, needle) + lines, col};
  };
  struct Case {
    std::string text;
    std::string needle;
    int col;
    std::string part;
  };
  const std::vector<Case> cases = {
      {replace(good, "mass = 8.18\n", ""), "[robot]", 1, "missing required key 'mass' in [robot]"},
      {replace(good, "mass = 8.18", "mass = -1"), "mass", 8,
       "robot.mass: must be in [1e-06, 1000000] kg"},
      {replace(good, "hip = [-0.300000, 0.200000, 0.0]", "hip = [-0.3, 0.2]"), "hip = [-0.3", 7,
       "robot.leg.hip: expected [x, y, z] in m, got an array of 2"},
      {replace(good, "hip = [-0.300000, 0.200000, 0.0]", "hip = \"x\""), "hip = \"x\"", 7,
       "expected [x, y, z] in m, got a string"},
      {replace(good, "K = 2675.0\nmu = 0.8\nphase = 0.500000\n[gait]",
               "K = -5.0\nmu = 0.8\nphase = 0.500000\n[gait]"),
       "K = -5", 5, "robot.leg.K: must be in [0.001, 1000000000] N/m, got -5"},
      {replace(good, "mu = 0.8", "mu = -0.1"), "mu = -0.1", 6, "robot.leg.mu: must be in [0, 100]"},
      {replace(good, "phase = 0.500000", "phase = 1.0"), "phase = 1.0", 9,
       "robot.leg.phase: must be in [0, 1) cycles"},
      {replace(good, "K = 2675.0\n", ""), "[[robot.leg]]", 1, "missing required key 'K'"},
      {replace(good, "mu = 0.8", "muu = 0.8"), "muu", 1, "did you mean 'mu'?"},
      {replace(good, "name = \"ML\"", "name = \"HL\""), "name = \"HL\"\nhip = [0.000000", 8,
       "'HL' names two legs"},
      {replace(good, "lift = 0.03", "lift = -0.03"), "lift", 8,
       "gait.lift: must be in [0, 1000] m"},
      {replace(good, "height = 0.1", "height = 0"), "height", 10,
       "gait.height: must be in [1e-06, 1000] m"},
      {"[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nlift = 0.03\n[run]\nduration = "
       "1\ndt = 0.1\n[friction]\nlaw = \"viscous\"\n",
       "lift", 8, "gait.lift: a parameter of the foot_path gait, given with kind = 'tripod'"},
      {replace(good, "name = \"legs\"", "name = \"bigant\""), "mass", 8,
       "robot.mass: a parameter of a leg table (name = 'legs')"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.part);
    const auto [line, col] = at(c.text, c.needle, c.col);
    expect_error(c.text, line, col, c.part);
  }
  // Fewer than 3 legs; no legs at all.
  const std::string two = "[robot]\nname = \"legs\"\nmass = 1.0\n" + leg("a", 0.1, 0.1, 0.0) +
                          leg("b", -0.1, -0.1, 0.5) +
                          "[gait]\nkind = \"foot_path\"\n[run]\nduration = 1\ndt = 0.1\n"
                          "[friction]\nlaw = \"viscous\"\n";
  expect_error(two, line_of(two, "[[robot.leg]]"), 1, "needs 3 to 1000 legs, got 2");
  const std::string none =
      "[robot]\nname = \"legs\"\nmass = 1.0\n[gait]\nkind = \"foot_path\"\n[run]\nduration = "
      "1\ndt = 0.1\n[friction]\nlaw = \"viscous\"\n";
  expect_error(none, 1, 1, "missing required [[robot.leg]] tables");
}

TEST(SceneFiles, EveryShippedSceneParsesComposesAndRuns) {
  // Scene files are the .toml files in a scenes/ folder of a study.
  const std::filesystem::path studies = std::filesystem::path(SLIPWALK_SOURCE_DIR) / "studies";
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(studies)) {
    const std::filesystem::path& p = entry.path();
    if (p.extension() != ".toml" || p.parent_path().filename() != "scenes") {
      continue;
    }
    SCOPED_TRACE(p.string());
    Scene scene = read_scene(p);
    scene.steps = std::min<long long>(scene.steps, 5);  // a smoke run
    const Simulator sim = compose(scene);
    const connection::TrajectorySummary summary = sim.run([](const connection::TrajectoryStep&) {});
    EXPECT_EQ(summary.frames, scene.steps + 1);
    ++count;
  }
  EXPECT_GE(count, 8);
}

}  // namespace
}  // namespace slipwalk::scene
