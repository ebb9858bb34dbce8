#pragma once
// Internal to friction/: the planar force/moment balance shared by the friction solvers and,
// through friction::ViscousSystem (viscous_system.hpp), the local connection (thesis §3.4, derived
// here in body coordinates).
//
// Body-frame balance. With x = (v_x, v_y, ω) (v = R_θᵀ ṗ_xy,0, ω = θ̇) foot k slides at
//   u_k = v + ω S q_k + q̇_k = J_k x + q̇_k,   J_k = [ I₂ | S q_k ]  (2 × 3),
// (eq. 3.5 premultiplied by R_θᵀ). Its planar force is F_k = −c_k φ_k G_k u_k with c_k = μ_k F_z,k,
// G_k = I + w_k w_kᵀ (eq. 3.19 in body coordinates: R_θ H_q R_θᵀ rotated back) and φ_k = 1
// (viscous-Coulomb), (ε + s_k)/(ε + s_k²) (eq. 3.14) or 1/s_k (Coulomb), s_k = ‖W_k u_k‖,
// W_k = G_k^{1/2}. Force balance Σ F_k = 0 and moment balance Σ (q_k × F_k)_z = Σ (S q_k)ᵀ F_k = 0
// together read Σ J_kᵀ F_k = 0, i.e.
//   M x = −b,   M = Σ c_k φ_k J_kᵀ G_k J_k = Σ c_k φ_k [ G_k      G_k S q_k       ]
//                                                    [ (S q_k)ᵀ G_k  (S q_k)ᵀ G_k S q_k ],
//               b = Σ c_k φ_k J_kᵀ G_k q̇_k = Σ c_k φ_k [ G_k q̇_k ; (S q_k)ᵀ G_k q̇_k ].
// M is symmetric positive semidefinite, definite as soon as two distinct points carry friction.
// The thesis (§3.4.3) prints the moment row with q_kᵀ S instead of (S q_k)ᵀ = −q_kᵀ S (eq. 3.17
// defines M_z = p̄ᵀ S F = −(p̄ × F)_z; its matrix is then not symmetric and the row's sign flips,
// harmless for "= 0"), garbles the block row of the intermediate system, drops the minus sign
// of the right-hand side and puts an extra Σ_k in front of eq. 3.20; with those fixed, eq. 3.20 is
//   x = −M⁻¹ Σ_k c_k J_kᵀ G_k q̇_k = Σ_k A_k q̇_k,   A_k = −c_k M⁻¹ J_kᵀ G_k.
//
// Numerics. The solvers work in scaled coordinates y = (v_x, v_y, L ω) with L the largest lever
// arm ‖q_xy,k‖ of a foot with friction (J̃_k = [I | S q_k / L]): all three unknowns are then
// velocities, M̃ = D M D (D = diag(1, 1, 1/L)) is well scaled, "least norm" is unit-consistent
// and one relative rank tolerance serves every robot size. The viscous system is the exception
// where M̃ is safely definite: the rank test is M̃'s (Psd3::factorize_definite with L², no √),
// but the LDLᵀ and the solve are M's own, since L comes last in its assembly (a maximum over the
// feet, a √, a division) and would otherwise stand between the sums and the solve. A diagonal
// scaling commutes with an unpivoted LDLᵀ, so the two differ by rounding only.
#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "contact/robot.hpp"
#include "core/lanes.hpp"

