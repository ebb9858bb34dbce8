#pragma once
// §4.3.2 and §4.4.2: the mounting errors (R̃_k, u_k; model.hpp) from the robot standing still in P
// poses, and the choice between Table 4.2's four models.
//
// The balance (eq. 4.8, derived). At rest, the chassis (legs excluded) is held by the K wrenches
// the legs apply through the transducers and its own weight G_ch = G_robot − Σ m_k g at its centre
// of mass C. With ŵ_pk = w_m,pk − w_o,k (the hanging stage's offsets), R_k = R_N,k R̃_k and
// c_k = p_N,k + u_k, pose p's residual in C is
//   e_p = Σ_k [R_k f̂_pk ; R_k τ̂_pk + c_k × R_k f̂_pk] + [G_ch ĝ_p ; 0],   ĝ_p = R^W_C,pᵀ (0, 0, −1),
// and the fit minimises Σ_p ‖e_p‖²_K with K = diag(1, 1, 1, κ, κ, κ) (the thesis: κ = 10). The
// rotation to W (the thesis writes e_p in W) leaves this K-norm unchanged. The thesis' printed form
// subtracts each leg's gravity wrench, centre of mass included, and asks for [0, 0, G_robot] with
// zero torque about C: that is the balance above minus Σ_k x_pk × m_k g ĝ_p in the torque
// (x_pk = c_k + R_k r_k(φ_pk), the leg's centre of mass in C) — the legs' gravity moment about
// the chassis' centre of mass, which is not zero and changes from pose to pose when the legs are
// heavy (6.2 N of 80 N each on BigANT). `thesis_literal` fits that form, to measure what it costs.
//
// The models (Table 4.2; DOF for K transducers):
//   full                  R̃_k and u_k free                   6K   (36)
//   shared_translation    R̃_k free, u_k = u for all k         3K+3 (21)   (no per-transducer p̃_k)
//   translations_only     R̃_k = I, u_k free                   3K   (18)
//   com_only              R̃_k = I, u_k = u                    3    (3)
// A rotation is parametrised by Cayley parameters (wrench.hpp) in the alternating solver (the
// thesis': with the rotations fixed the residual is linear in the translations, and with the
// translations fixed each sweep solves the rotations; repeat until the largest parameter change is
// below `tolerance`) and by Ceres' quaternion manifold on SO(3) in the joint solver. Both reach
// the same minimum; the sweeps converge linearly, slowly along the gauge below (on 543 poses:
// ~250 sweeps with tilts of ±0.08 rad, more than 1000 with ±0.02 rad), the joint solve in 4–12
// Levenberg–Marquardt iterations, 100–300 times faster.
//
// Standard errors. The residuals' force and torque components have their own scatter (the K-norm
// mixes units), and they are correlated: transducer k's force noise enters the torque about C
// through c_k × R_k n_f. Through the fixed transducer frames the noise reaches e_p (in C) with the
// same 6 × 6 covariance Σ at every pose, so the covariance is the sandwich
// (JᵀKJ)⁻¹ (Σ_p J_pᵀ K Σ K J_p) (JᵀKJ)⁻¹ with Σ = Σ_p e_p e_pᵀ / (P − DOF/6) at the solution (the
// full 6 × 6, its force and torque blocks and their coupling); J is taken in the rotation vector
// of R̃_k (radians) and u_k (m), so the rotations' errors are of the rotation vector.
//
// Errors in variables. The force readings are both data and regressors (c_k × R_k f̂): their noise
// adds Σ_k κ tr([c_k] R_k Σ_f,k R_kᵀ [c_k]ᵀ) to the expected cost (2κσ_f²|c_k|² per pose for
// isotropic noise σ_f² per axis), which the least-squares fit lowers by pulling the transducer
// origins c_k towards C: a bias of order σ_f² / var(force) × |c_k| that does not shrink with the
// number of poses (the rotations are not affected to first order). With BigANT-like loads and
// σ_f = 0.3 N it is a few mm, about 1.2 standard errors at 543 poses; the standard errors above
// describe the scatter, not this bias. `force_noise_variance` removes it: the fit then minimises
// the corrected score Σ_p ‖e_p‖²_K − 2Pκσ_f² Σ_k |c_k|² (whose expectation is the noiseless cost;
// Newton steps from the plain fit, the Hessian less the term's curvature, which also enters the
// sandwich). Not in the thesis; off by default.
//
// Gauge. A common turn of every transducer about the vertical through C, with the displacements
// turned along, changes e_p only through the tilts of ĝ_p: on level ground the full model is
// nearly free along it. Its conditioning is reported (the smallest singular value of K^{1/2} J).
#include <Eigen/Core>
#include <cstdint>
#include <string_view>
#include <vector>

#include "calibration/hanging.hpp"
#include "calibration/model.hpp"

