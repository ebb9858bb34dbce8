#pragma once
// §4.3.1: transducer offsets w_o, leg weights m_k g and leg centres of mass r_k(φ) from the robot
// hung in opposite directions (eqs. 4.4–4.7), per transducer and per pair of opposite hanging
// records (the thesis: ±x and ±z of the transducer frames).
//
// Exact form of the thesis' small-angle model. Hung with gravity along ±e (e: the body axis in
// transducer k's nominal frame, N_kᵀ a), transducer k sees gravity along unit vectors u↓ ≈ e and
// u↑ ≈ −e that differ from ±e by small rotations (the thesis' I + [s↓], I + [s↑]). With
// w = m_k g, the pair's half difference and half sum are exactly
//   f⁻ = (f↓ − f↑)/2 = w (u↓ + u↑')/2,   τ⁻_i = r(φ_i) × f⁻        (4.4 − 4.5, 4.6 − 4.7)
//   f⁺ = (f↓ + f↑)/2 = f_o + d,          τ⁺_i = r(φ_i) × d + τ_o   (4.4 + 4.5, 4.6 + 4.7)
// with u↑' = −u↑ and d = w (u↓ − u↑')/2. Because |u↓| = |u↑'| = 1, d ⊥ f⁻ and
// w = √(|f⁻|² + |d|²). So: f⁻ is the mean half difference; r(φ_i) follows from τ⁻_i (one pair
// leaves it free along f⁻, the thesis' null space; two pairs fix it); d (2 unknowns ⊥ f⁻) and τ_o
// (3) are the linear least-squares fit of τ⁺_i = [r_i] d + τ_o (the thesis' "minimise the spread
// of the torque offset" over s⁻); then f_o = mean f⁺ − d and w as above. This is exact for any
// misalignment. Dropping |d|² (w = |f⁻|, `thesis_first_order`) is a relative bias of
// 1 − cos(α/2) for the angle α between u↓ and u↑'. The thesis' printed estimator goes further:
// with s⁺ ⊥ e chosen so that (I + [s⁺])⁻¹ f⁻ lies along e, |s⁺| = tan β (β the angle between e and
// f⁻), and since (I + [s⁺]) e has length 1/cos β, (I + [s⁺])⁻¹ f⁻ · e = |f⁻| cos β = f⁻ · e — the
// weight of `no_misalignment`, biased by a further 1 − cos β (I + [s] is not a rotation). ŝ⁺ and
// ŝ⁻ are reported as rotation vectors ⊥ e: ŝ⁺ turns e onto f⁻/|f⁻| (angle β; the thesis' s⁺ is
// tan β along it), ŝ⁻ = e × d/w, from d = [ŝ⁻] w e to first order.
//
// The centre of mass (§4.3.1.3). Per sample, τ⁻_i = −[f⁻] r_i. The thesis runs a Kalman (RTS)
// smoother over the samples (state r, random-walk transition covariance Q, observation covariance
// R, both 0.01 I) per pair, then removes the null direction by matching the two pairs' estimates
// sample by sample (r = r_x + p f⁻_x = r_z + p' f⁻_z, p and p' by least squares) and averages.
// (With more than two pairs: r = (Σ_j P_j)⁻¹ Σ_j P_j r_j, P_j = I − f̂_j f̂_jᵀ, the same least
// squares.) Each pair's smoother starts from the minimum-norm solution of its first sample.
// `pointwise` solves both pairs' six equations for r_i at each sample directly (the smoother's
// limit R → 0): exact on noiseless data, where the smoother keeps its lag bias: in the interior
// its mean satisfies m_i − r_i⊥ = (ρ/(q|f⁻|²)) (m_{i+1} − 2m_i + m_{i−1}) exactly
// (rts_smoother.cpp), about (ρ/(q|f⁻|²)) A (2π/N)² for a CoM of amplitude A sampled N times a cycle
// — under 1e-9 m for the thesis' Q = R = 0.01 I, 6 N and N = 9000. Either way the samples are
// fitted with a periodic function of φ (model.hpp), and d is fitted against that fit r̂(φ_i), not
// the raw samples, whose noise would attenuate d (errors in variables).
//
// Pairing. The ↓ and ↑ records of a pair, and the two pairs, are matched sample by sample (the
// thesis: "the same set of varying shaft angles φ_i"): equal sample counts and shaft angles that
// agree to `max_phi_mismatch` turns modulo whole turns, or core::InputError naming the records'
// rows. In a pair the ↓ record is the one hung along the plus body axis (+x, +y, +z).
#include <Eigen/Core>
#include <vector>

#include "calibration/model.hpp"

