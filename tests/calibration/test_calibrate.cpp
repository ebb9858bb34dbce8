// The whole calibration against the synthetic robot's known truth (thesis ch. 4 without the
// robot). The oracles: with noiseless readings every parameter is recovered to round-off (the
// identities of hanging.hpp and the balance of standing.hpp are exact, and the generator computes
// its readings from the physics, not from those equations); with the thesis-like noise each
// estimate lies within three of its own standard errors of the truth, over twenty seeds; the
// calibrated ground contact wrenches of a pose sum to the robot's weight.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/synthetic.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {
namespace {

struct Synthetic {
  SyntheticTruth truth;
  std::vector<HangingRecord> hanging;
  StandingPoses poses;
};

Synthetic make(const SynthOptions& options) {
  Synthetic s{synthetic_truth(options), {}, {}};
  s.hanging = synthetic_hanging(s.truth, options);
  s.poses = synthetic_poses(s.truth, options);
  return s;
}

// The estimate-minus-truth of every estimated number, and its standard error.
struct Errors {
  std::vector<double> error;
  std::vector<double> se;
};

Errors errors_of(const Calibration& c, const SyntheticTruth& truth) {
  Errors e;
  const auto add = [&](double estimate, double truth_value, double se) {
    e.error.push_back(estimate - truth_value);
    e.se.push_back(se);
  };
  for (int k = 0; k < truth.legs(); ++k) {
    const auto uk = static_cast<std::size_t>(k);
    const LegEstimate& leg = c.hanging.legs[uk];
    add(leg.weight, truth.weight[uk], leg.weight_se);
    for (int i = 0; i < 6; ++i) {
      add(leg.offset(i), truth.offset[uk](i), leg.offset_se(i));
    }
    const Eigen::Vector3d rotation = rotation_vector(c.mounting.rotation[uk]);
    const Eigen::Vector3d rotation_truth = rotation_vector(truth.mounting_rotation[uk]);
    for (int i = 0; i < 3; ++i) {
      add(rotation(i), rotation_truth(i), c.mounting.rotation_se[uk](i));
      add(c.mounting.displacement[uk](i), truth.displacement(k)(i),
          c.mounting.displacement_se[uk](i));
    }
  }
  return e;
}

CalibrationOptions full_model() {
  CalibrationOptions options;
  options.select_model = false;
  options.mounting.model = MountingModel::full;
  return options;
}

TEST(Calibrate, RecoversEveryParameterToRoundOffFromNoiselessReadings) {
  SynthOptions synth;
  synth.noise_scale = 0.0;
  synth.samples_per_cycle = 200;
  synth.cycles = 2;
  const Synthetic s = make(synth);
  CalibrationOptions options = full_model();
  options.hanging.com = ComEstimator::pointwise;
  const Calibration c = calibrate(s.truth.geometry, s.hanging, s.poses, options);
  const Errors e = errors_of(c, s.truth);
  for (std::size_t i = 0; i < e.error.size(); ++i) {
    EXPECT_NEAR(e.error[i], 0.0, 1e-8) << "parameter " << i;
  }
  // The CoM fit: the four-bar's CoM is not a finite Fourier series, so the fit's truncation,
  // not round-off, bounds it.
  for (int k = 0; k < s.truth.legs(); ++k) {
    for (double phi = 0.0; phi < 1.0; phi += 0.05) {
      EXPECT_LT(
          (c.hanging.legs[static_cast<std::size_t>(k)].com(phi) - s.truth.leg_com(k, phi)).norm(),
          2e-4)
          << "leg " << k << " phi " << phi;
    }
  }
}

TEST(Calibrate, EstimatesLieWithinThreeStandardErrorsOfTheTruthOverTwentySeeds) {
  std::vector<double> z;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SynthOptions synth;
    synth.seed = seed;
    synth.samples_per_cycle = 300;
    const Synthetic s = make(synth);
    const Calibration c = calibrate(s.truth.geometry, s.hanging, s.poses, full_model());
    const Errors e = errors_of(c, s.truth);
    for (std::size_t i = 0; i < e.error.size(); ++i) {
      ASSERT_GT(e.se[i], 0.0) << "seed " << seed << " parameter " << i;
      z.push_back(e.error[i] / e.se[i]);
    }
  }
  std::size_t within = 0;
  double sum_squares = 0.0;
  for (const double value : z) {
    within += std::abs(value) <= 3.0 ? 1 : 0;
    sum_squares += value * value;
  }
  const double fraction = static_cast<double>(within) / static_cast<double>(z.size());
  const double z_rms = std::sqrt(sum_squares / static_cast<double>(z.size()));
  // A standard normal lies within ±3 with probability 0.9973; over 20 × 78 numbers that are
  // correlated within a seed, 98 % is a margin that still fails for standard errors that are
  // too small by a third. The RMS z tests the other side: errors much smaller than claimed.
  EXPECT_GE(fraction, 0.98) << "z rms " << z_rms;
  EXPECT_GT(z_rms, 0.6);
  EXPECT_LT(z_rms, 1.4);
}

