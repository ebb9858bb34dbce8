// slipwalk residual fit: on trials the template makes itself with a known B
// (residual/synthetic_trial.hpp) the command writes the B of a direct predict → fit call, bit for
// bit, as a residual file a scene's [residual] reads, with its sidecar and a summary; --ids,
// --skip and --estimator ridge select and fit as documented; every class of bad input exits 2
// naming the option or file:line[:col] and writes nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "residual/fit.hpp"
#include "residual/synthetic_trial.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"
#include "scene/effects.hpp"
#include "scene/scene.hpp"

namespace slipwalk::testing {
namespace {

using BMatrix = Eigen::Matrix<double, 3, Eigen::Dynamic>;

BMatrix known_b(int legs) {
  BMatrix B(3, 2 * legs);
  for (Eigen::Index i = 0; i < B.size(); ++i) {
    B.data()[i] = 0.01 * static_cast<double>((i * 7) % 11 - 5);
  }
  return B;
}

residual::MotionTrial synthetic(double dphi_pi, int legs = 8, long long samples = 102) {
  SyntheticOptions o;
  o.legs = legs;
  o.frequency = 1.25;
  o.dphi = dphi_pi * std::numbers::pi;
  o.samples = samples;
  o.substeps = 4;
  o.B = known_b(legs);
  return make_synthetic_trial(o).trial;
}

std::string trial_text(const residual::MotionTrial& t) {
  std::ostringstream out;
  residual::write_trial(out, t);
  return out.str();
}

/// Several trials in one file with an id column first (as a sweep's CSV of trials).
std::string multi_text(const std::vector<residual::MotionTrial>& trials,
                       const std::vector<std::string>& ids) {
  std::string text;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    std::istringstream in(trial_text(trials[i]));
    std::string line;
    std::getline(in, line);
    if (i == 0) {
      text.append("id,").append(line).append("\n");
    }
    while (std::getline(in, line)) {
      text.append(ids[i]).append(",").append(line).append("\n");
    }
  }
  return text;
}

/// The direct computation the command must reproduce.
residual::ResidualFit direct_fit(const std::vector<residual::MotionTrial>& trials) {
  const residual::TemplateRobot model = residual::multipod_template(trials.front().legs());
  std::vector<residual::ResidualTrial> data;
  for (const residual::MotionTrial& t : trials) {
    data.push_back(residual::residual_trial(residual::predict(model, t)));
  }
  return residual::fit_residual(data);
}

TEST(CliResidual, FitWritesTheBOfADirectFitAsAScenesResidualFileWithItsSidecar) {
  const ScratchDir dir;
  const std::vector<residual::MotionTrial> trials = {synthetic(0.65), synthetic(0.9),
                                                     synthetic(1.1), synthetic(1.35)};
  write_text(dir / "trials.csv", multi_text({trials[0], trials[1], trials[2]}, {"3", "5", "7"}));
  write_text(dir / "single.csv", trial_text(trials[3]));
  const auto r = run_slipwalk({"residual", "fit", "--robot", "multipod", "--trials",
                               (dir / "trials.csv").string(), (dir / "single.csv").string(),
                               "--out", (dir / "B.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // What the files hold, read back (round trip exact), fitted directly.
  std::vector<residual::MotionTrial> read = residual::read_trials(dir / "trials.csv");
  read.push_back(residual::read_trials(dir / "single.csv").front());
  const residual::ResidualFit fit = direct_fit(read);
  const std::string text = read_text(dir / "B.csv");
  const BMatrix B = scene::parse_residual(text, "B.csv", 8);
  EXPECT_EQ(B, fit.B);
  EXPECT_LT((B - known_b(8)).norm(), 0.2 * known_b(8).norm());  // near the truth (125 Hz)
  EXPECT_NE(text.find("# slipwalk residual fit: robot multipod (8 legs), estimator pinv"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("trials (4): " + (dir / "trials.csv").string() + ", id 3;"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("snapshots 400, rank 16 of 16"), std::string::npos) << text;
  EXPECT_NE(r.out.find("4 trials, 400 snapshots, 8 legs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("q̇ matrix: rank 16 of 16, condition"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rms residual after:"), std::string::npos) << r.out;

  // A scene of the same robot reads it as its [residual].
  write_text(dir / "s.toml",
             "[robot]\nname = \"multipod\"\nlegs = 8\n[gait]\nkind = \"undulation\"\n"
             "[run]\nduration = 0.1\ndt = 0.01\n[friction]\nlaw = \"viscous\"\n"
             "[residual]\nfile = \"B.csv\"\n");
  const scene::Scene scene = scene::read_scene(dir / "s.toml");
  ASSERT_TRUE(scene.residual.has_value());
  EXPECT_EQ(scene.residual->B, fit.B);

  const auto sidecar = nlohmann::json::parse(read_text(dir / "B.json"));
  EXPECT_EQ(sidecar["command"], "residual fit");
  EXPECT_EQ(sidecar["legs"], 8);
  EXPECT_EQ(sidecar["residual"], "B.csv");
  EXPECT_EQ(sidecar["snapshots"], 400);
  EXPECT_EQ(sidecar["rank"], 16);
  EXPECT_EQ(sidecar["condition"].get<double>(), fit.condition);
  EXPECT_EQ(sidecar["rms_after"][1].get<double>(), fit.rms_after(1));
  ASSERT_EQ(sidecar["trials"].size(), 4u);
  EXPECT_EQ(sidecar["trials"][1]["id"], "5");
  EXPECT_EQ(sidecar["trials"][3]["samples"], 102);
  EXPECT_TRUE(sidecar.contains("provenance"));
  EXPECT_EQ(files_under(dir.path()),
            (std::vector<std::string>{"B.csv", "B.json", "s.toml", "single.csv", "trials.csv"}));
}

TEST(CliResidual, IdsSkipAndRidgeSelectAndFitAsDocumented) {
  const ScratchDir dir;
  const std::vector<residual::MotionTrial> trials = {synthetic(0.65), synthetic(0.9),
                                                     synthetic(1.1), synthetic(1.35)};
  write_text(dir / "trials.csv", multi_text(trials, {"3", "5", "7", "9"}));
  const std::string file = (dir / "trials.csv").string();
  // --ids 3,9 --skip 0.196: two trials, each less its snapshots before t = 0.196 s (t_1 = 0.008 s
  // .. t_24 = 0.192 s: 24 dropped of 100).
  auto r = run_slipwalk({"residual", "fit", "--robot", "multipod", "--trials", file, "--out",
                         (dir / "B.csv").string(), "--ids", "3,9", "--skip", "0.196"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto sidecar = nlohmann::json::parse(read_text(dir / "B.json"));
  ASSERT_EQ(sidecar["trials"].size(), 2u);
  EXPECT_EQ(sidecar["trials"][0]["id"], "3");
  EXPECT_EQ(sidecar["trials"][1]["id"], "9");
  EXPECT_EQ(sidecar["trials"][0]["snapshots"], 76);
  EXPECT_EQ(sidecar["snapshots"], 152);

  // Ridge over an explicit grid: λ is one of the grid's, chosen by leave-one-trial-out.
  r = run_slipwalk({"residual", "fit", "--robot", "multipod", "--trials", file, "--out",
                    (dir / "R.csv").string(), "--estimator", "ridge", "--lambdas",
                    "0,1e-3,1e-1,10"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  sidecar = nlohmann::json::parse(read_text(dir / "R.json"));
  EXPECT_EQ(sidecar["estimator"], "ridge");
  EXPECT_EQ(sidecar["validation"]["lambdas"].size(), 4u);
  EXPECT_EQ(sidecar["lambda"], sidecar["validation"]["best"]);
  const BMatrix B = scene::parse_residual(read_text(dir / "R.csv"), "R.csv", 8);
  EXPECT_TRUE(B.allFinite());
  // The default grid: 0 and 13 multiples of σ_max².
  r = run_slipwalk({"residual", "fit", "--robot", "multipod", "--trials", file, "--out",
                    (dir / "D.csv").string(), "--estimator", "ridge"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(dir / "D.json"))["validation"]["lambdas"].size(), 14u);
}

TEST(CliResidual, EveryBadInputExitsTwoNamingThePlaceAndWritesNothing) {
  const ScratchDir dir;
  const std::string good = trial_text(synthetic(1.0));
  write_text(dir / "good.csv", good);
  write_text(dir / "two.csv", multi_text({synthetic(0.9), synthetic(1.1)}, {"1", "2"}));
  write_text(dir / "six.csv", "# six legs\n" + trial_text(synthetic(1.0, 6)));
  write_text(dir / "short.csv", trial_text(synthetic(1.0, 8, 12)));
  // A bad number in row 4 (line 5), column y; a time that goes back at line 6; no theta column.
  std::vector<std::string> lines;
  {
    std::istringstream in(good);
    for (std::string l; std::getline(in, l);) {
      lines.push_back(l);
    }
  }
  auto edited = [&](std::size_t line, const std::string& replacement) {
    std::string text;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      text.append(i + 1 == line ? replacement : lines[i]).append("\n");
    }
    return text;
  };
  write_text(dir / "number.csv", edited(5, "0.032,0,zero,0,0,0,0,0,0,0,0,0,0,0,0,0"));
  write_text(dir / "time.csv", edited(6, "0.01,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0"));
  write_text(dir / "columns.csv", edited(1,
                                         "t,x,y,angle,yaw1_1,roll_1,yaw2_1,yaw1_2,roll_2,yaw2_2,"
                                         "yaw1_3,roll_3,yaw2_3,yaw1_4,roll_4,yaw2_4"));
  const std::vector<std::string> inputs = files_under(dir.path());
  const std::string out = (dir / "B.csv").string();
  auto fails = [&](std::vector<std::string> args, const std::string& where) {
    args.insert(args.begin(), {"residual", "fit"});
    const auto r = run_slipwalk(args);
    EXPECT_EQ(r.exit_code, 2) << where << "\n" << r.err;
    EXPECT_NE(r.err.find("slipwalk: error: " + where), std::string::npos) << where << "\n" << r.err;
    EXPECT_EQ(files_under(dir.path()), inputs) << where;
  };
  const auto path = [&](const std::string& name) { return (dir / name).string(); };
  const std::vector<std::string> base = {"--robot", "multipod", "--out", out, "--trials"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  fails(with({path("number.csv")}), path("number.csv") + ":5:9: y: 'zero'");
  fails(with({path("time.csv")}), path("time.csv") + ":6:1: t must increase strictly");
  fails(with({path("columns.csv")}), path("columns.csv") + ":1: no column 'theta'");
  fails(with({path("missing.csv")}), path("missing.csv"));
  fails(with({path("good.csv"), path("six.csv")}),
        path("six.csv") + ":2: " + path("six.csv") + " is a Multipod of 6 legs");
  fails(with({path("short.csv")}), "--trials: 10 snapshots from 1 trial; B of 8 legs has 16");
  fails(with({path("good.csv"), "--estimator", "ridge"}), "--estimator: ridge");
  fails(with({path("good.csv"), "--lambdas", "1"}), "--lambdas");
  fails(with({path("two.csv"), "--estimator", "ridge", "--lambdas", "1,-1"}), "--lambdas");
  fails(with({path("two.csv"), "--ids", "1,4"}), "--ids: no trial has id 4");
  fails(with({path("good.csv"), "--ids", "1"}), "--ids: selects trials by id, but");
  fails(with({path("good.csv"), "--skip", "-1"}), "--skip");
  fails(with({path("good.csv"), "--skip", "5"}), "--skip: 5 s leaves no snapshot");
  fails(with({path("good.csv"), "--estimator", "lasso"}), "--estimator");
  fails({"--robot", "bigant", "--out", out, "--trials", path("good.csv")}, "--robot");
  fails({"--robot", "multipod", "--out", path("good.csv"), "--trials", path("good.csv")}, "--out");
  fails({"--robot", "multipod", "--out", path("B.json"), "--trials", path("good.csv")}, "--out");
}

}  // namespace
}  // namespace slipwalk::testing
