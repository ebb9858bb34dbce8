// Point kinds of the in-situ F/T calibration, thesis ch. 4, on the synthetic BigANT
// (calibration/synthetic.hpp: a robot whose true offsets, weights, centres of mass and mounting
// errors are known, so every estimate is compared with the truth, not with the thesis' numbers).
//
//   calib_parameters         one row per estimated number (Table 4.1 and the mounting errors):
//                            estimate, standard error, truth, error, z = error / se.
//   calib_com                the hanging stage's CoM samples binned by shaft angle (Fig. 4.4):
//                            quantiles per bin, the periodic fit and the truth at the bin centre.
//   calib_hanging_residuals  reading − predict_hanging per sample (subsampled), under the exact
//                            model and without the misalignment (Fig. 4.5).
//   calib_pose_residuals     the standing balance per pose (Fig. 4.6): the naive tare, the model
//                            without mounting errors (com_only), the full model, and the full model
//                            fitted to the thesis' literal eq. 4.8 — each the residual of its own
//                            balance target, in W.
//   calib_models             Table 4.2: RSS, cross-validated MSE, BIC per model, the selection.
//   calib_starts             §4.4.2's multistart: where each start ends, against the truth.
//   calib_accuracy           one calibration per (noise scale, poses, seed): its largest errors,
//                            z-scores and times (the cost of accuracy in data).
//
// Shared parameters (defaults): seed = 1, noise_scale = 1, poses = 543, samples_per_cycle = 900,
// cycles = 10, mounting_translation = 0.003 m, mounting_rotation = 0.035 rad (the synthetic options
// of calibration/synthetic.hpp;
// every other one at its default). Every kind but calib_accuracy takes its robot and default
// calibration from the process-wide cache of calibration.hpp; calib_accuracy makes its own (its
// grid is large and its times must be its own). The two kinds that time (calib_starts,
// calib_accuracy) are timed: they run one at a time.
//
// Units: forces N, torques N·m, rotations rad (rotation vectors), displacements m, phases turns.
#include "sweeps/points/calibration.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/hanging.hpp"
#include "calibration/standing.hpp"
#include "calibration/wrench.hpp"
#include "core/error.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

namespace cal = calibration;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegree = std::numbers::pi / 180.0;

// --- shared inputs ------------------------------------------------------------------------------

const std::vector<std::string_view> kSharedKeys = {"seed",
                                                   "noise_scale",
                                                   "poses",
                                                   "samples_per_cycle",
                                                   "cycles",
                                                   "mounting_translation",
                                                   "mounting_rotation"};

std::vector<std::string_view> keys_with(std::vector<std::string_view> own) {
  own.insert(own.end(), kSharedKeys.begin(), kSharedKeys.end());
  return own;
}

/// At most this many hanging samples per record (4 records × 42 numbers each: ≈ 130 MB).
constexpr double kMaxSamples = 1e5;
/// The hanging stage's fit needs 3 + 2H samples (H = 4 harmonics by default).
constexpr int kMinSamples = 3 + 2 * 4;
/// The full model has 36 parameters: 6 + 1 poses at least, and 5-fold cross-validation keeps
/// 4/5 of them for each fit.
constexpr long long kMinPoses = 10;
/// The full model's 36 parameters need 36 / 6 + 1 poses (calibration::fit_mounting).
constexpr int kMinFitPoses = 7;

SynthKey read_shared(const Reader& r) {
  SynthKey k;
  k.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 4294967295LL));
  k.noise_scale = r.number("noise_scale", 1.0, core::closed(0.0, 10.0, "(scale)"));
  k.poses = static_cast<int>(r.integer("poses", 543, kMinPoses, 729));
  k.samples_per_cycle = static_cast<int>(r.integer("samples_per_cycle", 900, 8, 100000));
  k.cycles = static_cast<int>(r.integer("cycles", 10, 1, 100));
  // The synthetic robot refuses translation errors of 5 cm or more (calibration/synthetic.hpp).
  k.mounting_translation = r.number("mounting_translation", 0.003, core::closed(0.0, 0.049, "m"));
  // ... and rotation errors of 0.3 rad or more (the small-angle tilt of its floor model).
  k.mounting_rotation = r.number("mounting_rotation", 0.035, core::closed(0.0, 0.29, "rad"));
  const double samples = static_cast<double>(k.samples_per_cycle) * k.cycles;
  r.limit_work("samples_per_cycle", "samples_per_cycle · cycles hanging samples per record",
               samples, kMaxSamples);
  if (samples < kMinSamples) {
    r.fail("samples_per_cycle", "samples_per_cycle · cycles = " + core::format_double(samples) +
                                    "; the hanging fit needs at least " +
                                    std::to_string(kMinSamples) + " samples per record");
  }
  return k;
}

