// §4.3.2 and §4.4.2 (standing.hpp states the balance, the models and the covariance): the inputs'
// checks, the fit's bookkeeping, the residuals, Table 4.2's scores and the multistart. The solvers
// are in standing_solvers.cpp.
//
// Model selection. BIC = P ln(RSS/P) + DOF ln P counts a pose as one observation (its six
// components are not independent draws: they share the pose's legs), as the thesis' Table 4.2.
// The cross-validation shuffles the poses once with a seeded std::mt19937_64 and our own
// arithmetic (Fisher–Yates with j = ⌊U (i + 1)⌋, U from the top 53 bits), cuts them into `folds`
// nearly equal folds and uses the same folds for every model, so that the models' CV errors differ
// by the models only.
#include "calibration/standing.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "calibration/standing_solvers.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {

namespace {

using standing_detail::BalanceData;

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11U) * 0x1.0p-53; }

std::string pose_where(const StandingPoses& poses, Eigen::Index p) {
  if (static_cast<Eigen::Index>(poses.rows.size()) > p) {
    return poses.rows[static_cast<std::size_t>(p)];
  }
  return (poses.source.empty() ? std::string("poses") : poses.source) + " pose " +
         std::to_string(p + 1);
}

bool is_rotation(const Eigen::Matrix3d& r, double tolerance) {
  return r.allFinite() && (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() <= tolerance &&
         r.determinant() > 0.0;
}

void check_start(const MountingStart& start, int legs) {
  if (!start.rotation.empty()) {
    if (static_cast<int>(start.rotation.size()) != legs) {
      throw core::InputError("mounting.start.rotation",
                             "has " + std::to_string(start.rotation.size()) + " rotations for " +
                                 std::to_string(legs) + " legs");
    }
    for (const auto& r : start.rotation) {
      if (!is_rotation(r, 1e-9)) {
        throw core::InputError("mounting.start.rotation", "holds a matrix that is not a rotation");
      }
    }
  }
  if (!start.displacement.empty()) {
    if (static_cast<int>(start.displacement.size()) != legs) {
      throw core::InputError("mounting.start.displacement",
                             "has " + std::to_string(start.displacement.size()) +
                                 " displacements for " + std::to_string(legs) + " legs");
    }
    for (const auto& u : start.displacement) {
      if (!u.allFinite()) {
        throw core::InputError("mounting.start.displacement", "is not finite");
      }
    }
  }
}

MountingEstimate fit_prepared(const BalanceData& data, const MountingOptions& options,
                              const MountingStart& start) {
  const int dof = model_dof(options.model, data.legs);
  const auto poses = static_cast<Eigen::Index>(data.poses.size());
  if (poses < dof / 6 + 1) {
    throw core::InputError("poses", "the " + std::string(model_label(options.model)) + " model (" +
                                        std::to_string(dof) + " parameters) needs at least " +
                                        std::to_string(dof / 6 + 1) + " poses, got " +
                                        std::to_string(poses));
  }
  const auto begin = std::chrono::steady_clock::now();
  standing_detail::SolveResult solved =
      options.solver == MountingSolver::alternating
          ? standing_detail::solve_alternating(data, options.model, options, start)
          : standing_detail::solve_joint(data, options.model, options, start);
  double variance = options.force_noise_variance;
  if (variance < 0.0) {
    variance = standing_detail::estimate_force_noise_variance(data, solved, dof);
  }
  if (variance > 0.0 &&
      !standing_detail::correct_errors_in_variables(data, options.model, variance, solved)) {
    variance = 0.0;  // the correction is undefined here: the plain fit stands, and says so
  }
  const auto end = std::chrono::steady_clock::now();
  MountingEstimate estimate;
  estimate.force_noise_variance = variance;
  estimate.model = options.model;
  estimate.solver = options.solver;
  estimate.target = options.target;
  estimate.rotation = solved.rotation;
  estimate.displacement = solved.displacement;
  estimate.chassis_weight = data.chassis_weight;
  estimate.rss = standing_detail::weighted_rss(data, solved.rotation, solved.displacement);
  if (!std::isfinite(estimate.rss)) {
    throw core::ComputationError("standing: the fit's residual is not finite");
  }
  estimate.poses = poses;
  estimate.dof = dof;
  estimate.iterations = solved.iterations;
  estimate.converged = solved.converged;
  estimate.seconds = std::chrono::duration<double>(end - begin).count();
  standing_detail::standard_errors(data, estimate);
  return estimate;
}

}  // namespace

