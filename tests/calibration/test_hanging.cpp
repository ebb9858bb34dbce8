// §4.3.1 against its oracles: the smoother against the dense batch MAP of the same Gaussian
// model, its null direction and its lag bias; exact recovery from records made here from the
// sensing model (eq. 4.1) with exact rotations for the hanging misalignments; the thesis'
// first-order weight and its 1 − cos(α/2) bias; the residuals the misalignment model removes;
// the standard errors against the scatter over seeds; and the errors for records that do not pair.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "calibration/hanging.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {
namespace {

using Eigen::Matrix3d;
using Eigen::Matrix3Xd;
using Eigen::Vector3d;

// ---- seeded draws, the same on every platform ------------------------------------------------

struct Draw {
  std::mt19937_64 rng;
  explicit Draw(std::uint64_t seed) : rng(seed) {}
  double uniform() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {  // Box–Muller
    const double u = 1.0 - uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * uniform());
  }
  Vector3d vector(double scale) { return scale * Vector3d(normal(), normal(), normal()); }
  Vector3d direction() { return vector(1.0).normalized(); }
  /// A rotation by an angle drawn in [0, max_angle] about a random axis.
  Matrix3d rotation(double max_angle) {
    return rotation_from_vector(uniform(0.0, max_angle) * direction());
  }
};

constexpr double kDeg = std::numbers::pi / 180.0;

// ---- the sensing model (eq. 4.1), exact rotations ---------------------------------------------

struct Truth {
  Geometry geometry;
  std::vector<double> weight;
  std::vector<Wrench> offset;
  std::vector<Matrix3d> mounting;  // R̃_k
  std::vector<PeriodicFit> com;    // r_k(φ), a short trigonometric series
  std::vector<double> phase;       // turns
};

Truth make_truth(int legs, Draw& draw, int harmonics = 2) {
  Truth t;
  for (int k = 0; k < legs; ++k) {
    t.geometry.legs.push_back("L" + std::to_string(k));
    Frame frame;
    if (k % 3 == 1) {
      frame.R =
          Eigen::AngleAxisd(std::numbers::pi, Vector3d::UnitZ()).toRotationMatrix();  // mirrored
    } else if (k % 3 == 2) {
      frame.R = draw.rotation(std::numbers::pi);
    }
    frame.p = draw.vector(0.2);
    t.geometry.transducer.push_back(frame);
    t.weight.push_back(draw.uniform(6.0, 6.5));
    Wrench offset;
    offset << draw.vector(3.0), draw.vector(0.5);
    t.offset.push_back(offset);
    t.mounting.push_back(draw.rotation(3.0 * kDeg));
    PeriodicFit com;
    com.coefficients = Matrix3Xd(3, 1 + 2 * harmonics);
    com.coefficients.col(0) = Vector3d(0.01, 0.02, -0.12) + draw.vector(0.01);
    for (int c = 1; c < 1 + 2 * harmonics; ++c) {
      com.coefficients.col(c) = draw.vector(0.02 / c);
    }
    t.com.push_back(com);
    t.phase.push_back(draw.uniform());
  }
  t.geometry.robot_weight = 80.0;
  return t;
}

/// The true gravity direction in transducer k's true frame when the body hangs with `down` along
/// gravity up to the record's misalignment `tilt` (a rotation of the body's axes).
Vector3d gravity_direction(const Truth& t, int k, BodyAxis down, const Matrix3d& tilt) {
  const Matrix3d body_to_true = (t.geometry.transducer[static_cast<std::size_t>(k)].R *
                                 t.mounting[static_cast<std::size_t>(k)])
                                    .transpose();
  return body_to_true * tilt * axis_vector(down);
}

