// slipwalk run SCENE.toml --out FILE.csv: a good scene writes the CSV (header,
// one row per frame, the pose integrating the written velocities exactly) and
// its sidecar; every parser error class exits 2 naming file:line:col and writes
// nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/se2.hpp"

namespace slipwalk::testing {
namespace {

const char* const kTripod = R"([robot]
name = "bigant"

[gait]
kind = "tripod"
frequency = 0.5

[run]
duration = 2.0
dt = 0.05

[friction]
law = "viscous"
)";

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    out.push_back(cell);
  }
  return out;
}

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  [[nodiscard]] std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) {
        return i;
      }
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Table read_csv(const std::filesystem::path& path) {
  std::stringstream text(read_text(path));
  Table t;
  std::string line;
  std::getline(text, line);
  t.header = split(line);
  while (std::getline(text, line)) {
    std::vector<double> row;
    for (const std::string& cell : split(line)) {
      row.push_back(std::stod(cell));
    }
    EXPECT_EQ(row.size(), t.header.size()) << line;
    t.rows.push_back(row);
  }
  return t;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CliRun, WritesTheTrajectoryAndItsSidecar) {
  ScratchDir dir;
  write_text(dir / "scene.toml", kTripod);
  const auto r =
      run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "out.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_csv(dir / "out.csv");
  const std::vector<std::string> first{"t",     "x",         "y",          "theta", "vx",
                                       "vy",    "omega",     "contact_HL", "Fz_HL", "Fx_HL",
                                       "Fy_HL", "slip_x_HL", "slip_y_HL"};
  ASSERT_GE(t.header.size(), first.size());
  EXPECT_EQ(std::vector<std::string>(t.header.begin(), t.header.begin() + 13), first);
  for (const char* leg : {"HL", "ML", "FL", "HR", "MR", "FR"}) {
    EXPECT_NE(std::find(t.header.begin(), t.header.end(), std::string("slip_y_") + leg),
              t.header.end());
  }
  ASSERT_EQ(t.rows.size(), 41u);  // t = 0, 0.05, ..., 2.0
  EXPECT_EQ(t.rows.front()[0], 0.0);
  EXPECT_DOUBLE_EQ(t.rows.back()[0], 2.0);
  // The CSV round-trips doubles, so the written pose must be the exact SE(2)
  // step of the written velocity, bit for bit; and the feet carry the weight
  // (BigANT: Mg = 8.18 kg · g).
  double distance = 0.0;
  for (std::size_t n = 0; n + 1 < t.rows.size(); ++n) {
    const auto& a = t.rows[n];
    const auto& b = t.rows[n + 1];
    const core::Pose2 next =
        core::advance(core::Pose2{a[1], a[2], a[3]}, Eigen::Vector3d(a[4], a[5], a[6]), 0.05);
    EXPECT_EQ(next.x, b[1]);
    EXPECT_EQ(next.y, b[2]);
    EXPECT_EQ(next.theta, b[3]);
    distance += std::hypot(b[1] - a[1], b[2] - a[2]);
    double load = 0.0;
    for (const char* leg : {"HL", "ML", "FL", "HR", "MR", "FR"}) {
      const double fz = a[t.column(std::string("Fz_") + leg)];
      load += fz;
      if (a[t.column(std::string("contact_") + leg)] == 0.0) {
        EXPECT_EQ(fz, 0.0);
      }
    }
    EXPECT_NEAR(load, 8.18 * 9.81, 1e-6 * 8.18 * 9.81) << "t = " << a[0];
  }
  EXPECT_GT(distance, 0.0);  // it walks

  const auto sidecar = nlohmann::json::parse(read_text(dir / "out.json"));
  EXPECT_EQ(sidecar["kernel"], "viscous");
  EXPECT_EQ(sidecar["frames"], 41);
  EXPECT_EQ(sidecar["scene"]["gait"]["kind"], "tripod");
  EXPECT_EQ(sidecar["columns"].size(), t.header.size());
  EXPECT_TRUE(sidecar.contains("provenance"));
  EXPECT_EQ(files_under(dir.path()),
            (std::vector<std::string>{"out.csv", "out.json", "scene.toml"}));
}