template <class Row>
Rows<Row> failed(const std::string& message) {
  Rows<Row> out;
  out.failed = true;
  out.message = message;
  return out;
}

/// A point's work that failed (the generator, a stage refusing its data, a solver): the point
/// fails with the message. A logic_error (a bug) goes through.
template <class Row, class Work>
Rows<Row> guarded(Work&& work) {
  try {
    return work();
  } catch (const core::ComputationError& e) {
    return failed<Row>(e.what());
  } catch (const core::InputError& e) {
    return failed<Row>(e.what());
  }
}

const cal::HangingRecord& record_of(const SyntheticRobot& robot, cal::BodyAxis down) {
  for (const cal::HangingRecord& r : robot.hanging) {
    if (r.down == down) {
      return r;
    }
  }
  throw core::ComputationError("the synthetic robot has no hanging record " +
                               std::string(cal::axis_label(down)));
}

/// The angle (rad) between two rotations.
double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return cal::rotation_vector(a.transpose() * b).norm();
}

// --- the estimated numbers (calib_parameters, calib_accuracy) ------------------------------------

/// One estimated number against the truth.
struct Estimate {
  std::string leg;
  std::string parameter;
  double estimate = 0.0;
  double se = 0.0;
  double truth = 0.0;

  [[nodiscard]] double error() const { return estimate - truth; }
  /// error / se; NaN where the estimate has no standard error (noiseless data).
  [[nodiscard]] double z() const { return se > 0.0 ? error() / se : kNaN; }
};

constexpr std::array<const char*, 6> kOffsetNames = {"offset_fx", "offset_fy", "offset_fz",
                                                     "offset_tx", "offset_ty", "offset_tz"};
constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};

/// Per leg: the six offsets and the weight (hanging, §4.3.1), the rotation vector of R̃_k and the
/// displacement u_k (standing, full model, §4.3.2).
std::vector<Estimate> estimates(const cal::SyntheticTruth& truth, const cal::Calibration& c) {
  std::vector<Estimate> out;
  const int legs = c.geometry.size();
  for (int k = 0; k < legs; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    const std::string& leg = c.geometry.legs[uk];
    const cal::LegEstimate& h = c.hanging.legs.at(uk);
    for (Eigen::Index i = 0; i < 6; ++i) {
      out.push_back({leg, kOffsetNames[static_cast<std::size_t>(i)], h.offset(i), h.offset_se(i),
                     truth.offset.at(uk)(i)});
    }
    out.push_back({leg, "weight", h.weight, h.weight_se, truth.weight.at(uk)});
    const Eigen::Vector3d rotation = cal::rotation_vector(c.mounting.rotation.at(uk));
    const Eigen::Vector3d true_rotation = cal::rotation_vector(truth.mounting_rotation.at(uk));
    const Eigen::Vector3d true_displacement = truth.displacement(k);
    for (Eigen::Index i = 0; i < 3; ++i) {
      out.push_back({leg, std::string("rotation_") + kAxes[static_cast<std::size_t>(i)],
                     rotation(i), c.mounting.rotation_se.at(uk)(i), true_rotation(i)});
    }
    for (Eigen::Index i = 0; i < 3; ++i) {
      out.push_back({leg, std::string("displacement_") + kAxes[static_cast<std::size_t>(i)],
                     c.mounting.displacement.at(uk)(i), c.mounting.displacement_se.at(uk)(i),
                     true_displacement(i)});
    }
  }
  return out;
}

// --- calib_parameters ---------------------------------------------------------------------------

SynthKey read_parameters(const Point& point) {
  return read_shared(Reader(point, "calib_parameters", keys_with({})));
}

