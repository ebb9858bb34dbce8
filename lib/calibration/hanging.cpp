// §4.3.1: offsets, leg weights and leg CoMs from opposite hanging records (hanging.hpp).
//
// Oracle (re-derived from the sensing model, eq. 4.1). Leg k hung with gravity along the unit
// vector u (transducer frame) reads f = w u + f_o, τ = r(φ) × w u + τ_o. For the ↓ record (u↓ ≈ e)
// and the ↑ record (u↑ ≈ −e, u↑' = −u↑ ≈ e) at the same φ_i:
//   f⁻ = (f↓ − f↑)/2 = w (u↓ + u↑')/2,   f⁺ = (f↓ + f↑)/2 = f_o + w (u↓ − u↑')/2 = f_o + d,
//   τ⁻_i = r_i × f⁻,                     τ⁺_i = r_i × d + τ_o.
// d · f⁻ = w² (|u↓|² − |u↑'|²)/4 = 0 and |f⁻|² + |d|² = w² (|u↓|² + |u↑'|²)/2 = w²: exact for any
// angle α between u↓ and u↑' (|f⁻| = w cos(α/2), |d| = w sin(α/2)). With the thesis' u↓ =
// (I + [s↓]) e and u↑' = (I + [s↑]) e: f⁻ = (I + [s⁺]) w e and d = [s⁻] w e.
//
// Steps per transducer and pair: f⁻ = mean of the per-sample half differences; the CoM samples
// (smoother per pair then the null-space reconciliation, or pointwise); the periodic fit r̂(φ);
// then d = B a (B: an orthonormal basis ⊥ f⁻) and τ_o from the centred least squares
// τ⁺_i − mean τ⁺ = [r̂_i − mean r̂] B a, τ_o = mean τ⁺ − mean r̂ × d. The regressor is the fitted
// r̂(φ_i), not the raw samples: their noise (σ_τ/|f⁻|, centimetres at the thesis' noise) would
// attenuate d (errors in variables). Nor does the fit's own error bias d: the residual r_i − r̂_i
// is, component by component, orthogonal over the samples to every basis function, and r̂_i − r̄
// is a combination of them, so the cross term Σ_i X_iᵀ (−[d])(r_i − r̂_i) of the normal equations
// vanishes (r̄ = mean r̂ = mean r too). On noiseless data the weights and offsets are therefore
// exact with `pointwise` whatever the CoM's shape and H (tested).
//
// Reconciling the pairs' CoMs (§4.3.1.3). Each pair j fixes r up to r_j + p_j f̂_j. The thesis
// equates two pairs (p, p' by least squares) and averages; that is min over r, p_j of
// Σ_j |r − r_j − p_j f̂_j|², whose solution is r = (Σ_j P_j)⁻¹ Σ_j P_j r_j with P_j = I − f̂_j f̂_jᵀ
// (for fixed p_j the best r is the average, and the remaining cost is half the thesis' one), and
// extends to any number of pairs. `pointwise` instead solves the stacked τ⁻_{j,i} = −[f⁻_j] r_i
// by least squares at each sample: one 3 × 3K pseudo-inverse for all samples.
//
// Standard errors from the residual scatter, samples independent: mean f⁻ and mean f⁺ from their
// sample covariances / n; a and τ_o from σ̂² (XᵀX)⁻¹ of the centred fit (σ̂² = RSS/(3n − 5));
// f_o = mean f⁺ − d (force and torque noise independent); w by the delta method,
// var w = (f⁻ᵀ Σ_f⁻ f⁻ + dᵀ Σ_d d)/w². The pairs' estimates are combined per component by inverse
// variance (equal weights where every variance is zero, i.e. noiseless data).
#include "calibration/hanging.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace slipwalk::calibration {