HangingRecord make_record(const Truth& t, BodyAxis down, const Matrix3d& tilt, int samples,
                          double cycles, double force_noise, double torque_noise, Draw& draw) {
  const int legs = t.geometry.size();
  HangingRecord record;
  record.down = down;
  record.source = std::string("record ") + std::string(axis_label(down));
  record.phi.resize(samples, legs);
  record.wrench.resize(samples, 6 * legs);
  for (int k = 0; k < legs; ++k) {
    const Vector3d force =
        t.weight[static_cast<std::size_t>(k)] * gravity_direction(t, k, down, tilt);
    for (int i = 0; i < samples; ++i) {
      const double phi = t.phase[static_cast<std::size_t>(k)] + cycles * i / samples;
      record.phi(i, k) = phi;
      Wrench w = force_at(force, t.com[static_cast<std::size_t>(k)](phi)) +
                 t.offset[static_cast<std::size_t>(k)];
      w.head<3>() += draw.vector(force_noise);
      w.tail<3>() += draw.vector(torque_noise);
      record.wrench.block<1, 6>(i, 6 * k) = w.transpose();
    }
  }
  return record;
}

struct Experiment {
  Truth truth;
  std::vector<HangingRecord> records;
  std::vector<Matrix3d> tilt;  // per record
};

Experiment make_experiment(std::uint64_t seed, int legs, const std::vector<BodyAxis>& axes,
                           double max_tilt, int samples = 400, double cycles = 2.0,
                           double force_noise = 0.0, double torque_noise = 0.0,
                           int com_harmonics = 2) {
  Draw draw(seed);
  Experiment e{make_truth(legs, draw, com_harmonics), {}, {}};
  for (const BodyAxis axis : axes) {
    e.tilt.push_back(draw.rotation(max_tilt));
    e.records.push_back(make_record(e.truth, axis, e.tilt.back(), samples, cycles, force_noise,
                                    torque_noise, draw));
  }
  return e;
}

const std::vector<BodyAxis> kFour = {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::plus_z,
                                     BodyAxis::minus_z};

HangingOptions pointwise(HangingModel model = HangingModel::exact) {
  HangingOptions o;
  o.model = model;
  o.com = ComEstimator::pointwise;
  return o;
}

// ---- the smoother ------------------------------------------------------------------------------

TEST(SmoothCom, EqualsTheBatchMapSolutionOfTheSameGaussianModel) {
  Draw draw(7);
  const int n = 25;
  const Vector3d f = draw.vector(4.0);
  const double q = 0.003;
  const double rho = 0.02;
  const double p0 = 0.5;
  const Vector3d prior = draw.vector(0.1);
  Matrix3Xd torque(3, n);
  for (int i = 0; i < n; ++i) {
    torque.col(i) = draw.vector(0.3);
  }
  // Dense normal equations of  |r_0 − prior|²/p0 + Σ |r_{i+1} − r_i|²/q + Σ |y_i + [f] r_i|²/ρ.
  const Matrix3d H = -skew(f);
  const Matrix3d I = Matrix3d::Identity();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * n);
  A.block<3, 3>(0, 0) += I / p0;
  b.segment<3>(0) += prior / p0;
  for (int i = 0; i < n; ++i) {
    A.block<3, 3>(3 * i, 3 * i) += H.transpose() * H / rho;
    b.segment<3>(3 * i) += H.transpose() * torque.col(i) / rho;
    if (i + 1 < n) {
      A.block<3, 3>(3 * i, 3 * i) += I / q;
      A.block<3, 3>(3 * i + 3, 3 * i + 3) += I / q;
      A.block<3, 3>(3 * i, 3 * i + 3) -= I / q;
      A.block<3, 3>(3 * i + 3, 3 * i) -= I / q;
    }
  }
  const Eigen::VectorXd map = A.ldlt().solve(b);
  const Matrix3Xd smoothed = smooth_com(torque, f, q, rho, prior, p0);
  for (int i = 0; i < n; ++i) {
    EXPECT_LT((smoothed.col(i) - map.segment<3>(3 * i)).norm(), 1e-9) << "sample " << i;
  }
}