struct ParameterRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  long long poses = 0;
  std::string leg;
  std::string parameter;
  double estimate = 0.0;
  double se = 0.0;
  double truth = 0.0;
  double error = 0.0;
  double z = 0.0;

  static std::vector<Column<ParameterRow>> columns() {
    using R = ParameterRow;
    return {value("id", &R::id),
            value("seed", &R::seed),
            value("noise_scale", &R::noise_scale),
            value("poses", &R::poses),
            value("leg", &R::leg),
            value("parameter", &R::parameter),
            value("estimate", &R::estimate, "N, N·m, rad or m"),
            value("se", &R::se, "as estimate"),
            value("truth", &R::truth, "as estimate"),
            value("error", &R::error, "as estimate"),
            value("z", &R::z)};
  }
};

Rows<ParameterRow> run_parameters(const Point& point) {
  const SynthKey key = read_parameters(point);
  return guarded<ParameterRow>([&] {
    const auto robot = cached_robot(key);
    const auto c = cached_calibration(key);
    Rows<ParameterRow> out;
    for (const Estimate& e : estimates(robot->truth, *c)) {
      ParameterRow r;
      r.id = point.id;
      r.seed = static_cast<long long>(key.seed);
      r.noise_scale = key.noise_scale;
      r.poses = key.poses;
      r.leg = e.leg;
      r.parameter = e.parameter;
      r.estimate = e.estimate;
      r.se = e.se;
      r.truth = e.truth;
      r.error = e.error();
      r.z = e.z();
      out.rows.push_back(std::move(r));
    }
    return out;
  });
}

// --- calib_com ----------------------------------------------------------------------------------

struct ComInputs {
  SynthKey key;
  int bins = 36;
};

ComInputs read_com(const Point& point) {
  const Reader r(point, "calib_com", keys_with({"bins"}));
  ComInputs in;
  in.key = read_shared(r);
  in.bins = static_cast<int>(r.integer("bins", 36, 1, 3600));
  return in;
}

struct ComRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  std::string leg;
  std::string axis;
  double phase = 0.0;
  long long samples = 0;
  double median = 0.0;
  double q25 = 0.0;
  double q75 = 0.0;
  double q025 = 0.0;
  double q975 = 0.0;
  double fit = 0.0;
  double truth = 0.0;

  static std::vector<Column<ComRow>> columns() {
    using R = ComRow;
    return {value("id", &R::id),
            value("seed", &R::seed),
            value("noise_scale", &R::noise_scale),
            value("leg", &R::leg),
            value("axis", &R::axis),
            value("phase", &R::phase, "turns"),
            value("samples", &R::samples),
            value("median", &R::median, "m"),
            value("q25", &R::q25, "m"),
            value("q75", &R::q75, "m"),
            value("q025", &R::q025, "m"),
            value("q975", &R::q975, "m"),
            value("fit", &R::fit, "m"),
            value("truth", &R::truth, "m")};
  }
};

Rows<ComRow> run_com(const Point& point) {
  const ComInputs in = read_com(point);
  return guarded<ComRow>([&] {
    const auto robot = cached_robot(in.key);
    const auto c = cached_calibration(in.key);
    Rows<ComRow> out;
    const int legs = c->geometry.size();
    for (int k = 0; k < legs; ++k) {
      const auto uk = static_cast<std::size_t>(k);
      const cal::LegEstimate& h = c->hanging.legs.at(uk);
      // The samples of each bin, per axis: φ wrapped to [0, 1) turn.
      std::vector<std::array<std::vector<double>, 3>> binned(static_cast<std::size_t>(in.bins));
      for (Eigen::Index i = 0; i < h.com_phi.size(); ++i) {
        const double wrapped = h.com_phi(i) - std::floor(h.com_phi(i));
        const auto b = std::min(static_cast<std::size_t>(wrapped * in.bins),
                                static_cast<std::size_t>(in.bins - 1));
        for (std::size_t a = 0; a < 3; ++a) {
          binned[b][a].push_back(h.com_samples(static_cast<Eigen::Index>(a), i));
        }
      }
      for (int b = 0; b < in.bins; ++b) {
        const double phase = (b + 0.5) / in.bins;
        const Eigen::Vector3d fit = h.com(phase);
        const Eigen::Vector3d truth = robot->truth.leg_com(k, phase);
        for (std::size_t a = 0; a < 3; ++a) {
          const std::vector<double>& v = binned[static_cast<std::size_t>(b)][a];
          ComRow r;
          r.id = point.id;
          r.seed = static_cast<long long>(in.key.seed);
          r.noise_scale = in.key.noise_scale;
          r.leg = c->geometry.legs[uk];
          r.axis = kAxes[a];
          r.phase = phase;
          r.samples = static_cast<long long>(v.size());
          r.median = median(v);
          r.q25 = quantile(v, 0.25);
          r.q75 = quantile(v, 0.75);
          r.q025 = quantile(v, 0.025);
          r.q975 = quantile(v, 0.975);
          r.fit = fit(static_cast<Eigen::Index>(a));
          r.truth = truth(static_cast<Eigen::Index>(a));
          out.rows.push_back(std::move(r));
        }
      }
    }
    return out;
  });
}

