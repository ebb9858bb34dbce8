// The synthetic BigANT (lib/calibration/synthetic.hpp) against oracles that do not share its
// code path: the sensing model with the record's true gravity, the chassis' balance with the true
// transducer frames (an independent statement of the whole robot's equilibrium), the legs'
// centroid recomputed from the four-bar, the floor's contact conditions, the truth's fixed values,
// the streams' independence, the noise's scatter and the option checks.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "calibration/synthetic.hpp"
#include "core/error.hpp"
#include "robots/bigant.hpp"
#include "robots/four_bar.hpp"

namespace slipwalk::calibration {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

SynthOptions small_options(double noise_scale = 0.0) {
  SynthOptions o;
  o.noise_scale = noise_scale;
  o.cycles = 2;
  o.samples_per_cycle = 90;
  o.poses = 120;
  return o;
}

/// The sample standard deviation of the entries of x.
double sample_sigma(const Eigen::ArrayXd& x) {
  const double mean = x.mean();
  return std::sqrt((x - mean).square().sum() / static_cast<double>(x.size() - 1));
}

// ---- the truth ----------------------------------------------------------------------------------

TEST(SyntheticTruth, CarriesTable41sOffsetsAndWeightsAndTheRobotsWeight) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  ASSERT_EQ(truth.legs(), 6);
  EXPECT_EQ(truth.geometry.legs, (std::vector<std::string>{"HL", "ML", "FL", "HR", "MR", "FR"}));
  // Table 4.1, columns HL ML FL HR MR FR: two entries of each row spelled out.
  EXPECT_DOUBLE_EQ(truth.offset[0](0), 1.47);
  EXPECT_DOUBLE_EQ(truth.offset[3](0), -8.49);
  EXPECT_DOUBLE_EQ(truth.offset[1](1), -4.884);
  EXPECT_DOUBLE_EQ(truth.offset[0](2), -5.61);
  EXPECT_DOUBLE_EQ(truth.offset[5](3), -0.3611);
  EXPECT_DOUBLE_EQ(truth.offset[3](4), 0.3449);
  EXPECT_DOUBLE_EQ(truth.offset[5](5), 0.0222);
  EXPECT_EQ(truth.weight, (std::vector<double>{6.2, 6.2, 6.2, 6.1, 6.2, 6.4}));
  EXPECT_DOUBLE_EQ(truth.geometry.robot_weight, 8.18 * 9.81);
  EXPECT_NEAR(truth.chassis_weight(), 8.18 * 9.81 - 37.3, 1e-12);
  EXPECT_NO_THROW(validate(truth.geometry));
}

TEST(SyntheticTruth, PutsTheChassisComWhereItBiasesTheTorqueByAbout2p5Nm) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  EXPECT_NEAR(truth.com_torque_bias(), 2.5, 0.05);
  EXPECT_NEAR(truth.com_torque_bias(),
              std::hypot(truth.chassis_com.x(), truth.chassis_com.y()) * truth.chassis_weight(),
              1e-12);
}

TEST(SyntheticTruth, MountsLeftTransducersAlongTheBodyAndRightOnesTurnedByPiAboveEachPivot) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  const robots::BigAntLegs legs = robots::bigant_legs();
  const Matrix3d turned = Eigen::AngleAxisd(std::numbers::pi, Vector3d::UnitZ()).toRotationMatrix();
  for (int k = 0; k < 6; ++k) {
    const Frame& n = truth.geometry.transducer[static_cast<std::size_t>(k)];
    EXPECT_LT((n.p - legs.pivot.col(k) - Vector3d(0, 0, kTransducerHeight)).norm(), 1e-15);
    const Matrix3d expected = k < 3 ? Matrix3d::Identity() : turned;
    EXPECT_LT((n.R - expected).norm(), 1e-15) << k;
  }
}