TEST(SmoothCom, KeepsThePriorAlongTheForceTheNullDirectionOfOnePair) {
  Draw draw(8);
  const Vector3d f = draw.vector(5.0);
  const Vector3d fhat = f.normalized();
  Matrix3Xd torque(3, 50);
  for (int i = 0; i < 50; ++i) {
    torque.col(i) = draw.vector(0.2);
  }
  const Vector3d prior = draw.vector(0.1);
  const Matrix3Xd a = smooth_com(torque, f, 0.01, 0.01, prior, 1.0);
  const Matrix3Xd b = smooth_com(torque, f, 0.01, 0.01, prior + 0.7 * fhat, 1.0);
  for (int i = 0; i < 50; ++i) {
    EXPECT_NEAR(fhat.dot(a.col(i)), fhat.dot(prior), 1e-12);
    EXPECT_LT((b.col(i) - a.col(i) - 0.7 * fhat).norm(), 1e-12);  // only the null part moves
  }
  // One pair's equations −[f] r = τ have rank 2: f × (−[f]) annihilates nothing but f.
  EXPECT_EQ(Eigen::FullPivLU<Matrix3d>(skew(f)).rank(), 2);
}

TEST(SmoothCom, LagsNoiselessDataByTheStatedMultipleOfTheSecondDifference) {
  Draw draw(9);
  const int n = 300;
  const Vector3d f = draw.vector(4.0);
  const double f2 = f.squaredNorm();
  const double q = 0.01;
  const double rho = 0.01;
  Matrix3Xd r(3, n);
  Matrix3Xd torque(3, n);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 100.0;
    r.col(i) = Vector3d(0.05 * std::cos(a), 0.03 * std::sin(a), 0.02 * std::sin(2.0 * a));
    torque.col(i) = r.col(i).cross(f);
  }
  const Matrix3d P = Matrix3d::Identity() - f * f.transpose() / f2;
  const Matrix3Xd m = smooth_com(torque, f, q, rho, P * r.col(0), 1.0);
  const double c = rho / (q * f2);
  double max_second = 0.0;
  for (int i = 1; i + 1 < n; ++i) {
    const Vector3d second = m.col(i + 1) - 2.0 * m.col(i) + m.col(i - 1);
    EXPECT_LT((m.col(i) - P * r.col(i) - c * second).norm(), 1e-13)
        << i;  // the stationarity identity
    max_second = std::max(max_second, (r.col(i + 1) - 2.0 * r.col(i) + r.col(i - 1)).norm());
  }
  for (int i = 5; i + 5 < n; ++i) {
    EXPECT_LT((m.col(i) - P * r.col(i)).norm(), 1.1 * c * max_second) << i;
  }
}

TEST(SmoothCom, RefusesNonPositiveVariances) {
  const Matrix3Xd torque = Matrix3Xd::Zero(3, 3);
  EXPECT_THROW((void)smooth_com(torque, Vector3d::UnitX(), 0.0, 0.01), core::InputError);
  EXPECT_THROW((void)smooth_com(torque, Vector3d::UnitX(), 0.01, -1.0), core::InputError);
  EXPECT_THROW((void)smooth_com(torque, Vector3d::UnitX(), 0.01, 0.01, Vector3d::Zero(), 0.0),
               core::InputError);
}

// ---- exact recovery ----------------------------------------------------------------------------

void expect_exact_parameters(const Experiment& e, const HangingCalibration& cal, double tolerance) {
  for (int k = 0; k < e.truth.geometry.size(); ++k) {
    const auto K = static_cast<std::size_t>(k);
    EXPECT_NEAR(cal.legs[K].weight, e.truth.weight[K], tolerance) << "leg " << k;
    EXPECT_LT((cal.legs[K].offset - e.truth.offset[K]).cwiseAbs().maxCoeff(), tolerance)
        << "leg " << k;
    for (const HangingPair& pair : cal.legs[K].pairs) {
      EXPECT_NEAR(pair.d.dot(pair.f_minus), 0.0, 1e-9);
      EXPECT_NEAR(pair.weight, e.truth.weight[K], tolerance);
    }
  }
}