// --- calib_hanging_residuals --------------------------------------------------------------------

struct HangingInputs {
  SynthKey key;
  int stride = 10;
};

HangingInputs read_hanging(const Point& point) {
  const Reader r(point, "calib_hanging_residuals", keys_with({"stride"}));
  HangingInputs in;
  in.key = read_shared(r);
  in.stride = static_cast<int>(r.integer("stride", 10, 1, 100000));
  return in;
}

constexpr std::array<const char*, 6> kComponents = {"fx", "fy", "fz", "tx", "ty", "tz"};

struct HangingRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  std::string leg;
  std::string orientation;
  std::string component;
  std::string model;
  long long sample = 0;
  double phi = 0.0;
  double residual = 0.0;

  static std::vector<Column<HangingRow>> columns() {
    using R = HangingRow;
    return {value("id", &R::id),
            value("seed", &R::seed),
            value("noise_scale", &R::noise_scale),
            value("leg", &R::leg),
            value("orientation", &R::orientation),
            value("component", &R::component),
            value("model", &R::model),
            value("sample", &R::sample),
            value("phi", &R::phi, "turns"),
            value("residual", &R::residual, "N or N·m")};
  }
};

Rows<HangingRow> run_hanging(const Point& point) {
  const HangingInputs in = read_hanging(point);
  return guarded<HangingRow>([&] {
    const auto robot = cached_robot(in.key);
    const auto c = cached_calibration(in.key);
    cal::HangingOptions naive_options = c->hanging.options;
    naive_options.model = cal::HangingModel::no_misalignment;
    const cal::HangingCalibration naive =
        cal::calibrate_hanging(c->geometry, robot->hanging, naive_options);
    const std::array<std::pair<const char*, const cal::HangingCalibration*>, 2> models = {
        std::pair{"exact", &c->hanging}, std::pair{"no_misalignment", &naive}};
    Rows<HangingRow> out;
    const int legs = c->geometry.size();
    for (const cal::HangingRecord& record : robot->hanging) {
      for (const auto& [model, hanging] : models) {
        const Eigen::MatrixXd residual =
            record.wrench - cal::predict_hanging(c->geometry, *hanging, record);
        for (int k = 0; k < legs; ++k) {
          for (Eigen::Index j = 0; j < 6; ++j) {
            for (Eigen::Index i = 0; i < record.samples(); i += in.stride) {
              HangingRow r;
              r.id = point.id;
              r.seed = static_cast<long long>(in.key.seed);
              r.noise_scale = in.key.noise_scale;
              r.leg = c->geometry.legs[static_cast<std::size_t>(k)];
              r.orientation = cal::axis_label(record.down);
              r.component = kComponents[static_cast<std::size_t>(j)];
              r.model = model;
              r.sample = static_cast<long long>(i);
              r.phi = record.phi(i, k);
              r.residual = residual(i, 6 * static_cast<Eigen::Index>(k) + j);
              out.rows.push_back(std::move(r));
            }
          }
        }
      }
    }
    return out;
  });
}

// --- calib_pose_residuals -----------------------------------------------------------------------

SynthKey read_poses(const Point& point) {
  return read_shared(Reader(point, "calib_pose_residuals", keys_with({})));
}

