#pragma once
// A synthetic BigANT with six F/T transducers whose true calibration is known (thesis ch. 4 without
// the robot): every estimate of hanging.hpp and standing.hpp can be compared with the truth.
//
// The truth is like the thesis' robot: offsets of Table 4.1 (its printed estimates taken as the
// true offsets), leg weights 6.1–6.4 N (Table 4.1), the whole robot 8.18 kg (§4.1.1), a chassis
// centre of mass off the body origin by enough to bias the torque by ≈ 2.5 N·m (§4.5), mounting
// errors of a few degrees and millimetres drawn from a seed. The legs are BigANT's four-bar legs
// (robots/bigant.hpp); a leg's centre of mass moves with its shaft angle because its links move
// (synthetic.cpp states the link masses). The readings are computed from the physics — gravity
// acting at the true centres of mass, ground forces at the toes, the chassis in equilibrium —
// and never from the calibration's model equations, so a calibration that recovers the truth
// has checked those equations too.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "calibration/model.hpp"
#include "robots/bigant.hpp"

namespace slipwalk::calibration {

/// The noise, the experiments' sizes and the truth's random parts.
struct SynthOptions {
  std::uint64_t seed =
      1;  ///< the draws of the mounting errors, hanging misalignments, poses, noise
  /// Multiplies the σ's of the readings (hanging_*_noise, pose_*_noise) and of attitude_noise
  /// (0: noiseless readings and attitudes). The draws do not depend on it: the data at scale s
  /// are the noiseless data plus s times the same noise. Misalignments, tilts, internal forces
  /// and mounting errors are part of the truth, not noise, and keep their σ's.
  double noise_scale = 1.0;

  // Hanging (§4.3.1): the thesis turned each leg ten cycles with 9,000 samples per cycle.
  int cycles = 10;
  int samples_per_cycle = 900;
  double hanging_force_noise = 0.1;     ///< N, σ per sample and axis
  double hanging_torque_noise = 0.005;  ///< N·m
  double hanging_misalignment = 0.035;  ///< rad, σ per axis of each hanging direction's error

  // Standing (§4.1.2.1): 3⁶ = 729 poses of shaft angles 0, ±36°; the thesis kept 543.
  int poses = 543;
  double pose_force_noise = 0.2;    ///< N, σ per pose and axis (settling, casing loads)
  double pose_torque_noise = 0.02;  ///< N·m
  double attitude_noise = 0.003;    ///< rad, σ per axis of motion capture's attitude
  double floor_tilt = 0.02;         ///< rad, σ per axis of the floor's tilt under each pose
  double internal_force = 0.15;     ///< self-equilibrated foot forces, × the mean normal load

  // Mounting errors (drawn per transducer).
  double mounting_rotation = 0.035;     ///< rad, σ per axis of R̃_k
  double mounting_translation = 0.003;  ///< m, σ per axis of p̃_k
};

/// Throws core::InputError("synth.<field>", ...) for values out of range (cycles 1..100,
/// samples per cycle 8..100000 and cycles × samples per cycle ≤ kMaxHangingSamples, poses 1..729,
/// σ's and scales finite and ≥ 0, angles < 0.3 rad, internal_force ≤ 1, mounting_translation
/// < 0.05 m).
void validate(const SynthOptions& options);

/// The most samples per hanging record (4 records × 1,000,000 samples × 42 columns ≈ 1.3 GB).
inline constexpr long kMaxHangingSamples = 1'000'000;

/// The synthetic leg's mass model (synthetic.cpp's head): shares of the leg's weight carried by
/// each part (they sum to 1), each part's centroid, and where the transducer sits.
struct LegMassShares {
  double motor = 0.50;    ///< motor, gearbox and bracket: fixed to the transducer
  double crank = 0.08;    ///< uniform bar O₂A
  double coupler = 0.12;  ///< uniform bar AB
  double toe = 0.18;      ///< uniform bar AP (the coupler's extension to the toe, foot included)
  double rocker = 0.12;   ///< uniform bar O₄B
};
inline constexpr LegMassShares kLegMassShares{};
inline constexpr double kTransducerHeight =
    0.04;  ///< m: nominal transducer origin above the crank pivot
inline constexpr double kMotorInboard =
    0.035;  ///< m: the motor part's centroid inboard of the leg plane
inline constexpr double kMotorHeight = 0.02;         ///< m: ... and above the crank pivot
inline constexpr double kFrictionCoefficient = 1.0;  ///< μ of the standing poses' friction cone

/// The true parameters.
struct SyntheticTruth {
  Geometry geometry;                                      ///< nominal: what the calibration is told
  std::vector<Wrench> offset;                             ///< (K) w_o, transducer frame
  std::vector<double> weight;                             ///< (K) m_k g, N
  std::vector<Eigen::Matrix3d> mounting_rotation;         ///< (K) R̃_k
  std::vector<Eigen::Vector3d> mounting_translation;      ///< (K) p̃_k, transducer frame, m
  Eigen::Vector3d chassis_com = Eigen::Vector3d::Zero();  ///< c_B, body frame, m
  robots::BigAntLegs bigant;  ///< the linkage and the nominal crank pivots (body frame, m)