TEST(CalibrateHanging, RecoversEveryParameterFromNoiselessRecordsWithMisalignmentsUpTo10Degrees) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Experiment e = make_experiment(seed, 3, kFour, 10.0 * kDeg);
    const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records, pointwise());
    expect_exact_parameters(e, cal, 1e-9);
    for (int k = 0; k < 3; ++k) {
      const LegEstimate& leg = cal.legs[static_cast<std::size_t>(k)];
      const PeriodicFit& truth = e.truth.com[static_cast<std::size_t>(k)];
      ASSERT_EQ(leg.com_samples.cols(), 400);
      for (Eigen::Index i = 0; i < leg.com_samples.cols(); ++i) {
        ASSERT_LT((leg.com_samples.col(i) - truth(leg.com_phi(i))).norm(), 1e-9)
            << "leg " << k << " sample " << i;
      }
      EXPECT_LT((leg.com.coefficients.leftCols(5) - truth.coefficients).cwiseAbs().maxCoeff(),
                1e-9);
      EXPECT_LT(leg.com.coefficients.rightCols(4).cwiseAbs().maxCoeff(), 1e-9);  // harmonics 3, 4
      EXPECT_LT(leg.com_fit_rms, 1e-10);
      EXPECT_EQ(leg.offset_se.maxCoeff(), leg.offset_se.maxCoeff());  // finite
    }
  }
}

TEST(CalibrateHanging, RecoversWeightsAndOffsetsExactlyWhenThePeriodicFitCannotFollowTheCom) {
  // A CoM with eight harmonics fitted with two: the fit's residual is orthogonal (over the
  // samples) to everything the fit spans, so it drops out of the d regression, and the weights
  // and offsets stay exact however poorly r̂ follows r.
  const Experiment e = make_experiment(14, 3, kFour, 10.0 * kDeg, 500, 2.0, 0.0, 0.0, 8);
  HangingOptions options = pointwise();
  options.harmonics = 2;
  const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records, options);
  EXPECT_GT(cal.legs[0].com_fit_rms, 1e-4);
  expect_exact_parameters(e, cal, 1e-9);
}

TEST(CalibrateHanging, UsesAThirdPairAndIgnoresTheLoneUprightRecord) {
  const Experiment e = make_experiment(
      11, 2,
      {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::plus_y, BodyAxis::minus_y, BodyAxis::minus_z},
      6.0 * kDeg);
  const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records, pointwise());
  ASSERT_EQ(cal.legs[0].pairs.size(), 2U);
  EXPECT_EQ(cal.legs[0].pairs[1].down, BodyAxis::plus_y);
  expect_exact_parameters(e, cal, 1e-9);

  const Experiment three = make_experiment(12, 2,
                                           {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::plus_y,
                                            BodyAxis::minus_y, BodyAxis::plus_z, BodyAxis::minus_z},
                                           6.0 * kDeg);
  const HangingCalibration cal3 =
      calibrate_hanging(three.truth.geometry, three.records, pointwise());
  ASSERT_EQ(cal3.legs[1].pairs.size(), 3U);
  expect_exact_parameters(three, cal3, 1e-9);
}

TEST(CalibrateHanging, TheSmootherRecoversTheComWithinItsLagBias) {
  const Experiment e = make_experiment(3, 3, kFour, 8.0 * kDeg, 1000, 2.0);
  HangingOptions options;  // smoother, Q = R = 0.01 I as the thesis
  const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records, options);
  // The CoM enters weights and offsets only through d's regressor r̂ (off by ~1e-6 m).
  expect_exact_parameters(e, cal, 1e-5);
  for (int k = 0; k < 3; ++k) {
    const auto K = static_cast<std::size_t>(k);
    const LegEstimate& leg = cal.legs[K];
    double min_f2 = 1e300;
    for (const HangingPair& pair : leg.pairs) {
      min_f2 = std::min(min_f2, pair.f_minus.squaredNorm());
    }
    const double c = options.observation_variance / (options.transition_variance * min_f2);
    double max_second = 0.0;
    const Eigen::Index n = leg.com_phi.size();
    for (Eigen::Index i = 1; i + 1 < n; ++i) {
      const PeriodicFit& r = e.truth.com[K];
      max_second = std::max(
          max_second,
          (r(leg.com_phi(i + 1)) - 2.0 * r(leg.com_phi(i)) + r(leg.com_phi(i - 1))).norm());
    }
    for (Eigen::Index i = 5; i + 5 < n; ++i) {
      ASSERT_LT((leg.com_samples.col(i) - e.truth.com[K](leg.com_phi(i))).norm(),
                2.0 * c * max_second)
          << "leg " << k << " sample " << i;
    }
    EXPECT_GT(leg.com_fit_rms, 0.0);  // the lag is real, and small:
    EXPECT_LT(
        (leg.com.coefficients.leftCols(5) - e.truth.com[K].coefficients).cwiseAbs().maxCoeff(),
        1e-5);
  }
}