struct PoseRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  double mounting_rotation = 0.0;
  long long pose = 0;
  std::string method;
  std::array<double, 6> e{};

  static std::vector<Column<PoseRow>> columns() {
    using R = PoseRow;
    std::vector<Column<R>> out = {value("id", &R::id),
                                  value("seed", &R::seed),
                                  value("noise_scale", &R::noise_scale),
                                  value("mounting_rotation", &R::mounting_rotation, "rad"),
                                  value("pose", &R::pose),
                                  value("method", &R::method)};
    for (std::size_t j = 0; j < 6; ++j) {
      out.push_back(value_at(kComponents[j], &R::e, j, j < 3 ? "N" : "N·m"));
    }
    return out;
  }
};

Rows<PoseRow> run_poses(const Point& point) {
  const SynthKey key = read_poses(point);
  return guarded<PoseRow>([&] {
    const auto robot = cached_robot(key);
    const auto c = cached_calibration(key);
    const cal::Geometry& g = c->geometry;
    cal::MountingOptions com_only = default_calibration_options(key.seed).mounting;
    com_only.model = cal::MountingModel::com_only;
    cal::MountingOptions literal = default_calibration_options(key.seed).mounting;
    literal.target = cal::BalanceTarget::thesis_literal;
    const std::array<std::pair<const char*, Eigen::MatrixXd>, 4> methods = {
        std::pair{"naive",
                  cal::naive_residuals(g, robot->poses, record_of(*robot, cal::BodyAxis::minus_z))},
        std::pair{"no_mounting",
                  cal::balance_residuals(g, robot->poses, c->hanging,
                                         cal::fit_mounting(g, robot->poses, c->hanging, com_only))},
        std::pair{"full", cal::balance_residuals(g, robot->poses, c->hanging, c->mounting)},
        std::pair{"literal",
                  cal::balance_residuals(g, robot->poses, c->hanging,
                                         cal::fit_mounting(g, robot->poses, c->hanging, literal))}};
    Rows<PoseRow> out;
    for (const auto& [method, e] : methods) {
      for (Eigen::Index p = 0; p < e.rows(); ++p) {
        PoseRow r;
        r.id = point.id;
        r.seed = static_cast<long long>(key.seed);
        r.noise_scale = key.noise_scale;
        r.mounting_rotation = key.mounting_rotation;
        r.pose = static_cast<long long>(p);
        r.method = method;
        for (std::size_t j = 0; j < 6; ++j) {
          r.e[j] = e(p, static_cast<Eigen::Index>(j));
        }
        out.rows.push_back(std::move(r));
      }
    }
    return out;
  });
}

// --- calib_models -------------------------------------------------------------------------------

struct ModelsInputs {
  SynthKey key;
  int folds = 5;
};

ModelsInputs read_models(const Point& point) {
  const Reader r(point, "calib_models", keys_with({"folds"}));
  ModelsInputs in;
  in.key = read_shared(r);
  in.folds = static_cast<int>(r.integer("folds", 5, 2, 20));
  // Each fit of the cross-validation keeps the poses outside its largest test fold.
  const int largest_fold = (in.key.poses + in.folds - 1) / in.folds;
  if (in.folds > in.key.poses || in.key.poses - largest_fold < kMinFitPoses) {
    r.fail("folds", "too many folds for " + std::to_string(in.key.poses) +
                        " poses: every fit needs " + std::to_string(kMinFitPoses) +
                        " poses outside its test fold");
  }
  return in;
}

struct ModelRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  long long poses = 0;
  double mounting_translation = 0.0;
  double mounting_rotation = 0.0;
  std::string model;
  long long dof = 0;
  double rss = 0.0;
  double cv_mse = 0.0;
  double bic = 0.0;
  bool selected = false;

  static std::vector<Column<ModelRow>> columns() {
    using R = ModelRow;
    return {value("id", &R::id),
            value("seed", &R::seed),
            value("noise_scale", &R::noise_scale),
            value("poses", &R::poses),
            value("mounting_translation", &R::mounting_translation),
            value("mounting_rotation", &R::mounting_rotation, "rad"),
            value("model", &R::model),
            value("dof", &R::dof),
            value("rss", &R::rss),
            value("cv_mse", &R::cv_mse),
            value("bic", &R::bic),
            value("selected", &R::selected)};
  }
};

