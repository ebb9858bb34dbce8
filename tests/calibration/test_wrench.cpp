// The rigid-body algebra of lib/calibration (wrench.hpp) and the periodic fit (model.hpp) against
// direct computations: a force at a point moved between frames, the transform's matrix and its
// composition, the Cayley map's angle, axis and inverse, the π refusal, the rotation-vector round
// trip and a known trigonometric series.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "calibration/model.hpp"
#include "calibration/wrench.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct Draw {
  std::mt19937_64 rng;
  explicit Draw(std::uint64_t seed) : rng(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
  }
  Vector3d vector(double scale) {
    return Vector3d(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
  }
  Matrix3d rotation() {
    const Vector3d axis = vector(1.0).normalized();
    return Eigen::AngleAxisd(uniform(0.0, std::numbers::pi), axis).toRotationMatrix();
  }
  Frame frame() { return {rotation(), vector(0.5)}; }
};

TEST(Skew, CrossesFromTheLeft) {
  Draw draw(1);
  const Vector3d v = draw.vector(2.0);
  const Vector3d x = draw.vector(2.0);
  EXPECT_LT((skew(v) * x - v.cross(x)).norm(), 1e-15);
  EXPECT_LT((skew(v) + skew(v).transpose()).norm(), 1e-15);
}

TEST(TransformWrench, MovesAForceAtAPointAsTheMomentAboutTheNewOriginSays) {
  Draw draw(2);
  for (int trial = 0; trial < 20; ++trial) {
    const Frame s_in_b = draw.frame();
    const Vector3d force_s = draw.vector(10.0);
    const Vector3d point_s = draw.vector(0.3);
    const Wrench w_s = force_at(force_s, point_s);
    EXPECT_LT((w_s.tail<3>() - point_s.cross(force_s)).norm(), 1e-14);
    // Directly in B: the force turned, acting at the point placed in B.
    const Vector3d force_b = s_in_b.R * force_s;
    const Vector3d point_b = s_in_b * point_s;
    const Wrench direct = force_at(force_b, point_b);
    EXPECT_LT((transform_wrench(s_in_b, w_s) - direct).norm(), 1e-12);
  }
}

TEST(TransformWrench, CarriesAPureCoupleAsATurnedCouple) {
  Draw draw(3);
  const Frame s_in_b = draw.frame();
  Wrench couple = Wrench::Zero();
  couple.tail<3>() = draw.vector(1.0);
  const Wrench moved = transform_wrench(s_in_b, couple);
  EXPECT_LT(moved.head<3>().norm(), 1e-15);
  EXPECT_LT((moved.tail<3>() - s_in_b.R * couple.tail<3>()).norm(), 1e-14);
}

TEST(TransformWrench, IsItsMatrixAndComposesAsTheFrames) {
  Draw draw(4);
  for (int trial = 0; trial < 20; ++trial) {
    const Frame a = draw.frame();
    const Frame b = draw.frame();
    Wrench w;
    w << draw.vector(5.0), draw.vector(1.0);
    EXPECT_LT((wrench_transform_matrix(a) * w - transform_wrench(a, w)).norm(), 1e-12);
    EXPECT_LT((transform_wrench(a, transform_wrench(b, w)) - transform_wrench(a * b, w)).norm(),
              1e-12);
    EXPECT_LT(
        (wrench_transform_matrix(a) * wrench_transform_matrix(b) - wrench_transform_matrix(a * b))
            .norm(),
        1e-12);
    EXPECT_LT((transform_wrench(a.inverse(), transform_wrench(a, w)) - w).norm(), 1e-12);
  }
}

TEST(Cayley, IsARotationByTwiceTheArctangentOfTheNormAboutMinusQ) {
  Draw draw(5);
  for (const double size : {1e-4, 0.1, 0.5, 1.0, 3.0, 20.0}) {
    const Vector3d q = size * draw.vector(1.0).normalized();
    const Matrix3d R = cayley(q);
    EXPECT_LT((R.transpose() * R - Matrix3d::Identity()).norm(), 1e-13) << size;
    EXPECT_NEAR(R.determinant(), 1.0, 1e-13);
    const Eigen::AngleAxisd aa(R);
    EXPECT_NEAR(aa.angle(), 2.0 * std::atan(q.norm()), 1e-12) << size;
    EXPECT_LT((aa.axis() + q.normalized()).norm(), 1e-9) << size;
    EXPECT_LT((cayley_inverse(R) - q).norm(), 1e-12 * std::max(1.0, q.squaredNorm())) << size;
  }
  const Vector3d small(1e-5, -2e-5, 3e-5);
  // (I − Q)(I + Q)⁻¹ = I − 2Q + 2Q² − 2Q³ + …: small q turns by about −2q.
  const Matrix3d Q = skew(small);
  EXPECT_LT((cayley(small) - (Matrix3d::Identity() - 2.0 * Q + 2.0 * Q * Q)).norm(), 1e-12);
  EXPECT_EQ(cayley(Vector3d::Zero()), Matrix3d::Identity());
}

