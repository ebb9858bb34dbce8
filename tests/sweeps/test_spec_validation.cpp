// A spec is validated whole before its first point runs: every key of every point kind, given a
// bad value (magnitudes 1e-320 … 1e308 of both signs, zero, a text, a fraction where an integer
// is due), is either refused by prepare() at the value's spec file:line:col, or accepted and
// then the point runs without throwing: a point that fails mid-sweep for a reason the check could
// have caught is a bug. The [quick] overrides and the values they override are both checked,
// and a refused spec writes nothing (`slipwalk sweep` exits 2 and creates no folder).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::run_slipwalk;
using testing::ScratchDir;
using testing::write_text;

/// A small valid point of each kind (its [params] lines), cheap to run. The inchworm kinds have
/// their own tests; kinds not listed here are reported and skipped (scale_out and
/// coordinator_throughput run the binary as a child, which a test binary is not: they have their
/// own tests in test_scale_out_points.cpp).
const std::map<std::string, std::string>& bases() {
  static const std::map<std::string, std::string> all = {
      {"legged_1d", "N = 3\ntrials = 2\n"},
      {"legged_compare", "N = 3\ntrials = 2\n"},
      {"legged_eps_error", "shape = \"polar\"\nn = 3\nangles = 8\n"},
      {"legged_force_map", "robot = \"robot.json\"\nn = 3\n"},
      {"legged_support_path", "robot = \"robot.json\"\n"},
      {"legged_cost", "robot = \"hexapod\"\nframes = 2\nrepeats = 1\n"},
      {"peer_scaling", "N = 3\nconfigs = 2\nbatches = 1\nmin_batch_us = 1\n"},
      {"parallel_overhead", "trajectories = 2\nsteps = 5\nmax_threads = 1\nblocks = 1\n"},
      {"peer_bigant", "duration = 0.2\nsample = 0.1\nsettle = 0.0\ndt = 0.01\ntimestep = 0.002\n"},
      {"peer_terrain", "scene = \"" SLIPWALK_SOURCE_DIR
                       "/studies/ch5_terrain/scenes/bigant_stairs.toml\"\ncycles = 0.02\n"
                       "settle = 0.0\n"},
      {"plan_replay", "steps = 2\nsettle = 0.0\n"},
      {"scene_cost", "steps = 5\nrepeats = 1\n"},
      {"slope_progress", "cycles = 2\nsteps_per_cycle = 10\nangle_deg = 5.0\n"},
      {"stall_slope", "cycles = 2\nsteps_per_cycle = 10\ntol_deg = 20.0\n"},
      {"plan_run", "goal = \"twist\"\nsteps = 2\n"},
      {"plan_summary", "goal = \"twist\"\nsteps = 2\n"},
      {"foot_path", "samples = 5\n"},
      {"planning_cost", "mode = \"kernel\"\noptions = 8\nrepeats = 1\n"},
      {"multipod_trial", "frequency = 2.4\ncycles = 1\nskip_cycles = 0\nsettle = 0.0\n"},
      {"residual_transfer",
       "test_frequency = 2.4\ncycles = 1\nskip_cycles = 0\nsettle = 0.0\ntrain_dphi_pi = "
       "\"1.0\"\n"},
      {"residual_errors",
       "test_frequency = 2.4\ncycles = 1\nskip_cycles = 0\nsettle = 0.0\ntrain_dphi_pi = "
       "\"1.0\"\n"},
      {"residual_training",
       "frequency = 2.4\ncycles = 1\nskip_cycles = 0\nsettle = 0.0\ntrain_trials = 1\ndraws = "
       "1\nvalidate_dphi_pi = \"1.8\"\n"},
      {"calib_parameters", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"calib_com", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"calib_hanging_residuals", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"calib_pose_residuals", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"calib_models", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"calib_starts",
       "poses = 60\nsamples_per_cycle = 90\ncycles = 2\nstarts = 1\nmax_iterations = 5\n"},
      {"calib_accuracy", "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n"},
      {"machine_limits", "repeats = 1\nmin_repeat_s = 1e-5\n"},
      {"noop", "i = 1\n"},
  };
  return all;
}