namespace {

struct RecordPair {
  const HangingRecord* down = nullptr;
  const HangingRecord* up = nullptr;
};

std::string sample_where(const HangingRecord& record, Eigen::Index i) {
  if (static_cast<Eigen::Index>(record.rows.size()) == record.samples()) {
    return record.rows[static_cast<std::size_t>(i)];
  }
  return record.source + " sample " + std::to_string(i + 1);
}

void check_record(const HangingRecord& record, int legs, int min_samples) {
  const std::string& where = record.source.empty() ? std::string("hanging record") : record.source;
  if (record.phi.cols() != legs || record.wrench.cols() != 6 * static_cast<Eigen::Index>(legs)) {
    throw core::InputError(where, "has " + std::to_string(record.phi.cols()) +
                                      " shaft angles and " + std::to_string(record.wrench.cols()) +
                                      " wrench columns for " + std::to_string(legs) +
                                      " legs (need K and 6K)");
  }
  if (record.wrench.rows() != record.phi.rows()) {
    throw core::InputError(where, "has " + std::to_string(record.phi.rows()) +
                                      " shaft-angle rows and " +
                                      std::to_string(record.wrench.rows()) + " wrench rows");
  }
  if (!record.rows.empty() && static_cast<Eigen::Index>(record.rows.size()) != record.samples()) {
    throw core::InputError(where, "names " + std::to_string(record.rows.size()) + " rows for " +
                                      std::to_string(record.samples()) + " samples");
  }
  if (record.samples() < min_samples) {
    throw core::InputError(where, "has " + std::to_string(record.samples()) +
                                      " samples; the fit needs " + std::to_string(min_samples));
  }
  for (Eigen::Index i = 0; i < record.samples(); ++i) {
    if (!record.phi.row(i).allFinite() || !record.wrench.row(i).allFinite()) {
      throw core::InputError(sample_where(record, i), "holds a non-finite value");
    }
  }
}

/// Angles that agree modulo one turn within `tolerance`.
void check_matched(const HangingRecord& a, const HangingRecord& b, double tolerance) {
  const std::string wa = a.source.empty() ? std::string("hanging record") : a.source;
  const std::string wb = b.source.empty() ? std::string("hanging record") : b.source;
  if (a.samples() != b.samples()) {
    throw core::InputError(wb, "has " + std::to_string(b.samples()) + " samples where " + wa +
                                   " has " + std::to_string(a.samples()) +
                                   ": paired records must sample the same shaft angles");
  }
  for (Eigen::Index i = 0; i < a.samples(); ++i) {
    for (Eigen::Index k = 0; k < a.phi.cols(); ++k) {
      const double diff = a.phi(i, k) - b.phi(i, k);
      if (std::abs(diff - std::round(diff)) > tolerance) {
        throw core::InputError(sample_where(b, i),
                               "shaft angle " + std::to_string(b.phi(i, k)) + " does not match " +
                                   std::to_string(a.phi(i, k)) + " at " + sample_where(a, i) +
                                   " (leg " + std::to_string(k + 1) + ")");
      }
    }
  }
}

std::vector<RecordPair> pair_records(int legs, const std::vector<HangingRecord>& records,
                                     const HangingOptions& options) {
  std::array<const HangingRecord*, 6> by_axis{};
  for (const HangingRecord& record : records) {
    check_record(record, legs, 3 + 2 * options.harmonics);
    auto& slot = by_axis.at(static_cast<std::size_t>(record.down));
    if (slot != nullptr) {
      throw core::InputError(record.source, "is a second record hung along " +
                                                std::string(axis_label(record.down)) +
                                                " (first: " + slot->source + ")");
    }
    slot = &record;
  }
  std::vector<RecordPair> pairs;
  for (std::size_t a = 0; a < 3; ++a) {
    const HangingRecord* plus = by_axis.at(2 * a);
    const HangingRecord* minus = by_axis.at(2 * a + 1);
    if (plus != nullptr && minus != nullptr) {
      pairs.push_back({plus, minus});
    } else if (plus != nullptr || minus != nullptr) {
      const HangingRecord& lone = plus != nullptr ? *plus : *minus;
      if (lone.down == BodyAxis::minus_z) {
        continue;  // the naive tare's upright record: no pair, not used
      }
      throw core::InputError(lone.source, "hangs along " + std::string(axis_label(lone.down)) +
                                              " but no record hangs along " +
                                              std::string(axis_label(opposite(lone.down))));
    }
  }
  if (pairs.size() < 2) {
    throw core::InputError(records.empty() ? std::string("hanging") : records.front().source,
                           "the hanging records form " + std::to_string(pairs.size()) +
                               " opposite pair(s); the CoM needs two (e.g. ±x and ±z)");
  }
  for (const RecordPair& pair : pairs) {
    check_matched(*pairs.front().down, *pair.down, options.max_phi_mismatch);
    check_matched(*pairs.front().down, *pair.up, options.max_phi_mismatch);
  }
  return pairs;
}

/// Mean and covariance of the mean of the columns of `x` (3 × n).
void mean_and_cov(const Eigen::Matrix3Xd& x, Eigen::Vector3d& mean, Eigen::Matrix3d& cov_of_mean) {
  const auto n = static_cast<double>(x.cols());
  mean = x.rowwise().mean();
  const Eigen::Matrix3Xd centred = x.colwise() - mean;
  cov_of_mean = centred * centred.transpose() / ((n - 1.0) * n);
}

/// Per-pair data of one leg.
struct PairData {
  Eigen::Vector3d e;
  Eigen::Matrix3Xd tau_minus, tau_plus;
  Eigen::Vector3d f_minus, f_plus;          // means
  Eigen::Matrix3d f_minus_cov, f_plus_cov;  // covariances of the means
  Eigen::Vector3d f_model;                  // f⁻ as the model sees it
};

PairData pair_data(const RecordPair& pair, const Eigen::Matrix3d& nominal, Eigen::Index k,
                   HangingModel model) {
  PairData data;
  data.e = nominal.transpose() * axis_vector(pair.down->down);
  const auto block = [&](const HangingRecord& r, Eigen::Index c) {
    return r.wrench.middleCols(6 * k + c, 3).transpose();
  };
  const Eigen::Matrix3Xd f_minus = 0.5 * (block(*pair.down, 0) - block(*pair.up, 0));
  const Eigen::Matrix3Xd f_plus = 0.5 * (block(*pair.down, 0) + block(*pair.up, 0));
  data.tau_minus = 0.5 * (block(*pair.down, 3) - block(*pair.up, 3));
  data.tau_plus = 0.5 * (block(*pair.down, 3) + block(*pair.up, 3));
  mean_and_cov(f_minus, data.f_minus, data.f_minus_cov);
  mean_and_cov(f_plus, data.f_plus, data.f_plus_cov);
  data.f_model = model == HangingModel::no_misalignment
                     ? Eigen::Vector3d(data.e * data.e.dot(data.f_minus))
                     : data.f_minus;
  return data;
}

/// The CoM samples (3 × n) from all pairs of one leg.
Eigen::Matrix3Xd com_samples(const std::vector<PairData>& pairs, const HangingOptions& options) {
  const Eigen::Index n = pairs.front().tau_minus.cols();
  if (options.com == ComEstimator::pointwise) {
    // Stacked τ⁻_j = −[f_j] r: r = (Σ [f_j]ᵀ[f_j])⁻¹ Σ (−[f_j])ᵀ τ⁻_j, the same matrix for every i.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    for (const PairData& p : pairs) {
      normal += skew(p.f_model).transpose() * skew(p.f_model);
    }
    const Eigen::Matrix3d inverse = normal.inverse();
    Eigen::Matrix3Xd r = Eigen::Matrix3Xd::Zero(3, n);
    for (const PairData& p : pairs) {
      r.noalias() += (inverse * skew(p.f_model)) * p.tau_minus;  // −[f]ᵀ = [f]
    }
    return r;
  }
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix3Xd weighted = Eigen::Matrix3Xd::Zero(3, n);
  for (const PairData& p : pairs) {
    const double f2 = p.f_model.squaredNorm();
    // Prior: the minimum-norm solution of the first sample (its ⊥ part; the part along f is
    // discarded by the reconciliation), so the smoother starts without a transient.
    const Eigen::Vector3d prior = p.f_model.cross(p.tau_minus.col(0)) / f2;
    const Eigen::Matrix3Xd r = smooth_com(p.tau_minus, p.f_model, options.transition_variance,
                                          options.observation_variance, prior, 1.0);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - p.f_model * p.f_model.transpose() / f2;
    normal += P;
    weighted.noalias() += P * r;
  }
  return normal.inverse() * weighted;
}