namespace slipwalk::calibration {

/// How the misalignment of the hanging directions is modelled (Fig. 4.5 compares the last two).
enum class HangingModel {
  exact,               ///< the exact identities above (default)
  thesis_first_order,  ///< the thesis' I + [s]: w = |f⁻| (its |d|² bias), otherwise as exact
  no_misalignment,     ///< "without ŝ": f⁻ taken along e (w = f⁻ · e, d = 0, f_o = mean f⁺,
                       ///< τ_o = mean τ⁺), the naive addition and subtraction of Fig. 4.5
};

enum class ComEstimator { smoother, pointwise };

struct HangingOptions {
  HangingModel model = HangingModel::exact;
  ComEstimator com = ComEstimator::smoother;
  double transition_variance = 0.01;  ///< Q = q I of the random walk per sample, m² (thesis 0.01)
  double observation_variance = 0.01;  ///< R = ρ I of the torque observation, (N·m)² (thesis 0.01)
  int harmonics = 4;                   ///< of the periodic CoM fit (the thesis fits one sinusoid)
  double max_phi_mismatch = 0.01;      ///< turns, between samples matched across records
};

/// Throws core::InputError("hanging.<field>", ...) for non-positive variances, harmonics outside
/// [0, 16] or a mismatch outside (0, 0.5].
void validate(const HangingOptions& options);

/// One opposite pair's intermediate results, per transducer (what the report shows of §4.3.1).
struct HangingPair {
  BodyAxis down = BodyAxis::plus_x;  ///< the ↓ record's axis (its ↑ partner is opposite(down))
  Eigen::Vector3d axis;              ///< e, the nominal gravity direction in the transducer frame
  Eigen::Vector3d f_minus;           ///< mean f⁻, N
  Eigen::Vector3d d;                 ///< N, ⊥ f⁻ (zero for no_misalignment)
  Eigen::Vector3d s_plus;            ///< ŝ⁺, rad (rotation vector ⊥ e)
  Eigen::Vector3d s_minus;           ///< ŝ⁻, rad
  double weight = 0.0;               ///< w from this pair alone, N
  Wrench offset;                     ///< w_o from this pair alone
  Wrench offset_se;                  ///< its standard errors (from the residual scatter)
  double weight_se = 0.0;
};

/// What the hanging experiments give for one transducer.
struct LegEstimate {
  Wrench offset = Wrench::Zero();  ///< w_o: the pairs' estimates, inverse-variance weighted
  Wrench offset_se = Wrench::Zero();
  double weight = 0.0;  ///< m_k g, N
  double weight_se = 0.0;
  PeriodicFit com;                 ///< r_k(φ), m, transducer frame
  Eigen::VectorXd com_phi;         ///< (n) the shaft angle of each CoM sample, turns
  Eigen::Matrix3Xd com_samples;    ///< (3 × n) r_k(φ_i) before the periodic fit (Fig. 4.4)
  double com_fit_rms = 0.0;        ///< m, RMS distance of the samples from the fit
  std::vector<HangingPair> pairs;  ///< one per opposite pair used
};

struct HangingCalibration {
  std::vector<LegEstimate> legs;  ///< (K), in the geometry's order
  HangingOptions options;
};

/// §4.3.1 over all transducers. `records` holds at least two opposite pairs whose axes are not
/// parallel (any extra records, e.g. a third pair, are used too; a record without its opposite
/// is ignored with no error only when it is −z, the naive tare's upright record, and the −z/+z
/// pair is otherwise complete). Throws core::InputError naming the record (its source) for a
/// missing opposite, fewer than two non-parallel pairs, wrong widths, non-finite entries, fewer
/// than 3 + 2H samples, or samples that do not pair up.
[[nodiscard]] HangingCalibration calibrate_hanging(const Geometry& geometry,
                                                   const std::vector<HangingRecord>& records,
                                                   const HangingOptions& options = {});

/// The hanging model's prediction of each sample's reading under the estimates, for `record`
/// (n × 6K): w_o + [w u; r(φ) × w u] with u the gravity direction the estimates imply for that
/// record (the exact model: u↓ = (f⁻ + d)/w, u↑ = −(f⁻ − d)/w, normalised; no_misalignment: ±e;
/// a record no pair used, e.g. the lone −z: its nominal e). w and w_o are the leg's combined ones.
[[nodiscard]] Eigen::MatrixXd predict_hanging(const Geometry& geometry,
                                              const HangingCalibration& calibration,
                                              const HangingRecord& record);

/// The Rauch–Tung–Striebel smoother for the CoM (§4.3.1.3, ref. 82): state r_i ∈ R³, r_{i+1} = r_i
/// + N(0, q I), observation y_i = H r_i + N(0, ρ I) with H = −[f] (the same f at every sample),
/// prior r_0 ~ N(prior, prior_variance I). Returns the smoothed means (3 × n). Linear in the
/// observations; equal to the batch least-squares (MAP) solution of the same Gaussian model; along
/// f it returns the prior's component (no observation sees it). O(n): the model separates into a
/// scalar filter ⊥ f (rts_smoother.cpp). Throws core::InputError for non-positive variances or
/// non-finite inputs.
[[nodiscard]] Eigen::Matrix3Xd smooth_com(const Eigen::Matrix3Xd& torque,
                                          const Eigen::Vector3d& force, double transition_variance,
                                          double observation_variance,
                                          const Eigen::Vector3d& prior = Eigen::Vector3d::Zero(),
                                          double prior_variance = 1.0);

}  // namespace slipwalk::calibration