const char* const kRobot = R"({"q": [[0.3, 0.2, -0.1], [0.0, -0.2, -0.1], [-0.3, 0.2, -0.1],
  [0.3, -0.2, -0.1], [0.0, 0.2, -0.1], [-0.3, -0.2, -0.1]],
 "qdot": [[-0.1, 0, 0], [-0.1, 0, 0], [-0.1, 0, 0], [0.1, 0, 0], [0.1, 0, 0], [0.1, 0, 0]],
 "K": [1000, 1000, 1000, 1000, 1000, 1000], "Mg": 80.0})";

std::string spec_text(const std::string& kind, const std::string& params) {
  return "study = \"t\"\nname = \"v\"\nkind = \"" + kind + "\"\n[params]\n" + params;
}

/// The keys a kind takes, read off its own refusal of an unknown key.
std::vector<std::string> keys_of(const std::string& kind, const std::filesystem::path& path) {
  try {
    (void)points::prepare(parse_spec(spec_text(kind, "zzz_not_a_key = 1\n"), path.string()));
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    const std::string marker = "expected one of ";
    std::vector<std::string> keys;
    std::size_t at = what.find(marker);
    if (at == std::string::npos) {
      return keys;
    }
    at += marker.size();
    while (at < what.size()) {
      const std::size_t comma = what.find(", ", at);
      keys.push_back(what.substr(at, comma - at));
      if (comma == std::string::npos) {
        break;
      }
      at = comma + 2;
    }
    return keys;
  }
  return {};
}

/// The bad values of the class, as TOML: the fixed ones, then seeded random magnitudes.
std::vector<std::string> bad_values() {
  std::vector<std::string> out = {"1e-320", "0",       "-1",  "-1e308",
                                  "1e308",  "\"bad\"", "0.5", "9007199254740993"};
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> exponent(-320.0, 308.0);
  for (int i = 0; i < 3; ++i) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17e",
                  (i % 2 == 0 ? 1.0 : -1.0) * std::pow(10.0, exponent(rng)));
    out.emplace_back(buffer);
  }
  return out;
}

/// params with `key = value` in place of the base's own line for `key`, if any; the value's
/// line is the last.
std::string with_key(const std::string& base, const std::string& key, const std::string& value) {
  std::string out;
  std::size_t at = 0;
  while (at < base.size()) {
    const std::size_t end = base.find('\n', at);
    const std::string line = base.substr(at, end - at);
    if (line.rfind(key + " = ", 0) != 0) {
      out += line + "\n";
    }
    at = end + 1;
  }
  return out + key + " = " + value + "\n";
}

