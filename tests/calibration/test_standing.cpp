// The standing stage (§4.3.2, §4.4.2) against a forward model written here: per pose, random leg
// wrenches made to balance the chassis exactly through the TRUE transducer frames (the last leg
// closes the balance), read through the offsets, with or without noise; attitudes tilted a few
// degrees. Oracles: exact recovery on noiseless data by both solvers, the solvers' agreement, the
// models' nesting, the BIC formula, the multistart's common minimum, the z-scores' spread over
// seeds, the naive tare's closed form, and the bad inputs.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "calibration/standing.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr int kLegs = 6;
constexpr double kRobotWeight = 80.0;

// ---- the forward model
// ---------------------------------------------------------------------------

class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng_() >> 11U) * 0x1.0p-53);
  }
  double normal() {  // Box–Muller
    const double u1 = 1.0 - uniform(0.0, 1.0);
    const double u2 = uniform(0.0, 1.0);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  Vector3d vector(double half) {
    return {uniform(-half, half), uniform(-half, half), uniform(-half, half)};
  }
  Matrix3d rotation(double max_angle) {
    return rotation_from_vector(vector(max_angle / std::sqrt(3.0)));
  }

 private:
  std::mt19937_64 rng_;
};

struct Truth {
  std::vector<Matrix3d> rotation;      // R̃_k
  std::vector<Vector3d> displacement;  // u_k
};

struct Scenario {
  Geometry geometry;
  HangingCalibration hanging;
  Truth truth;
  StandingPoses poses;
};

Geometry bigant_like() {
  Geometry g;
  g.legs = {"HL", "ML", "FL", "HR", "MR", "FR"};
  const double x[3] = {-0.3, 0.0, 0.3};
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < 3; ++i) {
      Frame f;
      f.p = Vector3d(x[i], side == 0 ? 0.18 : -0.18, 0.04);
      // Right transducers mounted mirrored (turned by π about z), so the nominal frames differ.
      f.R = side == 0 ? Matrix3d::Identity()
                      : Eigen::AngleAxisd(std::numbers::pi, Vector3d::UnitZ()).toRotationMatrix();
      g.transducer.push_back(f);
    }
  }
  g.robot_weight = kRobotWeight;
  return g;
}

struct ScenarioOptions {
  Eigen::Index poses = 60;
  double force_noise = 0.0;   // N
  double torque_noise = 0.0;  // N·m
  bool mounting_errors = true;
  bool shared_truth = false;   // R̃ = I and one u: the com_only truth
  bool rotation_truth = true;  // with shared_truth: R̃ drawn too (the shared_translation truth)
  bool displacement_truth = true;
  BalanceTarget target = BalanceTarget::chassis;
  double max_tilt = 0.08;  // rad
};