Eigen::Vector3d rotation_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d a = from.normalized();
  const Eigen::Vector3d b = to.normalized();
  const Eigen::Vector3d axis = a.cross(b);
  const double s = axis.norm();
  if (s == 0.0) {
    return Eigen::Vector3d::Zero();
  }
  return axis / s * std::atan2(s, a.dot(b));
}

/// One pair's estimates given the fitted CoM at each sample (3 × n).
HangingPair estimate_pair(const RecordPair& records, const PairData& p,
                          const Eigen::Matrix3Xd& fitted, HangingModel model) {
  HangingPair out;
  out.down = records.down->down;
  out.axis = p.e;
  out.f_minus = p.f_minus;
  const auto n = static_cast<double>(p.tau_plus.cols());
  Eigen::Matrix3d d_cov = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d tau_o_cov;
  Eigen::Vector3d tau_o;
  if (model == HangingModel::no_misalignment) {
    out.d.setZero();
    mean_and_cov(p.tau_plus, tau_o, tau_o_cov);
  } else {
    // d = B a, B orthonormal ⊥ f⁻; centred least squares of τ⁺ on [r̂_i] B.
    Eigen::Matrix<double, 3, 2> basis =
        Eigen::Matrix3d(Eigen::Matrix3d::Identity() -
                        p.f_minus * p.f_minus.transpose() / p.f_minus.squaredNorm())
            .jacobiSvd(Eigen::ComputeFullU)
            .matrixU()
            .leftCols<2>();
    const Eigen::Vector3d r_mean = fitted.rowwise().mean();
    const Eigen::Vector3d t_mean = p.tau_plus.rowwise().mean();
    Eigen::Matrix2d xtx = Eigen::Matrix2d::Zero();
    Eigen::Vector2d xty = Eigen::Vector2d::Zero();
    for (Eigen::Index i = 0; i < p.tau_plus.cols(); ++i) {
      const Eigen::Matrix<double, 3, 2> x = skew(fitted.col(i) - r_mean) * basis;
      xtx.noalias() += x.transpose() * x;
      xty.noalias() += x.transpose() * (p.tau_plus.col(i) - t_mean);
    }
    const Eigen::LDLT<Eigen::Matrix2d> solver(xtx);
    const Eigen::Vector2d a = solver.solve(xty);
    double rss = 0.0;
    for (Eigen::Index i = 0; i < p.tau_plus.cols(); ++i) {
      rss += (p.tau_plus.col(i) - t_mean - skew(fitted.col(i) - r_mean) * basis * a).squaredNorm();
    }
    const double sigma2 = rss / std::max(1.0, 3.0 * n - 5.0);
    const Eigen::Matrix2d a_cov = sigma2 * solver.solve(Eigen::Matrix2d::Identity());
    out.d = basis * a;
    d_cov = basis * a_cov * basis.transpose();
    tau_o = t_mean - r_mean.cross(out.d);
    const Eigen::Matrix<double, 3, 2> lever = skew(r_mean) * basis;
    tau_o_cov = sigma2 / n * Eigen::Matrix3d::Identity() + lever * a_cov * lever.transpose();
  }
  const Eigen::Vector3d f_o = p.f_plus - out.d;
  const Eigen::Matrix3d f_o_cov = p.f_plus_cov + d_cov;
  Eigen::Vector3d gradient =
      Eigen::Vector3d::Zero();  // of w with respect to f⁻ (and, for the exact model, d)
  double d_term = 0.0;
  switch (model) {
    case HangingModel::exact:
      out.weight = std::sqrt(p.f_minus.squaredNorm() + out.d.squaredNorm());
      gradient = p.f_minus / out.weight;
      d_term = out.d.dot(d_cov * out.d) / (out.weight * out.weight);
      break;
    case HangingModel::thesis_first_order:
      out.weight = p.f_minus.norm();
      gradient = p.f_minus / out.weight;
      break;
    case HangingModel::no_misalignment:
      out.weight = p.e.dot(p.f_minus);
      gradient = p.e;
      break;
  }
  out.weight_se = std::sqrt(std::max(0.0, gradient.dot(p.f_minus_cov * gradient) + d_term));
  out.offset << f_o, tau_o;
  out.offset_se << f_o_cov.diagonal().cwiseMax(0.0).cwiseSqrt(),
      tau_o_cov.diagonal().cwiseMax(0.0).cwiseSqrt();
  if (model != HangingModel::no_misalignment) {
    out.s_plus = rotation_between(p.e, p.f_minus);
    out.s_minus = p.e.cross(out.d) / out.weight;  // d = [ŝ⁻] w e = w ŝ⁻ × e, ŝ⁻ ⊥ e
  } else {
    out.s_plus.setZero();
    out.s_minus.setZero();
  }
  return out;
}