namespace standing_detail {

BalanceData prepare(const Geometry& geometry, const StandingPoses& poses,
                    const HangingCalibration& hanging, const MountingOptions& options) {
  validate(geometry);
  validate(options);
  const int legs = geometry.size();
  if (static_cast<int>(hanging.legs.size()) != legs) {
    throw core::InputError("hanging", "has " + std::to_string(hanging.legs.size()) +
                                          " legs, the geometry " + std::to_string(legs));
  }
  BalanceData data;
  data.legs = legs;
  data.target = options.target;
  data.sqrt_kappa = std::sqrt(options.torque_weight);
  double legs_weight = 0.0;
  for (int k = 0; k < legs; ++k) {
    const LegEstimate& leg = hanging.legs[static_cast<std::size_t>(k)];
    if (!std::isfinite(leg.weight) || leg.weight <= 0.0 || !leg.offset.allFinite() ||
        !leg.com.coefficients.allFinite()) {
      throw core::InputError("hanging[" + geometry.legs[static_cast<std::size_t>(k)] + "]",
                             "needs a positive weight and finite offsets and centre of mass");
    }
    data.nominal_rotation.push_back(geometry.transducer[static_cast<std::size_t>(k)].R);
    data.nominal_position.push_back(geometry.transducer[static_cast<std::size_t>(k)].p);
    data.leg_weight.push_back(leg.weight);
    legs_weight += leg.weight;
  }
  data.chassis_weight = geometry.robot_weight - legs_weight;
  if (!(data.chassis_weight > 0.0)) {
    throw core::InputError("geometry.robot_weight", "is not more than the legs' weights together");
  }
  const Eigen::Index count = poses.poses();
  if (poses.wrench.rows() != count || poses.wrench.cols() != Eigen::Index{6} * legs ||
      poses.phi.cols() != legs || static_cast<Eigen::Index>(poses.attitude.size()) != count) {
    throw core::InputError(poses.source.empty() ? "poses" : poses.source,
                           "needs " + std::to_string(legs) + " shaft angles, " +
                               std::to_string(6 * legs) +
                               " wrench columns and an attitude per pose");
  }
  data.poses.resize(static_cast<std::size_t>(count));
  for (Eigen::Index p = 0; p < count; ++p) {
    if (!poses.phi.row(p).allFinite() || !poses.wrench.row(p).allFinite()) {
      throw core::InputError(pose_where(poses, p), "holds a value that is not finite");
    }
    const Eigen::Matrix3d& attitude = poses.attitude[static_cast<std::size_t>(p)];
    if (!is_rotation(attitude, 1e-6)) {
      throw core::InputError(pose_where(poses, p), "has an attitude that is not a rotation");
    }
    standing_detail::PoseTerms& terms = data.poses[static_cast<std::size_t>(p)];
    terms.force.resize(3, legs);
    terms.torque.resize(3, legs);
    terms.com.resize(3, legs);
    for (int k = 0; k < legs; ++k) {
      const LegEstimate& leg = hanging.legs[static_cast<std::size_t>(k)];
      const Wrench w = poses.wrench.row(p).segment<6>(Eigen::Index{6} * k).transpose() - leg.offset;
      terms.force.col(k) = w.head<3>();
      terms.torque.col(k) = w.tail<3>();
      terms.com.col(k) = leg.com(poses.phi(p, k));
    }
    terms.attitude = attitude;
    terms.down = attitude.transpose() * Eigen::Vector3d(0.0, 0.0, -1.0);
  }
  return data;
}

BalanceData restrict_to(const BalanceData& data, const std::vector<Eigen::Index>& subset) {
  BalanceData out = data;
  out.poses.clear();
  for (const Eigen::Index p : subset) {
    out.poses.push_back(data.poses[static_cast<std::size_t>(p)]);
  }
  return out;
}

}  // namespace standing_detail

std::string_view model_label(MountingModel model) {
  switch (model) {
    case MountingModel::full:
      return "full";
    case MountingModel::shared_translation:
      return "shared_translation";
    case MountingModel::translations_only:
      return "translations_only";
    case MountingModel::com_only:
      return "com_only";
  }
  return "full";
}

int model_dof(MountingModel model, int legs) {
  switch (model) {
    case MountingModel::full:
      return 6 * legs;
    case MountingModel::shared_translation:
      return 3 * legs + 3;
    case MountingModel::translations_only:
      return 3 * legs;
    case MountingModel::com_only:
      return 3;
  }
  return 6 * legs;
}