/// The balance of standing.hpp evaluated with the true frames (written out again here with
/// transform_wrench, the independent statement).
Scenario make_scenario(std::uint64_t seed, const ScenarioOptions& o = {}) {
  Draw draw(seed);
  Scenario s;
  s.geometry = bigant_like();
  s.hanging.legs.resize(kLegs);
  for (auto& leg : s.hanging.legs) {
    leg.offset << draw.vector(3.0), draw.vector(0.3);
    leg.weight = draw.uniform(6.0, 6.4);
    leg.com.coefficients = Eigen::Matrix3Xd::Zero(3, 3);
    leg.com.coefficients.col(0) = Vector3d(0.0, 0.0, -0.12) + draw.vector(0.02);
    leg.com.coefficients.col(1) = draw.vector(0.02);
    leg.com.coefficients.col(2) = draw.vector(0.02);
  }
  double legs_weight = 0.0;
  for (const auto& leg : s.hanging.legs) {
    legs_weight += leg.weight;
  }
  const double chassis_weight = kRobotWeight - legs_weight;
  const Vector3d shared_u = draw.vector(0.05);
  for (int k = 0; k < kLegs; ++k) {
    const bool free = o.mounting_errors && o.rotation_truth;
    s.truth.rotation.push_back(free ? draw.rotation(0.06) : Matrix3d::Identity());
    s.truth.displacement.push_back(
        o.shared_truth
            ? shared_u
            : (o.mounting_errors && o.displacement_truth ? draw.vector(0.05) : Vector3d::Zero()));
  }
  std::vector<Frame> frame(kLegs);  // true transducer frames in C
  for (int k = 0; k < kLegs; ++k) {
    frame[k].R = s.geometry.transducer[k].R * s.truth.rotation[k];
    frame[k].p = s.geometry.transducer[k].p + s.truth.displacement[k];
  }
  s.poses.phi.resize(o.poses, kLegs);
  s.poses.wrench.resize(o.poses, Eigen::Index{6} * kLegs);
  s.poses.source = "test poses";
  for (Eigen::Index p = 0; p < o.poses; ++p) {
    const Matrix3d attitude =
        Eigen::AngleAxisd(draw.uniform(-3.0, 3.0), Vector3d::UnitZ()).toRotationMatrix() *
        rotation_from_vector(Vector3d(draw.uniform(-o.max_tilt, o.max_tilt),
                                      draw.uniform(-o.max_tilt, o.max_tilt), 0.0));
    s.poses.attitude.push_back(attitude);
    const Vector3d down = attitude.transpose() * Vector3d(0.0, 0.0, -1.0);
    Wrench total = Wrench::Zero();
    total.head<3>() = chassis_weight * down;
    std::vector<Wrench> in_c(kLegs);
    for (int k = 0; k < kLegs; ++k) {
      s.poses.phi(p, k) = draw.uniform(0.0, 1.0);
      if (k + 1 < kLegs) {
        in_c[k] << -chassis_weight / kLegs * down * draw.uniform(0.5, 1.5) + draw.vector(3.0),
            draw.vector(1.5);
        total += in_c[k];
      }
      if (o.target == BalanceTarget::thesis_literal) {  // the legs' gravity moment about C
        const Vector3d x = frame[k] * s.hanging.legs[k].com(s.poses.phi(p, k));
        total.tail<3>() -= x.cross(s.hanging.legs[k].weight * down);
      }
    }
    in_c[kLegs - 1] = -total;
    for (int k = 0; k < kLegs; ++k) {
      Wrench reading = transform_wrench(frame[k].inverse(), in_c[k]) + s.hanging.legs[k].offset;
      for (int i = 0; i < 3; ++i) {
        reading(i) += o.force_noise * draw.normal();
        reading(3 + i) += o.torque_noise * draw.normal();
      }
      s.poses.wrench.row(p).segment<6>(Eigen::Index{6} * k) = reading.transpose();
    }
  }
  return s;
}

double max_rotation_error(const MountingEstimate& e, const Truth& t) {
  double worst = 0.0;
  for (int k = 0; k < kLegs; ++k) {
    worst = std::max(worst, (e.rotation[k] - t.rotation[k]).cwiseAbs().maxCoeff());
  }
  return worst;
}
double max_displacement_error(const MountingEstimate& e, const Truth& t) {
  double worst = 0.0;
  for (int k = 0; k < kLegs; ++k) {
    worst = std::max(worst, (e.displacement[k] - t.displacement[k]).cwiseAbs().maxCoeff());
  }
  return worst;
}

MountingOptions with(MountingModel model, MountingSolver solver,
                     BalanceTarget target = BalanceTarget::chassis) {
  MountingOptions o;
  o.model = model;
  o.solver = solver;
  o.target = target;
  return o;
}

// ---- exact recovery
// ------------------------------------------------------------------------------

TEST(Standing, BothSolversRecoverTheMountingExactlyFromNoiselessPoses) {
  const Scenario s = make_scenario(1);
  for (const MountingSolver solver : {MountingSolver::alternating, MountingSolver::ceres_so3}) {
    SCOPED_TRACE(std::string(solver_label(solver)));
    const MountingEstimate e =
        fit_mounting(s.geometry, s.poses, s.hanging, with(MountingModel::full, solver));
    EXPECT_TRUE(e.converged);
    EXPECT_LT(max_rotation_error(e, s.truth), 1e-8);
    EXPECT_LT(max_displacement_error(e, s.truth), 1e-8);
    EXPECT_LT(e.rss, 1e-14);
    EXPECT_EQ(e.dof, 36);
    EXPECT_EQ(e.poses, 60);
    EXPECT_GT(e.smallest_singular_value, 0.0);
  }
}