namespace slipwalk::friction::detail {

/// Eigenvalues of M̃ below kRankTol · trace count as zero (contacts closer than ~1e-6 L are one
/// point: the rotation about it is undetermined).
inline constexpr double kRankTol = 1e-12;

/// c_k = μ_k F_z,k for a foot in contact that carries friction, 0 otherwise (and for NaN).
/// Branch-free (selects), so that a pass over feet in and out of contact is not mispredicted.
inline double friction_weight(const contact::Robot& robot, const contact::Frame& frame, int k) {
  const double c = robot.mu(k) * frame.Fz(k);
  const bool on = frame.contact[static_cast<std::size_t>(k)] != 0;
  return on && c > 0.0 && c < std::numeric_limits<double>::infinity() ? c : 0.0;
}

/// Per-solve constants. prepare() also stores, for an anisotropic robot, α_k of
/// W_k = I + α_k w_k w_kᵀ = G_k^{1/2} in frame.work_n (α = 1 / (1 + √(1 + ‖w‖²))).
struct Contacts {
  int active = 0;            ///< feet with c_k > 0
  double L = 1.0;            ///< lever scale, m (max ‖q_xy,k‖ over active feet; 1 if all at 0)
  double inv_L = 1.0;        ///< 1 / L
  double L2 = 1.0;           ///< L², m²
  double c_sum = 0.0;        ///< Σ c_k, N
  bool anisotropic = false;  ///< some active foot has w_k ≠ 0
  bool rows = false;         ///< viscous_balance left the feet as rows in frame.viscous
  /// viscous_balance's M and b are those of x = (v_x, v_y, ω) itself, not of the scaled y, and
  /// only L2 is set (factorize_system() scales them, and sets L, where M̃ is not safely definite)
  bool unscaled = false;

