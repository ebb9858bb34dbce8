// slipwalk calibrate and calibrate synth: a synthetic robot's files go through the calibration
// and come back with its leg weights; every class of bad input — a column, an orientation, a
// pairing, a pose count, a quaternion, an option — exits 2 naming the option or file:line[:col]
// before any work and writes nothing; synth writes its four files together or not at all and
// refuses to replace an earlier set without --force.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/files.hpp"
#include "calibration/standing.hpp"
#include "cli/command.hpp"

namespace slipwalk::testing {
namespace {

namespace cal = calibration;

cal::Geometry two_legs() {
  cal::Geometry g;
  g.legs = {"L1", "R1"};
  g.transducer.push_back({Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.3, 0.2, 0.04)});
  g.transducer.push_back({cal::rotation_from_vector(Eigen::Vector3d(0.0, 0.0, 3.0)),
                          Eigen::Vector3d(0.3, -0.2, 0.04)});
  g.robot_weight = 80.0;
  return g;
}

Eigen::MatrixXd numbers(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    m.data()[i] = static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5;
  }
  return m;
}

cal::HangingRecord record(cal::BodyAxis down, Eigen::Index n = 20) {
  cal::HangingRecord r;
  r.down = down;
  r.phi.resize(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    r.phi.row(i).setConstant(static_cast<double>(i) / static_cast<double>(n));
  }
  r.wrench = numbers(n, 12, static_cast<std::uint64_t>(down) + 1);
  return r;
}

std::string hanging_text(const std::vector<cal::HangingRecord>& records) {
  std::ostringstream out;
  cal::write_hanging(out, records, two_legs());
  return out.str();
}

std::string poses_text(Eigen::Index n) {
  cal::StandingPoses p;
  p.phi = numbers(n, 2, 7);
  p.wrench = numbers(n, 12, 8);
  for (Eigen::Index i = 0; i < n; ++i) {
    p.attitude.push_back(Eigen::Matrix3d::Identity());
  }
  std::ostringstream out;
  cal::write_poses(out, p, two_legs());
  return out.str();
}

/// A folder with valid hand-made inputs of a two-leg robot: g.toml, h.csv (+x −x +z −z), p.csv.
struct Inputs {
  ScratchDir dir;
  Inputs() {
    std::ostringstream g;
    cal::write_geometry(g, two_legs());
    write_text(dir / "g.toml", g.str());
    write_text(dir / "h.csv",
               hanging_text({record(cal::BodyAxis::plus_x), record(cal::BodyAxis::minus_x),
                             record(cal::BodyAxis::plus_z), record(cal::BodyAxis::minus_z)}));
    write_text(dir / "p.csv", poses_text(10));
  }
  [[nodiscard]] std::vector<std::string> args(const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> a = {"calibrate",
                                  "--geometry",
                                  (dir / "g.toml").string(),
                                  "--hanging",
                                  (dir / "h.csv").string(),
                                  "--poses",
                                  (dir / "p.csv").string(),
                                  "--out",
                                  (dir / "params.json").string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

/// Runs the command on `inputs` and expects exit 2 with `place` first in the message, and no
/// output written.
void expect_refused(const Inputs& in, const std::vector<std::string>& extra,
                    const std::string& place) {
  std::filesystem::remove(in.dir / "params.json");  // an earlier case's
  const CommandResult r = run_slipwalk(in.args(extra));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("slipwalk: error: " + place), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(in.dir / "params.json"));
}

TEST(CliCalibrate, ValidInputsPassEveryCheckAndReachTheCalibration) {
  const Inputs in;
  const CommandResult r = run_slipwalk(in.args());
  if (r.exit_code == 0) {
    const nlohmann::json j = nlohmann::json::parse(read_text(in.dir / "params.json"));
    EXPECT_EQ(j["command"], "calibrate");
    EXPECT_TRUE(j.contains("provenance"));
  } else {
    // The stages are stubs, or the calibration of random readings fails: either way not exit 2,
    // and nothing written.
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(in.dir / "params.json"));
  }
}

TEST(CliCalibrate, BadColumnsAreRefusedAtTheirHeader) {
  const Inputs in;
  const std::string h = read_text(in.dir / "h.csv");
  const std::string file = (in.dir / "h.csv").string();
  // A leg of the geometry without its columns (the header cut before R1's).
  write_text(in.dir / "h.csv", h.substr(0, h.find(",phi_R1")) + h.substr(h.find('\n')));
  expect_refused(in, {}, file + ":1: no column 'phi_R1' (leg R1 of the geometry)");
  // A duplicated column.
  write_text(in.dir / "h.csv", "fx_L1," + h);
  expect_refused(in, {}, file + ":1:");
}

TEST(CliCalibrate, OrientationsThatCannotPairAreRefusedAtTheirRows) {
  const Inputs in;
  const std::string file = (in.dir / "h.csv").string();
  // An unknown orientation.
  std::string h = read_text(in.dir / "h.csv");
  const std::size_t plus_x = h.find("\n+x");
  ASSERT_NE(plus_x, std::string::npos) << "the fixture has a +x record";
  h = h.substr(0, plus_x + 1) + "+q" + h.substr(plus_x + 3);
  write_text(in.dir / "h.csv", h);
  expect_refused(in, {}, file + ":2:1: orientation: '+q'");
  // An orientation without its opposite (+x without −x), at its first row.
  write_text(in.dir / "h.csv",
             hanging_text({record(cal::BodyAxis::plus_x), record(cal::BodyAxis::plus_z),
                           record(cal::BodyAxis::minus_z)}));
  expect_refused(in, {}, file + ":2: orientation +x has no -x record");
  // Records that do not pair: −x's shaft angles off by a tenth of a turn at its sample 5.
  cal::HangingRecord shifted = record(cal::BodyAxis::minus_x);
  shifted.phi(5, 0) += 0.1;
  write_text(in.dir / "h.csv",
             hanging_text({record(cal::BodyAxis::plus_x), shifted, record(cal::BodyAxis::plus_z),
                           record(cal::BodyAxis::minus_z)}));
  expect_refused(in, {}, file + ":27: shaft angle");
  // The same orientation in two files: the second is named.
  write_text(in.dir / "h2.csv", hanging_text({record(cal::BodyAxis::plus_z)}));
  write_text(in.dir / "h.csv",
             hanging_text({record(cal::BodyAxis::plus_x), record(cal::BodyAxis::minus_x),
                           record(cal::BodyAxis::plus_z), record(cal::BodyAxis::minus_z)}));
  std::vector<std::string> a = in.args();
  a.insert(a.begin() + 5, (in.dir / "h2.csv").string());
  const CommandResult r = run_slipwalk(a);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find((in.dir / "h2.csv").string() + ":2: orientation +z is given twice"),
            std::string::npos)
      << r.err;
}