/// Inverse-variance combination of scalars; exact values (variance 0) win, equally weighted.
std::pair<double, double> combine(const std::vector<double>& value, const std::vector<double>& se) {
  double exact_sum = 0.0;
  int exact_count = 0;
  double weight_sum = 0.0;
  double weighted = 0.0;
  for (std::size_t j = 0; j < value.size(); ++j) {
    if (se[j] == 0.0) {
      exact_sum += value[j];
      ++exact_count;
    } else {
      const double w = 1.0 / (se[j] * se[j]);
      weight_sum += w;
      weighted += w * value[j];
    }
  }
  if (exact_count > 0) {
    return {exact_sum / exact_count, 0.0};
  }
  return {weighted / weight_sum, std::sqrt(1.0 / weight_sum)};
}

}  // namespace

void validate(const HangingOptions& options) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(options.transition_variance)) {
    throw core::InputError("hanging.transition_variance", "must be a positive variance (m²)");
  }
  if (!positive(options.observation_variance)) {
    throw core::InputError("hanging.observation_variance", "must be a positive variance ((N·m)²)");
  }
  if (options.harmonics < 0 || options.harmonics > 16) {
    throw core::InputError("hanging.harmonics", "must lie in [0, 16]");
  }
  if (!(options.max_phi_mismatch > 0.0 && options.max_phi_mismatch <= 0.5)) {
    throw core::InputError("hanging.max_phi_mismatch", "must lie in (0, 0.5] turns");
  }
}

