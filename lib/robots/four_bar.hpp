#pragma once
// A planar crank-rocker four-bar linkage, the drive train of each BigANT leg (thesis §3.5.1.1,
// §4.1: "a four-bar linkage designed to provide advantageous foot clearance and gearing"). The
// motor turns the crank O₂A; the coupler AB is held by the rocker O₄B; the toe P is a point rigidly
// attached to the coupler (usually on AB extended). One crank angle fixes the whole leg.
//
// Loop closure in closed form (circle intersection): B lies on the circle of radius b about A and
// the circle of radius c about O₄. With ℓ = |O₄ − A|, u = (O₄ − A)/ℓ and n = u turned +90°,
//   x = (b² − c² + ℓ²) / (2ℓ),   h = √(b² − x²),   B = A + x u + σ h n,
// σ = ±1 the assembly branch. Velocities differentiate the two constraints |B − A|² = b² and
// |B − O₄|² = c² with respect to the crank angle θ:
//   (B − A)·(B' − A') = 0,   (B − O₄)·B' = 0,
// a 2 × 2 linear system for B' whose determinant (B − A) × (B − O₄) = b c sin μ (μ the
// transmission angle) never vanishes on a Grashof crank-rocker with strict inequalities (coupler
// and rocker are collinear only at ℓ = b + c or ℓ = |b − c|, which ℓ ∈ [d − a, d + a] excludes).
#include <Eigen/Core>

namespace slipwalk::robots {

/// Constants of a four-bar in its own plane (u, v), crank pivot O₂ at the origin. Lengths in m.
struct FourBar {
  double crank = 0.0;    ///< a = |A − O₂|; valid: shortest link
  double coupler = 0.0;  ///< b = |B − A|
  double rocker = 0.0;   ///< c = |B − O₄|
  Eigen::Vector2d rocker_pivot = Eigen::Vector2d::Zero();  ///< O₄; ground link d = |O₄|
  double toe_distance = 0.0;                               ///< e = |P − A|
  double toe_angle = 0.0;  ///< γ, rad: P − A is (B − A) turned by γ and scaled by e/b
  int branch = 1;          ///< σ = +1 or −1: B left (+1) or right (−1) of the ray A → O₄
};

/// The linkage at one crank angle θ (rad, from the u axis toward v), and its derivatives with
/// respect to θ (per radian of crank).
struct FourBarPose {
  Eigen::Vector2d A;        ///< crank pin
  Eigen::Vector2d B;        ///< coupler–rocker pin
  Eigen::Vector2d P;        ///< toe
  Eigen::Vector2d dA;       ///< dA/dθ
  Eigen::Vector2d dB;       ///< dB/dθ
  Eigen::Vector2d dP;       ///< dP/dθ
  double coupler_angle;     ///< θ₃ = arg(B − A), rad
  double rocker_angle;      ///< θ₄ = arg(B − O₄), rad
  double transmission_sin;  ///< sin μ = (B − A) × (B − O₄) / (b c); never 0 on a valid linkage
};

/// Throws core::InputError("four_bar.<field>", ...) unless the lengths are positive and finite, the
/// branch is ±1 and the linkage is a Grashof crank-rocker with the crank shortest and strict
/// inequalities (d + a < b + c and d − a > |b − c|), so the crank turns fully without toggling.
void validate(const FourBar& linkage);

/// The pose at crank angle θ by the closed-form loop closure above. No allocation; assumes a
/// valid linkage (validate()).
[[nodiscard]] FourBarPose four_bar_pose(const FourBar& linkage, double crank_angle);

}  // namespace slipwalk::robots