TEST(Cayley, InverseRefusesTurnsByPiAndNonRotations) {
  const Vector3d axis = Vector3d(1.0, 2.0, -0.5).normalized();
  const auto turn = [&](double angle) { return Eigen::AngleAxisd(angle, axis).toRotationMatrix(); };
  EXPECT_THROW((void)cayley_inverse(turn(std::numbers::pi)), core::InputError);
  EXPECT_THROW((void)cayley_inverse(turn(std::numbers::pi - 1e-7)), core::InputError);
  const Vector3d q = cayley_inverse(turn(std::numbers::pi - 1e-3));
  EXPECT_LT((cayley(q) - turn(std::numbers::pi - 1e-3)).norm(), 1e-9);
  EXPECT_THROW((void)cayley_inverse(2.0 * Matrix3d::Identity()), core::InputError);
  EXPECT_THROW((void)cayley_inverse(-Matrix3d::Identity()), core::InputError);  // a reflection
  Matrix3d nan = Matrix3d::Identity();
  nan(0, 1) = std::nan("");
  EXPECT_THROW((void)cayley_inverse(nan), core::InputError);
}

TEST(RotationVector, RoundTripsEveryAngleBelowPi) {
  Draw draw(6);
  for (const double angle : {0.0, 1e-8, 0.3, 1.5, 3.0, std::numbers::pi - 1e-6}) {
    const Vector3d theta = angle * draw.vector(1.0).normalized();
    const Matrix3d R = rotation_from_vector(theta);
    EXPECT_LT(
        (R - Eigen::AngleAxisd(angle, theta.norm() > 0 ? theta.normalized() : Vector3d::UnitX())
                 .toRotationMatrix())
            .norm(),
        1e-14);
    EXPECT_LT((rotation_vector(R) - theta).norm(), 1e-9) << angle;
  }
}

TEST(BodyAxes, LabelsParseBackAndOppositesPointOpposite) {
  for (int i = 0; i < 6; ++i) {
    const auto axis = static_cast<BodyAxis>(i);
    EXPECT_EQ(parse_axis(axis_label(axis)), axis);
    EXPECT_EQ(opposite(opposite(axis)), axis);
    EXPECT_EQ(axis_vector(opposite(axis)), -axis_vector(axis));
    EXPECT_EQ(axis_vector(axis).norm(), 1.0);
  }
  EXPECT_EQ(axis_vector(BodyAxis::minus_z), Vector3d(0.0, 0.0, -1.0));
  EXPECT_FALSE(parse_axis("z").has_value());
}

TEST(FitPeriodic, RecoversAKnownSeriesFromIrregularUnwrappedAngles) {
  Draw draw(7);
  PeriodicFit truth;
  truth.coefficients = Eigen::Matrix3Xd(3, 7);
  for (int c = 0; c < 7; ++c) {
    truth.coefficients.col(c) = draw.vector(0.05);
  }
  const int n = 200;
  Eigen::VectorXd phi(n);
  Eigen::Matrix3Xd values(3, n);
  for (int i = 0; i < n; ++i) {
    phi(i) = draw.uniform(-3.0, 7.0);  // several turns, not wrapped
    values.col(i) = truth(phi(i));
  }
  const PeriodicFit fit = fit_periodic(phi, values, 3);
  EXPECT_EQ(fit.harmonics(), 3);
  EXPECT_LT((fit.coefficients - truth.coefficients).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((fit(0.3) - fit(1.3)).norm(), 1e-12);  // one turn is one period
  // More harmonics than the series has: the extra ones come out zero.
  const PeriodicFit wider = fit_periodic(phi, values, 5);
  EXPECT_LT((wider.coefficients.leftCols(7) - truth.coefficients).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(wider.coefficients.rightCols(4).cwiseAbs().maxCoeff(), 1e-12);
  // No harmonics: the mean.
  const PeriodicFit mean = fit_periodic(phi, values, 0);
  EXPECT_LT((mean.coefficients.col(0) - values.rowwise().mean()).norm(), 1e-12);
}

TEST(FitPeriodic, RefusesNegativeHarmonicsAndTooFewSamples) {
  const Eigen::VectorXd phi = Eigen::VectorXd::LinSpaced(4, 0.0, 0.75);
  const Eigen::Matrix3Xd values = Eigen::Matrix3Xd::Ones(3, 4);
  EXPECT_THROW((void)fit_periodic(phi, values, -1), core::InputError);
  EXPECT_THROW((void)fit_periodic(phi, values, 2), core::InputError);  // needs 5
  EXPECT_NO_THROW((void)fit_periodic(phi, values, 1));
  EXPECT_THROW((void)fit_periodic(phi, Eigen::Matrix3Xd::Ones(3, 3), 0), core::InputError);
}

}  // namespace
}  // namespace slipwalk::calibration