TEST(CliRun, FilterAddsTheModelVelocityAndIsDeterministic) {
  ScratchDir dir;
  write_text(dir / "scene.toml", R"([robot]
name = "quadruped"
[gait]
kind = "trot"
[run]
duration = 0.5
dt = 0.01
[friction]
law = "coulomb"
[filter]
gamma = 0.15
)");
  for (const char* out : {"a.csv", "b.csv"}) {
    const auto r =
        run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / out).string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(read_text(dir / "a.csv"), read_text(dir / "b.csv"));
  const Table t = read_csv(dir / "a.csv");
  ASSERT_EQ(t.rows.size(), 51u);
  EXPECT_EQ(t.header[7], "vx_model");
  EXPECT_EQ(t.header[9], "omega_model");
  // y_n = γ y_{n−1} + (1 − γ) x_n from rest, column by column.
  double y = 0.0;
  for (const auto& row : t.rows) {
    y = 0.15 * y + 0.85 * row[7];
    EXPECT_NEAR(row[4], y, 1e-15);
  }
  const auto sidecar = nlohmann::json::parse(read_text(dir / "a.json"));
  EXPECT_EQ(sidecar["kernel"], "coulomb+filter");
}

TEST(CliRun, ExampleScenesParse) {
  // The shipped scenes are valid (run briefly: the same file with a short
  // [run]).
  for (const char* name : {"bigant_tripod", "bigant_metachronal", "multipod6", "quadruped_trot"}) {
    ScratchDir dir;
    const std::string text = read_text(std::filesystem::path(SLIPWALK_SOURCE_DIR) /
                                       "studies/ch3_robots/scenes" / (std::string(name) + ".toml"));
    ASSERT_FALSE(text.empty()) << name;
    const std::size_t run = text.find("[run]");
    const std::size_t next = text.find("\n[", run + 1);
    const std::string shortened = text.substr(0, run) + "[run]\nduration = 0.2\ndt = 0.01\n" +
                                  (next == std::string::npos ? "" : text.substr(next));
    write_text(dir / "scene.toml", shortened);
    const auto r =
        run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "o.csv").string()});
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_EQ(read_csv(dir / "o.csv").rows.size(), 21u) << name;
  }
}

TEST(CliRun, BadScenesExitTwoNamingTheirPlaceAndWriteNothing) {
  struct Case {
    std::string text;
    std::string where;
    std::string what;
  };
  const std::vector<Case> cases = {
      {replace(kTripod, "frequency", "frequncy"), "scene.toml:6:1", "did you mean 'frequency'?"},
      {replace(kTripod, "0.5", "\"fast\""), "scene.toml:6:13", "expected a number, got a string"},
      {replace(kTripod, "0.5", "-2"), "scene.toml:6:13", "must be in [1e-06, 1000] Hz"},
      {replace(kTripod, "duration = 2.0\n", ""), "scene.toml:8:1",
       "missing required key 'duration'"},
      {replace(kTripod, "law = \"viscous\"", "law = \"viscous\"\ntol = 1e-8"), "scene.toml:14:7",
       "a parameter of the coulomb law"},
      {replace(kTripod, "[run]", "[run"), "scene.toml:8:", ""},
  };
  for (const Case& c : cases) {
    ScratchDir dir;
    write_text(dir / "scene.toml", c.text);
    const auto r =
        run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "out.csv").string()});
    EXPECT_EQ(r.exit_code, 2) << c.text;
    EXPECT_NE(r.err.find("slipwalk: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find((dir / c.where).string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.what), std::string::npos) << r.err;
    EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"scene.toml"}) << r.err;
  }
}

TEST(CliRun, BadUsageExitsTwo) {
  ScratchDir dir;
  const auto missing =
      run_slipwalk({"run", (dir / "none.toml").string(), "--out", (dir / "o.csv").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("none.toml"), std::string::npos);
  write_text(dir / "scene.toml", kTripod);
  EXPECT_EQ(run_slipwalk({"run", (dir / "scene.toml").string()}).exit_code,
            2);  // no --out
  const auto json_out =
      run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "o.json").string()});
  EXPECT_EQ(json_out.exit_code, 2);
  EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"scene.toml"});
}