Rows<ModelRow> run_models(const Point& point) {
  const ModelsInputs in = read_models(point);
  return guarded<ModelRow>([&] {
    const auto robot = cached_robot(in.key);
    const auto c = cached_calibration(in.key);
    const std::vector<cal::ModelScore> scores =
        cal::score_models(c->geometry, robot->poses, c->hanging,
                          default_calibration_options(in.key.seed).mounting, in.folds, in.key.seed);
    std::size_t best = 0;
    for (std::size_t i = 1; i < scores.size(); ++i) {
      best = scores[i].bic < scores[best].bic ? i : best;
    }
    Rows<ModelRow> out;
    for (std::size_t i = 0; i < scores.size(); ++i) {
      ModelRow r;
      r.id = point.id;
      r.seed = static_cast<long long>(in.key.seed);
      r.noise_scale = in.key.noise_scale;
      r.poses = in.key.poses;
      r.mounting_translation = in.key.mounting_translation;
      r.mounting_rotation = in.key.mounting_rotation;
      r.model = cal::model_label(scores[i].model);
      r.dof = scores[i].dof;
      r.rss = scores[i].rss;
      r.cv_mse = scores[i].cv_mse;
      r.bic = scores[i].bic;
      r.selected = i == best;
      out.rows.push_back(std::move(r));
    }
    return out;
  });
}

// --- calib_starts -------------------------------------------------------------------------------

struct StartsInputs {
  SynthKey key;
  cal::MountingSolver solver = cal::MountingSolver::alternating;
  int starts = 20;
  double max_angle_deg = 15.0;
  double max_displacement = 0.73 / 3.0;
  int max_iterations = 1000;
};

StartsInputs read_starts(const Point& point) {
  const Reader r(
      point, "calib_starts",
      keys_with({"solver", "starts", "max_angle_deg", "max_displacement", "max_iterations"}));
  StartsInputs in;
  in.key = read_shared(r);
  in.solver = r.choice("solver", {"alternating", "ceres_so3"}) == "alternating"
                  ? cal::MountingSolver::alternating
                  : cal::MountingSolver::ceres_so3;
  in.starts = static_cast<int>(r.integer("starts", 20, 1, 200));
  in.max_angle_deg = r.number("max_angle_deg", 15.0, core::closed(0.0, 90.0, "deg"));
  in.max_displacement = r.number("max_displacement", 0.73 / 3.0, core::closed(0.0, 1.0, "m"));
  in.max_iterations = static_cast<int>(r.integer("max_iterations", 1000, 1, 100000));
  return in;
}

struct StartRow {
  long long id = 0;
  long long seed = 0;
  double noise_scale = 0.0;
  long long start = 0;
  std::string solver;
  double cost = 0.0;
  long long iterations = 0;
  bool converged = false;
  double seconds = 0.0;
  double rotation_error_deg = 0.0;
  double displacement_error_mm = 0.0;

  static std::vector<Column<StartRow>> columns() {
    using R = StartRow;
    return {value("id", &R::id),
            value("seed", &R::seed),
            value("noise_scale", &R::noise_scale),
            value("start", &R::start),
            value("solver", &R::solver),
            value("cost", &R::cost),
            value("iterations", &R::iterations),
            value("converged", &R::converged),
            timing("seconds", &R::seconds),
            value("rotation_error_deg", &R::rotation_error_deg, "deg"),
            value("displacement_error_mm", &R::displacement_error_mm, "mm")};
  }
};

/// The largest rotation error (rad) and displacement error (m) over the legs.
std::pair<double, double> mounting_errors(const cal::SyntheticTruth& truth,
                                          const cal::MountingEstimate& m) {
  double rotation = 0.0;
  double displacement = 0.0;
  for (int k = 0; k < truth.legs(); ++k) {
    const auto uk = static_cast<std::size_t>(k);
    rotation =
        std::max(rotation, rotation_angle(m.rotation.at(uk), truth.mounting_rotation.at(uk)));
    displacement = std::max(displacement, (m.displacement.at(uk) - truth.displacement(k)).norm());
  }
  return {rotation, displacement};
}