TEST(Standing, TheLiteralTargetRecoversTheMountingOfPosesThatBalanceItsWay) {
  ScenarioOptions o;
  o.target = BalanceTarget::thesis_literal;
  const Scenario s = make_scenario(2, o);
  for (const MountingSolver solver : {MountingSolver::alternating, MountingSolver::ceres_so3}) {
    SCOPED_TRACE(std::string(solver_label(solver)));
    const MountingEstimate e =
        fit_mounting(s.geometry, s.poses, s.hanging,
                     with(MountingModel::full, solver, BalanceTarget::thesis_literal));
    EXPECT_LT(max_rotation_error(e, s.truth), 1e-8);
    EXPECT_LT(max_displacement_error(e, s.truth), 1e-8);
  }
  // The chassis balance cannot absorb the legs' moment: it leaves a residual on the same poses.
  const MountingEstimate chassis = fit_mounting(
      s.geometry, s.poses, s.hanging, with(MountingModel::full, MountingSolver::ceres_so3));
  EXPECT_GT(chassis.rss, 1e-3);
}

TEST(Standing, TheComOnlyModelRecoversASharedDisplacementInOneLinearSolve) {
  ScenarioOptions o;
  o.shared_truth = true;
  o.rotation_truth = false;
  const Scenario s = make_scenario(3, o);
  const MountingEstimate e = fit_mounting(
      s.geometry, s.poses, s.hanging, with(MountingModel::com_only, MountingSolver::alternating));
  EXPECT_EQ(e.iterations, 1);
  EXPECT_LT(max_displacement_error(e, s.truth), 1e-10);
  EXPECT_LT(max_rotation_error(e, s.truth), 1e-15);
}

TEST(Standing, EveryModelRecoversATruthOfItsOwnFormByBothSolvers) {
  struct Case {
    MountingModel model;
    bool shared;
    bool rotations;
  };
  for (const Case c : {Case{MountingModel::shared_translation, true, true},
                       Case{MountingModel::translations_only, false, false},
                       Case{MountingModel::com_only, true, false}}) {
    ScenarioOptions o;
    o.shared_truth = c.shared;
    o.rotation_truth = c.rotations;
    const Scenario s = make_scenario(13, o);
    for (const MountingSolver solver : {MountingSolver::alternating, MountingSolver::ceres_so3}) {
      SCOPED_TRACE(std::string(model_label(c.model)) + " " + std::string(solver_label(solver)));
      const MountingEstimate e =
          fit_mounting(s.geometry, s.poses, s.hanging, with(c.model, solver));
      EXPECT_TRUE(e.converged);
      EXPECT_LT(max_rotation_error(e, s.truth), 1e-8);
      EXPECT_LT(max_displacement_error(e, s.truth), 1e-8);
      EXPECT_EQ(e.dof, model_dof(c.model, kLegs));
      for (int k = 0; k < kLegs; ++k) {  // what the model fixes carries no error
        if (!c.rotations) {
          EXPECT_EQ(e.rotation_se[k], Vector3d::Zero());
        }
        if (c.shared) {
          EXPECT_EQ(e.displacement[k], e.displacement[0]);
          EXPECT_EQ(e.displacement_se[k], e.displacement_se[0]);
        }
      }
    }
  }
}

// ---- the solvers agree
// ---------------------------------------------------------------------------