TEST(CalibrateHanging, TheThesisFirstOrderWeightFallsShortByOneMinusCosineOfHalfTheAngle) {
  const Experiment e = make_experiment(4, 3, kFour, 10.0 * kDeg);
  const HangingCalibration cal =
      calibrate_hanging(e.truth.geometry, e.records, pointwise(HangingModel::thesis_first_order));
  for (int k = 0; k < 3; ++k) {
    const auto K = static_cast<std::size_t>(k);
    const double w = e.truth.weight[K];
    for (std::size_t j = 0; j < 2; ++j) {
      // Records 2j (↓) and 2j + 1 (↑); α between u↓ and u↑' = −u↑.
      const Vector3d down = gravity_direction(e.truth, k, kFour[2 * j], e.tilt[2 * j]);
      const Vector3d up_flipped =
          -gravity_direction(e.truth, k, kFour[2 * j + 1], e.tilt[2 * j + 1]);
      const double alpha = std::acos(std::clamp(down.dot(up_flipped), -1.0, 1.0));
      EXPECT_GT(alpha, 0.0);
      EXPECT_NEAR(w - cal.legs[K].pairs[j].weight, w * (1.0 - std::cos(alpha / 2.0)), 1e-9);
    }
  }
}

double rms(const Eigen::MatrixXd& m) {
  return std::sqrt(m.squaredNorm() / static_cast<double>(m.size()));
}

TEST(CalibrateHanging, LeavesResidualsWithoutTheMisalignmentModelThatTheExactModelRemoves) {
  const Experiment e = make_experiment(5, 3, kFour, 5.0 * kDeg);
  const HangingCalibration exact = calibrate_hanging(e.truth.geometry, e.records, pointwise());
  const HangingCalibration naive =
      calibrate_hanging(e.truth.geometry, e.records, pointwise(HangingModel::no_misalignment));
  for (const HangingRecord& record : e.records) {
    const double exact_rms = rms(record.wrench - predict_hanging(e.truth.geometry, exact, record));
    const double naive_rms = rms(record.wrench - predict_hanging(e.truth.geometry, naive, record));
    EXPECT_LT(exact_rms, 1e-9) << record.source;
    EXPECT_GT(naive_rms, 1e-3) << record.source;
  }
  for (const HangingPair& pair : naive.legs[0].pairs) {
    EXPECT_EQ(pair.d.norm(), 0.0);
    EXPECT_EQ(pair.s_plus.norm(), 0.0);
  }
}

TEST(CalibrateHanging, ReportsTheMisalignmentsAsTheThesisDefinesThem) {
  const Experiment e = make_experiment(6, 2, kFour, 2.0 * kDeg);
  const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records, pointwise());
  for (const HangingPair& pair : cal.legs[1].pairs) {
    EXPECT_NEAR(pair.s_plus.dot(pair.axis), 0.0, 1e-12);
    EXPECT_NEAR(pair.s_minus.dot(pair.axis), 0.0, 1e-12);
    // ŝ⁺ turns e onto f⁻/|f⁻|; d = [ŝ⁻] w e to first order (d ⊥ e up to the tilt).
    EXPECT_LT((rotation_from_vector(pair.s_plus) * pair.axis - pair.f_minus.normalized()).norm(),
              1e-12);
    EXPECT_LT((pair.weight * pair.s_minus.cross(pair.axis) - pair.d).norm(),
              0.1 * pair.d.norm() + 1e-12);
  }
}

