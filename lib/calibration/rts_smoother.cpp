// The Rauch–Tung–Striebel smoother of the leg CoM (§4.3.1.3, ref. 82), hanging.hpp's smooth_com.
//
// Derivation (why a scalar filter is exact here). The Gaussian model is
//   r_0 ~ N(r̄, p₀ I),  r_{i+1} = r_i + N(0, q I),  y_i = −[f] r_i + N(0, ρ I),
// and the smoothed means are its MAP path. Write f̂ = f/|f| and P = I − f̂f̂ᵀ. Because
// −[f] r = r × f only sees P r and f × (y + f × r) = f × y − |f|² P r, the observation term splits
//   |y_i + [f] r_i|²/ρ = (f̂ · y_i)²/ρ + |P r_i − z_i|² / σ²,   z_i = f × y_i/|f|²,  σ² = ρ/|f|²,
// (|f × v| = |f||v| for v ⊥ f). The prior and the transitions are isotropic, so the MAP problem
// separates into (a) the component along f̂, a random walk without observations, whose MAP path is
// its prior mean f̂f̂ᵀ r̄ at every sample (the thesis' null direction), and (b) the two components
// ⊥ f, each an independent scalar random walk observed through z_i with variance σ². Their Kalman
// gains do not depend on the data and are the same for both, so one scalar filter (variances
// P_i) acting on 3-vectors in the plane ⊥ f is the whole smoother: O(n), no matrix per sample.
// tests/calibration/test_hanging.cpp checks it against the dense batch MAP of the full 3-D model.
//
// Its bias on noiseless data: in the interior the MAP's stationarity condition reads
//   (m_i − z_i)/σ² = (m_{i+1} − 2 m_i + m_{i−1})/q,   i.e.   m_i − z_i = (ρ/(q|f|²)) Δ²m_i,
// a lag (smoothing) error of (ρ/(q|f|²)) times the second difference of the path; for a CoM of
// amplitude A sampled N times a cycle it is about (ρ/(q|f|²)) A (2π/N)².
#include <cmath>

#include "calibration/hanging.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {

Eigen::Matrix3Xd smooth_com(const Eigen::Matrix3Xd& torque, const Eigen::Vector3d& force,
                            double transition_variance, double observation_variance,
                            const Eigen::Vector3d& prior, double prior_variance) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(transition_variance)) {
    throw core::InputError("smooth_com.transition_variance", "must be a positive number");
  }
  if (!positive(observation_variance)) {
    throw core::InputError("smooth_com.observation_variance", "must be a positive number");
  }
  if (!positive(prior_variance)) {
    throw core::InputError("smooth_com.prior_variance", "must be a positive number");
  }
  if (!torque.allFinite() || !force.allFinite() || !prior.allFinite()) {
    throw core::InputError("smooth_com", "torque, force and prior must be finite");
  }
  const Eigen::Index n = torque.cols();
  const double f2 = force.squaredNorm();
  if (f2 == 0.0) {
    // No observation sees r: the MAP path is the prior mean.
    return prior.replicate(1, n);
  }
  const Eigen::Vector3d fhat = force / std::sqrt(f2);
  const Eigen::Vector3d prior_along = fhat * fhat.dot(prior);
  const double sigma2 = observation_variance / f2;
  const double q = transition_variance;

  Eigen::Matrix3Xd mean(3, n);
  Eigen::VectorXd variance(n);
  Eigen::Vector3d predicted_mean = prior - prior_along;
  double predicted_variance = prior_variance;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d z = force.cross(torque.col(i)) / f2;
    const double gain = predicted_variance / (predicted_variance + sigma2);
    mean.col(i) = predicted_mean + gain * (z - predicted_mean);
    variance(i) = predicted_variance * sigma2 / (predicted_variance + sigma2);
    predicted_mean = mean.col(i);
    predicted_variance = variance(i) + q;
  }
  // Backward pass: m^s_i = m_i + G_i (m^s_{i+1} − m_i), G_i = P_i / (P_i + q).
  for (Eigen::Index i = n - 2; i >= 0; --i) {
    const double gain = variance(i) / (variance(i) + q);
    mean.col(i) += gain * (mean.col(i + 1) - mean.col(i));
  }
  mean.colwise() += prior_along;
  return mean;
}

}  // namespace slipwalk::calibration
