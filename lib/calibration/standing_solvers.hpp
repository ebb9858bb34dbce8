#pragma once
// The standing stage's working parts (standing.hpp states the balance and the models): the data of
// the balance prepared once per fit, the balance itself (generic over the scalar, for Ceres'
// automatic differentiation), the linear displacement solve, the two solvers and the sandwich
// standard errors. Internal to lib/calibration: standing.cpp and standing_solvers.cpp.
#include <Eigen/Core>
#include <vector>

#include "calibration/standing.hpp"

namespace slipwalk::calibration::standing_detail {

/// One pose's terms of the balance.
struct PoseTerms {
  Eigen::Matrix3Xd force;    ///< (3 × K) f̂_pk = f_m − f_o, N, transducer axes
  Eigen::Matrix3Xd torque;   ///< (3 × K) τ̂_pk, N·m
  Eigen::Matrix3Xd com;      ///< (3 × K) r_k(φ_pk), m, transducer frame (thesis_literal only)
  Eigen::Vector3d down;      ///< ĝ_p = R^W_Cᵀ (0, 0, −1), unit, in C
  Eigen::Matrix3d attitude;  ///< R^W_C
};

/// Everything the balance needs, validated.
struct BalanceData {
  int legs = 0;
  BalanceTarget target = BalanceTarget::chassis;
  double sqrt_kappa = 1.0;                        ///< √κ: torque rows are weighted by it
  double chassis_weight = 0.0;                    ///< G_ch, N
  std::vector<Eigen::Matrix3d> nominal_rotation;  ///< (K) R_N,k
  std::vector<Eigen::Vector3d> nominal_position;  ///< (K) p_N,k, m
  std::vector<double> leg_weight;                 ///< (K) m_k g, N
  std::vector<PoseTerms> poses;                   ///< (P)
};

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Validates the inputs (core::InputError naming the pose's row) and prepares the terms.
[[nodiscard]] BalanceData prepare(const Geometry& geometry, const StandingPoses& poses,
                                  const HangingCalibration& hanging,
                                  const MountingOptions& options);

/// The terms of the poses `subset` only (indices into data.poses).
[[nodiscard]] BalanceData restrict_to(const BalanceData& data,
                                      const std::vector<Eigen::Index>& subset);

/// e_p in C (force N, torque N·m about C, unweighted) for mounting rotations R̃_k and
/// displacements u_k.
[[nodiscard]] Vector6d residual_in_c(const BalanceData& data, Eigen::Index pose,
                                     const std::vector<Eigen::Matrix3d>& rotation,
                                     const std::vector<Eigen::Vector3d>& displacement);

/// Σ_p ‖e_p‖²_K.
[[nodiscard]] double weighted_rss(const BalanceData& data,
                                  const std::vector<Eigen::Matrix3d>& rotation,
                                  const std::vector<Eigen::Vector3d>& displacement);

/// With the rotations fixed only the torque depends on the displacements, linearly: the exact
/// least-squares u_k (K equal entries when `shared`).
[[nodiscard]] std::vector<Eigen::Vector3d> solve_displacements(
    const BalanceData& data, const std::vector<Eigen::Matrix3d>& rotation, bool shared);

struct SolveResult {
  std::vector<Eigen::Matrix3d> rotation;      ///< (K) R̃_k
  std::vector<Eigen::Vector3d> displacement;  ///< (K) u_k
  int iterations = 0;
  bool converged = false;
};

[[nodiscard]] SolveResult solve_alternating(const BalanceData& data, MountingModel model,
                                            const MountingOptions& options,
                                            const MountingStart& start);
[[nodiscard]] SolveResult solve_joint(const BalanceData& data, MountingModel model,
                                      const MountingOptions& options, const MountingStart& start);

/// σ_f² from the force rows of the residuals (tr Σ_FF / 3K: transducers of equal isotropic noise).
[[nodiscard]] double estimate_force_noise_variance(const BalanceData& data, const SolveResult& fit,
                                                   int dof);

/// Newton steps from `fit` to the minimum of Σ_p ‖e_p‖²_K − 2Pκσ² Σ_k |c_k|² (standing.hpp).
/// False, with `fit` unchanged, where that score has no minimum (its Hessian is not positive
/// definite) or the steps do not settle in 50.
[[nodiscard]] bool correct_errors_in_variables(const BalanceData& data, MountingModel model,
                                               double variance, SolveResult& fit);

/// Fills rotation_se, displacement_se and smallest_singular_value of `estimate` (its rotation and
/// displacement set) with the sandwich covariance of standing.hpp.
void standard_errors(const BalanceData& data, MountingEstimate& estimate);

}  // namespace slipwalk::calibration::standing_detail
