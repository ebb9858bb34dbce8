// The planar friction forces at a prescribed body velocity (thesis §3.4).
//
// ---- What is computed ---------------------------------------------------------------------------
// Foot k of a robot whose body moves at x = (v_x, v_y, ω) (body frame) slides at
//   u_k = v + ω S q_k + q̇_k                                       (eq. 3.5 rotated by R_θᵀ)
// and its planar force is F_k = −c_k φ(s_k) G_k u_k with c_k = μ_k F_z,k, G_k = I + w_k w_kᵀ
// (eq. 3.19 in body coordinates) and s_k = √(u_kᵀ G_k u_k) = ‖W_k u_k‖, where
//   φ = 1                  the viscous-Coulomb ansatz (eq. 3.14 with ε → ∞, eq. 3.19),
//   φ = 1/s                Coulomb friction (eq. 3.13; anisotropic: the force lies on the rim of
//                          the friction ellipse {F : Fᵀ G⁻¹ F ≤ c²}),
//   φ = (ε + s)/(ε + s²)   the ε-family of eq. 3.14, between the two.
// planar_forces returns Σ F_k and Σ (q_k × F_k)_z = Σ (q_x F_y − q_y F_x) over the feet in
// contact: the left-hand sides of the force and moment balance (eqs. 3.16–3.18), which the
// solvers of friction/solvers.hpp drive to zero. These are the solvers' laws and metric exactly
// (friction/balance.hpp), written out per foot without the solvers' scaled coordinates.
//
// ---- Where the Coulomb law is set-valued --------------------------------------------------------
// At u_k = 0 a Coulomb foot sticks and carries any force in its ellipse; foot_force returns the
// ellipse's centre, 0. A sum over feet one of which sticks is therefore not the balance's sum,
// and Fig. 3.2's force map shows this point discontinuity at each foot's rest velocity.
//
// ---- Oracles (tests/friction/test_planar_forces.cpp) --------------------------------------------
// At the body velocity each balance solver returns (viscous-Coulomb; Coulomb, with the solver's
// forces on the sticking feet; ε) both sums vanish to the solver's accuracy and each sliding
// foot's force is the solver's frame.Fxy; one foot by hand (Coulomb: magnitude μ F_z opposite the
// slip, the maximum-dissipation point of its ellipse; viscous: linear in the slip); invariance
// under a rotation of the body frame and a change of reference point (the moment shifts by
// d × ΣF); the ε-law tends to Coulomb as ε → 0 and is viscous-Coulomb at ε = ∞.
#include "friction/planar_forces.hpp"

#include <cmath>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::friction {

namespace {

void check_epsilon(ForceLaw law, double epsilon) {
  if (law == ForceLaw::kEpsilon && !(epsilon > 0.0)) {
    throw core::InputError("epsilon", "must be positive, got " + core::format_double(epsilon));
  }
}

/// foot_force without the check of ε.
Eigen::Vector2d force_of(const contact::Robot& robot, const contact::Frame& frame, int k,
                         const Eigen::Vector2d& u, ForceLaw law, double epsilon) {
  const Eigen::Vector2d w = robot.w.col(k);
  const Eigen::Vector2d Gu = u + w * w.dot(u);  // G u = u + w (w·u)
  double scale = robot.mu(k) * frame.Fz(k);     // c = μ F_z
  if (law == ForceLaw::kCoulomb) {
    const double s = std::sqrt(u.dot(Gu));
    scale = s > 0.0 ? scale / s : 0.0;
  } else if (law == ForceLaw::kEpsilon && !std::isinf(epsilon)) {
    const double s = std::sqrt(u.dot(Gu));
    scale *= (epsilon + s) / (epsilon + s * s);
  }
  return -scale * Gu;
}

}  // namespace

Eigen::Vector2d foot_force(const contact::Robot& robot, const contact::Frame& frame, int k,
                           const Eigen::Vector2d& u, ForceLaw law, double epsilon) {
  check_epsilon(law, epsilon);
  return force_of(robot, frame, k, u, law, epsilon);
}

PlanarSum planar_forces(const contact::Robot& robot, const contact::Frame& frame,
                        const Eigen::Vector2d& v, double omega, ForceLaw law, double epsilon) {
  check_epsilon(law, epsilon);
  PlanarSum sum;
  for (int k = 0; k < frame.legs(); ++k) {
    if (frame.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    const Eigen::Vector2d q = frame.q.col(k).head<2>();
    const Eigen::Vector2d u =
        v + omega * Eigen::Vector2d(-q(1), q(0)) + frame.qdot.col(k).head<2>();  // v + ω S q + q̇
    const Eigen::Vector2d F = force_of(robot, frame, k, u, law, epsilon);
    sum.force += F;
    sum.moment += q(0) * F(1) - q(1) * F(0);
  }
  return sum;
}

}  // namespace slipwalk::friction
