#include "residual/fit.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace slipwalk::residual {

namespace {

/// All trials' snapshots stacked, in trial order.
void stack(const std::vector<ResidualTrial>& trials, Eigen::MatrixXd& q, Eigen::MatrixXd& r) {
  Eigen::Index rows = 0;
  for (const ResidualTrial& t : trials) {
    rows += t.qdot.rows();
  }
  q.resize(rows, trials.front().qdot.cols());
  r.resize(rows, 3);
  Eigen::Index at = 0;
  for (const ResidualTrial& t : trials) {
    q.middleRows(at, t.qdot.rows()) = t.qdot;
    r.middleRows(at, t.qdot.rows()) = t.residual;
    at += t.qdot.rows();
  }
}

Eigen::Vector3d rms(const Eigen::MatrixXd& r) {
  if (r.rows() == 0) {
    return Eigen::Vector3d::Zero();
  }
  return (r.colwise().squaredNorm() / static_cast<double>(r.rows())).cwiseSqrt().transpose();
}

/// Rank and condition from descending singular values.
void rank_of(const Eigen::VectorXd& sigma, double tol, ResidualFit& fit) {
  fit.singular_values = sigma;
  const double top = sigma.size() > 0 ? sigma(0) : 0.0;
  fit.rank = 0;
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    if (sigma(i) > tol * top) {
      ++fit.rank;
    }
  }
  fit.condition =
      fit.rank == 0 ? std::numeric_limits<double>::infinity() : top / sigma(fit.rank - 1);
}

/// Bᵀ = V diag(σ / (σ² + λ)) Uᵀ R from the thin SVD, singular values under the tolerance dropped.
Eigen::MatrixXd ridge_solve(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, const Eigen::MatrixXd& r,
                            double lambda, double tol) {
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double top = sigma.size() > 0 ? sigma(0) : 0.0;
  Eigen::VectorXd gain = Eigen::VectorXd::Zero(sigma.size());
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    if (sigma(i) > tol * top) {
      gain(i) = sigma(i) / (sigma(i) * sigma(i) + lambda);
    }
  }
  return svd.matrixV() * gain.asDiagonal() * (svd.matrixU().transpose() * r);
}

ResidualFit finish(Eigen::MatrixXd bt, const Eigen::MatrixXd& q, const Eigen::MatrixXd& r,
                   ResidualFit fit) {
  fit.B = bt.transpose();
  fit.snapshots = q.rows();
  fit.rms_before = rms(r);
  fit.rms_after = rms(r - q * bt);
  return fit;
}

}  // namespace

void validate(const std::vector<ResidualTrial>& trials) {
  if (trials.empty()) {
    throw core::InputError("trials", "no trials to fit");
  }
  const Eigen::Index width = trials.front().qdot.cols();
  if (width == 0 || width % 2 != 0) {
    throw core::InputError("trials[0].qdot",
                           "needs 2K columns (q̇_x, q̇_y per foot), got " + std::to_string(width));
  }
  Eigen::Index rows = 0;
  for (std::size_t k = 0; k < trials.size(); ++k) {
    const std::string where = "trials[" + std::to_string(k) + "]";
    const ResidualTrial& t = trials[k];
    if (t.qdot.cols() != width) {
      throw core::InputError(
          where + ".qdot",
          std::to_string(t.qdot.cols()) + " columns where trial 0 has " + std::to_string(width));
    }
    if (t.residual.cols() != 3 || t.residual.rows() != t.qdot.rows()) {
      throw core::InputError(where + ".residual",
                             "needs " + std::to_string(t.qdot.rows()) + " rows of 3 (v_x, v_y, ω)");
    }
    if (!t.qdot.allFinite() || !t.residual.allFinite()) {
      throw core::InputError(where, "holds a value that is not finite");
    }
    rows += t.qdot.rows();
  }
  if (rows == 0) {
    throw core::InputError("trials", "no snapshots to fit");
  }
}

double default_rank_tolerance(Eigen::Index rows, Eigen::Index cols) {
  return static_cast<double>(std::max(rows, cols)) * std::numeric_limits<double>::epsilon();
}

ResidualFit fit_residual(const std::vector<ResidualTrial>& trials, double rank_tolerance) {
  validate(trials);
  Eigen::MatrixXd q;
  Eigen::MatrixXd r;
  stack(trials, q, r);
  const double tol =
      rank_tolerance > 0.0 ? rank_tolerance : default_rank_tolerance(q.rows(), q.cols());
  // The minimum-norm least-squares solution (the pseudo-inverse's), §5.3.1.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(tol);
  cod.compute(q);
  ResidualFit fit;
  rank_of(Eigen::JacobiSVD<Eigen::MatrixXd>(q).singularValues(), tol, fit);
  return finish(cod.solve(r), q, r, fit);
}

ResidualFit fit_residual_ridge(const std::vector<ResidualTrial>& trials, double lambda) {
  validate(trials);
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) {
    throw core::InputError("lambda", "must be a finite number ≥ 0");
  }
  Eigen::MatrixXd q;
  Eigen::MatrixXd r;
  stack(trials, q, r);
  const double tol = default_rank_tolerance(q.rows(), q.cols());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(q, Eigen::ComputeThinU | Eigen::ComputeThinV);
  ResidualFit fit;
  fit.lambda = lambda;
  rank_of(svd.singularValues(), tol, fit);
  return finish(ridge_solve(svd, r, lambda, tol), q, r, fit);
}

RidgeValidation validate_ridge(const std::vector<ResidualTrial>& trials,
                               const std::vector<double>& lambdas) {
  validate(trials);
  if (trials.size() < 2) {
    throw core::InputError("trials", "cross-validation needs at least two trials");
  }
  if (lambdas.empty()) {
    throw core::InputError("lambdas", "no ridge parameters to try");
  }
  for (double l : lambdas) {
    if (!(l >= 0.0) || !std::isfinite(l)) {
      throw core::InputError("lambdas", "every λ must be a finite number ≥ 0");
    }
  }
  RidgeValidation v;
  v.lambdas = lambdas;
  v.error.assign(lambdas.size(), 0.0);
  std::vector<ResidualTrial> rest;
  rest.reserve(trials.size() - 1);
  for (std::size_t out = 0; out < trials.size(); ++out) {
    rest.clear();
    for (std::size_t k = 0; k < trials.size(); ++k) {
      if (k != out) {
        rest.push_back(trials[k]);
      }
    }
    Eigen::MatrixXd q;
    Eigen::MatrixXd r;
    stack(rest, q, r);
    const double tol = default_rank_tolerance(q.rows(), q.cols());
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(q, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const ResidualTrial& held = trials[out];
    for (std::size_t i = 0; i < lambdas.size(); ++i) {
      const Eigen::MatrixXd bt = ridge_solve(svd, r, lambdas[i], tol);
      const Eigen::MatrixXd miss = held.residual - held.qdot * bt;
      const double n = static_cast<double>(std::max<Eigen::Index>(miss.size(), 1));
      v.error[i] += std::sqrt(miss.squaredNorm() / n) / static_cast<double>(trials.size());
    }
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < lambdas.size(); ++i) {
    const bool better =
        v.error[i] < v.error[best] || (v.error[i] == v.error[best] && lambdas[i] > lambdas[best]);
    if (better) {
      best = i;
    }
  }
  v.best = lambdas[best];
  return v;
}

}  // namespace slipwalk::residual