  /// L², L and 1/L from L² = max ‖q_xy,k‖² over the active feet (L = 1 when all are at the origin).
  void set_lever_scale(double lever2) {
    set_lever_squared(lever2);
    L = std::sqrt(L2);
    inv_L = 1.0 / L;
  }
  /// L² alone: the unscaled viscous system needs no more where it is definite, and L and 1/L
  /// cost a √ and a division (factorize_system()). L and 1/L are NaN until set_lever_scale(L2).
  void set_lever_squared(double lever2) {
    L2 = lever2 > 0.0 ? lever2 : 1.0;
    L = std::numeric_limits<double>::quiet_NaN();
    inv_L = L;
  }
};
Contacts prepare(const contact::Robot& robot, contact::Frame& frame);

/// The metric of foot k: G = I + w wᵀ and its square root W = I + α w wᵀ. The isotropic
/// specialization is the identity, so a flat isotropic robot pays nothing for anisotropy.
template <bool kAniso>
struct Metric {
  const contact::Robot& robot;
  const contact::Frame& frame;
  [[nodiscard]] Eigen::Vector2d G(int k, const Eigen::Vector2d& a) const {
    if constexpr (kAniso) {
      const auto w = robot.w.col(k);
      return a + w * w.dot(a);
    } else {
      (void)k;
      return a;
    }
  }
  [[nodiscard]] Eigen::Vector2d W(int k, const Eigen::Vector2d& a) const {
    if constexpr (kAniso) {
      const auto w = robot.w.col(k);
      return a + frame.work_n(k) * w * w.dot(a);
    } else {
      (void)k;
      return a;
    }
  }
  [[nodiscard]] Eigen::Vector2d W_inv(int k, const Eigen::Vector2d& a) const {
    if constexpr (kAniso) {
      const auto w = robot.w.col(k);
      const double al = frame.work_n(k);
      return a - (al / (1.0 + al * w.squaredNorm())) * w * w.dot(a);
    } else {
      (void)k;
      return a;
    }
  }
  /// G as a matrix (for assembling M).
  [[nodiscard]] Eigen::Matrix2d G(int k) const {
    if constexpr (kAniso) {
      const auto w = robot.w.col(k);
      return Eigen::Matrix2d::Identity() + w * w.transpose();
    } else {
      (void)k;
      return Eigen::Matrix2d::Identity();
    }
  }
  [[nodiscard]] Eigen::Matrix2d W(int k) const {
    if constexpr (kAniso) {
      const auto w = robot.w.col(k);
      return Eigen::Matrix2d::Identity() + frame.work_n(k) * w * w.transpose();
    } else {
      (void)k;
      return Eigen::Matrix2d::Identity();
    }
  }
};

/// s̃_k = S q_xy,k / L: the third column of J̃_k.
inline Eigen::Vector2d lever(const contact::Frame& frame, int k, double inv_L) {
  return Eigen::Vector2d(-frame.q(1, k) * inv_L, frame.q(0, k) * inv_L);
}

/// u_k = J̃_k y + q̇_k, given the lever s̃_k.
inline Eigen::Vector2d slip(const contact::Frame& frame, int k, const Eigen::Vector2d& s,
                            const Eigen::Vector3d& y) {
  return Eigen::Vector2d(y(0) + frame.qdot(0, k) + y(2) * s(0),
                         y(1) + frame.qdot(1, k) + y(2) * s(1));
}

/// J̃ᵀ a for J̃ = [I | s].
inline Eigen::Vector3d jt(const Eigen::Vector2d& s, const Eigen::Vector2d& a) {
  return {a(0), a(1), s.dot(a)};
}

/// M += J̃ᵀ P J̃ for a symmetric 2 × 2 P (upper triangle and lower triangle both written).
inline void add_jt_p_j(Eigen::Matrix3d& M, const Eigen::Vector2d& s, const Eigen::Matrix2d& P) {
  const Eigen::Vector2d Ps = P * s;
  M.topLeftCorner<2, 2>() += P;
  M(0, 2) += Ps(0);
  M(1, 2) += Ps(1);
  M(2, 0) += Ps(0);
  M(2, 1) += Ps(1);
  M(2, 2) += s.dot(Ps);
}

/// A symmetric positive semidefinite 3 × 3 system, solved in the least-norm sense: an unpivoted
/// LDLᵀ when every pivot exceeds kRankTol · trace (the usual, full-rank case; ~20 flops), else a
/// symmetric eigendecomposition whose eigenvalues below kRankTol · trace count as zero.
class Psd3 {
 public:
  /// Returns false when the matrix is not (numerically) positive definite, i.e. the eigen path.
  bool factorize(const Eigen::Matrix3d& M);
  /// Like factorize(), but returns false without any fallback work when a pivot is below
  /// pivot_tol · trace (the caller then uses another matrix); solve() is only valid after a true
  /// return. With L2 = L² ≠ 1 the test is that of M̃ = D M D, D = diag(1, 1, 1/L), but the factors
  /// are M's own: solve() and inverse() are then in M's coordinates (factorize_system()).
  bool factorize_definite(const Eigen::Matrix3d& M, double pivot_tol = kRankTol, double L2 = 1.0);
  [[nodiscard]] Eigen::Vector3d solve(const Eigen::Vector3d& b) const;
  [[nodiscard]] Eigen::Matrix3d inverse() const;
  [[nodiscard]] int rank() const { return rank_; }
  /// Removes from y its components along the null space (no-op when full rank).
  [[nodiscard]] Eigen::Vector3d project_to_range(const Eigen::Vector3d& y) const;
  /// A += scale · (projector onto the null space) (no-op when full rank).
  void add_null_space(Eigen::Matrix3d& A, double scale) const;

