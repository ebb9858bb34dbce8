// The residual kinds (sweeps/points/residual.cpp) against known truth: their checks refuse bad
// parameters at the value's file:line:col; the trial cache computes a trial once per key however
// many threads ask and hands out the one object; on synthetic trials made from the template plus
// a known B (a trial source put in for the test), the fit recovers B and (A(q) + B) q̇ is the
// measured velocity; residual_training's draws are seeded, reproducible and never take a
// validation trial. With MuJoCo, one tiny end-to-end point: least squares never makes the training
// error worse than the template's, and the transfer rows of a point sum to its errors row.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "core/se2.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"
#include "robots/multipod.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/residual.hpp"

namespace slipwalk::sweeps {
namespace {

using points::MultipodTrialKey;

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

std::string text(const PointKind& f, const Cells& row, const std::string& name) {
  return std::get<std::string>(row.at(test_support::column(f, name)));
}

PointResult run(const std::string& kind, const std::string& params) {
  const PointKind& f = test_support::point_kind(kind);
  const std::vector<Point> pts = test_support::points_of(kind, "[params]\n" + params);
  EXPECT_EQ(pts.size(), 1U);
  f.check(pts.at(0));
  return f.run(pts.at(0));
}

TEST(ResidualPoints, ChecksRefuseBadParametersAtTheValue) {
  test_support::expect_refused_at_last_line("multipod_trial", "cycles = 21\n");
  test_support::expect_refused_at_last_line("multipod_trial", "dphi_pi = 2.5\n");
  test_support::expect_refused_at_last_line("multipod_trial", "frequency = 0.0\n");
  test_support::expect_refused_at_last_line("multipod_trial", "skip_cycles = 8\n");
  test_support::expect_refused_at_last_line("multipod_trial", "asymmetry = 2.5\n");
  test_support::expect_refused_at_last_line("multipod_trial", "seed = 0.5\n");
  test_support::expect_refused_at_last_line("multipod_trial", "sample_rate = 1001\n");
  test_support::expect_refused_at_last_line("multipod_trial", "timestep = 0.01\n");
  test_support::expect_refused_at_last_line("multipod_trial", "dphi = 1.0\n");
  // A trial of 20 cycles at 0.05 Hz with a 10 µs step is 4e7 MuJoCo steps: over the bound.
  test_support::expect_refused_at_last_line(
      "multipod_trial", "cycles = 20\nfrequency = 0.05\nsample_rate = 10\ntimestep = 1e-5\n");
  test_support::expect_refused_at_last_line("residual_transfer", "train_dphi_pi = \"0.65 x\"\n");
  test_support::expect_refused_at_last_line("residual_transfer", "train_dphi_pi = \"0.65 0.65\"\n");
  test_support::expect_refused_at_last_line("residual_transfer", "train_dphi_pi = \"\"\n");
  test_support::expect_refused_at_last_line("residual_transfer", "train_dphi_pi = 0.65\n");
  test_support::expect_refused_at_last_line("residual_transfer", "estimator = \"lasso\"\n");
  test_support::expect_refused_at_last_line("residual_transfer",
                                            "train_dphi_pi = \"1.0\"\nestimator = \"ridge\"\n");
  test_support::expect_refused_at_last_line("residual_errors", "test_frequency = 50\n");
  test_support::expect_refused_at_last_line("residual_errors", "train_frequency = 0.01\n");
  test_support::expect_refused_at_last_line("residual_training", "draws = 101\n");
  test_support::expect_refused_at_last_line("residual_training",
                                            "train_trials = 21\n");  // pool: 26 − 6
  test_support::expect_refused_at_last_line("residual_training", "validate_dphi_pi = \"3.0\"\n");
  test_support::expect_refused_at_last_line("residual_training", "train_trials = 0\n");
}

// --- the cache ----------------------------------------------------------------------------------

/// A small trial whose x is the key's Δφ/π (so a test sees which key made it).
residual::MotionTrial stub_trial(const MultipodTrialKey& key) {
  residual::MotionTrial t;
  t.label = points::trial_label(key);
  t.t = Eigen::VectorXd::LinSpaced(5, 0.0, 0.04);
  t.pose = Eigen::MatrixX3d::Zero(5, 3);
  t.pose.col(0).setConstant(key.dphi_pi);
  t.joints = Eigen::MatrixXd::Zero(5, 12);
  return t;
}

/// Puts a source in for one test and the default back after it.
class SourceGuard {
 public:
  explicit SourceGuard(points::TrialSource source)
      : previous_(points::set_trial_source(std::move(source))) {}
  SourceGuard(const SourceGuard&) = delete;
  SourceGuard& operator=(const SourceGuard&) = delete;
  ~SourceGuard() { points::set_trial_source(previous_); }