std::string_view solver_label(MountingSolver solver) {
  return solver == MountingSolver::alternating ? "alternating" : "ceres_so3";
}

void validate(const MountingOptions& options) {
  if (!std::isfinite(options.torque_weight) || options.torque_weight <= 0.0) {
    throw core::InputError("mounting.torque_weight", "must be positive and finite");
  }
  if (!(options.tolerance > 0.0 && options.tolerance < 1.0)) {
    throw core::InputError("mounting.tolerance", "must lie in (0, 1)");
  }
  if (!std::isfinite(options.force_noise_variance)) {
    throw core::InputError("mounting.force_noise_variance", "must be finite");
  }
  if (options.max_iterations < 1) {
    throw core::InputError("mounting.max_iterations", "must be 1 or more");
  }
}

MountingEstimate fit_mounting(const Geometry& geometry, const StandingPoses& poses,
                              const HangingCalibration& hanging, const MountingOptions& options,
                              const MountingStart& start) {
  const BalanceData data = standing_detail::prepare(geometry, poses, hanging, options);
  check_start(start, data.legs);
  return fit_prepared(data, options, start);
}

Eigen::MatrixXd balance_residuals(const Geometry& geometry, const StandingPoses& poses,
                                  const HangingCalibration& hanging,
                                  const MountingEstimate& estimate) {
  MountingOptions options;
  options.target = estimate.target;
  const BalanceData data = standing_detail::prepare(geometry, poses, hanging, options);
  if (static_cast<int>(estimate.rotation.size()) != data.legs ||
      static_cast<int>(estimate.displacement.size()) != data.legs) {
    throw core::InputError("mounting estimate",
                           "does not have one rotation and displacement per leg");
  }
  Eigen::MatrixXd out(poses.poses(), 6);
  for (Eigen::Index p = 0; p < poses.poses(); ++p) {
    const standing_detail::Vector6d e =
        standing_detail::residual_in_c(data, p, estimate.rotation, estimate.displacement);
    const Eigen::Matrix3d& a = data.poses[static_cast<std::size_t>(p)].attitude;
    out.row(p).head<3>() = (a * e.head<3>()).transpose();
    out.row(p).tail<3>() = (a * e.tail<3>()).transpose();
  }
  return out;
}

Eigen::MatrixXd naive_residuals(const Geometry& geometry, const StandingPoses& poses,
                                const HangingRecord& air, double cycles) {
  validate(geometry);
  const int legs = geometry.size();
  const std::string air_where =
      air.source.empty() ? "hanging record " + std::string(axis_label(air.down)) : air.source;
  if (!(cycles > 0.0) || !std::isfinite(cycles)) {
    throw core::InputError("cycles", "must be a positive number of turns");
  }
  if (air.samples() < 1 || air.phi.cols() != legs || air.wrench.cols() != Eigen::Index{6} * legs ||
      air.wrench.rows() != air.samples()) {
    throw core::InputError(air_where, "needs samples with " + std::to_string(legs) +
                                          " shaft angles and " + std::to_string(6 * legs) +
                                          " wrench columns");
  }
  if (!air.phi.allFinite() || !air.wrench.allFinite()) {
    throw core::InputError(air_where, "holds a value that is not finite");
  }
  // Poses' checks as the fit's (weights and offsets play no part here).
  HangingCalibration unit;
  unit.legs.resize(static_cast<std::size_t>(legs));
  for (auto& leg : unit.legs) {
    leg.weight = geometry.robot_weight / (2.0 * legs);
  }
  const BalanceData data = standing_detail::prepare(geometry, poses, unit, MountingOptions{});
  std::vector<Wrench> bias(static_cast<std::size_t>(legs), Wrench::Zero());
  for (int k = 0; k < legs; ++k) {
    Eigen::Index n = 0;
    for (Eigen::Index i = 0; i < air.samples(); ++i) {
      if (i > 0 && std::abs(air.phi(i, k) - air.phi(0, k)) >= cycles) {
        break;
      }
      bias[static_cast<std::size_t>(k)] +=
          air.wrench.row(i).segment<6>(Eigen::Index{6} * k).transpose();
      ++n;
    }
    bias[static_cast<std::size_t>(k)] /= static_cast<double>(n);
  }
  Eigen::MatrixXd out(poses.poses(), 6);
  for (Eigen::Index p = 0; p < poses.poses(); ++p) {
    Wrench sum = Wrench::Zero();
    for (int k = 0; k < legs; ++k) {
      const Wrench w = poses.wrench.row(p).segment<6>(Eigen::Index{6} * k).transpose() -
                       bias[static_cast<std::size_t>(k)];
      sum += transform_wrench(geometry.transducer[static_cast<std::size_t>(k)], w);
    }
    const Eigen::Matrix3d& a = data.poses[static_cast<std::size_t>(p)].attitude;
    out.row(p).head<3>() =
        (a * sum.head<3>() - Eigen::Vector3d(0.0, 0.0, geometry.robot_weight)).transpose();
    out.row(p).tail<3>() = (a * sum.tail<3>()).transpose();
  }
  return out;
}

