// scene::parse_scene: every field of the format, and every error class naming
// file:line:col (unknown key with a suggestion, wrong type, out of range,
// missing field, a parameter of an effect that is not chosen, TOML syntax);
// random mutations of a good scene parse or raise InputError.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scene/friction_laws.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {
namespace {

const char* const kGood = R"([robot]
name = "bigant"

[gait]
kind = "tripod"
frequency = 0.2
steer = -0.5

[run]
duration = 10.0
dt = 0.01

[friction]
law = "coulomb"
tol = 1e-9

[filter]
gamma = 0.3
)";

/// Parses `text` expecting an InputError at `line:col` whose message contains
/// `part`.
void expect_error(const std::string& text, const std::string& at, const std::string& part) {
  try {
    (void)parse_scene(text, "scene.toml");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "scene.toml:" + at) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Scene, ReadsEveryField) {
  const Scene s = parse_scene(kGood, "scene.toml");
  EXPECT_EQ(s.path, "scene.toml");
  EXPECT_EQ(s.robot, "bigant");
  ASSERT_TRUE(std::holds_alternative<robots::TripodGait>(s.gait));
  EXPECT_EQ(std::get<robots::TripodGait>(s.gait).frequency, 0.2);
  EXPECT_EQ(std::get<robots::TripodGait>(s.gait).steer, -0.5);
  EXPECT_STREQ(gait_kind(s.gait), "tripod");
  EXPECT_EQ(s.gait_origin, "scene.toml:4:1");
  EXPECT_EQ(s.duration, 10.0);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.steps, 1000);
  EXPECT_EQ(s.friction.law, connection::FrictionLaw::kCoulomb);
  EXPECT_EQ(s.friction.coulomb.tol, 1e-9);
  ASSERT_TRUE(s.filter.has_value());
  EXPECT_EQ(s.filter->gamma, 0.3);
  const auto json = to_json(s);
  EXPECT_EQ(json["gait"]["kind"], "tripod");
  EXPECT_EQ(json["filter"]["gamma"], 0.3);
  EXPECT_EQ(json["run"]["steps"], 1000);
}

TEST(Scene, DefaultsAndTheOtherRobots) {
  const Scene a = parse_scene(R"([robot]
name = "bigant"
[gait]
kind = "metachronal"
[run]
duration = 2
steps = 8
[friction]
law = "viscous"
)",
                              "a.toml");
  ASSERT_TRUE(std::holds_alternative<robots::MetachronalGait>(a.gait));
  EXPECT_EQ(std::get<robots::MetachronalGait>(a.gait).frequency,
            robots::MetachronalGait{}.frequency);
  EXPECT_EQ(a.steps, 8);
  EXPECT_EQ(a.dt, 0.25);
  EXPECT_EQ(a.friction.law, connection::FrictionLaw::kViscousCoulomb);
  EXPECT_FALSE(a.filter.has_value());

  const Scene m = parse_scene(R"([robot]
name = "multipod"
legs = 12
[gait]
kind = "undulation"
frequency = 1.2
dphi = 1.5
[run]
duration = 1
dt = 0.125
[friction]
law = "viscous"
[filter]
)",
                              "m.toml");
  const auto& u = std::get<robots::UndulationGait>(m.gait);
  EXPECT_EQ(u.legs, 12);
  EXPECT_EQ(u.frequency, 1.2);
  EXPECT_EQ(u.dphi, 1.5);
  EXPECT_EQ(u.roll_amplitude, robots::UndulationGait{}.roll_amplitude);
  ASSERT_TRUE(m.filter.has_value());
  EXPECT_EQ(m.filter->gamma,
            0.15);  // the thesis' value when [filter] gives none

  const Scene d = parse_scene(R"([robot]
name = "disk"
legs = 9
radius = 0.5
[gait]
kind = "disk"
[run]
duration = 1
dt = 0.1
[friction]
law = "viscous"
)",
                              "d.toml");
  EXPECT_EQ(std::get<robots::DiskGait>(d.gait).legs, 9);
  EXPECT_EQ(std::get<robots::DiskGait>(d.gait).radius, 0.5);
  EXPECT_EQ(d.steps, 10);  // 1 / 0.1 is 10 to rounding

  const Scene q = parse_scene(R"([robot]
name = "quadruped"
[gait]
kind = "trot"
frequency = 2
[run]
duration = 1
dt = 0.5
[friction]
law = "viscous"
)",
                              "q.toml");
  EXPECT_EQ(std::get<robots::TrotGait>(q.gait).frequency, 2.0);
}