TEST(Standing, TheAlternatingAndJointSolversReachTheSameMinimumOnNoisyPoses) {
  ScenarioOptions o;
  o.force_noise = 0.2;
  o.torque_noise = 0.02;
  const Scenario s = make_scenario(4, o);
  for (const MountingModel model : kMountingModels) {
    SCOPED_TRACE(std::string(model_label(model)));
    const MountingEstimate a =
        fit_mounting(s.geometry, s.poses, s.hanging, with(model, MountingSolver::alternating));
    const MountingEstimate c =
        fit_mounting(s.geometry, s.poses, s.hanging, with(model, MountingSolver::ceres_so3));
    EXPECT_NEAR(a.rss, c.rss, 1e-8 * c.rss);
    for (int k = 0; k < kLegs; ++k) {
      // Within a thousandth of a standard error (the gauge of standing.hpp leaves the yaw of every
      // transducer together weakly determined, so absolute agreement follows the conditioning).
      const Vector3d dtheta = rotation_vector(c.rotation[k].transpose() * a.rotation[k]);
      EXPECT_LE(dtheta.norm(), 1e-3 * c.rotation_se[k].norm());
      EXPECT_LE((a.displacement[k] - c.displacement[k]).norm(), 1e-3 * c.displacement_se[k].norm());
      EXPECT_LE((a.rotation_se[k] - c.rotation_se[k]).norm(), 1e-3 * c.rotation_se[k].norm());
    }
  }
}

// ---- residuals
// -----------------------------------------------------------------------------------

TEST(Standing, BalanceResidualsAreZeroAtTheTruthAndTheirKNormIsTheRss) {
  ScenarioOptions o;
  o.force_noise = 0.2;
  o.torque_noise = 0.02;
  const Scenario clean = make_scenario(5);
  MountingEstimate truth;
  truth.rotation = clean.truth.rotation;
  truth.displacement = clean.truth.displacement;
  EXPECT_LT(
      balance_residuals(clean.geometry, clean.poses, clean.hanging, truth).cwiseAbs().maxCoeff(),
      1e-11);

  const Scenario noisy = make_scenario(5, o);
  const MountingEstimate e = fit_mounting(noisy.geometry, noisy.poses, noisy.hanging,
                                          with(MountingModel::full, MountingSolver::ceres_so3));
  const Eigen::MatrixXd r = balance_residuals(noisy.geometry, noisy.poses, noisy.hanging, e);
  ASSERT_EQ(r.rows(), 60);
  ASSERT_EQ(r.cols(), 6);
  const double k_norm = r.leftCols<3>().squaredNorm() + 10.0 * r.rightCols<3>().squaredNorm();
  EXPECT_NEAR(k_norm, e.rss, 1e-9 * e.rss);
}

TEST(Standing, TheNaiveTareOfAnUprightRobotLeavesExactlyTheLegsGravityMoment) {
  // No mounting error, C at B's origin, upright poses, an air record at one shaft angle: its mean
  // is offset + leg gravity, so the naive sum is the ground wrench, whose force is G_robot up and
  // whose moment about C balances the legs' gravity: Σ_k x_k × m_k g ẑ remains (in W).
  ScenarioOptions o;
  o.mounting_errors = false;
  o.max_tilt = 0.0;
  const Scenario s = make_scenario(6, o);  // tilt 0: only the heading turns C in W
  HangingRecord air;
  air.down = BodyAxis::minus_z;
  const int n = 50;
  air.phi.resize(n, kLegs);
  air.wrench.resize(n, Eigen::Index{6} * kLegs);
  Vector3d moment = Vector3d::Zero();
  for (int k = 0; k < kLegs; ++k) {
    const Frame& nk = s.geometry.transducer[k];
    const Vector3d u = nk.R.transpose() * Vector3d(0, 0, -1);
    const Vector3d r = s.hanging.legs[k].com(0.0);
    const Wrench reading = s.hanging.legs[k].offset + force_at(s.hanging.legs[k].weight * u, r);
    for (int i = 0; i < n; ++i) {
      air.phi(i, k) = 0.1 * i;
      air.wrench.row(i).segment<6>(Eigen::Index{6} * k) = reading.transpose();
    }
    moment += (nk * r).cross(s.hanging.legs[k].weight * Vector3d::UnitZ());
  }
  const Eigen::MatrixXd naive = naive_residuals(s.geometry, s.poses, air);
  for (Eigen::Index p = 0; p < naive.rows(); ++p) {
    EXPECT_LT(naive.row(p).head<3>().norm(), 1e-10);
    EXPECT_LT((naive.row(p).tail<3>().transpose() - s.poses.attitude[p] * moment).norm(), 1e-10);
  }
}