Rows<StartRow> run_starts(const Point& point) {
  const StartsInputs in = read_starts(point);
  return guarded<StartRow>([&] {
    const auto robot = cached_robot(in.key);
    const auto c = cached_calibration(in.key);
    cal::MountingOptions options = default_calibration_options(in.key.seed).mounting;
    options.solver = in.solver;
    options.max_iterations = in.max_iterations;
    const std::vector<cal::MountingEstimate> fits =
        cal::multistart(c->geometry, robot->poses, c->hanging, options, in.starts, in.key.seed,
                        in.max_angle_deg * kDegree, in.max_displacement);
    Rows<StartRow> out;
    for (std::size_t s = 0; s < fits.size(); ++s) {
      const auto [rotation, displacement] = mounting_errors(robot->truth, fits[s]);
      StartRow r;
      r.id = point.id;
      r.seed = static_cast<long long>(in.key.seed);
      r.noise_scale = in.key.noise_scale;
      r.start = static_cast<long long>(s);
      r.solver = cal::solver_label(fits[s].solver);
      r.cost = fits[s].rss;
      r.iterations = fits[s].iterations;
      r.converged = fits[s].converged;
      r.seconds = fits[s].seconds;
      r.rotation_error_deg = rotation / kDegree;
      r.displacement_error_mm = displacement * 1000.0;
      out.rows.push_back(std::move(r));
    }
    return out;
  });
}

// --- calib_accuracy -----------------------------------------------------------------------------

SynthKey read_accuracy(const Point& point) {
  return read_shared(Reader(point, "calib_accuracy", keys_with({})));
}

/// The φ grid of com_err_rms: this many equally spaced shaft angles over one turn.
constexpr int kComGrid = 100;

struct AccuracyRow {
  long long id = 0;
  double noise_scale = 0.0;
  long long poses = 0;
  long long seed = 0;
  double weight_err_max = 0.0;
  double offset_force_err_max = 0.0;
  double offset_torque_err_max = 0.0;
  double com_err_rms = 0.0;
  double rotation_err_max_deg = 0.0;
  double displacement_err_max_mm = 0.0;
  double z_abs_max = 0.0;
  double z_rms = 0.0;
  double within_3se = 0.0;
  double seconds_hanging = 0.0;
  double seconds_standing = 0.0;
  double rss = 0.0;

  static std::vector<Column<AccuracyRow>> columns() {
    using R = AccuracyRow;
    return {value("id", &R::id),
            value("noise_scale", &R::noise_scale),
            value("poses", &R::poses),
            value("seed", &R::seed),
            value("weight_err_max", &R::weight_err_max, "N"),
            value("offset_force_err_max", &R::offset_force_err_max, "N"),
            value("offset_torque_err_max", &R::offset_torque_err_max, "N·m"),
            value("com_err_rms", &R::com_err_rms, "m"),
            value("rotation_err_max_deg", &R::rotation_err_max_deg, "deg"),
            value("displacement_err_max_mm", &R::displacement_err_max_mm, "mm"),
            value("z_abs_max", &R::z_abs_max),
            value("z_rms", &R::z_rms),
            value("within_3se", &R::within_3se),
            timing("seconds_hanging", &R::seconds_hanging),
            timing("seconds_standing", &R::seconds_standing),
            value("rss", &R::rss)};
  }
};

/// The row of one calibration against its truth.
AccuracyRow accuracy(const cal::SyntheticTruth& truth, const cal::Calibration& c) {
  AccuracyRow r;
  double z_sum = 0.0;
  int z_count = 0;
  int within = 0;
  for (const Estimate& e : estimates(truth, c)) {
    const double err = std::abs(e.error());
    if (e.parameter == "weight") {
      r.weight_err_max = std::max(r.weight_err_max, err);
    } else if (e.parameter.rfind("offset_f", 0) == 0) {
      r.offset_force_err_max = std::max(r.offset_force_err_max, err);
    } else if (e.parameter.rfind("offset_t", 0) == 0) {
      r.offset_torque_err_max = std::max(r.offset_torque_err_max, err);
    }
    const double z = e.z();
    if (std::isfinite(z)) {
      r.z_abs_max = std::max(r.z_abs_max, std::abs(z));
      z_sum += z * z;
      ++z_count;
      within += std::abs(z) <= 3.0 ? 1 : 0;
    }
  }
  r.z_rms = z_count > 0 ? std::sqrt(z_sum / z_count) : kNaN;
  r.within_3se = z_count > 0 ? static_cast<double>(within) / z_count : kNaN;
  if (z_count == 0) {
    r.z_abs_max = kNaN;
  }
  double com_sq = 0.0;
  for (int k = 0; k < truth.legs(); ++k) {
    const cal::LegEstimate& h = c.hanging.legs.at(static_cast<std::size_t>(k));
    for (int i = 0; i < kComGrid; ++i) {
      const double phi = static_cast<double>(i) / kComGrid;
      com_sq += (h.com(phi) - truth.leg_com(k, phi)).squaredNorm();
    }
  }
  r.com_err_rms = std::sqrt(com_sq / (static_cast<double>(truth.legs()) * kComGrid));
  const auto [rotation, displacement] = mounting_errors(truth, c.mounting);
  r.rotation_err_max_deg = rotation / kDegree;
  r.displacement_err_max_mm = displacement * 1000.0;
  r.seconds_hanging = c.seconds_hanging;
  r.seconds_standing = c.seconds_standing;
  r.rss = c.mounting.rss;
  return r;
}