TEST(CliRun, ARunTooLargeExitsTwoAtItsStepWithTheEstimateAndWritesNothing) {
  ScratchDir dir;
  // 5e6 rows of BigANT's 52 columns: about 6.5 GB.
  write_text(dir / "scene.toml", replace(replace(kTripod, "duration = 2.0", "duration = 5e4"),
                                         "dt = 0.05", "dt = 0.01"));
  const auto r =
      run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "o.csv").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find((dir / "scene.toml").string() + ":10:6: run.dt: the run would write "
                                                       "5000001 rows"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("GB; at most 4 GB"), std::string::npos) << r.err;
  EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"scene.toml"});
}

TEST(CliRun, EveryInputThatIsAFolderExitsTwoNamingItAndWritesNothing) {
  ScratchDir dir;
  std::filesystem::create_directories(dir / "folder.toml");
  std::filesystem::create_directories(dir / "B.csv");
  // The scene itself, and the residual file it names.
  const auto scene =
      run_slipwalk({"run", (dir / "folder.toml").string(), "--out", (dir / "o.csv").string()});
  EXPECT_EQ(scene.exit_code, 2) << scene.err;
  EXPECT_NE(scene.err.find((dir / "folder.toml").string()), std::string::npos) << scene.err;
  write_text(dir / "scene.toml", kTripod + std::string("[residual]\nfile = \"B.csv\"\n"));
  const auto residual =
      run_slipwalk({"run", (dir / "scene.toml").string(), "--out", (dir / "o.csv").string()});
  EXPECT_EQ(residual.exit_code, 2) << residual.err;
  EXPECT_NE(residual.err.find((dir / "scene.toml").string() + ":15:8"), std::string::npos)
      << residual.err;
  EXPECT_NE(residual.err.find((dir / "B.csv").string()), std::string::npos) << residual.err;
  // A sweep spec, and a robot file a spec names.
  const auto spec =
      run_slipwalk({"sweep", (dir / "folder.toml").string(), "--data", (dir / "data").string()});
  EXPECT_EQ(spec.exit_code, 2) << spec.err;
  EXPECT_NE(spec.err.find((dir / "folder.toml").string()), std::string::npos) << spec.err;
  write_text(dir / "spec.toml",
             "study = \"t\"\nname = \"m\"\nkind = \"legged_force_map\"\n[params]\n"
             "robot = \"B.csv\"\n");
  const auto robot =
      run_slipwalk({"sweep", (dir / "spec.toml").string(), "--data", (dir / "data").string()});
  EXPECT_EQ(robot.exit_code, 2) << robot.err;
  EXPECT_NE(robot.err.find((dir / "spec.toml").string() + ":5:9"), std::string::npos) << robot.err;
  EXPECT_NE(robot.err.find((dir / "B.csv").string()), std::string::npos) << robot.err;
  // Studies: a folder holding none, a study whose study.toml is a folder, a [[scene]] file and
  // a sweep spec that are folders.
  std::filesystem::create_directories(dir / "studies" / "empty");
  const auto none = run_slipwalk({"reproduce", "--no-report", "--studies",
                                  (dir / "studies").string(), "--data", (dir / "data").string()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("--studies: '" + (dir / "studies").string() + "' holds no study"),
            std::string::npos)
      << none.err;
  std::filesystem::create_directories(dir / "studies" / "odd" / "study.toml");
  const auto odd =
      run_slipwalk({"reproduce", "--no-report", "--studies", (dir / "studies").string(), "--data",
                    (dir / "data").string(), "odd"});
  EXPECT_EQ(odd.exit_code, 2) << odd.err;
  EXPECT_NE(odd.err.find((dir / "studies" / "odd" / "study.toml").string()), std::string::npos)
      << odd.err;
  std::filesystem::create_directories(dir / "studies" / "s" / "sub");
  for (const std::string& entry : {std::string("[[scene]]\nname = \"x\"\nfile = \"sub\"\n"),
                                   std::string("sweeps = [\"sub\"]\n")}) {
    write_text(dir / "studies" / "s" / "study.toml", "title = \"t\"\n" + entry);
    const auto r =
        run_slipwalk({"reproduce", "--no-report", "--studies", (dir / "studies").string(), "--data",
                      (dir / "data").string(), "s"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find((dir / "studies" / "s" / "study.toml").string() + ":"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find((dir / "studies" / "s" / "sub").string() + " is a folder"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "data"));
  EXPECT_FALSE(std::filesystem::exists(dir / "o.csv"));
}

}  // namespace
}  // namespace slipwalk::testing