TEST(SyntheticTruth, ComposesTheMountingErrorInTheTransducersAxesAndDefinesTheDisplacement) {
  SynthOptions o;
  o.mounting_rotation = 0.05;
  o.mounting_translation = 0.004;
  const SyntheticTruth truth = synthetic_truth(o);
  double largest_angle = 0.0;
  for (int k = 0; k < 6; ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const Frame t = truth.transducer_frame(k);
    const Frame& n = truth.geometry.transducer[ks];
    // A point x in the transducer frame sits at N (R̃ x + p̃) in B.
    const Vector3d x(0.1, -0.2, 0.3);
    EXPECT_LT(
        (t * x - n * (truth.mounting_rotation[ks] * x + truth.mounting_translation[ks])).norm(),
        1e-15);
    // Its origin in C: p_N + u.
    EXPECT_LT((t.p - truth.chassis_com - (n.p + truth.displacement(k))).norm(), 1e-15);
    largest_angle = std::max(largest_angle, rotation_vector(truth.mounting_rotation[ks]).norm());
  }
  EXPECT_GT(largest_angle, 0.01);  // the errors are drawn, not zero
  EXPECT_LT(largest_angle, 0.3);
}

// ---- the leg ------------------------------------------------------------------------------------

/// The leg's centre of mass recomputed from its links: bars' midpoints weighted by their shares,
/// placed in B by the nominal crank pivot and moved into the nominal transducer frame by N⁻¹.
Vector3d centroid_of_links(const SyntheticTruth& truth, int k, double phi) {
  const robots::FourBar linkage = robots::bigant_linkage();
  const robots::FourBarPose pose =
      robots::four_bar_pose(linkage, robots::kBigAntCrankPhase - 2.0 * std::numbers::pi * phi);
  const Vector3d pivot = truth.bigant.pivot.col(k);
  const auto in_body = [&](const Eigen::Vector2d& v) {
    return Vector3d(pivot + Vector3d(v.x(), 0.0, v.y()));
  };
  const double side = pivot.y() > 0 ? 1.0 : -1.0;
  const Vector3d motor = pivot + Vector3d(0.0, -side * kMotorInboard, kMotorHeight);
  const Vector3d crank = 0.5 * (pivot + in_body(pose.A));
  const Vector3d coupler = 0.5 * (in_body(pose.A) + in_body(pose.B));
  const Vector3d toe = 0.5 * (in_body(pose.A) + in_body(pose.P));
  const Vector3d rocker = 0.5 * (in_body(linkage.rocker_pivot) + in_body(pose.B));
  const LegMassShares& s = kLegMassShares;
  const Vector3d sum =
      s.motor * motor + s.crank * crank + s.coupler * coupler + s.toe * toe + s.rocker * rocker;
  const double mass = s.motor + s.crank + s.coupler + s.toe + s.rocker;
  return truth.geometry.transducer[static_cast<std::size_t>(k)].inverse() * (sum / mass);
}

TEST(SyntheticLeg, ComIsTheCentroidOfItsLinksInTheTransducerFrame) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  for (int k = 0; k < 6; ++k) {
    for (int i = -10; i <= 30; ++i) {
      const double phi = 0.05 * i;
      EXPECT_LT((truth.leg_com(k, phi) - centroid_of_links(truth, k, phi)).norm(), 1e-14)
          << k << " " << phi;
    }
  }
}

TEST(SyntheticLeg, ComMovesAFewCentimetresInTheLegsPlaneAndIsPeriodic) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix3Xd r(3, 200);
    for (int i = 0; i < 200; ++i) {
      r.col(i) = truth.leg_com(k, i / 200.0);
    }
    const Vector3d span = r.rowwise().maxCoeff() - r.rowwise().minCoeff();
    EXPECT_LT(span.y(), 1e-15);  // lateral: the leg moves in its xz-plane
    EXPECT_GT(span.x(), 0.01);
    EXPECT_GT(span.z(), 0.01);
    EXPECT_LT(span.maxCoeff(), 0.06);
    EXPECT_LT((truth.leg_com(k, 0.3) - truth.leg_com(k, 2.3)).norm(), 1e-12);
  }
}

TEST(SyntheticLeg, ToeAtMidStanceIsTheBigAntToeSeenFromTheNominalTransducer) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  const robots::BigAntLegs legs = robots::bigant_legs();
  for (int k = 0; k < 6; ++k) {
    Vector3d q;
    Vector3d dq;
    robots::bigant_toe(legs, k, 0.1, q, dq);
    const Frame& n = truth.geometry.transducer[static_cast<std::size_t>(k)];
    EXPECT_LT((n * truth.toe(k, 0.1) - q).norm(), 1e-14);
  }
}

// ---- the forward model --------------------------------------------------------------------------

