// Every number a scene file holds is read in its range (scene/ranges.hpp): a value outside it —
// generated over magnitudes 1e-320 … 1e308, both signs, zero, ±inf, NaN, and values of the wrong
// type — is refused by parse_scene at the value's file:line:col, the message naming the key, the
// range and its unit; nothing reaches the robot factories or the run. A run whose CSV would pass
// kMaxRunBytes is refused at its dt or steps with the estimate, and a run whose state turns
// non-finite stops (exit 1 for `slipwalk run`) instead of writing NaN rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "scene/ranges.hpp"
#include "scene/run_writer.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {
namespace {

/// A scene with one line `<key> = @` (the value under test) and the rest valid.
struct KeyCase {
  std::string key;  ///< as the message names it ("gait.stride", "robot.leg.K")
  std::string text;
  core::Range range;
};

const std::string kRun = "[run]\nduration = 2.0\ndt = 0.01\n";
const std::string kViscous = "[friction]\nlaw = \"viscous\"\n";
const std::string kBigant = "[robot]\nname = \"bigant\"\n";

std::string tripod(const std::string& line) {
  return kBigant + "[gait]\nkind = \"tripod\"\n" + line + "\n" + kRun + kViscous;
}
std::string legs(const std::string& robot_line, const std::string& leg_line,
                 const std::string& gait_line) {
  std::string text = "[robot]\nname = \"legs\"\n" + robot_line + "\n";
  const char* hips[] = {"[0.3, 0.2, 0.0]", "[0.0, -0.2, 0.0]", "[-0.3, 0.2, 0.0]"};
  for (int k = 0; k < 3; ++k) {
    text += "[[robot.leg]]\nhip = " + std::string(hips[k]) + "\n";
    if (k != 1 || leg_line.rfind("K = ", 0) != 0) {
      text += "K = 1000.0\n";
    }
    if (k == 1) {
      text += leg_line + "\n";
    }
  }
  return text + "[gait]\nkind = \"foot_path\"\n" + gait_line + "\n" + kRun + kViscous;
}

std::vector<KeyCase> key_cases() {
  namespace r = ranges;
  const std::string mass = "mass = 8.0";
  std::vector<KeyCase> cases = {
      {"gait.frequency", tripod("frequency = @"), r::kFrequency},
      {"gait.steer", tripod("steer = @"), r::kSteer},
      {"gait.duty", tripod("duty = @"), r::kDuty},
      {"gait.sweep", tripod("sweep = @"), r::kSweep},
      {"gait.sweep", kBigant + "[gait]\nkind = \"metachronal\"\nsweep = @\n" + kRun + kViscous,
       r::kSweep},
      {"gait.dphi",
       "[robot]\nname = \"multipod\"\n[gait]\nkind = \"undulation\"\ndphi = @\n" + kRun + kViscous,
       r::kPhaseLag},
      {"gait.roll_amplitude",
       "[robot]\nname = \"multipod\"\n[gait]\nkind = \"undulation\"\nroll_amplitude = @\n" + kRun +
           kViscous,
       r::kRollAmplitude},
      {"gait.yaw_amplitude",
       "[robot]\nname = \"multipod\"\n[gait]\nkind = \"undulation\"\nyaw_amplitude = @\n" + kRun +
           kViscous,
       r::kYawAmplitude},
      {"robot.stiffness",
       "[robot]\nname = \"multipod\"\nstiffness = @\n[gait]\nkind = \"undulation\"\n" + kRun +
           kViscous,
       r::kStiffness},
      {"gait.duty",
       "[robot]\nname = \"quadruped\"\n[gait]\nkind = \"trot\"\nduty = @\n" + kRun + kViscous,
       r::kDuty},
      {"gait.stride",
       "[robot]\nname = \"quadruped\"\n[gait]\nkind = \"trot\"\nstride = @\n" + kRun + kViscous,
       r::kTrotStride},
      {"gait.swing_height",
       "[robot]\nname = \"quadruped\"\n[gait]\nkind = \"trot\"\nswing_height = @\n" + kRun +
           kViscous,
       r::kTrotSwingHeight},
      {"robot.radius",
       "[robot]\nname = \"disk\"\nradius = @\n[gait]\nkind = \"disk\"\n" + kRun + kViscous,
       r::kRadius},
      {"robot.mass", legs("mass = @", "", ""), r::kMass},
      {"robot.leg.K", legs(mass, "K = @", ""), r::kStiffness},
      {"robot.leg.mu", legs(mass, "mu = @", ""), r::kFrictionCoefficient},
      {"robot.leg.phase", legs(mass, "phase = @", ""), r::kPhase},
      {"gait.frequency", legs(mass, "", "frequency = @"), r::kFrequency},
      {"gait.stride", legs(mass, "", "stride = @"), r::kLength},
      {"gait.height", legs(mass, "", "height = @"), r::kLength},
      {"gait.lift", legs(mass, "", "lift = @"), r::kLengthOrZero},
      {"run.duration",
       kBigant + "[gait]\nkind = \"tripod\"\n[run]\nduration = @\nsteps = 10\n" + kViscous,
       r::kDuration},
      {"run.dt", kBigant + "[gait]\nkind = \"tripod\"\n[run]\nduration = 1e-9\ndt = @\n" + kViscous,
       r::kStep},
      {"friction.tol",
       kBigant + "[gait]\nkind = \"tripod\"\n" + kRun + "[friction]\nlaw = \"coulomb\"\ntol = @\n",
       r::kCoulombTolerance},
      {"filter.gamma", tripod("") + "[filter]\ngamma = @\n", r::kFilterGamma},
      {"noise.sigma", tripod("") + "[noise]\nsigma = @\n", r::kNoiseXY},
      {"noise.sigma_theta", tripod("") + "[noise]\nsigma = 0.0\nsigma_theta = @\n", r::kNoiseTheta},
      {"terrain.angle_deg", tripod("") + "[terrain]\nkind = \"slope\"\nangle_deg = @\n",
       r::kSlopeAngle},
      {"terrain.heading_deg",
       tripod("") + "[terrain]\nkind = \"slope\"\nangle_deg = 5.0\nheading_deg = @\n", r::kHeading},
      {"terrain.com_height",
       tripod("") + "[terrain]\nkind = \"slope\"\nangle_deg = 5.0\ncom_height = @\n",
       r::kLengthOrZero},
      {"terrain.tread", tripod("") + "[terrain]\nkind = \"stairs\"\nriser = 0.1\ntread = @\n",
       r::kLength},
      {"terrain.riser", tripod("") + "[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = @\n",
       r::kLengthOrZero},
  };
  cases.push_back({"friction.w",
                   kBigant + "[gait]\nkind = \"tripod\"\n" + kRun +
                       "[friction]\nlaw = \"anisotropic\"\nw = @\n",
                   r::kAnisotropy});
  return cases;
}

/// A TOML float spelling of x that reads back as x (toml++ has inf and nan).
std::string toml_float(double x) {
  if (std::isnan(x)) {
    return "nan";
  }
  if (std::isinf(x)) {
    return x > 0 ? "inf" : "-inf";
  }
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17e", x);
  return buffer;
}

/// The bad values of the class: magnitudes 10^-320 … 10^308 of both signs drawn with a seeded
/// RNG, the ends and specials; the ones inside a key's range are skipped by the test.
std::vector<double> magnitudes() {
  std::vector<double> out = {0.0,
                             -0.0,
                             1e-320,
                             -1e-320,
                             1e308,
                             -1e308,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(),
                             -1.0};
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> exponent(-320.0, 308.0);
  for (int i = 0; i < 14; ++i) {
    const double x = std::pow(10.0, exponent(rng));
    out.push_back(i % 2 == 0 ? x : -x);
  }
  return out;
}

std::string with_value(const std::string& text, const std::string& value) {
  std::string out = text;
  const std::size_t at = out.find('@');
  return out.replace(at, 1, value);
}

/// "scene.toml:<line>:<col>" of the '@' in `text`.
std::string place_of_value(const std::string& text) {
  const std::size_t at = text.find('@');
  const std::size_t line_start = text.rfind('\n', at) + 1;
  const long line = std::count(text.begin(), text.begin() + static_cast<long>(at), '\n') + 1;
  return "scene.toml:" + std::to_string(line) + ":" + std::to_string(at - line_start + 1);
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "scene.toml");
  } catch (const core::InputError& e) {
    return e.what();
  }
  return {};
}

