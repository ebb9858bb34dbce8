#pragma once
// The in-situ F/T calibration of thesis ch. 4 as data: what is known before calibrating (the
// design file's transducer frames and the robot's weight), the two experiments' recordings, and
// the estimates. The algorithms are free functions in hanging.hpp (§4.3.1), standing.hpp (§4.3.2,
// §4.4.2) and calibrate.hpp (both, in order).
//
// Frames (§4.2.1). B: the body frame (x forward, y left, z up, origin near the chassis centroid);
// C: B's axes moved to the chassis' centre of mass; W: the floating-base frame (z against
// gravity), reached from C by the motion-capture attitude R^W_C; ft_k: transducer k's frame.
//
// The sensing model (eq. 4.1): transducer k reads w_m = w_a + w_o + n, where w_a is the wrench the
// leg (everything below the transducer) applies to the chassis, at ft_k's origin in ft_k's axes,
// w_o a constant offset and n noise. Hanging, w_a is the leg's gravity m_k g acting at its centre
// of mass r_k(φ) (ft_k frame, a function of the leg's shaft angle φ through its four-bar, §4.1.1):
// w_a = [m_k g u; r_k(φ) × m_k g u], u the unit gravity direction in ft_k. Standing, w_a adds the
// ground contact wrench of the foot.
//
// The mounting (eq. 4.2). Transducer k sits at T^B_ft_k = N_k · (R̃_k, p̃_k): N_k the nominal frame
// of the design file, (R̃_k, p̃_k) the unknown mounting error in the transducer's own axes (a tilt
// about the transducer, not about the body origin; the thesis composes the error on the other
// side, T^B T̃_k T^B_ft, which turns a transducer 35 cm from the origin about that origin — with
// free per-leg translations, Table 4.2's full model, the two are the same family). The chassis'
// centre of mass sits at c_B in B. What the standing experiment can resolve is, per transducer,
// the rotation R̃_k and the displacement u_k = R_N,k p̃_k − c_B of its origin in C from the nominal
// position: the origin of ft_k in C is p_N,k + u_k (the thesis' p̃'_k, up to its convention).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/wrench.hpp"

namespace slipwalk::calibration {

/// What the design files and a scale give (§4.2.2 step 1, §4.1.1), known before calibrating.
struct Geometry {
  std::vector<std::string>
      legs;  ///< (K) leg names, unique, [A-Za-z0-9_]+ (BigANT: HL ML FL HR MR FR)
  std::vector<Frame> transducer;  ///< (K) N_k: transducer k's nominal frame in B (m)
  double robot_weight = 0.0;      ///< G_robot, N: the whole robot, legs included (> 0)

  [[nodiscard]] int size() const { return static_cast<int>(legs.size()); }
};

/// Throws core::InputError("geometry.<field>", ...) unless there is at least one leg, names are
/// unique and well formed, every frame is finite with a proper rotation (‖RᵀR − I‖ ≤ 1e-9, det > 0)
/// and |p| ≤ 100 m, and the weight is finite and positive.
void validate(const Geometry& geometry);

/// The body axis that points along gravity (down) during a hanging experiment.
enum class BodyAxis { plus_x, minus_x, plus_y, minus_y, plus_z, minus_z };

[[nodiscard]] std::string_view axis_label(BodyAxis axis);  ///< "+x", "-x", ..., "-z"
[[nodiscard]] std::optional<BodyAxis> parse_axis(std::string_view label);
[[nodiscard]] Eigen::Vector3d axis_vector(BodyAxis axis);  ///< the unit vector in B
[[nodiscard]] BodyAxis opposite(BodyAxis axis);

/// One hanging experiment (§4.3.1, Fig. 4.3): the robot hung with body axis `down` (nominally)
/// along gravity, no foot touching anything, every leg turning slowly. The upright robot with its
/// feet in the air, from which the naive tare of §4.1.2.1 takes its bias, is `down` = −z.
struct HangingRecord {
  BodyAxis down = BodyAxis::minus_z;
  Eigen::MatrixXd phi;  ///< (n × K) shaft angles, turns, as recorded (not wrapped)
  Eigen::MatrixXd
      wrench;  ///< (n × 6K) readings; leg k's fx fy fz (N) τx τy τz (N·m) in columns 6k..6k+5
  std::vector<std::string> rows;  ///< (n, or empty) "file:line" of each sample's row
  std::string source;             ///< where it came from ("hanging.csv:2" or a label)

  [[nodiscard]] Eigen::Index samples() const { return phi.rows(); }
};

/// The standing experiment (§4.1.2.1, §4.3.2): the robot at rest on the ground in P poses, each
/// the median of a settled window; the attitude from motion capture.
struct StandingPoses {
  Eigen::MatrixXd phi;                    ///< (P × K) turns
  Eigen::MatrixXd wrench;                 ///< (P × 6K) as HangingRecord
  std::vector<Eigen::Matrix3d> attitude;  ///< (P) R^W_C: the body's axes in W
  std::vector<std::string> rows;          ///< (P, or empty) "file:line" of each pose's row
  std::string source;

  [[nodiscard]] Eigen::Index poses() const { return phi.rows(); }
};

/// An R³-valued periodic function of the shaft angle (period one turn):
/// c₀ + Σ_{h=1..H} (a_h cos 2πhφ + b_h sin 2πhφ).
struct PeriodicFit {
  Eigen::Matrix3Xd coefficients =
      Eigen::Matrix3Xd::Zero(3, 1);  ///< (3 × (1 + 2H)): c₀, a₁, b₁, a₂, ...

  [[nodiscard]] int harmonics() const { return static_cast<int>((coefficients.cols() - 1) / 2); }
  [[nodiscard]] Eigen::Vector3d operator()(double phi) const;
};

/// Least-squares fit of `values` (3 × n) sampled at `phi` (n, turns) with H harmonics. Throws
/// core::InputError("harmonics", ...) for H < 0 or fewer than 1 + 2H samples.
[[nodiscard]] PeriodicFit fit_periodic(const Eigen::VectorXd& phi, const Eigen::Matrix3Xd& values,
                                       int harmonics);

}  // namespace slipwalk::calibration