TEST(SyntheticReading, IsTheLegsGravityAndFootForceAboutTheTransducerPlusTheOffset) {
  SynthOptions o;
  o.mounting_rotation = 0.1;
  o.mounting_translation = 0.01;
  const SyntheticTruth truth = synthetic_truth(o);
  const Vector3d down = Vector3d(0.1, -0.2, -1.0).normalized();
  const Vector3d foot(3.0, -2.0, 14.0);
  for (int k = 0; k < 6; ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const Frame t = truth.transducer_frame(k);
    const Wrench w = true_reading(truth, k, 0.37, down, foot) - truth.offset[ks];
    // In B about B's origin: the leg's weight at its CoM and the foot force at its toe.
    const Wrench expected = force_at(truth.weight[ks] * down, t * truth.leg_com(k, 0.37)) +
                            force_at(foot, t * truth.toe(k, 0.37));
    EXPECT_LT((transform_wrench(t, w) - expected).norm(), 1e-12) << k;
  }
}

// ---- hanging ------------------------------------------------------------------------------------

TEST(SyntheticHanging, NoiselessReadingsAreTheSensingModelWithTheRecordsTrueGravity) {
  SynthOptions o = small_options(0.0);
  o.mounting_rotation = 0.08;
  const SyntheticTruth truth = synthetic_truth(o);
  const std::vector<HangingRecord> records = synthetic_hanging(truth, o);
  const std::vector<Vector3d> gravity = synthetic_hanging_gravity(o);
  ASSERT_EQ(records.size(), 4U);
  ASSERT_EQ(gravity.size(), 4U);
  const BodyAxis order[] = {BodyAxis::plus_x, BodyAxis::minus_x, BodyAxis::plus_z,
                            BodyAxis::minus_z};
  for (std::size_t r = 0; r < 4; ++r) {
    const HangingRecord& rec = records[r];
    EXPECT_EQ(rec.down, order[r]);
    EXPECT_NEAR(gravity[r].norm(), 1.0, 1e-15);
    EXPECT_GT(gravity[r].dot(axis_vector(rec.down)), std::cos(0.3));
    EXPECT_GT((gravity[r] - axis_vector(rec.down)).norm(), 1e-4);  // misaligned
    ASSERT_EQ(rec.samples(), 180);
    ASSERT_EQ(rec.wrench.cols(), 36);
    for (Eigen::Index i = 0; i < rec.samples(); ++i) {
      for (int k = 0; k < 6; ++k) {
        const auto ks = static_cast<std::size_t>(k);
        const double phi = rec.phi(i, k);
        EXPECT_DOUBLE_EQ(phi, static_cast<double>(i) / 90.0);  // recorded, not wrapped
        const Vector3d u = truth.transducer_frame(k).R.transpose() * gravity[r];
        const Vector3d f = truth.weight[ks] * u;
        Wrench model;
        model << f, truth.leg_com(k, phi).cross(f);
        model += truth.offset[ks];
        const Wrench got = rec.wrench.block<1, 6>(i, 6 * static_cast<Eigen::Index>(k)).transpose();
        ASSERT_LT((got - model).norm(), 1e-12) << r << " " << i << " " << k;
      }
    }
  }
}

TEST(SyntheticHanging, NoiseHasTheOptionsSigmaAndIsTheSameDrawAtEveryScale) {
  SynthOptions o;
  o.samples_per_cycle = 900;
  o.cycles = 2;
  const SyntheticTruth truth = synthetic_truth(o);
  SynthOptions quiet = o;
  quiet.noise_scale = 0.0;
  SynthOptions loud = o;
  loud.noise_scale = 2.0;
  const auto clean = synthetic_hanging(truth, quiet);
  const auto noisy = synthetic_hanging(truth, o);
  const auto louder = synthetic_hanging(truth, loud);
  std::vector<double> force;
  std::vector<double> torque;
  for (std::size_t r = 0; r < 4; ++r) {
    const Eigen::MatrixXd d = noisy[r].wrench - clean[r].wrench;
    EXPECT_LT((louder[r].wrench - clean[r].wrench - 2.0 * d).cwiseAbs().maxCoeff(), 1e-12);
    for (Eigen::Index c = 0; c < d.cols(); ++c) {
      auto& into = c % 6 < 3 ? force : torque;
      into.insert(into.end(), d.col(c).data(), d.col(c).data() + d.rows());
    }
  }
  const double sf = sample_sigma(Eigen::Map<Eigen::ArrayXd>(force.data(), std::ssize(force)));
  const double st = sample_sigma(Eigen::Map<Eigen::ArrayXd>(torque.data(), std::ssize(torque)));
  EXPECT_NEAR(sf / o.hanging_force_noise, 1.0, 0.03);  // 129,600 draws: 0.2 % standard error
  EXPECT_NEAR(st / o.hanging_torque_noise, 1.0, 0.03);
}