TEST(SceneRanges, EveryGoodTemplateParses) {
  for (const KeyCase& c : key_cases()) {
    // The range's lower end (its upper one where the lower is open) is a valid value.
    const double x = c.range.lo_open ? c.range.hi : c.range.lo;
    const std::string good =
        with_value(c.text, c.key == "friction.w" ? "[" + toml_float(x) + ", 0.1]" : toml_float(x));
    EXPECT_EQ(error_of(good), "") << c.key << "\n" << good;
  }
}

TEST(SceneRanges, AValueOutsideItsRangeIsRefusedAtItsPlaceWithTheRangeAndUnit) {
  int refused = 0;
  for (const KeyCase& c : key_cases()) {
    for (const double x : magnitudes()) {
      if (c.range.contains(x)) {
        continue;  // inside the range: not this class
      }
      std::string value = toml_float(x);
      if (c.key == "friction.w") {
        value.insert(0, 1, '[').append(", 0.0]");
      }
      const std::string text = with_value(c.text, value);
      const std::string error = error_of(text);
      std::string place = place_of_value(c.text);
      if (c.key == "friction.w") {
        place.back() += 1;  // the pair's first element, after '['
      }
      const std::string leaf = c.key.substr(c.key.rfind('.') + 1);
      EXPECT_EQ(error.rfind(place + ": ", 0), 0U) << c.key << " = " << value << ": " << error;
      EXPECT_NE(error.find(leaf + ": must be in " + c.range.describe()), std::string::npos)
          << c.key << " = " << value << ": " << error << " [" << c.range.describe() << "]";
      ++refused;
    }
  }
  EXPECT_GT(refused, 500);
}