  [[nodiscard]] int legs() const { return geometry.size(); }
  /// r_k(φ): the leg's centre of mass in its (true) transducer frame, m.
  [[nodiscard]] Eigen::Vector3d leg_com(int leg, double phi) const;
  /// The toe of leg k at φ in its (true) transducer frame, m.
  [[nodiscard]] Eigen::Vector3d toe(int leg, double phi) const;
  /// The true T^B_ft_k = N_k · (R̃_k, p̃_k).
  [[nodiscard]] Frame transducer_frame(int leg) const;
  /// u_k = R_N,k p̃_k − c_B (model.hpp): what the standing fit estimates.
  [[nodiscard]] Eigen::Vector3d displacement(int leg) const;
  /// G_robot − Σ m_k g, N.
  [[nodiscard]] double chassis_weight() const;
  /// The torque bias (N·m) that an unknown chassis CoM leaves in the standing balance:
  /// |c_B,xy| · G_ch (§4.5: "removed the 2.5 N·m bias").
  [[nodiscard]] double com_torque_bias() const;
};

/// The truth for `options.seed` (only the mounting errors are drawn; the rest is fixed as above).
[[nodiscard]] SyntheticTruth synthetic_truth(const SynthOptions& options);

/// The hanging experiments: +x, −x, +z, −z (body axes along gravity; −z is the upright robot),
/// each `cycles` turns of every leg sampled `samples_per_cycle` times per turn, every leg at the
/// same φ_i = i / samples_per_cycle. The hanging direction of each record is off by a small
/// rotation (σ hanging_misalignment per axis), the readings carry Gaussian noise.
[[nodiscard]] std::vector<HangingRecord> synthetic_hanging(const SyntheticTruth& truth,
                                                           const SynthOptions& options);

/// The true gravity direction (unit vector, body axes) of each record of synthetic_hanging, in
/// its order (+x, −x, +z, −z): the axis turned by the record's misalignment. Depends only on
/// options.seed and options.hanging_misalignment.
[[nodiscard]] std::vector<Eigen::Vector3d> synthetic_hanging_gravity(const SynthOptions& options);

/// The standing experiment with what the generator knows and the recording does not.
struct SyntheticStanding {
  StandingPoses poses;                       ///< what is recorded (noisy readings and attitudes)
  std::vector<Eigen::Matrix3d> attitude;     ///< (P) the true R^W_C (floor tilt · heading)
  std::vector<Eigen::Matrix3Xd> foot_force;  ///< (P) 3 × K ground forces on the toes, body axes, N
  std::vector<Eigen::Matrix3Xd> toe;         ///< (P) 3 × K toe positions, body frame, m
};

/// The standing poses: `poses` of the 729 combinations of φ_k ∈ {0, ±0.1 turn}, drawn without
/// replacement (P poses are the first P of the same shuffle); each on a floor tilted by a small
/// random rotation, under a random heading, every foot loaded (each foot pushing against gravity,
/// the least-squares load distribution of equal vertical springs, synthetic.cpp) plus a random
/// self-equilibrated set of foot forces, so that the whole robot is exactly at rest with every
/// normal load positive and every foot inside the friction cone (μ = kFrictionCoefficient);
/// readings with noise, the attitude as motion capture measures it (with noise). Throws
/// core::ComputationError when a floor is too steep for the cone (tilt > atan 0.9).
[[nodiscard]] StandingPoses synthetic_poses(const SyntheticTruth& truth,
                                            const SynthOptions& options);
/// The same poses with their true attitudes and foot forces (synthetic_poses returns .poses).
[[nodiscard]] SyntheticStanding synthetic_standing(const SyntheticTruth& truth,
                                                   const SynthOptions& options);

/// The noiseless reading of transducer k (its leg's applied wrench plus offset, transducer frame)
/// for a ground force `foot_force` (N, body axes) at the leg's toe, the leg at φ and gravity along
/// the unit vector `down` (body axes): the forward model the generators use, exposed for tests.
[[nodiscard]] Wrench true_reading(const SyntheticTruth& truth, int leg, double phi,
                                  const Eigen::Vector3d& down, const Eigen::Vector3d& foot_force);

}  // namespace slipwalk::calibration