 private:
  points::TrialSource previous_;
};

TEST(ResidualPoints, TheCacheComputesATrialOnceForConcurrentRequestsAndSharesIt) {
  std::atomic<int> calls{0};
  const SourceGuard guard([&](const MultipodTrialKey& key) {
    ++calls;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // others arrive meanwhile
    return stub_trial(key);
  });
  MultipodTrialKey key;
  key.dphi_pi = 0.52;
  std::vector<std::shared_ptr<const residual::MotionTrial>> got(8);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i) {
    threads.emplace_back([&, i] { got[i] = points::cached_trial(key); });
  }
  for (std::thread& t : threads) {
    t.join();
  }
  EXPECT_EQ(calls.load(), 1);
  for (const auto& p : got) {
    EXPECT_EQ(p.get(), got.front().get());
  }
  // The grid's 0.2 + 5 · 0.064 is the same trial as the written 0.52.
  MultipodTrialKey from_grid = key;
  from_grid.dphi_pi = linspace(0.2, 1.8, 26)[5];
  EXPECT_EQ(points::cached_trial(from_grid).get(), got.front().get());
  EXPECT_EQ(calls.load(), 1);
  // Any other parameter is another trial.
  MultipodTrialKey other = key;
  other.seed = 2;
  EXPECT_NE(points::cached_trial(other).get(), got.front().get());
  EXPECT_EQ(calls.load(), 2);
}

TEST(ResidualPoints, AFailedTrialFailsEveryPointThatNeedsItWithItsMessageOnce) {
  std::atomic<int> calls{0};
  const SourceGuard guard([&](const MultipodTrialKey&) -> residual::MotionTrial {
    ++calls;
    throw core::ComputationError("the robot flew away");
  });
  const std::string params = "frequency = 2.4\ncycles = 2\ndphi_pi = 0.9\n";
  for (int i = 0; i < 2; ++i) {
    const PointResult r = run("multipod_trial", params);
    EXPECT_TRUE(r.failed);
    EXPECT_NE(r.message.find("the robot flew away"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("dphi = 0.9 pi"), std::string::npos) << r.message;
  }
  const PointResult e = run("residual_errors",
                            "test_frequency = 2.4\ncycles = 2\n"
                            "train_dphi_pi = \"0.9\"\n");
  EXPECT_TRUE(e.failed);
  EXPECT_NE(e.message.find("the robot flew away"), std::string::npos) << e.message;
  EXPECT_EQ(calls.load(), 1);  // the failure is kept: Δφ = 0.9 is not tried again
}

// --- synthetic trials: the template plus a known B ----------------------------------------------

/// B (3 × 16), seeded, entries of a few cm/s per m/s of foot velocity.
Eigen::Matrix<double, 3, Eigen::Dynamic> known_b() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::Matrix<double, 3, Eigen::Dynamic> b(3, 16);
  for (Eigen::Index i = 0; i < b.size(); ++i) {
    b(i) = u(rng);
  }
  return b;
}

/// A trial whose measured velocity is exactly (A(q) + B) q̇ at every snapshot: the gait's joints
/// plus a small excitation of each joint at its own frequency (so the trials' q̇ span all 16
/// directions), then poses built so that the central SE(2) difference of residual::predict reads
/// back the wanted twist: g_{j+1} = g_{j−1} exp((t_{j+1} − t_{j−1}) w_j).
residual::MotionTrial synthetic_trial(const MultipodTrialKey& key) {
  const auto n =
      static_cast<Eigen::Index>(std::llround(key.cycles / key.frequency * key.sample_rate)) + 1;
  residual::MotionTrial trial;
  trial.label = points::trial_label(key);
  trial.t = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / key.sample_rate);
  trial.pose = Eigen::MatrixX3d::Zero(n, 3);
  trial.joints = Eigen::MatrixXd::Zero(n, 12);
  robots::UndulationGait gait;
  gait.legs = 8;
  gait.dphi = key.dphi_pi * std::numbers::pi;
  gait.frequency = key.frequency;
  robots::MultipodJoints q(3, 4);
  robots::MultipodJoints rates(3, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    robots::multipod_gait_joints(gait, trial.t(i), q, rates);
    for (Eigen::Index j = 0; j < 12; ++j) {
      const double w =
          2.0 * std::numbers::pi * key.frequency * (1.3 + 0.17 * static_cast<double>(j));
      trial.joints(i, j) =
          q(j % 3, j / 3) + 0.05 * std::sin(w * trial.t(i) + static_cast<double>(j) + key.dphi_pi);
    }
  }
  const residual::TemplatePrediction p0 = residual::predict(residual::multipod_template(8), trial);
  const Eigen::MatrixX3d w = residual::with_residual(p0, known_b());
  std::vector<core::Pose2> g(static_cast<std::size_t>(n));
  std::vector<double> theta(static_cast<std::size_t>(n), 0.0);
  g[1] = core::exp(w.row(0).transpose() * (trial.t(1) - trial.t(0)));
  theta[1] = g[1].theta;
  for (Eigen::Index j = 1; j + 1 < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const double dt = trial.t(j + 1) - trial.t(j - 1);
    g[k + 1] = core::compose(g[k - 1], core::exp(w.row(j - 1).transpose() * dt));
    theta[k + 1] = theta[k - 1] + dt * w(j - 1, 2);
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    trial.pose.row(i) << g[k].x, g[k].y, theta[k];
  }
  return trial;
}