TEST(SceneRanges, AValueOfTheWrongTypeIsRefusedAtItsPlace) {
  for (const KeyCase& c : key_cases()) {
    for (const std::string value : {"\"0.5\"", "true", "{ x = 1 }", "1979-05-27"}) {
      const std::string error = error_of(with_value(c.text, value));
      EXPECT_EQ(error.rfind(place_of_value(c.text) + ": ", 0), 0U) << c.key << ": " << error;
      EXPECT_NE(error.find("expected"), std::string::npos) << c.key << ": " << error;
    }
  }
}

TEST(SceneRanges, IntegerKeysRefuseFloatsAndOutOfRangeIntegers) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"steps",
       kBigant + "[gait]\nkind = \"tripod\"\n[run]\nduration = 1.0\nsteps = @\n" + kViscous},
      {"legs", "[robot]\nname = \"disk\"\nlegs = @\n[gait]\nkind = \"disk\"\n" + kRun + kViscous},
      {"legs",
       "[robot]\nname = \"multipod\"\nlegs = @\n[gait]\nkind = \"undulation\"\n" + kRun + kViscous},
      {"max_iterations", kBigant + "[gait]\nkind = \"tripod\"\n" + kRun +
                             "[friction]\nlaw = \"coulomb\"\nmax_iterations = @\n"},
      {"seed", tripod("") + "[noise]\nsigma = 0.0\nseed = @\n"},
  };
  for (const auto& [key, text] : cases) {
    for (const std::string value :
         {"-1", "-9223372036854775808", "9223372036854775807", "1e308", "6.0", "nan", "inf"}) {
      if (key == "seed" && value == "9223372036854775807") {
        continue;  // a valid seed
      }
      const std::string error = error_of(with_value(text, value));
      EXPECT_EQ(error.rfind(place_of_value(text) + ": ", 0), 0U)
          << key << " = " << value << ": " << error;
    }
  }
}