TEST(Calibrate, GroundContactWrenchesOfAStandingPoseSumToTheRobotsWeight) {
  SynthOptions synth;
  synth.noise_scale = 0.0;
  synth.samples_per_cycle = 200;
  synth.cycles = 2;
  synth.poses = 60;
  const Synthetic s = make(synth);
  CalibrationOptions options = full_model();
  options.hanging.com = ComEstimator::pointwise;
  const Calibration c = calibrate(s.truth.geometry, s.hanging, s.poses, options);
  for (Eigen::Index p = 0; p < s.poses.poses(); ++p) {
    Wrench total = Wrench::Zero();
    for (int k = 0; k < s.truth.legs(); ++k) {
      const Wrench reading = s.poses.wrench.row(p).segment<6>(6 * k).transpose();
      total += ground_contact_wrench(c, k, s.poses.phi(p, k), reading,
                                     s.poses.attitude[static_cast<std::size_t>(p)]);
    }
    // The ground holds the whole robot: its forces sum to G_robot upward in W.
    EXPECT_NEAR(total(0), 0.0, 1e-6);
    EXPECT_NEAR(total(1), 0.0, 1e-6);
    EXPECT_NEAR(total(2), s.truth.geometry.robot_weight, 1e-6);
  }
}

// BIC = P ln(RSS/P) + DOF ln P charges the full model's 15 extra parameters 15 ln 543 ≈ 94 over
// six rotations and one translation: it is chosen when the transducers' own translation errors
// move the residual by more than that, as on the thesis' robot (Table 4.2: RSS 29 % below). With
// 2 cm errors they do (RSS 20 % below); with the default robot's 3 mm ones (3 % below) BIC picks
// the shared translation while cross-validation still prefers the full model (the study reports
// both).
TEST(Calibrate, SelectsTheFullModelWhenTheTransducersTranslationErrorsStandOutOfTheNoise) {
  SynthOptions synth;
  synth.samples_per_cycle = 200;
  synth.mounting_translation = 0.02;
  const Synthetic s = make(synth);
  const Calibration c = calibrate(s.truth.geometry, s.hanging, s.poses, CalibrationOptions{});
  ASSERT_EQ(c.models.size(), 4U);
  EXPECT_EQ(c.mounting.model, MountingModel::full);
}

TEST(Calibrate, RefusesFoldsOutsideTheNumberOfPoses) {
  SynthOptions synth;
  synth.samples_per_cycle = 50;
  synth.cycles = 1;
  synth.poses = 10;
  const Synthetic s = make(synth);
  CalibrationOptions options;
  options.folds = 11;
  EXPECT_THROW((void)calibrate(s.truth.geometry, s.hanging, s.poses, options), core::InputError);
}

}  // namespace
}  // namespace slipwalk::calibration