TEST(SpecValidation, EveryKeyOfEveryKindIsRefusedUpFrontOrRunsCleanly) {
  const ScratchDir dir;
  write_text(dir / "robot.json", kRobot);
  const std::filesystem::path path = dir / "spec.toml";
  int refused = 0;
  int at_value = 0;
  int ran = 0;
  for (const PointKind& kind : points::all_kinds()) {
    if (kind.name.rfind("inchworm", 0) == 0) {
      continue;
    }
    const auto base = bases().find(kind.name);
    if (base == bases().end()) {
      std::printf("note: kind %s has no base point here; skipped\n", kind.name.c_str());
      continue;
    }
    // The base itself is valid and runs.
    const PreparedSweep good =
        points::prepare(parse_spec(spec_text(kind.name, base->second), path.string()));
    ASSERT_EQ(good.points.size(), 1U);
    const std::vector<std::string> keys = keys_of(kind.name, path);
    ASSERT_FALSE(keys.empty()) << kind.name;
    for (const std::string& key : keys) {
      for (const std::string& value : bad_values()) {
        const std::string params = with_key(base->second, key, value);
        const std::string text = spec_text(kind.name, params);
        const long line = std::count(text.begin(), text.end(), '\n');  // the value's line
        const std::string place =
            path.string() + ":" + std::to_string(line) + ":" + std::to_string(key.size() + 4);
        try {
          const PreparedSweep sweep = points::prepare(parse_spec(text, path.string()));
          // Accepted: the point must run without an error the check could have raised.
          EXPECT_NO_THROW((void)sweep.kind->run(sweep.points.front()))
              << kind.name << ": " << key << " = " << value;
          ++ran;
        } catch (const core::InputError& e) {
          // At the value, or (a check across keys: "give both vx_min and vx_max") elsewhere in
          // the spec; always before any point ran.
          EXPECT_EQ(e.where().rfind(path.string(), 0), 0U) << e.what();
          at_value += e.where() == place ? 1 : 0;
          ++refused;
        }
      }
    }
  }
  std::printf("%d bad values refused (%d at the value itself), %d accepted and run\n", refused,
              at_value, ran);
  EXPECT_GT(refused, 300);
  EXPECT_GT(at_value, refused * 9 / 10);
  EXPECT_GT(ran, 0);
}

TEST(SpecValidation, AValueQuickOverridesIsCheckedInQuickRuns) {
  const std::string text =
      "study = \"t\"\nname = \"v\"\nkind = \"legged_compare\"\n[params]\nN = 3\ntrials = "
      "100000000\n[quick]\nparams.trials = 2\n";
  try {
    (void)points::prepare(parse_spec(text, "spec.toml", true));
    ADD_FAILURE() << "the full spec's trials passed under --quick";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "spec.toml:6:10") << e.what();
    EXPECT_NE(std::string(e.what()).find("(in the spec without --quick)"), std::string::npos)
        << e.what();
  }
}

TEST(SpecValidation, AQuickValueIsCheckedInFullRuns) {
  const std::string text =
      "study = \"t\"\nname = \"v\"\nkind = \"legged_compare\"\n[params]\nN = 3\ntrials = "
      "2\n[quick]\nparams.radius = -1.0\n";
  try {
    (void)points::prepare(parse_spec(text, "spec.toml"));
    ADD_FAILURE() << "a bad [quick] value passed a full run";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "spec.toml:8:17") << e.what();
    EXPECT_NE(std::string(e.what()).find("radius: must be in ["), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(in the spec under --quick)"), std::string::npos)
        << e.what();
  }
}

TEST(SpecValidation, AComputedAxisValueIsNamedByItsAxis) {
  const std::string text =
      "study = \"t\"\nname = \"v\"\nkind = \"legged_compare\"\n[params]\nN = 3\n[axes]\n"
      "radius = { linspace = [0.1, 1e300], n = 3 }\n";
  try {
    (void)points::prepare(parse_spec(text, "spec.toml"));
    ADD_FAILURE() << "radius 1e300 accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "spec.toml:7:10") << e.what();
    EXPECT_NE(std::string(e.what()).find("radius: must be in"), std::string::npos) << e.what();
  }
}

TEST(SpecValidation, ARefusedSpecExitsTwoAndCreatesNoFolder) {
  const ScratchDir dir;
  write_text(dir / "robot.json", kRobot);
  for (const auto& [kind, base] : bases()) {
    const std::vector<std::string> keys = keys_of(kind, dir / "spec.toml");
    ASSERT_FALSE(keys.empty()) << kind;
    // The first key, at a magnitude no kind accepts for any key.
    write_text(dir / "spec.toml", spec_text(kind, with_key(base, keys.front(), "-1e308")));
    const auto r = run_slipwalk(
        {"sweep", (dir / "spec.toml").string(), "--data", (dir / "data").string(), "--no-timing"});
    EXPECT_EQ(r.exit_code, 2) << kind << ": " << r.err;
    EXPECT_NE(r.err.find((dir / "spec.toml").string() + ":"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "data")) << kind;
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