TEST(SceneRanges, HipCoordinatesAndResidualEntriesAreBounded) {
  std::string text = legs("mass = 8.0", "", "");
  text.replace(text.find("[0.0, -0.2, 0.0]"), 16, "[0.0, @, 0.0]");
  for (const double x : {1e308, -1e4, 1001.0, std::nan("")}) {
    const std::string error = error_of(with_value(text, toml_float(x)));
    EXPECT_EQ(error.rfind(place_of_value(text) + ": robot.leg.hip: must be in [-1000, 1000] m", 0),
              0U)
        << error;
  }
  const testing::ScratchDir dir;
  testing::write_text(dir / "B.csv", "0,0,0,0,0,0,0,0,0,0,0,0\n0,1e308,0,0,0,0,0,0,0,0,0,0\n" +
                                         std::string("0,0,0,0,0,0,0,0,0,0,0,0\n"));
  testing::write_text(dir / "scene.toml", tripod("") + "[residual]\nfile = \"B.csv\"\n");
  try {
    (void)read_scene(dir / "scene.toml");
    ADD_FAILURE() << "B = 1e308 accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), (dir / "B.csv").string() + ":2:3") << e.what();
    EXPECT_NE(std::string(e.what()).find("must be in [-1000, 1000]"), std::string::npos);
  }
}

TEST(SceneRanges, ARunTooLargeToWriteIsRefusedAtItsStepWithTheEstimate) {
  // BigANT's 52 columns at 25 bytes: 4 GB is about 3 million rows.
  const std::string dt =
      kBigant + "[gait]\nkind = \"tripod\"\n[run]\nduration = 1e4\ndt = 1e-3\n" + kViscous;
  std::string error = error_of(dt);
  EXPECT_EQ(error.rfind("scene.toml:7:6: run.dt: the run would write 10000001 rows of ", 0), 0U)
      << error;
  EXPECT_NE(error.find("GB; at most 4 GB"), std::string::npos) << error;
  const std::string steps =
      kBigant + "[gait]\nkind = \"tripod\"\n[run]\nduration = 1.0\nsteps = 9000000\n" + kViscous;
  error = error_of(steps);
  EXPECT_EQ(error.rfind("scene.toml:7:9: run.steps: the run would write 9000001 rows", 0), 0U)
      << error;
  // A thousand-legged disk reaches the limit with far fewer rows.
  const std::string disk = "[robot]\nname = \"disk\"\nlegs = 1000\n[gait]\nkind = \"disk\"\n" +
                           std::string("[run]\nduration = 100.0\ndt = 1e-3\n") + kViscous;
  error = error_of(disk);
  EXPECT_EQ(error.rfind("scene.toml:8:6: run.dt: the run would write 100001 rows of ", 0), 0U)
      << error;
}

TEST(SceneRanges, ANonFiniteStateStopsTheRunAndWritesNothing) {
  const Scene scene = parse_scene(tripod(""), "scene.toml");
  Simulator sim = compose(scene);
  // The feet turn NaN at t = 1 s: a state no input in range produces, standing for any fault.
  const robots::FootKinematics feet = sim.walker.feet;
  sim.walker.feet = [feet](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    feet(t, q, qdot);
    if (t > 0.995) {
      qdot.row(0).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  };
  long long seen = 0;
  bool finite = true;
  const connection::TrajectorySummary summary = sim.run([&](const connection::TrajectoryStep& s) {
    ++seen;
    finite = finite && std::isfinite(s.v_body.sum() + s.pose.x);
  });
  EXPECT_EQ(summary.non_finite_step, 100);
  EXPECT_EQ(summary.frames, 100);
  EXPECT_EQ(seen, 100);
  EXPECT_TRUE(finite);
  EXPECT_NE(summary.non_finite.find("(step 100): "), std::string::npos) << summary.non_finite;

  const testing::ScratchDir dir;
  EXPECT_THROW((void)write_run(scene, sim, dir / "run.csv", nlohmann::json::object(), nullptr),
               core::ComputationError);
  EXPECT_TRUE(testing::files_under(dir.path()).empty());
}

}  // namespace
}  // namespace slipwalk::scene