// ---- standing -----------------------------------------------------------------------------------

TEST(SyntheticStanding, EveryNoiselessPoseBalancesTheChassisWithTheTrueFrames) {
  SynthOptions o = small_options(0.0);
  o.poses = 729;
  o.mounting_rotation = 0.08;
  o.mounting_translation = 0.01;
  o.floor_tilt = 0.1;
  const SyntheticTruth truth = synthetic_truth(o);
  const StandingPoses poses = synthetic_poses(truth, o);
  ASSERT_EQ(poses.poses(), 729);
  ASSERT_EQ(poses.attitude.size(), 729U);
  double worst = 0.0;
  for (Eigen::Index p = 0; p < poses.poses(); ++p) {
    // e_p = Σ_k transform(T_k in C, w_k − w_o) + [G_ch ĝ; 0], ĝ = R^W_Cᵀ (0, 0, −1).
    Wrench e = Wrench::Zero();
    e.head<3>() = truth.chassis_weight() *
                  (poses.attitude[static_cast<std::size_t>(p)].transpose() * Vector3d(0, 0, -1));
    for (int k = 0; k < 6; ++k) {
      Frame in_c = truth.transducer_frame(k);
      in_c.p -= truth.chassis_com;
      e += transform_wrench(
          in_c, poses.wrench.block<1, 6>(p, 6 * static_cast<Eigen::Index>(k)).transpose() -
                    truth.offset[static_cast<std::size_t>(k)]);
    }
    worst = std::max(worst, e.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-10);
}

TEST(SyntheticStanding, FeetCarryPositiveLoadsInsideTheFrictionConeAndHoldTheWholeRobot) {
  SynthOptions o = small_options(0.0);
  o.poses = 729;
  o.internal_force = 0.3;
  const SyntheticTruth truth = synthetic_truth(o);
  const SyntheticStanding s = synthetic_standing(truth, o);
  double spread = 0.0;  // how far the forces are from all pointing up: the internal set is there
  for (std::size_t p = 0; p < s.foot_force.size(); ++p) {
    const Eigen::Matrix3Xd& f = s.foot_force[p];
    const Vector3d down = s.attitude[p].transpose() * Vector3d(0, 0, -1);
    Wrench total = Wrench::Zero();
    total.head<3>() = truth.chassis_weight() * down;
    total.tail<3>() = truth.chassis_com.cross(truth.chassis_weight() * down);
    for (int k = 0; k < 6; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const Frame t = truth.transducer_frame(k);
      EXPECT_GT(f(2, k), 0.0);  // body z is the floor normal
      EXPECT_LE(f.col(k).head<2>().norm(), kFrictionCoefficient * f(2, k));
      EXPECT_LT(
          (s.toe[p].col(k) - t * truth.toe(k, s.poses.phi(static_cast<Eigen::Index>(p), k))).norm(),
          1e-15);
      total += force_at(truth.weight[ks] * down,
                        t * truth.leg_com(k, s.poses.phi(static_cast<Eigen::Index>(p), k)));
      total += force_at(f.col(k), s.toe[p].col(k));
      spread = std::max(spread, (f.col(k).normalized() + down).norm());
    }
    EXPECT_LT(total.cwiseAbs().maxCoeff(), 1e-11) << p;
  }
  EXPECT_GT(spread, 0.05);
}

TEST(SyntheticStanding, PosesAreDistinctCombinationsOfThreeShaftAnglesAndAPrefixOfTheFullDraw) {
  SynthOptions few = small_options(1.0);
  few.poses = 50;
  SynthOptions all = few;
  all.poses = 729;
  const SyntheticTruth truth = synthetic_truth(few);
  const StandingPoses a = synthetic_poses(truth, few);
  const StandingPoses b = synthetic_poses(truth, all);
  EXPECT_EQ(a.phi, b.phi.topRows(50));
  EXPECT_EQ(a.wrench, b.wrench.topRows(50));
  std::vector<int> seen(729, 0);
  for (Eigen::Index p = 0; p < b.poses(); ++p) {
    int code = 0;
    for (int k = 5; k >= 0; --k) {
      const double phi = b.phi(p, k);
      ASSERT_TRUE(phi == 0.0 || phi == 0.1 || phi == -0.1) << phi;
      code = 3 * code + static_cast<int>(std::lround(phi / 0.1)) + 1;
    }
    ++seen[static_cast<std::size_t>(code)];
  }
  for (const int count : seen) {
    EXPECT_EQ(count, 1);
  }
}

TEST(SyntheticStanding, NoiseOfReadingsAndAttitudesHasTheOptionsSigma) {
  SynthOptions o;
  o.poses = 729;
  SynthOptions quiet = o;
  quiet.noise_scale = 0.0;
  const SyntheticTruth truth = synthetic_truth(o);
  const SyntheticStanding clean = synthetic_standing(truth, quiet);
  const SyntheticStanding noisy = synthetic_standing(truth, o);
  EXPECT_EQ(clean.attitude, noisy.attitude);  // the truth of the poses does not move with noise
  const Eigen::MatrixXd d = noisy.poses.wrench - clean.poses.wrench;
  std::vector<double> force;
  std::vector<double> torque;
  std::vector<double> angle;
  for (Eigen::Index c = 0; c < d.cols(); ++c) {
    auto& into = c % 6 < 3 ? force : torque;
    into.insert(into.end(), d.col(c).data(), d.col(c).data() + d.rows());
  }
  for (std::size_t p = 0; p < noisy.attitude.size(); ++p) {
    const Vector3d eta = rotation_vector(noisy.attitude[p].transpose() * noisy.poses.attitude[p]);
    angle.insert(angle.end(), eta.data(), eta.data() + 3);
  }
  const auto sigma = [](std::vector<double>& v) {
    return sample_sigma(Eigen::Map<Eigen::ArrayXd>(v.data(), std::ssize(v)));
  };
  EXPECT_NEAR(sigma(force) / o.pose_force_noise, 1.0, 0.04);  // 13,122 draws: 0.6 %
  EXPECT_NEAR(sigma(torque) / o.pose_torque_noise, 1.0, 0.04);
  EXPECT_NEAR(sigma(angle) / o.attitude_noise, 1.0, 0.06);  // 2,187 draws: 1.5 %
}

// ---- determinism and streams --------------------------------------------------------------------

TEST(SyntheticStreams, TheSameSeedGivesTheSameDataAndAnotherSeedOtherData) {
  const SynthOptions o = small_options(1.0);
  SynthOptions other = o;
  other.seed = 2;
  const SyntheticTruth t1 = synthetic_truth(o);
  const SyntheticTruth t2 = synthetic_truth(o);
  const SyntheticTruth t3 = synthetic_truth(other);
  EXPECT_EQ(t1.mounting_rotation, t2.mounting_rotation);
  EXPECT_EQ(t1.mounting_translation, t2.mounting_translation);
  EXPECT_NE(t1.mounting_translation, t3.mounting_translation);
  const auto h1 = synthetic_hanging(t1, o);
  const auto h2 = synthetic_hanging(t2, o);
  const auto h3 = synthetic_hanging(t1, other);
  for (std::size_t r = 0; r < 4; ++r) {
    EXPECT_EQ(h1[r].wrench, h2[r].wrench);
    EXPECT_NE(h1[r].wrench, h3[r].wrench);
  }
  const StandingPoses p1 = synthetic_poses(t1, o);
  const StandingPoses p2 = synthetic_poses(t2, o);
  const StandingPoses p3 = synthetic_poses(t1, other);
  EXPECT_EQ(p1.wrench, p2.wrench);
  EXPECT_EQ(p1.attitude, p2.attitude);
  EXPECT_NE(p1.phi, p3.phi);
}

TEST(SyntheticStreams, TheTruthDoesNotDependOnTheExperimentsOrTheNoise) {
  const SynthOptions base = small_options(1.0);
  SynthOptions changed = base;
  changed.poses = 7;
  changed.cycles = 5;
  changed.samples_per_cycle = 33;
  changed.noise_scale = 3.0;
  changed.hanging_misalignment = 0.1;
  changed.floor_tilt = 0.05;
  const SyntheticTruth a = synthetic_truth(base);
  const SyntheticTruth b = synthetic_truth(changed);
  EXPECT_EQ(a.mounting_rotation, b.mounting_rotation);
  EXPECT_EQ(a.mounting_translation, b.mounting_translation);
  // The hanging directions depend on the hanging stream only.
  EXPECT_EQ(synthetic_hanging_gravity(base), synthetic_hanging_gravity([&] {
              SynthOptions c = changed;
              c.hanging_misalignment = base.hanging_misalignment;
              return c;
            }()));
}

TEST(SyntheticDefaults, GiveFourRecordsOf9000SamplesAnd543PosesOfEveryLeg) {
  const SynthOptions o;
  const auto start = std::chrono::steady_clock::now();
  const SyntheticTruth truth = synthetic_truth(o);
  const std::vector<HangingRecord> records = synthetic_hanging(truth, o);
  const StandingPoses poses = synthetic_poses(truth, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("default synthetic robot generated in %.3f s\n", seconds);
  ASSERT_EQ(records.size(), 4U);
  for (const HangingRecord& r : records) {
    EXPECT_EQ(r.samples(), 9000);
    EXPECT_EQ(r.phi.cols(), 6);
    EXPECT_EQ(r.wrench.cols(), 36);
    EXPECT_TRUE(r.wrench.allFinite());
  }
  EXPECT_EQ(poses.poses(), 543);
  EXPECT_EQ(poses.wrench.cols(), 36);
  EXPECT_EQ(poses.attitude.size(), 543U);
  EXPECT_TRUE(poses.wrench.allFinite());
}

// ---- bad options --------------------------------------------------------------------------------

TEST(SyntheticOptions, EachOutOfRangeValueIsAnInputErrorNamingItsField) {
  const double nan = std::nan("");
  const std::vector<std::pair<std::string, std::function<void(SynthOptions&)>>> cases = {
      {"synth.cycles", [](SynthOptions& o) { o.cycles = 0; }},
      {"synth.cycles", [](SynthOptions& o) { o.cycles = 101; }},
      {"synth.samples_per_cycle", [](SynthOptions& o) { o.samples_per_cycle = 7; }},
      {"synth.samples_per_cycle", [](SynthOptions& o) { o.samples_per_cycle = 100001; }},
      {"synth.samples_per_cycle",
       [](SynthOptions& o) { o.cycles = 100, o.samples_per_cycle = 20000; }},
      {"synth.poses", [](SynthOptions& o) { o.poses = 0; }},
      {"synth.poses", [](SynthOptions& o) { o.poses = 730; }},
      {"synth.noise_scale", [](SynthOptions& o) { o.noise_scale = -1.0; }},
      {"synth.noise_scale", [nan](SynthOptions& o) { o.noise_scale = nan; }},
      {"synth.hanging_force_noise", [](SynthOptions& o) { o.hanging_force_noise = -0.1; }},
      {"synth.hanging_torque_noise", [](SynthOptions& o) { o.hanging_torque_noise = HUGE_VAL; }},
      {"synth.pose_force_noise", [nan](SynthOptions& o) { o.pose_force_noise = nan; }},
      {"synth.pose_torque_noise", [](SynthOptions& o) { o.pose_torque_noise = -1e-9; }},
      {"synth.hanging_misalignment", [](SynthOptions& o) { o.hanging_misalignment = 0.3; }},
      {"synth.attitude_noise", [](SynthOptions& o) { o.attitude_noise = -0.01; }},
      {"synth.floor_tilt", [](SynthOptions& o) { o.floor_tilt = 0.5; }},
      {"synth.mounting_rotation", [nan](SynthOptions& o) { o.mounting_rotation = nan; }},
      {"synth.mounting_translation", [](SynthOptions& o) { o.mounting_translation = 0.05; }},
      {"synth.internal_force", [](SynthOptions& o) { o.internal_force = 1.5; }},
  };
  for (const auto& [field, spoil] : cases) {
    SynthOptions o;
    spoil(o);
    try {
      validate(o);
      ADD_FAILURE() << field << " was accepted";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), field) << e.what();
    }
    EXPECT_THROW((void)synthetic_truth(o), core::InputError) << field;
  }
  EXPECT_NO_THROW(validate(SynthOptions{}));
}

TEST(SyntheticTruth, RefusesALegOutsideTheRobot) {
  const SyntheticTruth truth = synthetic_truth(SynthOptions{});
  EXPECT_THROW((void)truth.leg_com(6, 0.0), core::InputError);
  EXPECT_THROW((void)truth.transducer_frame(-1), core::InputError);
}

}  // namespace
}  // namespace slipwalk::calibration