HangingCalibration calibrate_hanging(const Geometry& geometry,
                                     const std::vector<HangingRecord>& records,
                                     const HangingOptions& options) {
  validate(geometry);
  validate(options);
  const int legs = geometry.size();
  const std::vector<RecordPair> pairs = pair_records(legs, records, options);
  HangingCalibration out;
  out.options = options;
  out.legs.resize(static_cast<std::size_t>(legs));
  for (int k = 0; k < legs; ++k) {
    LegEstimate& leg = out.legs[static_cast<std::size_t>(k)];
    std::vector<PairData> data;
    data.reserve(pairs.size());
    for (const RecordPair& pair : pairs) {
      data.push_back(
          pair_data(pair, geometry.transducer[static_cast<std::size_t>(k)].R, k, options.model));
      if (data.back().f_model.squaredNorm() == 0.0) {
        throw core::InputError(pair.down->source,
                               "leg " + geometry.legs[static_cast<std::size_t>(k)] +
                                   " shows no weight between the opposite records");
      }
    }
    leg.com_phi = pairs.front().down->phi.col(k);
    leg.com_samples = com_samples(data, options);
    leg.com = fit_periodic(leg.com_phi, leg.com_samples, options.harmonics);
    Eigen::Matrix3Xd fitted(3, leg.com_phi.size());
    for (Eigen::Index i = 0; i < leg.com_phi.size(); ++i) {
      fitted.col(i) = leg.com(leg.com_phi(i));
    }
    leg.com_fit_rms =
        std::sqrt((leg.com_samples - fitted).squaredNorm() / static_cast<double>(fitted.cols()));
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      leg.pairs.push_back(estimate_pair(pairs[j], data[j], fitted, options.model));
    }
    std::vector<double> value(pairs.size());
    std::vector<double> se(pairs.size());
    for (int c = 0; c < 7; ++c) {
      for (std::size_t j = 0; j < pairs.size(); ++j) {
        value[j] = c < 6 ? leg.pairs[j].offset(c) : leg.pairs[j].weight;
        se[j] = c < 6 ? leg.pairs[j].offset_se(c) : leg.pairs[j].weight_se;
      }
      const auto [estimate, error] = combine(value, se);
      if (c < 6) {
        leg.offset(c) = estimate;
        leg.offset_se(c) = error;
      } else {
        leg.weight = estimate;
        leg.weight_se = error;
      }
    }
  }
  return out;
}