TEST(Scene, BigAntLinkageIsARobotKeyOfBothBigAntGaits) {
  // Absent: the standard leg; "stairs" picks the stairs leg (robots.hpp) and reaches the walker;
  // a misspelling names the choices; another robot does not take the key.
  const Scene standard = parse_scene(kGood, "s.toml");
  EXPECT_EQ(std::get<robots::TripodGait>(standard.gait).linkage, robots::BigAntLinkage::kStandard);
  const std::string stairs_text =
      replace(kGood, "name = \"bigant\"", "name = \"bigant\"\nlinkage = \"stairs\"");
  const Scene stairs = parse_scene(stairs_text, "s.toml");
  EXPECT_EQ(std::get<robots::TripodGait>(stairs.gait).linkage, robots::BigAntLinkage::kStairs);
  EXPECT_EQ(gait_json(stairs.gait).at("linkage"), "stairs");
  const Scene meta =
      parse_scene(replace(replace(stairs_text, "kind = \"tripod\"", "kind = \"metachronal\""),
                          "steer = -0.5\n", ""),
                  "s.toml");
  EXPECT_EQ(std::get<robots::MetachronalGait>(meta.gait).linkage, robots::BigAntLinkage::kStairs);
  // The two legs walk differently: their toes differ at mid-return.
  Eigen::Matrix3Xd qa(3, 6);
  Eigen::Matrix3Xd qb(3, 6);
  Eigen::Matrix3Xd qd(3, 6);
  make_walker(standard.gait).feet(2.5, qa, qd);
  make_walker(stairs.gait).feet(2.5, qb, qd);
  EXPECT_GT((qa - qb).norm(), 0.05);
  expect_error(replace(kGood, "name = \"bigant\"", "name = \"bigant\"\nlinkage = \"stair\""),
               "3:11", "robot.linkage");
}

TEST(Scene, UnknownKeysSuggestTheNearestName) {
  expect_error(replace(kGood, "frequency = 0.2", "frequncy = 0.2"), "6:1",
               "unknown key 'frequncy' in [gait]; did you mean 'frequency'?");
  expect_error(replace(kGood, "[friction]", "[frition]"), "13:2",
               "unknown table [frition]; did you mean [friction]?");
  expect_error(replace(kGood, "dt = 0.01", "dt = 0.01\ngamma = 0.2"), "12:1",
               "unknown key 'gamma' in [run]; it belongs in [filter]");
  expect_error(std::string("duration = 3\n") + kGood, "1:1",
               "unknown key 'duration' at the top level; it belongs in [run]");
  expect_error(replace(kGood, "steer = -0.5", "colour = 1"), "7:1", "unknown key 'colour'");
  expect_error(replace(kGood, "name = \"bigant\"", "name = \"bigamt\""), "2:8",
               "robot.name: unknown value 'bigamt'; did you mean 'bigant'?");
  expect_error(replace(kGood, "law = \"coulomb\"", "law = \"colomb\""), "14:7",
               "did you mean 'coulomb'?");
}

TEST(Scene, WrongTypes) {
  expect_error(replace(kGood, "frequency = 0.2", "frequency = \"fast\""), "6:13",
               "gait.frequency: expected a number, got a string");
  expect_error(replace(kGood, "name = \"bigant\"", "name = 3"), "2:8",
               "robot.name: expected a string, got an integer");
  expect_error(replace(kGood, "dt = 0.01", "steps = 10.0"), "11:9",
               "run.steps: expected an integer, got a float");
  expect_error("filter = 1\n" + replace(kGood, "[filter]\ngamma = 0.3\n", ""), "1:1",
               "expected a table [filter], got an integer");
  expect_error(replace(kGood, "duration = 10.0", "duration = nan"), "10:12",
               "run.duration: must be in [1e-09, 1000000000] s, got nan");
}