const std::string kSynthetic = "test_frequency = 1.2\ncycles = 3\nskip_cycles = 1\n";

TEST(ResidualPoints, OnTheTemplatePlusAKnownBTheFitRecoversBAndItsVelocityIsTheMeasuredOne) {
  const SourceGuard guard(synthetic_trial);
  const PointKind& fe = test_support::point_kind("residual_errors");
  const PointResult e = run("residual_errors", kSynthetic);
  ASSERT_FALSE(e.failed) << e.message;
  ASSERT_EQ(e.rows.size(), 1U);
  const Cells& row = e.rows[0];
  EXPECT_EQ(num(fe, row, "rank"), 16.0);
  EXPECT_NEAR(num(fe, row, "b_norm"), known_b().norm(), 1e-6 * known_b().norm());
  EXPECT_EQ(text(fe, row, "train_dphi_pi"), "0.65 0.9 1.1 1.35");
  for (const char* c : {"x", "y", "w"}) {
    EXPECT_LT(num(fe, row, std::string("train_rmse_fit_") + c), 1e-9) << c;
    EXPECT_LT(num(fe, row, std::string("test_rmse_fit_") + c), 1e-9) << c;
    EXPECT_GT(num(fe, row, std::string("test_rmse_model_") + c), 1e-4) << c;
    EXPECT_NEAR(num(fe, row, std::string("test_mean_fit_") + c),
                num(fe, row, std::string("test_mean_true_") + c), 1e-9)
        << c;
  }
  // A row per snapshot after the first cycle.
  const PointKind& ft = test_support::point_kind("residual_transfer");
  const PointResult t = run("residual_transfer", kSynthetic);
  ASSERT_FALSE(t.failed) << t.message;
  MultipodTrialKey key;
  key.frequency = 1.2;
  key.cycles = 3.0;
  const residual::MotionTrial test_trial = synthetic_trial(key);
  const double first = 1.0 / 1.2;
  std::size_t expected = 0;
  for (Eigen::Index j = 1; j + 1 < test_trial.samples(); ++j) {
    expected += test_trial.t(j) >= first - 1e-9 ? 1 : 0;
  }
  EXPECT_EQ(t.rows.size(), expected);
  EXPECT_GE(num(ft, t.rows.front(), "t"), first - 1e-9);
  for (const Cells& r : t.rows) {
    for (const char* c : {"x", "y", "w"}) {
      EXPECT_NEAR(num(ft, r, std::string("v_fit_") + c), num(ft, r, std::string("v_true_") + c),
                  1e-9);
    }
  }
  // The ridge's cross-validated λ on exact data: the fit is as good.
  const PointResult ridge = run("residual_errors", kSynthetic + "estimator = \"ridge\"\n");
  ASSERT_FALSE(ridge.failed) << ridge.message;
  EXPECT_LT(num(fe, ridge.rows[0], "test_rmse_fit_y"), 1e-6);
}