TEST(CliCalibrate, TooFewPosesOrABadQuaternionAreRefused) {
  const Inputs in;
  const std::string file = (in.dir / "p.csv").string();
  // Two poses: the full model of two transducers (12 DOF) needs three.
  write_text(in.dir / "p.csv", poses_text(2));
  expect_refused(in, {}, file + ":1: 2 poses; the full model of 2 transducers needs at least 3");
  // Three poses fit the full model alone, but not five folds of it.
  write_text(in.dir / "p.csv", poses_text(3));
  expect_refused(in, {}, "--folds");
  // A quaternion off unit length, at its row's first column.
  std::string p = poses_text(10);
  const std::size_t line4 = p.find('\n', p.find('\n', p.find('\n') + 1) + 1) + 1;
  p.replace(line4, p.find(',', line4) - line4, "0.5");
  write_text(in.dir / "p.csv", p);
  expect_refused(in, {}, file + ":4:1: the attitude quaternion");
}

TEST(CliCalibrate, EachModelsPoseCountIsItsDofOverSixPlusOne) {
  const Inputs in;
  for (const cal::MountingModel m : cal::kMountingModels) {
    const int dof = cal::model_dof(m, 2);
    const std::string label{cal::model_label(m)};
    const Eigen::Index needed = dof / 6 + 1;
    if (needed > 1) {
      write_text(in.dir / "p.csv", poses_text(needed - 1));
      expect_refused(in, {"--model", label},
                     (in.dir / "p.csv").string() + ":1: " + std::to_string(needed - 1) + " poses");
    }
    write_text(in.dir / "p.csv", poses_text(needed));
    const CommandResult r = run_slipwalk(in.args({"--model", label}));
    EXPECT_NE(r.exit_code, 2) << label << ": " << r.err;
  }
}