 private:
  bool ldlt(const Eigen::Matrix3d& M, double pivot_tol, double L2);
  bool chol_ = true;
  int rank_ = 3;
  double l10_ = 0, l20_ = 0, l21_ = 0;
  Eigen::Vector3d d_ = Eigen::Vector3d::Ones();
  Eigen::Vector3d inv_d_ = Eigen::Vector3d::Ones();       ///< 1/d_
  Eigen::Matrix3d V_ = Eigen::Matrix3d::Identity();       ///< eigenvectors (eigen path)
  Eigen::Vector3d inv_lambda_ = Eigen::Vector3d::Zero();  ///< 1/λ or 0 (eigen path)
};

/// The seven sums of the isotropic viscous system (G = I: M = Σ c J_kᵀ J_k, b = Σ c J_kᵀ q̇_k),
/// unscaled, lane by lane: Σ c, Σ c q_x, Σ c q_y, Σ c ‖q_xy‖², Σ c q̇_x, Σ c q̇_y and
/// Σ c (S q)ᵀ q̇ = Σ c (q_x q̇_y − q_y q̇_x). The lanes are four feet of one frame
/// (viscous_balance's isotropic assembly) or one foot of four frames (viscous_batch.cpp).
struct IsotropicSums {
  using V = core::Lanes<4>::V;
  V c{}, cx{}, cy{}, crr{}, cdx{}, cdy{}, cm{};
  [[gnu::always_inline]] void add(V weight, V x, V y, V dx, V dy) {
    const V wx = weight * x;
    const V wy = weight * y;
    c += weight;
    cx += wx;
    cy += wy;
    crr += wx * x + wy * y;
    cdx += weight * dx;
    cdy += weight * dy;
    cm += wx * dy - wy * dx;
  }
};

/// The two columns of A_k = −c_k P J_kᵀ (eq. 3.20) of an isotropic foot (G = I): −P (c, 0, −c q_y)
/// and −P (0, c, c q_x), as foot k's six entries of A (column-major 3 × 2N), with P = M⁺ unscaled
/// and read entry by entry (p_ij: row i, column j; the one-frame route's P is symmetric only to
/// rounding where it comes from an eigendecomposition). Lanes as for IsotropicSums: four feet of
/// one frame (connection/local_connection.cpp) or one foot of four frames (viscous_batch.cpp).
template <class V>
struct IsotropicColumns {
  V p00, p01, p02, p10, p11, p12, p20, p21, p22;
  [[gnu::always_inline]] void operator()(V c, V x, V y, V (&e)[6]) const {
    const V s0 = -y * c;  // c (S q)_x
    const V s1 = x * c;   // c (S q)_y
    e[0] = -(p00 * c + p02 * s0);
    e[1] = -(p10 * c + p12 * s0);
    e[2] = -(p20 * c + p22 * s0);
    e[3] = -(p01 * c + p02 * s1);
    e[4] = -(p11 * c + p12 * s1);
    e[5] = -(p21 * c + p22 * s1);
  }
};

/// Assembles M̃ = Σ c_k φ_k J̃ᵀ G J̃ and b̃ = Σ c_k φ_k J̃ᵀ G q̇ (φ ≡ 1) in scaled coordinates.
template <bool kAniso>
void viscous_system(const contact::Robot& robot, const contact::Frame& frame, double inv_L,
                    Eigen::Matrix3d& M, Eigen::Vector3d& b) {
  const Metric<kAniso> metric{robot, frame};
  M.setZero();
  b.setZero();
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = friction_weight(robot, frame, k);
    if (c == 0.0) {
      continue;
    }
    const Eigen::Vector2d s = lever(frame, k, inv_L);
    add_jt_p_j(M, s, c * metric.G(k));
    b += jt(s, c * metric.G(k, frame.qdot.col(k).head<2>()));
  }
}

/// prepare() and viscous_system() in one pass, for callers that need G only (not W): the contact
/// summary, M and b (φ ≡ 1) of the unscaled x = (v, ω) (Contacts::unscaled: see the top), and c_k
/// (0 for a foot without friction). For an isotropic robot (every w_k = 0) the feet and c_k are
/// left as rows in
/// frame.viscous (contact/robot.hpp, ViscousScratch), which the force pass of the viscous-Coulomb
/// solve reads (Contacts::rows says so); otherwise c_k is left in frame.work_n.
/// With from_support, an isotropic frame whose support the Newton route certified is read from the
/// rows that route left (friction::FeetSource::kSupportRows, viscous_system.hpp).
Contacts viscous_balance(const contact::Robot& robot, contact::Frame& frame, Eigen::Matrix3d& M,
                         Eigen::Vector3d& b, bool from_support = false);