TEST(ResidualPoints, TrialRowsAreTheTrialSampleForSampleAndReadBackAsATrialFile) {
  const SourceGuard guard(synthetic_trial);
  const PointKind& f = test_support::point_kind("multipod_trial");
  const PointResult r =
      run("multipod_trial", "frequency = 2.4\ncycles = 1\nskip_cycles = 0\ndphi_pi = 1.1\n");
  ASSERT_FALSE(r.failed) << r.message;
  MultipodTrialKey key;
  key.dphi_pi = 1.1;
  key.frequency = 2.4;
  key.cycles = 1.0;
  const residual::MotionTrial truth = synthetic_trial(key);
  ASSERT_EQ(r.rows.size(), static_cast<std::size_t>(truth.samples()));
  std::ostringstream csv;
  const std::vector<std::string> names = f.column_names();
  for (std::size_t c = 0; c < names.size(); ++c) {
    csv << (c ? "," : "") << names[c];
  }
  csv << "\n";
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    EXPECT_EQ(num(f, r.rows[i], "t"), truth.t(static_cast<Eigen::Index>(i)));
    EXPECT_EQ(num(f, r.rows[i], "yaw2_3"), truth.joints(static_cast<Eigen::Index>(i), 8));
    for (std::size_t c = 0; c < names.size(); ++c) {
      const Cell& cell = r.rows[i][c];
      csv << (c ? "," : "");
      if (const auto* d = std::get_if<double>(&cell)) {
        csv << core::format_double(*d);
      } else if (const auto* n = std::get_if<long long>(&cell)) {
        csv << *n;
      } else {
        csv << std::get<std::string>(cell);
      }
    }
    csv << "\n";
  }
  const std::vector<residual::MotionTrial> back = residual::parse_trials(csv.str(), "rows.csv");
  ASSERT_EQ(back.size(), 1U);
  EXPECT_EQ(back[0].pose, truth.pose);
  EXPECT_EQ(back[0].joints, truth.joints);
}

// --- residual_training's draws ------------------------------------------------------------------

TEST(ResidualPoints, TrainingDrawsAreSeededTheSameEverywhereAndEvenOverThePool) {
  const auto a = points::draw_subsets(1, 4, 20, 5);
  EXPECT_EQ(a, points::draw_subsets(1, 4, 20, 5));
  EXPECT_EQ(a[2], points::draw_subsets(1, 4, 20, 3)[2]);  // draw d whatever the count
  EXPECT_NE(a, points::draw_subsets(2, 4, 20, 5));
  for (const auto& s : a) {
    ASSERT_EQ(s.size(), 4U);
    EXPECT_TRUE(std::is_sorted(s.begin(), s.end()));
    EXPECT_EQ(std::set<int>(s.begin(), s.end()).size(), 4U);
    EXPECT_GE(s.front(), 0);
    EXPECT_LT(s.back(), 20);
  }
  // mt19937_64's output is fixed by the standard and the reduction is ours: these are the
  // subsets on every platform and library.
  EXPECT_EQ(a[0], (std::vector<int>{1, 3, 4, 17}));
  // Even over the pool: 4000 single draws of 20, each index 200 ± 5σ (σ ≈ 13.8).
  std::vector<int> count(20, 0);
  for (const auto& s : points::draw_subsets(3, 1, 20, 4000)) {
    ++count[static_cast<std::size_t>(s[0])];
  }
  for (int c : count) {
    EXPECT_NEAR(c, 200, 70);
  }
}