TEST(CalibrateHanging, TheThesisPrintedWeightEstimatorIsTheNaiveProjectionOnE) {
  // The thesis picks s⁺ ⊥ e with (I + [s⁺])⁻¹ f⁻ along e, then reads w off the e component. With
  // |s⁺| = tan β along ŝ⁺ that component is |f⁻| cos β = f⁻ · e, the no_misalignment weight.
  const Experiment e = make_experiment(13, 3, kFour, 8.0 * kDeg);
  const HangingCalibration exact = calibrate_hanging(e.truth.geometry, e.records, pointwise());
  const HangingCalibration naive =
      calibrate_hanging(e.truth.geometry, e.records, pointwise(HangingModel::no_misalignment));
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t j = 0; j < 2; ++j) {
      const HangingPair& pair = exact.legs[k].pairs[j];
      const double beta = pair.s_plus.norm();
      ASSERT_GT(beta, 0.0);
      const Vector3d s = std::tan(beta) * pair.s_plus / beta;
      const Vector3d undone = (Matrix3d::Identity() + skew(s)).inverse() * pair.f_minus;
      EXPECT_LT((undone - pair.axis * pair.axis.dot(undone)).norm(), 1e-12);  // along e
      EXPECT_NEAR(pair.axis.dot(undone), naive.legs[k].pairs[j].weight, 1e-12);
      EXPECT_NEAR(pair.axis.dot(undone), pair.f_minus.norm() * std::cos(beta), 1e-12);
    }
  }
}

// ---- standard errors ---------------------------------------------------------------------------

TEST(CalibrateHanging, StandardErrorsMatchTheScatterOverSeeds) {
  std::vector<double> z_weight;
  std::vector<double> z_force;
  std::vector<double> z_torque;
  for (std::uint64_t seed = 100; seed < 130; ++seed) {
    const Experiment e = make_experiment(seed, 2, kFour, 5.0 * kDeg, 600, 3.0, 0.05, 0.01);
    // Odd seeds with the thesis' smoother, even ones pointwise: the same errors either way.
    const HangingCalibration cal = calibrate_hanging(
        e.truth.geometry, e.records, seed % 2 == 1 ? HangingOptions{} : pointwise());
    for (int k = 0; k < 2; ++k) {
      const auto K = static_cast<std::size_t>(k);
      const LegEstimate& leg = cal.legs[K];
      z_weight.push_back((leg.weight - e.truth.weight[K]) / leg.weight_se);
      for (int c = 0; c < 3; ++c) {
        z_force.push_back((leg.offset(c) - e.truth.offset[K](c)) / leg.offset_se(c));
        z_torque.push_back((leg.offset(3 + c) - e.truth.offset[K](3 + c)) / leg.offset_se(3 + c));
      }
    }
  }
  for (const auto* z : {&z_weight, &z_force, &z_torque}) {
    double sum2 = 0.0;
    for (const double v : *z) {
      sum2 += v * v;
    }
    const double spread = std::sqrt(sum2 / static_cast<double>(z->size()));
    std::printf("rms z over %zu estimates: %.3f\n", z->size(), spread);
    EXPECT_GT(spread, 0.7);
    EXPECT_LT(spread, 1.4);
  }
}

// ---- records that do not pair ------------------------------------------------------------------

TEST(CalibrateHanging, RefusesARecordWithoutItsOppositeNamingIt) {
  const Experiment e = make_experiment(
      20, 2,
      {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::plus_z, BodyAxis::minus_z, BodyAxis::plus_y},
      3.0 * kDeg, 50);
  try {
    (void)calibrate_hanging(e.truth.geometry, e.records, pointwise());
    FAIL() << "a lone +y record must be refused";
  } catch (const core::InputError& error) {
    EXPECT_EQ(error.where(), "record +y");
  }
}