std::vector<ModelScore> score_models(const Geometry& geometry, const StandingPoses& poses,
                                     const HangingCalibration& hanging,
                                     const MountingOptions& options, int folds,
                                     std::uint64_t seed) {
  const BalanceData data = standing_detail::prepare(geometry, poses, hanging, options);
  const auto count = static_cast<Eigen::Index>(data.poses.size());
  if (folds < 2 || folds > count) {
    throw core::InputError("folds", "must lie in [2, " + std::to_string(count) + "] for " +
                                        std::to_string(count) + " poses");
  }
  std::vector<Eigen::Index> order(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::mt19937_64 rng(seed);
  for (Eigen::Index i = count - 1; i > 0; --i) {
    const auto j =
        std::min(static_cast<Eigen::Index>(uniform01(rng) * static_cast<double>(i + 1)), i);
    std::swap(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(j)]);
  }
  std::vector<ModelScore> scores;
  for (const MountingModel model : kMountingModels) {
    MountingOptions fit_options = options;
    fit_options.model = model;
    const MountingEstimate all = fit_prepared(data, fit_options, {});
    ModelScore score;
    score.model = model;
    score.dof = all.dof;
    score.rss = all.rss;
    const double p = static_cast<double>(count);
    score.bic = p * std::log(all.rss / p) + all.dof * std::log(p);
    double cv = 0.0;
    for (int f = 0; f < folds; ++f) {
      std::vector<Eigen::Index> train;
      std::vector<Eigen::Index> test;
      for (Eigen::Index i = 0; i < count; ++i) {
        (i * folds / count == f ? test : train).push_back(order[static_cast<std::size_t>(i)]);
      }
      const BalanceData train_data = standing_detail::restrict_to(data, train);
      const BalanceData test_data = standing_detail::restrict_to(data, test);
      const MountingEstimate fitted = fit_prepared(train_data, fit_options, {});
      cv += standing_detail::weighted_rss(test_data, fitted.rotation, fitted.displacement) /
            static_cast<double>(test.size());
    }
    score.cv_mse = cv / folds;
    scores.push_back(score);
  }
  return scores;
}

std::vector<MountingEstimate> multistart(const Geometry& geometry, const StandingPoses& poses,
                                         const HangingCalibration& hanging,
                                         const MountingOptions& options, int starts,
                                         std::uint64_t seed, double max_angle,
                                         double max_displacement) {
  if (starts < 1) {
    throw core::InputError("starts", "must be 1 or more");
  }
  if (!(max_angle >= 0.0 && max_angle < 3.0) ||
      !(max_displacement >= 0.0 && std::isfinite(max_displacement))) {
    throw core::InputError("starts",
                           "needs an angle in [0, 3) rad and a finite radius of 0 or more");
  }
  const BalanceData data = standing_detail::prepare(geometry, poses, hanging, options);
  std::mt19937_64 rng(seed);
  const auto uniform = [&](double half) { return (2.0 * uniform01(rng) - 1.0) * half; };
  std::vector<MountingEstimate> out;
  for (int s = 0; s < starts; ++s) {
    MountingStart start;
    if (s > 0) {
      for (int k = 0; k < data.legs; ++k) {
        const Eigen::Matrix3d r = (Eigen::AngleAxisd(uniform(max_angle), Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(uniform(max_angle), Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(uniform(max_angle), Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
        Eigen::Vector3d u;
        do {  // uniform in the ball: rejection from its cube
          u = Eigen::Vector3d(uniform(1.0), uniform(1.0), uniform(1.0));
        } while (u.squaredNorm() > 1.0);
        start.rotation.push_back(r);
        start.displacement.push_back(max_displacement * u);
      }
    }
    out.push_back(fit_prepared(data, options, start));
  }
  return out;
}

}  // namespace slipwalk::calibration