// ---- models
// --------------------------------------------------------------------------------------

TEST(Standing, TheModelsNestTheirResidualsAndTheBicFollowsItsFormula) {
  ScenarioOptions o;
  o.force_noise = 0.05;  // the mounting errors stand well above the noise: full wins BIC too
  o.torque_noise = 0.005;
  const Scenario s = make_scenario(7, o);
  const std::vector<ModelScore> scores = score_models(
      s.geometry, s.poses, s.hanging, with(MountingModel::full, MountingSolver::ceres_so3), 5, 3);
  ASSERT_EQ(scores.size(), 4U);
  const auto rss = [&](MountingModel m) {
    for (const auto& score : scores) {
      if (score.model == m) {
        return score.rss;
      }
    }
    return -1.0;
  };
  const double slack = 1e-9 * rss(MountingModel::com_only);
  EXPECT_LE(rss(MountingModel::full), rss(MountingModel::shared_translation) + slack);
  EXPECT_LE(rss(MountingModel::shared_translation), rss(MountingModel::com_only) + slack);
  EXPECT_LE(rss(MountingModel::full), rss(MountingModel::translations_only) + slack);
  EXPECT_LE(rss(MountingModel::translations_only), rss(MountingModel::com_only) + slack);
  const double p = 60.0;
  for (const auto& score : scores) {
    SCOPED_TRACE(std::string(model_label(score.model)));
    EXPECT_EQ(score.dof, model_dof(score.model, kLegs));
    EXPECT_NEAR(score.bic, p * std::log(score.rss / p) + score.dof * std::log(p), 1e-9);
    EXPECT_GT(score.cv_mse, score.rss / p);  // held-out poses fit worse than the training ones
  }
  // The truth has every mounting error: the full model wins both criteria.
  for (const auto& score : scores) {
    if (score.model != MountingModel::full) {
      EXPECT_GT(score.bic, scores[0].bic);
      EXPECT_GT(score.cv_mse, scores[0].cv_mse);
    }
  }
  const std::vector<ModelScore> again =
      score_models(s.geometry, s.poses, s.hanging,
                   with(MountingModel::com_only, MountingSolver::ceres_so3), 5, 3);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    EXPECT_DOUBLE_EQ(again[i].cv_mse, scores[i].cv_mse);  // seeded folds; options.model ignored
  }
}

TEST(Standing, BicPicksTheComOnlyModelWhenTheTruthIsAShiftedCentreOfMass) {
  ScenarioOptions o;
  o.shared_truth = true;
  o.rotation_truth = false;
  o.force_noise = 0.2;
  o.torque_noise = 0.02;
  const Scenario s = make_scenario(8, o);
  const std::vector<ModelScore> scores = score_models(
      s.geometry, s.poses, s.hanging, with(MountingModel::full, MountingSolver::ceres_so3));
  for (const auto& score : scores) {
    if (score.model != MountingModel::com_only) {
      EXPECT_GT(score.bic, scores[3].bic) << model_label(score.model);
    }
  }
}

// ---- multistart
// ----------------------------------------------------------------------------------