Rows<AccuracyRow> run_accuracy(const Point& point) {
  const SynthKey key = read_accuracy(point);
  return guarded<AccuracyRow>([&] {
    // Not from the cache: the grid's robots are many, and the times must be this point's own.
    const SyntheticRobot robot = make_synthetic_robot(key);
    const cal::Calibration c = cal::calibrate(robot.truth.geometry, robot.hanging, robot.poses,
                                              default_calibration_options(key.seed));
    AccuracyRow r = accuracy(robot.truth, c);
    r.id = point.id;
    r.noise_scale = key.noise_scale;
    r.poses = key.poses;
    r.seed = static_cast<long long>(key.seed);
    Rows<AccuracyRow> out;
    out.rows.push_back(r);
    return out;
  });
}

}  // namespace

std::vector<PointKind> calibration_kinds() {
  return {
      make_point_kind<ParameterRow>(
          "calib_parameters",
          "ch. 4, Table 4.1: the synthetic BigANT's calibration, one row per estimated number "
          "(offsets, weight, mounting rotation vector, displacement; full model) with its "
          "standard error, the truth, the error and z = error / se",
          Timed::kNo, [](const Point& p) { (void)read_parameters(p); }, run_parameters),
      make_point_kind<ComRow>(
          "calib_com",
          "ch. 4, Fig. 4.4: the hanging stage's leg CoM samples binned by shaft angle (median, "
          "quartiles, 2.5/97.5 %), the periodic fit and the truth at each bin centre",
          Timed::kNo, [](const Point& p) { (void)read_com(p); }, run_com),
      make_point_kind<HangingRow>(
          "calib_hanging_residuals",
          "ch. 4, Fig. 4.5: hanging readings less the hanging model's prediction, per sample "
          "(every stride-th), exact model and without misalignment",
          Timed::kNo, [](const Point& p) { (void)read_hanging(p); }, run_hanging),
      make_point_kind<PoseRow>(
          "calib_pose_residuals",
          "ch. 4, Fig. 4.6: the standing balance residual per pose in W: naive tare, no mounting "
          "errors (com_only), full model, full model on the thesis' literal eq. 4.8",
          Timed::kNo, [](const Point& p) { (void)read_poses(p); }, run_poses),
      make_point_kind<ModelRow>(
          "calib_models",
          "ch. 4, Table 4.2: the four mounting models' DOF, RSS, cross-validated MSE and BIC; "
          "the smallest BIC selected",
          Timed::kNo, [](const Point& p) { (void)read_models(p); }, run_models),
      make_point_kind<StartRow>(
          "calib_starts",
          "ch. 4, §4.4.2: the full model's fit from random starts (the thesis: 15°, a third of "
          "73 cm): cost, iterations, time and the largest errors against the truth",
          Timed::kYes, [](const Point& p) { (void)read_starts(p); }, run_starts),
      make_point_kind<AccuracyRow>(
          "calib_accuracy",
          "ch. 4: one whole calibration of a synthetic robot (noise scale, poses, seed): largest "
          "errors against the truth, z-scores, the within-3-SE fraction and the stages' times",
          Timed::kYes, [](const Point& p) { (void)read_accuracy(p); }, run_accuracy),
  };
}

}  // namespace slipwalk::sweeps::points