TEST(Scene, ValuesOutOfRange) {
  expect_error(replace(kGood, "frequency = 0.2", "frequency = -1"), "6:13",
               "gait.frequency: must be in [1e-06, 1000] Hz, got -1");
  expect_error(replace(kGood, "steer = -0.5", "steer = 1.5"), "7:9",
               "gait.steer: must be in [-1, 1], got 1.5");
  expect_error(replace(kGood, "duration = 10.0", "duration = 0"), "10:12",
               "run.duration: must be in [1e-09, 1000000000] s");
  expect_error(replace(kGood, "dt = 0.01", "dt = 0.3"), "11:6",
               "the duration must be a whole number of steps, got duration / dt = 33.3");
  expect_error(replace(kGood, "dt = 0.01", "dt = 1e-9"), "11:6", "at most 10000000");
  expect_error(replace(kGood, "dt = 0.01", "steps = 0"), "11:9", "run.steps: must be from 1");
  expect_error(replace(kGood, "tol = 1e-9", "tol = 0"), "15:7",
               "friction.tol: must be in [1e-15, 1], got 0");
  expect_error(replace(kGood, "gamma = 0.3", "gamma = 1"), "18:9",
               "filter.gamma: must be in [0, 1), got 1");
  expect_error(R"([robot]
name = "multipod"
legs = 7
[gait]
kind = "undulation"
[run]
duration = 1
dt = 0.1
[friction]
law = "viscous"
)",
               "3:8", "robot.legs: the multipod has 6, 8, 10 or 12 legs, got 7");
}

TEST(Scene, RangesTheRobotFactoriesCheckNameTheKey) {
  // duty, sweep, amplitudes, stride … are checked by the factories; their errors point at the key.
  expect_error(replace(kGood, "steer = -0.5", "steer = -0.5\nduty = 1.5"), "8:8", "gait.duty: ");
  expect_error(replace(kGood, "steer = -0.5", "sweep = 0.9"), "7:9", "gait.sweep: ");
  const std::string multipod = R"([robot]
name = "multipod"
stiffness = 1000.0
[gait]
kind = "undulation"
roll_amplitude = 0.3
[run]
duration = 1
dt = 0.1
[friction]
law = "viscous"
)";
  (void)parse_scene(multipod, "scene.toml");
  expect_error(replace(multipod, "roll_amplitude = 0.3", "roll_amplitude = 2.0"), "6:18",
               "gait.roll_amplitude: ");
  expect_error(replace(multipod, "stiffness = 1000.0", "stiffness = -1.0"), "3:13",
               "robot.stiffness: ");
}

TEST(Scene, MissingRequiredFields) {
  expect_error(replace(kGood, "name = \"bigant\"\n", ""), "1:1",
               "missing required key 'name' in [robot]");
  expect_error(replace(kGood, "kind = \"tripod\"\n", "# no kind\n"), "4:1",
               "missing required key 'kind' in [gait]");
  expect_error(replace(kGood, "dt = 0.01\n", ""), "9:1", "missing required key 'dt' (or 'steps')");
  expect_error(replace(kGood, "[run]\nduration = 10.0\ndt = 0.01\n", ""), "1:1",
               "missing required table [run]");
  expect_error(replace(kGood, "law = \"coulomb\"\ntol = 1e-9\n", ""), "13:1",
               "missing required key 'law' in [friction]");
}

