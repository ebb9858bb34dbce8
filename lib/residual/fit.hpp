#pragma once
// Fitting the connection residual B of thesis §5.3.1 from motion data. The template model gives
// the body velocity A(q) q̇ (eq. 3.20); the measured one is g̊_true. The residual model is
//   g̊_true,t ≈ (A(q_t) + B) q̇_t,   B ∈ R^{3 × 2K} constant,
// so with r_t = g̊_true,t − A(q_t) q̇_t stacked as rows R (n × 3) and the feet's planar velocities
// vec(q̇_xy,t) as rows Q (n × 2K; columns 2k, 2k + 1 are foot k's q̇_x, q̇_y, the ordering of A
// and of connection::LinearResidual), the fit is the least-squares problem min ‖Q Bᵀ − R‖_F.
//
// Two estimators:
//  - the Moore–Penrose pseudo-inverse, Bᵀ = Q⁺ R (the thesis' choice), by Eigen's complete
//    orthogonal decomposition: the minimum-norm solution, which is the unique least-squares
//    solution when Q has full column rank and otherwise leaves B zero on the directions q̇ never
//    takes. A periodic gait spans few directions of R^{2K} (q̇ of 2K coordinates driven by a few
//    oscillators), so the rank and the conditioning of Q are reported with every fit;
//  - ridge regression, Bᵀ = (QᵀQ + λ I)⁻¹ Qᵀ R, from the SVD of Q, with λ chosen by
//    leave-one-trial-out cross-validation over a grid (snapshots within one trial are correlated,
//    so folds are whole trials). λ → 0 is the pseudo-inverse.
#include <Eigen/Core>
#include <vector>

namespace slipwalk::residual {

/// The snapshots of one trial: rows of vec(q̇_xy) (n × 2K, m/s) and of the residual velocity
/// r = g̊_true − A(q) q̇ (n × 3: v_x, v_y in m/s, ω in rad/s; body frame).
struct ResidualTrial {
  Eigen::MatrixXd qdot;
  Eigen::MatrixXd residual;
};

struct ResidualFit {
  Eigen::Matrix<double, 3, Eigen::Dynamic> B;  ///< (3 × 2K)
  Eigen::Index snapshots = 0;                  ///< n, rows of Q
  Eigen::Index rank = 0;                       ///< numerical rank of Q
  Eigen::VectorXd singular_values;             ///< of Q, descending (2K, or n when n < 2K)
  /// σ_max / σ_min over the singular values counted in `rank` (1 for a rank-1 Q, +∞ for rank 0).
  double condition = 0.0;
  double lambda = 0.0;  ///< the ridge parameter (0 for the pseudo-inverse)
  /// RMS of each component of the residual before (R) and after (R − Q Bᵀ) the fit, over the
  /// training snapshots.
  Eigen::Vector3d rms_before = Eigen::Vector3d::Zero();
  Eigen::Vector3d rms_after = Eigen::Vector3d::Zero();
};

/// Throws core::InputError ("trials[2].residual", ...) when there are no trials, the sizes
/// disagree (q̇ columns differ between trials, rows of q̇ and r differ, r not 3 wide, an odd q̇
/// width), an entry is not finite, or there are no snapshots.
void validate(const std::vector<ResidualTrial>& trials);

/// The relative threshold below which a singular value counts as zero: σ ≤ tol · σ_max
/// (the default is LAPACK's, max(n, 2K) · ε).
[[nodiscard]] double default_rank_tolerance(Eigen::Index rows, Eigen::Index cols);

/// B = (Q⁺ R)ᵀ over all trials' snapshots stacked. `rank_tolerance` ≤ 0: the default.
[[nodiscard]] ResidualFit fit_residual(const std::vector<ResidualTrial>& trials,
                                       double rank_tolerance = 0.0);

/// B = ((QᵀQ + λ I)⁻¹ Qᵀ R)ᵀ over all trials' snapshots; λ ≥ 0 (0: the pseudo-inverse through
/// the SVD, with the default rank tolerance).
[[nodiscard]] ResidualFit fit_residual_ridge(const std::vector<ResidualTrial>& trials,
                                             double lambda);

/// Leave-one-trial-out cross-validation of ridge regression over `lambdas` (each ≥ 0; needs at
/// least two trials): for each λ the mean over held-out trials of the held-out RMS residual
/// (all three components, after the fit). `best` is the λ with the least error (the larger λ on
/// a tie: the simpler model).
struct RidgeValidation {
  std::vector<double> lambdas;
  std::vector<double> error;  ///< mean held-out RMS residual per λ
  double best = 0.0;
};
[[nodiscard]] RidgeValidation validate_ridge(const std::vector<ResidualTrial>& trials,
                                             const std::vector<double>& lambdas);

}  // namespace slipwalk::residual