namespace slipwalk::calibration {

enum class MountingModel { full, shared_translation, translations_only, com_only };
inline constexpr MountingModel kMountingModels[] = {
    MountingModel::full, MountingModel::shared_translation, MountingModel::translations_only,
    MountingModel::com_only};
[[nodiscard]] std::string_view model_label(
    MountingModel model);  ///< "full", "shared_translation", ...
[[nodiscard]] int model_dof(MountingModel model, int legs);

enum class BalanceTarget { chassis, thesis_literal };
enum class MountingSolver { alternating, ceres_so3 };
[[nodiscard]] std::string_view solver_label(MountingSolver solver);  ///< "alternating", "ceres_so3"

struct MountingOptions {
  MountingModel model = MountingModel::full;
  /// The joint solve by default: the thesis' alternation reaches the same minimum but, along the
  /// gauge, 100–300 times slower (above); `alternating` keeps it for comparison.
  MountingSolver solver = MountingSolver::ceres_so3;
  BalanceTarget target = BalanceTarget::chassis;
  double torque_weight = 10.0;  ///< κ
  double tolerance = 1e-10;  ///< alternating: largest parameter change; Ceres: relative cost change
  int max_iterations = 1000;  ///< alternating sweeps, or Ceres iterations
  /// σ_f², N² per axis, of each transducer's pose force reading, for the errors-in-variables
  /// correction (above): 0 leaves the thesis' plain least squares; > 0 uses this value; < 0
  /// estimates it from the plain fit's force residuals (tr Σ_FF / 3K: transducers of equal,
  /// isotropic noise; attitude noise, which also enters the force residual, inflates it).
  double force_noise_variance = 0.0;
};

/// Throws core::InputError("mounting.<field>", ...) for κ not positive and finite, a tolerance
/// outside (0, 1) or fewer than one iteration.
void validate(const MountingOptions& options);

/// A starting point (identity rotations and zero displacements by default).
struct MountingStart {
  std::vector<Eigen::Matrix3d> rotation;      ///< (K)
  std::vector<Eigen::Vector3d> displacement;  ///< (K); a shared model starts from their mean
};

struct MountingEstimate {
  MountingModel model = MountingModel::full;
  MountingSolver solver = MountingSolver::alternating;
  BalanceTarget target = BalanceTarget::chassis;
  std::vector<Eigen::Matrix3d> rotation;         ///< (K) R̃_k (identity where the model fixes it)
  std::vector<Eigen::Vector3d> displacement;     ///< (K) u_k, m (all equal in a shared model)
  std::vector<Eigen::Vector3d> rotation_se;      ///< (K) rad, of the rotation vector; 0 where fixed
  std::vector<Eigen::Vector3d> displacement_se;  ///< (K) m
  double chassis_weight = 0.0;                   ///< G_ch used, N
  double rss = 0.0;                              ///< Σ_p ‖e_p‖²_K at the solution
  Eigen::Index poses = 0;
  int dof = 0;
  int iterations = 0;  ///< alternating sweeps or Ceres iterations
  bool converged = false;
  double seconds = 0.0;  ///< wall time of the solve
  /// Of K^{1/2} J at the solution (the gauge's conditioning).
  double smallest_singular_value = 0.0;
  /// σ_f² the correction used, N²; 0: not corrected — not asked for, or undefined because the
  /// corrected score has no minimum (a noise large against the forces' spread; the plain fit
  /// stands)
  double force_noise_variance = 0.0;
};

/// Fits the chosen model to `poses` (all of them) given the hanging stage's offsets, weights and
/// CoM fits. Throws core::InputError naming the pose's row for non-finite entries, attitudes that
/// are not rotations, wrong widths or fewer poses than the model's DOF / 6 + 1; ComputationError
/// when the solver fails outright (a non-finite cost).
[[nodiscard]] MountingEstimate fit_mounting(const Geometry& geometry, const StandingPoses& poses,
                                            const HangingCalibration& hanging,
                                            const MountingOptions& options = {},
                                            const MountingStart& start = {});

/// e_p for every pose (P × 6), in W (force N, torque N·m about C, unweighted), under `estimate`.
[[nodiscard]] Eigen::MatrixXd balance_residuals(const Geometry& geometry,
                                                const StandingPoses& poses,
                                                const HangingCalibration& hanging,
                                                const MountingEstimate& estimate);

/// The naive tare of §4.1.2.1 (Fig. 4.2, Fig. 4.6 blue): each transducer's bias is its mean reading
/// over the first `cycles` turns of its leg in `air` (the upright robot, feet in the air); the
/// readings less the bias, through the nominal frames, summed about B's origin, rotated to W, less
/// [0, 0, G_robot, 0, 0, 0]: (P × 6).
[[nodiscard]] Eigen::MatrixXd naive_residuals(const Geometry& geometry, const StandingPoses& poses,
                                              const HangingRecord& air, double cycles = 2.0);

/// One row of Table 4.2.
struct ModelScore {
  MountingModel model = MountingModel::full;
  int dof = 0;
  double rss = 0.0;     ///< on all poses
  double cv_mse = 0.0;  ///< mean over the folds of the test poses' mean ‖e_p‖²_K
  double bic = 0.0;     ///< P ln(RSS/P) + DOF ln P
};

/// Table 4.2: every model fitted to all poses (RSS, BIC) and by `folds`-fold cross-validation over
/// a seeded shuffle of the poses (the same folds for every model). `options.model` is ignored.
[[nodiscard]] std::vector<ModelScore> score_models(const Geometry& geometry,
                                                   const StandingPoses& poses,
                                                   const HangingCalibration& hanging,
                                                   const MountingOptions& options, int folds = 5,
                                                   std::uint64_t seed = 1);

/// §4.4.2's multistart: `starts` fits from random starts (each rotation by a uniform angle below
/// `max_angle` about each axis, each displacement uniform in a ball of radius `max_displacement`;
/// the thesis: 15° and a third of the robot's 73 cm), seeded; the first start is the default one.
[[nodiscard]] std::vector<MountingEstimate> multistart(
    const Geometry& geometry, const StandingPoses& poses, const HangingCalibration& hanging,
    const MountingOptions& options, int starts = 20, std::uint64_t seed = 1,
    double max_angle = 0.2617993877991494, double max_displacement = 0.73 / 3.0);

}  // namespace slipwalk::calibration