TEST(Scene, ParametersOfEffectsThatAreNotChosen) {
  expect_error(replace(kGood, "law = \"coulomb\"", "law = \"viscous\""), "15:7",
               "friction.tol: a parameter of the coulomb law, given with law = "
               "'viscous'");
  expect_error(replace(kGood, "kind = \"tripod\"", "kind = \"metachronal\""), "7:9",
               "gait.steer: a parameter of the tripod gait, given with kind = "
               "'metachronal'");
  expect_error(replace(kGood, "name = \"bigant\"", "name = \"bigant\"\nlegs = 6"), "3:8",
               "robot.legs: a parameter of the multipod and disk robots, given with "
               "name = "
               "'bigant'");
  expect_error(replace(kGood, "steer = -0.5", "steer = -0.5\ndphi = 1"), "8:8",
               "gait.dphi: a parameter of the undulation gait, given with kind "
               "= 'tripod'");
  expect_error(
      replace(kGood, "steer = -0.5", "stride = 0.1"), "7:10",
      "gait.stride: a parameter of the trot and foot_path gaits, given with kind = 'tripod'");
  expect_error(replace(kGood, "name = \"bigant\"", "name = \"bigant\"\nstiffness = 5"), "3:13",
               "robot.stiffness: a parameter of the multipod robot");
  expect_error(replace(kGood, "kind = \"tripod\"", "kind = \"trot\""), "5:8",
               "gait.kind: unknown value 'trot' (valid: tripod, metachronal)");
  expect_error(replace(kGood, "dt = 0.01", "dt = 0.01\nsteps = 1000"), "12:9",
               "give dt or steps, not both");
}

TEST(Scene, TomlSyntaxErrorsNameTheirPlace) {
  expect_error(replace(kGood, "frequency = 0.2", "frequency = = 0.2"), "6:13", "");
  expect_error(replace(kGood, "[run]", "[run"), "9:5", "");
  expect_error(replace(kGood, "[filter]", "[gait]"), "17:1",
               "");  // a table defined twice
}

TEST(Scene, UnreadableFileIsAnInputError) {
  try {
    (void)read_scene("/nonexistent/scene.toml");
    ADD_FAILURE();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/scene.toml");
  }
}

TEST(Scene, EditDistanceAndNearest) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("gamma", "gamma"), 0u);
  EXPECT_EQ(nearest("frequncy", {"kind", "frequency", "steer"}), "frequency");
  EXPECT_EQ(nearest("zzzzzz", {"kind", "frequency", "steer"}), "");
}