TEST(Standing, StartsFifteenDegreesAwayReachTheSameMinimum) {
  ScenarioOptions o;
  o.force_noise = 0.2;
  o.torque_noise = 0.02;
  const Scenario s = make_scenario(9, o);
  for (const MountingSolver solver : {MountingSolver::alternating, MountingSolver::ceres_so3}) {
    SCOPED_TRACE(std::string(solver_label(solver)));
    const std::vector<MountingEstimate> fits =
        multistart(s.geometry, s.poses, s.hanging, with(MountingModel::full, solver), 3, 11);
    ASSERT_EQ(fits.size(), 3U);
    for (const auto& fit : fits) {
      EXPECT_TRUE(fit.converged);
      EXPECT_NEAR(fit.rss, fits[0].rss, 1e-8 * fits[0].rss);
      for (int k = 0; k < kLegs; ++k) {
        const Vector3d dtheta = rotation_vector(fits[0].rotation[k].transpose() * fit.rotation[k]);
        EXPECT_LE(dtheta.norm(), 1e-3 * fits[0].rotation_se[k].norm());
        EXPECT_LE((fit.displacement[k] - fits[0].displacement[k]).norm(),
                  1e-3 * fits[0].displacement_se[k].norm());
      }
    }
  }
}

// ---- standard errors
// -----------------------------------------------------------------------------

// The force noise also sits in the regressors (errors in variables, standing.hpp): its O(σ_f²)
// attenuation of the displacements does not shrink with poses, so the z-scores' spread is checked
// where the noise, not that bias, dominates (60 poses; with torque noise only the spread is 1.0 on
// 543 poses as well).
TEST(Standing, TheSandwichStandardErrorsMatchTheScatterOverSeeds) {
  ScenarioOptions o;
  o.force_noise = 0.3;
  o.torque_noise = 0.03;
  std::vector<double> z;
  for (std::uint64_t seed = 100; seed < 130; ++seed) {
    const Scenario s = make_scenario(seed, o);
    const MountingEstimate e = fit_mounting(s.geometry, s.poses, s.hanging,
                                            with(MountingModel::full, MountingSolver::ceres_so3));
    for (int k = 0; k < kLegs; ++k) {
      const Vector3d dtheta = rotation_vector(s.truth.rotation[k].transpose() * e.rotation[k]);
      const Vector3d du = e.displacement[k] - s.truth.displacement[k];
      for (int i = 0; i < 3; ++i) {
        z.push_back(dtheta(i) / e.rotation_se[k](i));
        z.push_back(du(i) / e.displacement_se[k](i));
      }
    }
  }
  double mean = 0.0;
  for (const double v : z) {
    mean += v;
  }
  mean /= static_cast<double>(z.size());
  double var = 0.0;
  for (const double v : z) {
    var += (v - mean) * (v - mean);
  }
  const double sd = std::sqrt(var / static_cast<double>(z.size() - 1));
  RecordProperty("z_sd", std::to_string(sd));
  EXPECT_GT(sd, 0.7);
  EXPECT_LT(sd, 1.4);
  EXPECT_LT(std::abs(mean), 0.2);
}

TEST(Standing, TheErrorsInVariablesCorrectionRemovesTheForceNoisesAttenuation) {
  // Force noise well above the torque noise and many poses: the plain fit's displacement errors
  // are dominated by the attenuation, the corrected fit's by the scatter its SE states.
  ScenarioOptions o;
  o.poses = 200;
  o.force_noise = 0.6;
  o.torque_noise = 0.01;
  double plain = 0.0;
  double corrected = 0.0;
  double estimated = 0.0;
  double variance_sum = 0.0;
  int n = 0;
  constexpr int kSeeds = 6;
  for (std::uint64_t seed = 200; seed < 200 + kSeeds; ++seed) {
    const Scenario s = make_scenario(seed, o);
    MountingOptions options = with(MountingModel::full, MountingSolver::ceres_so3);
    const MountingEstimate a = fit_mounting(s.geometry, s.poses, s.hanging, options);
    options.force_noise_variance = o.force_noise * o.force_noise;
    const MountingEstimate b = fit_mounting(s.geometry, s.poses, s.hanging, options);
    options.force_noise_variance = -1.0;
    const MountingEstimate c = fit_mounting(s.geometry, s.poses, s.hanging, options);
    variance_sum += c.force_noise_variance;
    for (int k = 0; k < kLegs; ++k) {
      for (int i = 0; i < 3; ++i) {
        const auto z = [&](const MountingEstimate& e) {
          const double dz =
              (e.displacement[k](i) - s.truth.displacement[k](i)) / e.displacement_se[k](i);
          return dz * dz;
        };
        plain += z(a);
        corrected += z(b);
        estimated += z(c);
        ++n;
      }
    }
  }
  plain = std::sqrt(plain / n);
  corrected = std::sqrt(corrected / n);
  estimated = std::sqrt(estimated / n);
  EXPECT_GT(plain, 1.4);
  EXPECT_GT(corrected, 0.8);
  EXPECT_LT(corrected, 1.25);
  EXPECT_GT(estimated, 0.8);
  EXPECT_LT(estimated, 1.25);
  EXPECT_NEAR(variance_sum / kSeeds, o.force_noise * o.force_noise,
              0.05 * o.force_noise * o.force_noise);
  RecordProperty("z_rms_plain", std::to_string(plain));
  RecordProperty("z_rms_corrected", std::to_string(corrected));
}