TEST(ResidualPoints, TrainingNeverDrawsAValidationTrialAndRepeatsItsDraws) {
  const SourceGuard guard(synthetic_trial);
  const PointKind& f = test_support::point_kind("residual_training");
  const std::string params =
      "frequency = 2.4\ncycles = 2\ntrain_trials = 3\ndraws = 6\nseed = 4\n"
      "validate_dphi_pi = \"0.2 0.52 1.8\"\n";
  const PointResult r = run("residual_training", params);
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_EQ(r.rows.size(), 6U);
  const std::vector<double> grid = points::thesis_dphi_grid();
  for (const Cells& row : r.rows) {
    std::istringstream drawn(text(f, row, "train_dphi_pi"));
    std::set<double> seen;
    double x = 0.0;
    while (drawn >> x) {
      EXPECT_NE(x, 0.2);
      EXPECT_NE(x, 0.52);
      EXPECT_NE(x, 1.8);
      EXPECT_NE(std::find(grid.begin(), grid.end(), x), grid.end()) << x;
      seen.insert(x);
    }
    EXPECT_EQ(seen.size(), 3U);
    EXPECT_EQ(num(f, row, "validation_rmse_model_y"), num(f, r.rows[0], "validation_rmse_model_y"));
  }
  const PointResult again = run("residual_training", params);
  EXPECT_EQ(test_support::first_value_difference(f, r, again), "");
}

// --- MuJoCo, end to end -------------------------------------------------------------------------

#ifdef SLIPWALK_HAVE_MUJOCO
TEST(ResidualPoints, OnMuJoCoTheFitNeverMakesTheTrainingErrorWorseAndItsRowsAddUp) {
  points::clear_trial_cache();
  const PointKind& f = test_support::point_kind("residual_errors");
  const PointResult r = run("residual_errors",
                            "test_frequency = 2.4\ncycles = 2\nsettle = 0.2\n"
                            "train_dphi_pi = \"0.9 1.1\"\n");
  ASSERT_FALSE(r.failed) << r.message;
  const Cells& row = r.rows.at(0);
  EXPECT_GT(num(f, row, "snapshots"), 100.0);
  for (const char* c : {"x", "y", "w"}) {
    const double model = num(f, row, std::string("train_rmse_model_") + c);
    const double fit = num(f, row, std::string("train_rmse_fit_") + c);
    EXPECT_TRUE(std::isfinite(model)) << c;
    EXPECT_LE(fit, model * (1.0 + 1e-9)) << c;  // B = 0 is one of the candidates
    EXPECT_TRUE(std::isfinite(num(f, row, std::string("test_rmse_fit_") + c))) << c;
  }
  // The same point's transfer rows give the test errors and means again, summed here.
  const PointKind& ft = test_support::point_kind("residual_transfer");
  const PointResult t = run("residual_transfer",
                            "test_frequency = 2.4\ncycles = 2\nsettle = 0.2\n"
                            "train_dphi_pi = \"0.9 1.1\"\n");
  ASSERT_FALSE(t.failed) << t.message;
  for (const char* c : {"x", "y", "w"}) {
    double sq_model = 0.0;
    double sq_fit = 0.0;
    double sum_true = 0.0;
    for (const Cells& snapshot : t.rows) {
      const double truth = num(ft, snapshot, std::string("v_true_") + c);
      sq_model += std::pow(num(ft, snapshot, std::string("v_model_") + c) - truth, 2);
      sq_fit += std::pow(num(ft, snapshot, std::string("v_fit_") + c) - truth, 2);
      sum_true += truth;
    }
    const auto n = static_cast<double>(t.rows.size());
    EXPECT_NEAR(std::sqrt(sq_model / n), num(f, row, std::string("test_rmse_model_") + c), 1e-12)
        << c;
    EXPECT_NEAR(std::sqrt(sq_fit / n), num(f, row, std::string("test_rmse_fit_") + c), 1e-12) << c;
    EXPECT_NEAR(sum_true / n, num(f, row, std::string("test_mean_true_") + c), 1e-12) << c;
  }
  // A trial's rows: a sample every 1/125 s from 0 to cycles / f = 2/2.4 s.
  const PointResult trial = run("multipod_trial",
                                "frequency = 2.4\ncycles = 2\nsettle = 0.2\n"
                                "dphi_pi = 0.9\n");
  ASSERT_FALSE(trial.failed) << trial.message;
  EXPECT_EQ(trial.rows.size(), static_cast<std::size_t>(std::floor(2.0 / 2.4 * 125.0)) + 1);
}
#else
TEST(ResidualPoints, WithoutMuJoCoThePointsFailAndSayWhy) {
  points::clear_trial_cache();
  const PointResult r = run("multipod_trial", "frequency = 2.4\ncycles = 1\n");
  EXPECT_TRUE(r.failed);
  EXPECT_NE(r.message.find("built without MuJoCo"), std::string::npos) << r.message;
}
#endif

}  // namespace
}  // namespace slipwalk::sweeps