TEST(Scene, MutatedScenesParseOrRaiseInputError) {
  // Random byte edits of a good scene: never a crash or another exception type.
  std::mt19937 rng(11);
  const std::string good = kGood;
  const std::string alphabet = "[]=\"#.,-+0123456789 \nabcdefgilmnoprstuyz_{}";
  int errors = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % text.size();
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          text[at] = c;
          break;
        case 1:
          text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), c);
          break;
        default:
          text.erase(at, 1);
      }
    }
    try {
      (void)parse_scene(text, "fuzz.toml");
    } catch (const core::InputError& e) {
      ++errors;
      EXPECT_EQ(e.where().rfind("fuzz.toml:", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(errors, 100);
}

// ---- compose: the scene to a simulator (needs the robot factories)
// -----------------------------

Scene short_scene(const std::string& robot, const std::string& gait, const std::string& law,
                  bool filter) {
  std::string text = "[robot]\nname = \"";
  text.append(robot).append("\"\n[gait]\nkind = \"").append(gait);
  text.append("\"\n[run]\nduration = 0.5\ndt = 0.05\n[friction]\nlaw = \"").append(law);
  text.append("\"\n");
  if (filter) {
    text.append("[filter]\ngamma = 0.2\n");
  }
  return parse_scene(text, "c.toml");
}

// The gait and law tables: every robot's gaits and every isotropic law read back under their own
// names in the scene, its JSON and its kernel; every key of a table is listed once.
TEST(SceneTables, NamesRoundTripThroughReaderJsonAndKernel) {
  EXPECT_EQ(robot_names(),
            (std::vector<std::string_view>{"bigant", "multipod", "quadruped", "disk", "legs"}));
  const std::vector<std::pair<const char*, const char*>> gaits = {{"bigant", "tripod"},
                                                                  {"bigant", "metachronal"},
                                                                  {"multipod", "undulation"},
                                                                  {"quadruped", "trot"},
                                                                  {"disk", "disk"}};
  for (const auto& [robot, gait] : gaits) {
    for (const char* law : {"viscous", "coulomb"}) {
      const Scene scene = short_scene(robot, gait, law, false);
      EXPECT_STREQ(gait_kind(scene.gait), gait);
      EXPECT_EQ(friction_law_of(scene.friction).name, law);
      const nlohmann::json json = to_json(scene);
      EXPECT_EQ(json["robot"], robot);
      EXPECT_EQ(json["gait"]["kind"], gait);
      EXPECT_EQ(json["friction"]["law"], law);
      EXPECT_EQ(compose(scene).kernel_name, law);
    }
  }
  for (const auto& keys : {robot_table_keys(), gait_table_keys(), friction_table_keys()}) {
    for (std::string_view key : keys) {
      EXPECT_EQ(std::count(keys.begin(), keys.end(), key), 1) << key;
    }
  }
}

TEST(SceneCompose, PicksTheKernelOnceAndRunsEveryFrame) {
  for (bool filter : {false, true}) {
    for (const char* law : {"viscous", "coulomb"}) {
      const Scene scene = short_scene("bigant", "tripod", law, filter);
      const Simulator sim = compose(scene);
      EXPECT_EQ(sim.kernel_name, std::string(law) + (filter ? "+filter" : ""));
      EXPECT_EQ(sim.walker.legs(), 6);
      EXPECT_EQ(sim.options.steps, 10);
      EXPECT_EQ(sim.options.dt, 0.05);
      // The composed kernel is connection::integrate with that law and filter,
      // bit for bit.
      std::vector<Eigen::Vector3d> composed;
      std::vector<Eigen::Vector3d> direct;
      const auto summary = sim.run([&](const connection::TrajectoryStep& s) {
        composed.push_back(Eigen::Vector3d(s.pose.x, s.pose.y, s.pose.theta));
      });
      EXPECT_EQ(summary.frames, 11);
      connection::TrajectoryData data(sim.walker.robot);
      const connection::TrajectorySink sink = [&](const connection::TrajectoryStep& s) {
        direct.push_back(Eigen::Vector3d(s.pose.x, s.pose.y, s.pose.theta));
      };
      const bool coulomb = std::string(law) == "coulomb";
      if (coulomb && filter) {
        connection::integrate(sim.walker.robot, sim.walker.feet, sim.options,
                              connection::CoulombKernel{}, connection::IirFilter{0.2}, data, sink);
      } else if (coulomb) {
        connection::integrate(sim.walker.robot, sim.walker.feet, sim.options,
                              connection::CoulombKernel{}, connection::NoFilter{}, data, sink);
      } else if (filter) {
        connection::integrate(sim.walker.robot, sim.walker.feet, sim.options,
                              connection::ViscousCoulombKernel{}, connection::IirFilter{0.2}, data,
                              sink);
      } else {
        connection::integrate(sim.walker.robot, sim.walker.feet, sim.options,
                              connection::ViscousCoulombKernel{}, connection::NoFilter{}, data,
                              sink);
      }
      EXPECT_EQ(composed, direct);
    }
  }
}

TEST(SceneCompose, EveryRobot) {
  struct Case {
    const char* robot;
    const char* gait;
    int legs;
  };
  for (const Case& c : {Case{"bigant", "metachronal", 6}, Case{"multipod", "undulation", 6},
                        Case{"quadruped", "trot", 4}, Case{"disk", "disk", 6}}) {
    const Simulator sim = compose(short_scene(c.robot, c.gait, "viscous", false));
    EXPECT_EQ(sim.walker.legs(), c.legs) << c.robot;
    EXPECT_EQ(static_cast<int>(sim.walker.leg_names.size()), c.legs) << c.robot;
    const auto summary = sim.run([](const connection::TrajectoryStep&) {});
    EXPECT_EQ(summary.frames, 11) << c.robot;
  }
}

}  // namespace
}  // namespace slipwalk::scene