TEST(CliCalibrate, BadOptionsAndFilesAreRefusedNamingThem) {
  const Inputs in;
  expect_refused(in, {"--harmonics", "17"}, "--harmonics");
  expect_refused(in, {"--folds", "1"}, "--folds");
  const CommandResult model = run_slipwalk(in.args({"--model", "everything"}));
  EXPECT_EQ(model.exit_code, 2);
  EXPECT_NE(model.err.find("--model"), std::string::npos) << model.err;
  // A missing input; the output on an input.
  std::vector<std::string> a = in.args();
  a[2] = (in.dir / "missing.toml").string();
  const CommandResult missing = run_slipwalk(a);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("missing.toml"), std::string::npos) << missing.err;
  a = in.args();
  a[8] = (in.dir / "p.csv").string();
  const CommandResult onto = run_slipwalk(a);
  EXPECT_EQ(onto.exit_code, 2);
  EXPECT_NE(onto.err.find("--out"), std::string::npos) << onto.err;
  // A required option missing; an option of calibrate given to synth.
  const CommandResult bare = run_slipwalk({"calibrate", "--out", "x.json"});
  EXPECT_EQ(bare.exit_code, 2);
  EXPECT_NE(bare.err.find("--geometry: is required"), std::string::npos) << bare.err;
  const CommandResult mixed =
      run_slipwalk({"calibrate", "--model", "full", "synth", "--out", (in.dir / "s").string()});
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_NE(mixed.err.find("--model"), std::string::npos) << mixed.err;
  EXPECT_FALSE(std::filesystem::exists(in.dir / "s"));
}

TEST(CliCalibrateSynth, RefusesAFolderWithAnEarlierSetUnlessForced) {
  const ScratchDir dir;
  write_text(dir / "poses.csv", "kept\n");
  const CommandResult r = run_slipwalk({"calibrate", "synth", "--out", dir.path().string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--out: " + dir.path().string() + " already holds poses.csv; --force"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(read_text(dir / "poses.csv"), "kept\n");
  EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"poses.csv"});

  const CommandResult forced =
      run_slipwalk({"calibrate", "synth", "--out", dir.path().string(), "--force", "--poses", "20",
                    "--samples-per-cycle", "16", "--cycles", "1"});
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_EQ(files_under(dir.path()),
            (std::vector<std::string>{"geometry.toml", "hanging.csv", "poses.csv", "truth.json"}));
}

TEST(CliCalibrateSynth, ABadOptionIsRefusedNamingItAndWritesNothing) {
  const ScratchDir dir;
  const CommandResult r =
      run_slipwalk({"calibrate", "synth", "--out", (dir / "s").string(), "--poses", "800"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("slipwalk: error: --poses"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "s"));
}

TEST(CliCalibrateSynth, ItsFilesCalibrateToTheTruthsWeights) {
  const ScratchDir dir;
  const std::filesystem::path s = dir / "synth";
  const CommandResult made =
      run_slipwalk({"calibrate", "synth", "--out", s.string(), "--seed", "3", "--poses", "80",
                    "--samples-per-cycle", "100", "--cycles", "3"});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const nlohmann::json truth = nlohmann::json::parse(read_text(s / "truth.json"));
  EXPECT_EQ(truth["command"], "calibrate synth");
  EXPECT_TRUE(truth.contains("provenance"));

  // The files read back as the library wrote them: the geometry's legs, four records, 80 poses.
  const cal::Geometry g = cal::read_geometry(s / "geometry.toml");
  EXPECT_EQ(cal::read_hanging(s / "hanging.csv", g).size(), 4U);
  EXPECT_EQ(cal::read_poses(s / "poses.csv", g).poses(), 80);

  // The weights come from the hanging stage; the one-translation model keeps the standing stage
  // quick (the selection's fits are the standing stage's tests).
  const CommandResult r =
      run_slipwalk({"calibrate", "--geometry", (s / "geometry.toml").string(), "--hanging",
                    (s / "hanging.csv").string(), "--poses", (s / "poses.csv").string(), "--out",
                    (dir / "params.json").string(), "--model", "com_only"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("slipwalk calibrate: 6 transducers, 4 hanging records, 80 poses"),
            std::string::npos)
      << r.out;
  const nlohmann::json params = nlohmann::json::parse(read_text(dir / "params.json"));
  ASSERT_EQ(params["legs"].size(), truth["legs"].size());
  for (std::size_t k = 0; k < params["legs"].size(); ++k) {
    EXPECT_EQ(params["legs"][k]["leg"], truth["legs"][k]["leg"]);
    EXPECT_NEAR(params["legs"][k]["weight"].get<double>(), truth["legs"][k]["weight"].get<double>(),
                0.1)
        << params["legs"][k]["leg"];
  }
  EXPECT_TRUE(params.contains("provenance"));
}

}  // namespace
}  // namespace slipwalk::testing