TEST(CalibrateHanging, RefusesASinglePairTheCoMWouldBeFreeAlongFMinus) {
  const Experiment e = make_experiment(
      21, 2, {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::minus_z}, 3.0 * kDeg, 50);
  EXPECT_THROW((void)calibrate_hanging(e.truth.geometry, e.records, pointwise()), core::InputError);
}

TEST(CalibrateHanging, RefusesRecordsThatDoNotMatchSampleBySample) {
  Experiment e = make_experiment(22, 2, kFour, 3.0 * kDeg, 50);
  e.records[1].rows.assign(50, "");
  for (int i = 0; i < 50; ++i) {
    e.records[1].rows[static_cast<std::size_t>(i)] = "h.csv:" + std::to_string(i + 2);
  }
  e.records[1].phi(7, 1) += 0.1;
  try {
    (void)calibrate_hanging(e.truth.geometry, e.records, pointwise());
    FAIL();
  } catch (const core::InputError& error) {
    EXPECT_EQ(error.where(), "h.csv:9");
  }
  e.records[1].phi(7, 1) += 0.9;  // a whole turn off: the same angle
  EXPECT_NO_THROW((void)calibrate_hanging(e.truth.geometry, e.records, pointwise()));

  Experiment shorter = make_experiment(22, 2, kFour, 3.0 * kDeg, 50);
  shorter.records[2] = make_experiment(22, 2, kFour, 3.0 * kDeg, 49).records[2];
  EXPECT_THROW((void)calibrate_hanging(shorter.truth.geometry, shorter.records, pointwise()),
               core::InputError);
}

TEST(CalibrateHanging, RefusesBadWidthsNonFiniteEntriesTooFewSamplesAndDuplicates) {
  const Experiment good = make_experiment(23, 2, kFour, 3.0 * kDeg, 50);
  const auto refuses = [&](auto&& edit) {
    Experiment e = good;
    edit(e);
    EXPECT_THROW((void)calibrate_hanging(e.truth.geometry, e.records, pointwise()),
                 core::InputError);
  };
  refuses([](Experiment& e) { e.records[0].wrench.conservativeResize(Eigen::NoChange, 11); });
  refuses([](Experiment& e) { e.records[0].phi.conservativeResize(Eigen::NoChange, 1); });
  refuses([](Experiment& e) { e.records[3].wrench(4, 5) = std::nan(""); });
  refuses([](Experiment& e) { e.records.push_back(e.records[0]); });
  refuses([](Experiment& e) {
    for (auto& r : e.records) {
      r.phi.conservativeResize(10, Eigen::NoChange);
      r.wrench.conservativeResize(10, Eigen::NoChange);
    }
  });
  HangingOptions bad = pointwise();
  bad.harmonics = 17;
  EXPECT_THROW(validate(bad), core::InputError);
  bad = pointwise();
  bad.observation_variance = 0.0;
  EXPECT_THROW(validate(bad), core::InputError);
  bad = pointwise();
  bad.transition_variance = std::nan("");
  EXPECT_THROW(validate(bad), core::InputError);
  bad = pointwise();
  bad.max_phi_mismatch = 0.6;
  EXPECT_THROW(validate(bad), core::InputError);
  EXPECT_NO_THROW(validate(HangingOptions{}));
}

// ---- the thesis' size: 4 records × 90,000 samples × 6 legs ------------------------------------

TEST(CalibrateHanging, CalibratesTheThesisSizedExperimentQuickly) {
  const Experiment e = make_experiment(30, 6, kFour, 5.0 * kDeg, 90000, 10.0, 0.05, 0.01);
  const auto start = std::chrono::steady_clock::now();
  const HangingCalibration cal = calibrate_hanging(e.truth.geometry, e.records);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("calibrate_hanging, 4 x 90000 samples x 6 legs (smoother): %.3f s\n", seconds);
  for (int k = 0; k < 6; ++k) {
    const auto K = static_cast<std::size_t>(k);
    EXPECT_LT(std::abs(cal.legs[K].weight - e.truth.weight[K]),
              5.0 * cal.legs[K].weight_se + 1e-12);
  }
}

}  // namespace
}  // namespace slipwalk::calibration
