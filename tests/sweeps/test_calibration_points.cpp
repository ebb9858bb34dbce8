// The calibration kinds (sweeps/points/calibration.cpp): every kind is registered with the columns
// the report reads; their checks refuse bad parameters at the value's file:line:col; the cache
// computes a robot and its calibration once per key however many threads ask. End to end on a
// small synthetic robot, the rows are the calibration's own numbers (read back from the cache and
// recomputed through the library), the accuracy kind's own calibration agrees with the cached one,
// and Table 4.2's rows select exactly one model.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "calibration/hanging.hpp"
#include "calibration/standing.hpp"
#include "calibration/wrench.hpp"
#include "core/error.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/calibration.hpp"

namespace slipwalk::sweeps {
namespace {

namespace cal = calibration;

double num(const PointKind& f, const Cells& row, const std::string& name) {
  const Cell& c = row.at(test_support::column(f, name));
  if (const auto* d = std::get_if<double>(&c)) {
    return *d;
  }
  return static_cast<double>(std::get<long long>(c));
}

std::string text(const PointKind& f, const Cells& row, const std::string& name) {
  return std::get<std::string>(row.at(test_support::column(f, name)));
}

/// The small robot of the end-to-end tests (the study's quick robot).
constexpr const char* kSmall = "poses = 60\nsamples_per_cycle = 90\ncycles = 2\n";

points::SynthKey small_key(double noise_scale = 1.0) {
  points::SynthKey k;
  k.noise_scale = noise_scale;
  k.poses = 60;
  k.samples_per_cycle = 90;
  k.cycles = 2;
  return k;
}

PointResult run(const std::string& kind, const std::string& params) {
  const PointKind& f = test_support::point_kind(kind);
  const std::vector<Point> pts = test_support::points_of(kind, "[params]\n" + params);
  EXPECT_EQ(pts.size(), 1U);
  f.check(pts.at(0));
  PointResult r = f.run(pts.at(0));
  EXPECT_FALSE(r.failed) << r.message;
  return r;
}

TEST(CalibrationPoints, EveryKindIsRegisteredWithTheColumnsTheReportReads) {
  const std::map<std::string, std::vector<std::string>> wanted = {
      {"calib_parameters", {"leg", "parameter", "estimate", "se", "truth", "error", "z"}},
      {"calib_com",
       {"leg", "axis", "phase", "median", "q25", "q75", "q025", "q975", "fit", "truth"}},
      {"calib_hanging_residuals",
       {"leg", "orientation", "component", "model", "sample", "residual"}},
      {"calib_pose_residuals", {"pose", "method", "fx", "fy", "fz", "tx", "ty", "tz"}},
      {"calib_models", {"model", "dof", "rss", "cv_mse", "bic", "selected"}},
      {"calib_starts",
       {"start", "solver", "cost", "iterations", "converged", "seconds", "rotation_error_deg",
        "displacement_error_mm"}},
      {"calib_accuracy",
       {"noise_scale", "poses", "seed", "weight_err_max", "offset_force_err_max",
        "offset_torque_err_max", "com_err_rms", "rotation_err_max_deg", "displacement_err_max_mm",
        "z_abs_max", "z_rms", "within_3se", "seconds_hanging", "seconds_standing", "rss"}},
  };
  for (const auto& [kind, columns] : wanted) {
    const PointKind& f = test_support::point_kind(kind);
    for (const std::string& c : columns) {
      EXPECT_NO_THROW((void)test_support::column(f, c)) << kind << " lacks " << c;
    }
    // Exactly the timing columns are flagged as such (written as 0 under --no-timing).
    for (const ColumnInfo& c : f.columns) {
      const bool is_time = c.name == "seconds" || c.name.rfind("seconds_", 0) == 0;
      EXPECT_EQ(c.timing, is_time) << kind << "." << c.name;
    }
  }
  EXPECT_EQ(test_support::point_kind("calib_starts").timed, Timed::kYes);
  EXPECT_EQ(test_support::point_kind("calib_accuracy").timed, Timed::kYes);
  EXPECT_EQ(test_support::point_kind("calib_parameters").timed, Timed::kNo);
}

TEST(CalibrationPoints, ChecksRefuseBadParametersAtTheValue) {
  test_support::expect_refused_at_last_line("calib_parameters", "poses = 5\n");
  test_support::expect_refused_at_last_line("calib_parameters", "poses = 730\n");
  test_support::expect_refused_at_last_line("calib_parameters", "seed = 0.5\n");
  test_support::expect_refused_at_last_line("calib_parameters", "noise_scale = -1\n");
  test_support::expect_refused_at_last_line("calib_parameters", "noise_scale = \"loud\"\n");
  test_support::expect_refused_at_last_line("calib_parameters", "cycles = 0\n");
  test_support::expect_refused_at_last_line("calib_parameters",
                                            "cycles = 100\nsamples_per_cycle = 9000\n");
  test_support::expect_refused_at_last_line("calib_parameters",
                                            "cycles = 1\nsamples_per_cycle = 8\n");
  test_support::expect_refused_at_last_line("calib_parameters",
                                            "bins = 36\n");  // another kind's key
  test_support::expect_refused_at_last_line("calib_com", "bins = 0\n");
  test_support::expect_refused_at_last_line("calib_hanging_residuals", "stride = 0\n");
  test_support::expect_refused_at_last_line("calib_models", "folds = 1\n");
  test_support::expect_refused_at_last_line("calib_models", "poses = 10\nfolds = 3\n");
  test_support::expect_refused_at_last_line("calib_models", "poses = 10\nfolds = 11\n");
  test_support::expect_refused_at_last_line("calib_starts", "solver = \"newton\"\n");
  test_support::expect_refused_at_last_line("calib_starts", "starts = 0\n");
  test_support::expect_refused_at_last_line("calib_starts", "max_iterations = 0\n");
  test_support::expect_refused_at_last_line("calib_starts", "max_angle_deg = 91\n");
  test_support::expect_refused_at_last_line("calib_starts", "max_displacement = -0.1\n");
  test_support::expect_refused_at_last_line("calib_accuracy", "stride = 10\n");
}

TEST(CalibrationPoints, TheCacheComputesARobotAndItsCalibrationOnceForConcurrentRequests) {
  points::clear_calibration_cache();
  const points::SynthKey key = small_key();
  constexpr int kThreads = 8;
  std::vector<std::shared_ptr<const cal::Calibration>> got(kThreads);
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back(
        [&, i] { got[static_cast<std::size_t>(i)] = points::cached_calibration(key); });
  }
  for (std::thread& t : threads) {
    t.join();
  }
  // One robot and one calibration; every thread saw the same one.
  EXPECT_EQ(points::calibration_cache_computations(), 2U);
  ASSERT_NE(got.front(), nullptr);
  for (const auto& c : got) {
    EXPECT_EQ(c, got.front());
  }
  // Later requests of the same key compute nothing; another key computes its own.
  (void)points::cached_robot(key);
  EXPECT_EQ(points::calibration_cache_computations(), 2U);
  (void)points::cached_robot(small_key(0.5));
  EXPECT_EQ(points::calibration_cache_computations(), 3U);
}

TEST(CalibrationPoints, ParameterRowsAreTheCalibrationsOwnNumbersAgainstTheTruth) {
  const auto robot = points::cached_robot(small_key());
  const auto c = points::cached_calibration(small_key());
  const PointKind& f = test_support::point_kind("calib_parameters");
  const PointResult r = run("calib_parameters", kSmall);
  const int legs = c->geometry.size();
  ASSERT_EQ(r.rows.size(), static_cast<std::size_t>(13 * legs));
  for (const Cells& row : r.rows) {
    const std::string leg = text(f, row, "leg");
    const auto k =
        static_cast<std::size_t>(std::find(c->geometry.legs.begin(), c->geometry.legs.end(), leg) -
                                 c->geometry.legs.begin());
    ASSERT_LT(k, c->geometry.legs.size()) << leg;
    const std::string p = text(f, row, "parameter");
    double estimate = 0.0;
    double truth = 0.0;
    if (p == "weight") {
      estimate = c->hanging.legs[k].weight;
      truth = robot->truth.weight[k];
    } else if (p == "offset_fz") {
      estimate = c->hanging.legs[k].offset(2);
      truth = robot->truth.offset[k](2);
    } else if (p == "displacement_y") {
      estimate = c->mounting.displacement[k](1);
      truth = robot->truth.displacement(static_cast<int>(k))(1);
    } else if (p == "rotation_x") {
      estimate = cal::rotation_vector(c->mounting.rotation[k])(0);
      truth = cal::rotation_vector(robot->truth.mounting_rotation[k])(0);
    } else {
      continue;
    }
    EXPECT_EQ(num(f, row, "estimate"), estimate) << leg << " " << p;
    EXPECT_EQ(num(f, row, "truth"), truth) << leg << " " << p;
    EXPECT_DOUBLE_EQ(num(f, row, "error"), estimate - truth);
    const double se = num(f, row, "se");
    if (se > 0.0) {
      EXPECT_DOUBLE_EQ(num(f, row, "z"), (estimate - truth) / se);
    }
  }
}

TEST(CalibrationPoints, ComRowsBinTheSamplesAndCarryTheFitAndTheTruth) {
  const auto robot = points::cached_robot(small_key());
  const auto c = points::cached_calibration(small_key());
  const PointKind& f = test_support::point_kind("calib_com");
  const PointResult r = run("calib_com", std::string(kSmall) + "bins = 6\n");
  const int legs = c->geometry.size();
  ASSERT_EQ(r.rows.size(), static_cast<std::size_t>(legs * 6 * 3));
  double samples = 0.0;
  for (const Cells& row : r.rows) {
    const double phase = num(f, row, "phase");
    const std::string leg = text(f, row, "leg");
    const int k =
        static_cast<int>(std::find(c->geometry.legs.begin(), c->geometry.legs.end(), leg) -
                         c->geometry.legs.begin());
    const Eigen::Index a = text(f, row, "axis") == "x" ? 0 : text(f, row, "axis") == "y" ? 1 : 2;
    EXPECT_EQ(num(f, row, "fit"), c->hanging.legs[static_cast<std::size_t>(k)].com(phase)(a));
    EXPECT_EQ(num(f, row, "truth"), robot->truth.leg_com(k, phase)(a));
    EXPECT_LE(num(f, row, "q025"), num(f, row, "q25"));
    EXPECT_LE(num(f, row, "q25"), num(f, row, "median"));
    EXPECT_LE(num(f, row, "median"), num(f, row, "q75"));
    EXPECT_LE(num(f, row, "q75"), num(f, row, "q975"));
    samples += num(f, row, "samples");
  }
  // Every sample lands in one bin, once per axis.
  double total = 0.0;
  for (const cal::LegEstimate& h : c->hanging.legs) {
    total += static_cast<double>(h.com_phi.size());
  }
  EXPECT_EQ(samples, 3.0 * total);
}

TEST(CalibrationPoints, ResidualRowsAreReadingsLessTheModelsPrediction) {
  const auto robot = points::cached_robot(small_key());
  const auto c = points::cached_calibration(small_key());
  const PointKind& f = test_support::point_kind("calib_hanging_residuals");
  const PointResult r = run("calib_hanging_residuals", std::string(kSmall) + "stride = 7\n");
  const Eigen::Index n = robot->hanging.front().samples();
  const auto per_record = static_cast<std::size_t>((n + 6) / 7);
  ASSERT_EQ(r.rows.size(), robot->hanging.size() * 2 * 36 * per_record);
  // The exact model's rows of the first record against predict_hanging directly.
  const cal::HangingRecord& record = robot->hanging.front();
  const Eigen::MatrixXd residual =
      record.wrench - cal::predict_hanging(c->geometry, c->hanging, record);
  int checked = 0;
  for (const Cells& row : r.rows) {
    if (text(f, row, "model") != "exact" ||
        text(f, row, "orientation") != std::string(cal::axis_label(record.down)) ||
        text(f, row, "leg") != c->geometry.legs[1] || text(f, row, "component") != "tz") {
      continue;
    }
    const auto i = static_cast<Eigen::Index>(num(f, row, "sample"));
    EXPECT_EQ(num(f, row, "residual"), residual(i, 6 + 5));
    EXPECT_EQ(num(f, row, "phi"), record.phi(i, 1));
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(per_record));

  // Pose residuals: the full model's rows are balance_residuals under the cached estimate.
  const PointKind& g = test_support::point_kind("calib_pose_residuals");
  const PointResult poses = run("calib_pose_residuals", kSmall);
  ASSERT_EQ(poses.rows.size(), static_cast<std::size_t>(4 * 60));
  const Eigen::MatrixXd e =
      cal::balance_residuals(c->geometry, robot->poses, c->hanging, c->mounting);
  for (const Cells& row : poses.rows) {
    if (text(g, row, "method") == "full") {
      const auto p = static_cast<Eigen::Index>(num(g, row, "pose"));
      EXPECT_EQ(num(g, row, "fx"), e(p, 0));
      EXPECT_EQ(num(g, row, "tz"), e(p, 5));
    }
  }
}

TEST(CalibrationPoints, TableFourTwoSelectsTheSmallestBicAndTheAccuracyRowAgreesWithTheParameters) {
  const PointKind& f = test_support::point_kind("calib_models");
  const PointResult models = run("calib_models", kSmall);
  ASSERT_EQ(models.rows.size(), 4U);
  double best = std::numeric_limits<double>::infinity();
  for (const Cells& row : models.rows) {
    best = std::min(best, num(f, row, "bic"));
  }
  int selected = 0;
  for (const Cells& row : models.rows) {
    if (num(f, row, "selected") == 1.0) {
      ++selected;
      EXPECT_EQ(num(f, row, "bic"), best);
    }
    const double rss = num(f, row, "rss");
    EXPECT_NEAR(num(f, row, "bic"),
                60.0 * std::log(rss / 60.0) + num(f, row, "dof") * std::log(60.0),
                1e-9 * (1.0 + std::abs(num(f, row, "bic"))));
  }
  EXPECT_EQ(selected, 1);

  // calib_accuracy calibrates on its own (not the cache); the calibration is deterministic, so
  // its largest weight error is the largest of calib_parameters' weight errors.
  const PointKind& a = test_support::point_kind("calib_accuracy");
  const PointResult acc = run("calib_accuracy", kSmall);
  ASSERT_EQ(acc.rows.size(), 1U);
  const PointKind& p = test_support::point_kind("calib_parameters");
  const PointResult params = run("calib_parameters", kSmall);
  double weight = 0.0;
  int within = 0;
  int with_se = 0;
  for (const Cells& row : params.rows) {
    if (text(p, row, "parameter") == "weight") {
      weight = std::max(weight, std::abs(num(p, row, "error")));
    }
    if (num(p, row, "se") > 0.0) {
      ++with_se;
      within += std::abs(num(p, row, "z")) <= 3.0 ? 1 : 0;
    }
  }
  EXPECT_EQ(num(a, acc.rows[0], "weight_err_max"), weight);
  EXPECT_DOUBLE_EQ(num(a, acc.rows[0], "within_3se"), static_cast<double>(within) / with_se);
}

TEST(CalibrationPoints, NoiselessDataGiveTheTruthBack) {
  const PointKind& a = test_support::point_kind("calib_accuracy");
  const PointResult acc = run("calib_accuracy", std::string(kSmall) + "noise_scale = 0\n");
  ASSERT_EQ(acc.rows.size(), 1U);
  const Cells& row = acc.rows[0];
  // Far below the noisy robot's errors (0.003 N, 0.02 N, 3°, 50 mm on this robot); not 1e-9:
  // the RTS smoother's lag bias in the CoM (hanging.hpp) reaches d, the offsets and the weights.
  EXPECT_LT(num(a, row, "weight_err_max"), 1e-4);
  EXPECT_LT(num(a, row, "offset_force_err_max"), 1e-3);
  EXPECT_LT(num(a, row, "rotation_err_max_deg"), 0.01);
  EXPECT_LT(num(a, row, "displacement_err_max_mm"), 0.01);
}

}  // namespace
}  // namespace slipwalk::sweeps