Eigen::MatrixXd predict_hanging(const Geometry& geometry, const HangingCalibration& calibration,
                                const HangingRecord& record) {
  const int legs = geometry.size();
  if (static_cast<int>(calibration.legs.size()) != legs) {
    throw core::InputError("predict_hanging",
                           "the calibration has " + std::to_string(calibration.legs.size()) +
                               " legs for a geometry of " + std::to_string(legs));
  }
  check_record(record, legs, 0);
  const bool naive = calibration.options.model == HangingModel::no_misalignment;
  Eigen::MatrixXd out(record.samples(), 6 * legs);
  for (int k = 0; k < legs; ++k) {
    const LegEstimate& leg = calibration.legs[static_cast<std::size_t>(k)];
    Eigen::Vector3d u =
        geometry.transducer[static_cast<std::size_t>(k)].R.transpose() * axis_vector(record.down);
    for (const HangingPair& pair : leg.pairs) {
      const bool is_down = pair.down == record.down;
      if (!is_down && opposite(pair.down) != record.down) {
        continue;
      }
      const double sign = is_down ? 1.0 : -1.0;
      // u↓ = (f⁻ + d)/|f⁻ + d|, u↑ = −(f⁻ − d)/|f⁻ − d|; ±e without misalignment.
      u = naive ? Eigen::Vector3d(sign * pair.axis)
                : Eigen::Vector3d(sign * (pair.f_minus + sign * pair.d).normalized());
      break;
    }
    const Eigen::Vector3d force = leg.weight * u;
    const Eigen::Index column = 6 * static_cast<Eigen::Index>(k);
    for (Eigen::Index i = 0; i < record.samples(); ++i) {
      const Eigen::Vector3d r = leg.com(record.phi(i, k));
      out.block<1, 3>(i, column) = (force + leg.offset.head<3>()).transpose();
      out.block<1, 3>(i, column + 3) = (r.cross(force) + leg.offset.tail<3>()).transpose();
    }
  }
  return out;
}

}  // namespace slipwalk::calibration