// ---- bad inputs
// ----------------------------------------------------------------------------------

TEST(Standing, BadInputsAreRefusedNamingWhere) {
  const Scenario good = make_scenario(10);
  const MountingOptions options;
  const auto message = [&](const StandingPoses& poses) {
    try {
      (void)fit_mounting(good.geometry, poses, good.hanging, options);
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  StandingPoses p = good.poses;
  p.rows.assign(60, "poses.csv:9");
  p.rows[7] = "poses.csv:9";
  p.wrench(7, 3) = std::nan("");
  EXPECT_NE(message(p).find("poses.csv:9"), std::string::npos);
  p = good.poses;
  p.attitude[4](0, 0) = 2.0;
  EXPECT_NE(message(p).find("pose 5"), std::string::npos);
  p = good.poses;
  p.wrench.conservativeResize(Eigen::NoChange, 30);
  EXPECT_NE(message(p).find("test poses"), std::string::npos);
  p = good.poses;
  p.phi.conservativeResize(6, Eigen::NoChange);
  p.wrench.conservativeResize(6, Eigen::NoChange);
  p.attitude.resize(6);
  EXPECT_NE(message(p).find("needs at least 7 poses"), std::string::npos);

  MountingOptions bad;
  bad.torque_weight = 0.0;
  EXPECT_THROW(validate(bad), core::InputError);
  bad = {};
  bad.tolerance = 1.0;
  EXPECT_THROW(validate(bad), core::InputError);
  bad = {};
  bad.max_iterations = 0;
  EXPECT_THROW(validate(bad), core::InputError);
  bad = {};
  bad.force_noise_variance = std::numeric_limits<double>::infinity();
  EXPECT_THROW(validate(bad), core::InputError);

  MountingStart start;
  start.rotation.assign(5, Matrix3d::Identity());
  EXPECT_THROW((void)fit_mounting(good.geometry, good.poses, good.hanging, options, start),
               core::InputError);
  HangingCalibration heavy = good.hanging;
  heavy.legs[0].weight = 100.0;
  EXPECT_THROW((void)fit_mounting(good.geometry, good.poses, heavy, options), core::InputError);
  EXPECT_THROW((void)score_models(good.geometry, good.poses, good.hanging, options, 1),
               core::InputError);
  EXPECT_THROW((void)multistart(good.geometry, good.poses, good.hanging, options, 0),
               core::InputError);
}

TEST(Standing, LabelsAndDegreesOfFreedomAreTableFourTwos) {
  EXPECT_EQ(model_dof(MountingModel::full, 6), 36);
  EXPECT_EQ(model_dof(MountingModel::shared_translation, 6), 21);
  EXPECT_EQ(model_dof(MountingModel::translations_only, 6), 18);
  EXPECT_EQ(model_dof(MountingModel::com_only, 6), 3);
  EXPECT_EQ(model_label(MountingModel::shared_translation), "shared_translation");
  EXPECT_EQ(solver_label(MountingSolver::ceres_so3), "ceres_so3");
}

}  // namespace
}  // namespace slipwalk::calibration