/// Factorizes viscous_balance's system for the solve: unscaled where M̃ is safely definite (the
/// usual case), else M and b scaled in place to M̃ and b̃ (cs.unscaled then false) and factorized
/// least-norm in the scaled coordinates, as for every other system of this file.
void factorize_system(Psd3& solver, Contacts& cs, Eigen::Matrix3d& M, Eigen::Vector3d& b);

/// The sums over the feet of a viscous-Coulomb force pass: Σ F_k, Σ (q_k × F_k)_z, the
/// dissipation −Σ F_k·u_k and the size of the terms that cancel, Σ c_k ‖G_k‖ (‖q̇_k‖ + ‖J_k x‖).
struct ForceSums {
  double fx = 0.0;
  double fy = 0.0;
  double mz = 0.0;
  double dissipation = 0.0;
  double scale = 0.0;
};

/// The viscous-Coulomb forces F_k = −c_k u_k, u_k = v + ω S q_k + q̇_k, of an isotropic frame
/// whose rows viscous_balance left (Contacts::rows), four feet at a time: written to frame.Fxy,
/// summed as ForceSums (balance.cpp).
ForceSums viscous_forces_rows(contact::Frame& frame, double v0, double v1, double om);

/// Writes v_body from scaled coordinates.
inline void set_velocity(contact::Frame& frame, const Eigen::Vector3d& y, double L) {
  frame.v_body = Eigen::Vector3d(y(0), y(1), y(2) / L);
}

/// Σ F_k and Σ (q_k × F_k)_z of the forces written so far, and the relative balance residual
/// max(‖Σ F‖ / F, |Σ M| / (F L)) with F the force scale the caller supplies (the magnitude of the
/// terms that cancel); 0 when F = 0.
struct BalanceSum {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  double moment = 0.0;
  void add(const contact::Frame& frame, int k, const Eigen::Vector2d& f) {
    force += f;
    moment += frame.q(0, k) * f(1) - frame.q(1, k) * f(0);
  }
  /// max(‖ΣF‖, |ΣM| / L) / force_scale (0 when nothing is in balance). The square root, |ΣM| / L
  /// and 1 / force_scale are independent: one multiplication after the root, not a division (the
  /// residual ends every solve's serial path).
  [[nodiscard]] double residual(double force_scale, double L) const {
    if (!(force_scale > 0.0)) {
      return 0.0;
    }
    const double r = force.norm();
    const double m = std::abs(moment) / L;
    return (r > m ? r : m) * (1.0 / force_scale);
  }
  /// The same from L² (the unscaled viscous system's, which takes no √ of it): the root of
  /// max(‖ΣF‖², ΣM² / L²), over force_scale.
  [[nodiscard]] double residual_from_squared_lever(double force_scale, double L2) const {
    if (!(force_scale > 0.0)) {
      return 0.0;
    }
    const double r2 = force.squaredNorm();
    const double m2 = moment * moment / L2;
    return std::sqrt(r2 > m2 ? r2 : m2) * (1.0 / force_scale);
  }
};

/// Marks a solve as failed with a non-finite result (balance.cpp; out of line, the cold path).
void mark_non_finite(contact::Frame& frame);

/// The end-of-solve check of every solver: a body velocity, a force or a summary number that is
/// not finite is no result, so friction.converged becomes false and the message says why.
/// `force_sum` is any sum over all the forces written (frame.Fxy.sum(), or sums the solver already
/// has): a sum with a non-finite term is not finite, so the forces need no second pass.
inline void flag_non_finite(contact::Frame& frame, double force_sum) {
  const auto& s = frame.friction;
  if (!std::isfinite(force_sum + frame.v_body.sum() + s.residual + s.certificate + s.dissipation))
      [[unlikely]] {
    mark_non_finite(frame);
  }
}

}  // namespace slipwalk::friction::detail
