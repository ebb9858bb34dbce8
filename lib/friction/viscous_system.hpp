#pragma once
// The viscous balance of one frame, assembled and factorized once (thesis §3.4.3, eq. 3.20).
// With φ_k ≡ 1 the planar balance Σ J_kᵀ F_k = 0 is the linear system M x = −b of
// friction/balance.hpp, x = (v_x, v_y, ω) in the body frame, M = Σ c_k J_kᵀ G_k J_k,
// b = Σ c_k J_kᵀ G_k q̇_k, c_k = μ_k F_z,k. Two results of the model come from the same M:
//   - the local connection A_k = −c_k M⁺ J_kᵀ G_k of eq. 3.20 (connection::local_connection),
//   - the viscous-Coulomb body velocity x = −M⁺ b and its forces (friction::solve_viscous_coulomb).
// connection::evaluate builds one ViscousSystem per frame and hands it to both, so the system is
// assembled and factorized once. M⁺ is the inverse when two distinct points carry friction and the
// least-norm pseudo-inverse (in the scaled coordinates of balance.hpp) otherwise.
#include <Eigen/Core>

#include "contact/robot.hpp"
#include "friction/balance.hpp"

namespace slipwalk::friction {

/// Where ViscousSystem reads the feet's positions, contact flags and loads from.
enum class FeetSource {
  kFrame,  ///< frame.q, frame.contact and frame.Fz: any frame
  /// q and the contact flags as the padded rows the spring support's Newton route left in
  /// frame.support_newton (contact/robot.hpp: the same values), read four feet at a time without
  /// a partial last group, where that route certified the frame (frame.support.route, else as
  /// kFrame); F_z from the frame. Only right after contact::spring_support on this frame, with q,
  /// contact and Fz untouched since: connection::evaluate.
  kSupportRows,
};

/// M and b of eq. 3.20 for one frame, with M factorized. Built from frame.q, frame.qdot,
/// frame.contact and frame.Fz (contact::spring_support first); one pass over the feet, no
/// allocation. Building it writes c_k to the frame's scratch (the row c_k of frame.viscous for an
/// isotropic robot, else frame.work_n), so it describes that frame until another solver runs on
/// it.
class ViscousSystem {
 public:
  ViscousSystem(const contact::Robot& robot, contact::Frame& frame,
                FeetSource feet = FeetSource::kFrame);

  /// c_k = μ_k F_z,k of foot k, N; 0 for a foot in the air or without friction.
  [[nodiscard]] double weight(int k) const { return weights_[k]; }
  /// (N) all the c_k, N, as weight() gives them (contiguous: for a pass over the feet).
  [[nodiscard]] const double* weights() const { return weights_; }
  /// Whether some foot with friction has an anisotropy w_k ≠ 0 (eq. 3.19); false: G_k = I for
  /// every foot, and a pass over the feet can skip the anisotropy terms.
  [[nodiscard]] bool anisotropic() const { return contacts_.anisotropic; }
  /// Whether the robot is isotropic and the assembly left the feet as rows in frame.viscous
  /// (contact/robot.hpp: q_x, q_y, q̇_x, q̇_y, c_k), which a pass over the feet may then read.
  [[nodiscard]] bool rows() const { return contacts_.rows; }
  /// (3 x 3) M⁺ in body coordinates x = (v_x, v_y, ω), so that x = −M⁺ b. The least-norm inverse
  /// is taken in the scaled coordinates of balance.hpp: M⁺ = D M̃⁺ D, D = diag(1, 1, 1/L).
  [[nodiscard]] Eigen::Matrix3d inverse() const;

 private:
  friend void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame,
                                    const ViscousSystem& system);

  const double* weights_;      ///< where the assembly left c_k (frame.viscous or frame.work_n)
  detail::Contacts contacts_;  ///< active feet, lever scale L, anisotropy
  /// M factorized: in body coordinates where definite (contacts_.unscaled), else M̃ (scaled)
  detail::Psd3 solver_;
  Eigen::Vector3d b_;  ///< b, in the coordinates of solver_
};

/// solve_viscous_coulomb(robot, frame) from the frame's already built system: the same v_body,
/// Fxy and friction summary to the bit, without assembling or factorizing M again.
void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame,
                           const ViscousSystem& system);

}  // namespace slipwalk::friction
