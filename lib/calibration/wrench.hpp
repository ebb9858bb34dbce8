#pragma once
// Rigid-body algebra of the calibration (thesis §4.2.1): wrenches w = [f; τ] (N, N·m), frames as
// rotation + translation, the skew matrix [v] (v × x = [v] x), the wrench transform (the
// transposed adjoint of the thesis) and the Cayley map of §4.3.2.
//
// Frames. A Frame {R, p} places frame S in frame B: a point with coordinates x_S in S has
// coordinates x_B = R x_S + p in B (the thesis' T^B_S with R = R^B_S, p = p^B_S).
//
// The wrench transform. A wrench measured at S's origin in S's axes, [f_S; τ_S], is the same force
// system as [f_B; τ_B] about B's origin in B's axes with
//   f_B = R f_S,   τ_B = R τ_S + p × R f_S.
// This is the thesis' w^B = [Ad_{(T^B_S)^{-1}}]^T w^S (§4.2.1): with T^S_B = (T^B_S)^{-1} =
// (Rᵀ, −Rᵀ p) its printed block matrix [[R, 0], [[p] R, R]] is what the two lines above say.
// Checked against a direct computation in tests/calibration/test_wrench.cpp: a force F at the point
// x_S has τ_S = x_S × F, and about B the moment of R F at R x_S + p.
//
// The Cayley map (§4.3.2, ref. 83): R(q) = (I − [q]) (I + [q])^{-1}, a rotation for every q ∈ R³
// (I + [q] is never singular: its eigenvalues are 1 and 1 ± i|q|), by the angle 2 atan|q| about
// −q/|q|; its inverse [q] = (I − R)(I + R)^{-1} exists for every rotation by less than π. Small
// q: R ≈ I − 2[q], so q ≈ −θ/2 for a rotation vector θ.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace slipwalk::calibration {

using Wrench = Eigen::Matrix<double, 6, 1>;  ///< [f (N); τ (N·m)]

/// Frame S placed in frame B: x_B = R x_S + p.
struct Frame {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  [[nodiscard]] Eigen::Vector3d operator*(const Eigen::Vector3d& x) const { return R * x + p; }
  /// The composition: (*this) * inner places inner's frame in this frame's parent.
  [[nodiscard]] Frame operator*(const Frame& inner) const { return {R * inner.R, R * inner.p + p}; }
  [[nodiscard]] Frame inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
};

/// [v]: the skew-symmetric matrix with [v] x = v × x.
[[nodiscard]] Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// The wrench w_S (at S's origin, S's axes) about B's origin in B's axes, S placed in B by
/// `s_in_b`: [R f; R τ + p × R f].
[[nodiscard]] Wrench transform_wrench(const Frame& s_in_b, const Wrench& w_s);

/// The 6 × 6 matrix of transform_wrench (w_B = M w_S).
[[nodiscard]] Eigen::Matrix<double, 6, 6> wrench_transform_matrix(const Frame& s_in_b);

/// The wrench of a force f applied at the point x (both in one frame) about that frame's origin:
/// [f; x × f].
[[nodiscard]] Wrench force_at(const Eigen::Vector3d& f, const Eigen::Vector3d& x);

/// R(q) = (I − [q])(I + [q])^{-1}.
[[nodiscard]] Eigen::Matrix3d cayley(const Eigen::Vector3d& q);

/// The q with cayley(q) = R, from [q] = (I − R)(I + R)^{-1}. Throws core::InputError("rotation",
/// ...) when R turns by π or within 1e-6 rad of it (I + R singular), or is not a rotation
/// (‖RᵀR − I‖ > 1e-9 or det R < 0).
[[nodiscard]] Eigen::Vector3d cayley_inverse(const Eigen::Matrix3d& R);

/// exp([θ]): the rotation by |θ| about θ/|θ| (Rodrigues), and its inverse (angle in [0, π]).
[[nodiscard]] Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& theta);
[[nodiscard]] Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R);

}  // namespace slipwalk::calibration
