// The fit of the connection residual B (connection/residual_fit.hpp) against a known synthetic
// truth: data generated with a chosen B is fitted back to round-off, the fit does not depend on
// the order of the snapshots, a rank-deficient q̇ (a periodic gait spans few directions) gives
// the minimum-norm B that still predicts every snapshot, ridge regression tends to the
// pseudo-inverse as λ → 0 and its cross-validation prefers no shrinkage on noise-free data, and
// bad trials are refused by name.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "residual/fit.hpp"

namespace slipwalk::residual {
namespace {

constexpr int kLegs = 8;  // Multipod-like: 2K = 16 columns

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    m.data()[i] = n(rng);
  }
  return m;
}

/// Trials whose residual is exactly q̇ Bᵀ for the given B.
std::vector<ResidualTrial> trials_of(const Eigen::MatrixXd& b, const std::vector<int>& sizes,
                                     std::mt19937_64& rng) {
  std::vector<ResidualTrial> trials;
  for (int n : sizes) {
    ResidualTrial t;
    t.qdot = random_matrix(n, b.cols(), rng);
    t.residual = t.qdot * b.transpose();
    trials.push_back(std::move(t));
  }
  return trials;
}

TEST(ResidualFit, RecoversAKnownBToRoundOffFromDataGeneratedWithIt) {
  std::mt19937_64 rng(1);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  const ResidualFit fit = fit_residual(trials_of(truth, {40, 25, 60, 31}, rng));
  EXPECT_EQ(fit.rank, 2 * kLegs);
  EXPECT_EQ(fit.snapshots, 156);
  EXPECT_LT((fit.B - truth).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(fit.rms_after.maxCoeff(), 1e-12);
  EXPECT_GT(fit.rms_before.minCoeff(), 0.1);
  EXPECT_GE(fit.condition, 1.0);
  EXPECT_TRUE(std::isfinite(fit.condition));
}

TEST(ResidualFit, DoesNotDependOnTheOrderOfTheSnapshots) {
  std::mt19937_64 rng(2);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  std::vector<ResidualTrial> trials = trials_of(truth, {50, 50}, rng);
  for (ResidualTrial& t : trials) {  // noise, so the fit is a compromise and not exact
    t.residual += 0.1 * random_matrix(t.residual.rows(), 3, rng);
  }
  const ResidualFit forward = fit_residual(trials);
  // The same snapshots shuffled across one trial, and the trials in the other order.
  ResidualTrial all;
  all.qdot.resize(100, 2 * kLegs);
  all.residual.resize(100, 3);
  std::vector<int> order(100);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  for (int i = 0; i < 100; ++i) {
    const ResidualTrial& from =
        trials[static_cast<std::size_t>(order[static_cast<std::size_t>(i)] / 50)];
    all.qdot.row(i) = from.qdot.row(order[static_cast<std::size_t>(i)] % 50);
    all.residual.row(i) = from.residual.row(order[static_cast<std::size_t>(i)] % 50);
  }
  const ResidualFit shuffled = fit_residual({all});
  const ResidualFit swapped = fit_residual({trials[1], trials[0]});
  EXPECT_LT((forward.B - shuffled.B).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((forward.B - swapped.B).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ResidualFit, GivesTheMinimumNormBWhenTheGaitSpansFewDirections) {
  // q̇ = s(t) Pᵀ: every snapshot in the span of two directions (a gait of two oscillators), so
  // Q has rank 2 and B is determined only on that span. The pseudo-inverse's B predicts every
  // snapshot and is zero on the directions q̇ never takes (B N = 0 for N ⊥ span).
  std::mt19937_64 rng(3);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  const Eigen::MatrixXd basis = random_matrix(2 * kLegs, 2, rng);
  ResidualTrial t;
  const int n = 200;
  Eigen::MatrixXd s(n, 2);
  for (int i = 0; i < n; ++i) {
    const double phase = 2.0 * M_PI * i / 50.0;  // four whole cycles
    s(i, 0) = std::cos(phase);
    s(i, 1) = std::sin(phase);
  }
  t.qdot = s * basis.transpose();
  t.residual = t.qdot * truth.transpose();
  const ResidualFit fit = fit_residual({t});
  EXPECT_EQ(fit.rank, 2);
  EXPECT_LT(fit.rms_after.maxCoeff(), 1e-12);
  // Orthogonal complement of the span: B times any vector orthogonal to both basis columns is 0.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
  const Eigen::MatrixXd full_q =
      qr.householderQ() * Eigen::MatrixXd::Identity(2 * kLegs, 2 * kLegs);
  const Eigen::MatrixXd complement = full_q.rightCols(2 * kLegs - 2);
  EXPECT_LT((fit.B * complement).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(ResidualFit, RidgeTendsToThePseudoInverseAsLambdaVanishesAndShrinksBAsItGrows) {
  std::mt19937_64 rng(4);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  std::vector<ResidualTrial> trials = trials_of(truth, {80}, rng);
  trials[0].residual += 0.05 * random_matrix(80, 3, rng);
  const ResidualFit pinv = fit_residual(trials);
  const ResidualFit zero = fit_residual_ridge(trials, 0.0);
  EXPECT_LT((pinv.B - zero.B).cwiseAbs().maxCoeff(), 1e-11);
  double previous = zero.B.norm();
  for (double lambda : {1e-3, 1.0, 100.0, 1e4}) {
    const ResidualFit r = fit_residual_ridge(trials, lambda);
    EXPECT_LT(r.B.norm(), previous) << lambda;
    EXPECT_EQ(r.lambda, lambda);
    previous = r.B.norm();
  }
}

TEST(ResidualFit, CrossValidationKeepsTheSmallestLambdaOnNoiseFreeData) {
  std::mt19937_64 rng(5);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  const std::vector<ResidualTrial> trials = trials_of(truth, {40, 40, 40, 40}, rng);
  const RidgeValidation v = validate_ridge(trials, {0.0, 1e-2, 1.0, 100.0});
  EXPECT_EQ(v.best, 0.0);
  EXPECT_LT(v.error[0], 1e-12);
  for (std::size_t i = 1; i < v.error.size(); ++i) {
    EXPECT_GT(v.error[i], v.error[i - 1]);
  }
}

TEST(ResidualFit, CrossValidationShrinksWhenFewNoisySnapshotsFitManyColumns) {
  // 2K = 16 unknowns per component from trials of 12 noisy snapshots each: the unregularized fit
  // chases the noise, and some λ > 0 predicts held-out trials better.
  std::mt19937_64 rng(6);
  const Eigen::MatrixXd truth = 0.1 * random_matrix(3, 2 * kLegs, rng);
  std::vector<ResidualTrial> trials = trials_of(truth, {12, 12, 12, 12, 12}, rng);
  for (ResidualTrial& t : trials) {
    t.residual += random_matrix(t.residual.rows(), 3, rng);
  }
  const RidgeValidation v = validate_ridge(trials, {0.0, 1.0, 10.0, 100.0, 1000.0});
  EXPECT_GT(v.best, 0.0);
}

void expect_refused(const std::vector<ResidualTrial>& trials, const std::string& where) {
  try {
    validate(trials);
    ADD_FAILURE() << "accepted; expected an error at " << where;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), where) << e.what();
  }
}

TEST(ResidualFit, RefusesTrialsThatDisagreeOrHoldNoNumbers) {
  std::mt19937_64 rng(7);
  const Eigen::MatrixXd truth = random_matrix(3, 2 * kLegs, rng);
  expect_refused({}, "trials");
  std::vector<ResidualTrial> t = trials_of(truth, {5, 5}, rng);
  t[1].qdot.conservativeResize(5, 2 * kLegs - 2);
  expect_refused(t, "trials[1].qdot");
  t = trials_of(truth, {5, 5}, rng);
  t[1].residual.conservativeResize(4, 3);
  expect_refused(t, "trials[1].residual");
  t = trials_of(truth, {5}, rng);
  t[0].qdot(2, 3) = NAN;
  expect_refused(t, "trials[0]");
  ResidualTrial odd;
  odd.qdot = Eigen::MatrixXd::Zero(3, 5);
  odd.residual = Eigen::MatrixXd::Zero(3, 3);
  expect_refused({odd}, "trials[0].qdot");
  ResidualTrial empty;
  empty.qdot = Eigen::MatrixXd::Zero(0, 4);
  empty.residual = Eigen::MatrixXd::Zero(0, 3);
  expect_refused({empty}, "trials");
  EXPECT_THROW((void)validate_ridge(trials_of(truth, {5}, rng), {0.0}), core::InputError);
  EXPECT_THROW((void)fit_residual_ridge(trials_of(truth, {5}, rng), -1.0), core::InputError);
}

}  // namespace
}  // namespace slipwalk::residual
