#pragma once
// Internal to contact/ (and to planning/fast_kernel.cpp, whose warm substeps take the same steps
// and certificate): the fast route of the spring-support search (spring_support.hpp), an
// active-set (semismooth) Newton method on the convex potential U of spring_support.cpp. Each
// step is one vectorized pass over the feet; the answer is certified or rejected, never guessed.
#include <limits>

#include "contact/robot.hpp"
#include "core/lanes.hpp"  // cell_newton_step takes its lanes (and -Wpsabi is off for them there)
#include "core/sym3.hpp"

namespace slipwalk::contact::detail {

// The certificate's constants, shared with the batched route (support_batch.cpp).
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr int kMaxSteps = 12;
inline constexpr double kDefiniteTol = 1e-10;  // λ_min(H̃) / tr(H̃) below this: leave it to the path
inline constexpr double kPolished = 1e-14;     // balance residual that needs no refinement
inline constexpr double kRoundingCap = 1e-10;  // a stalled refinement is accepted only below this
/// Adds feet with weights w (K_j where the foot is in the cell, else 0), coefficients y = q_y,
/// x = −q_x and heights h to a pass's sums: Σ w, Σ w y, Σ w x, Σ w y², Σ w y x, Σ w x² (the cell's
/// H) and Σ w h y, Σ w h x, Σ w h (its gradient, less Mg e_z). Sums: any struct with those nine
/// members k, y, x, yy, yx, xx, gy, gx, gz of type V (lanes of four feet, or of four frames).
template <class Sums, class V>
[[gnu::always_inline]] inline void accumulate_cell(Sums& s, V w, V y, V x, V h) {
  const V wy = w * y;
  const V wx = w * x;
  const V wh = w * h;
  s.k += w;
  s.y += wy;
  s.x += wx;
  s.yy += wy * y;
  s.yx += wy * x;
  s.xx += wx * x;
  s.gy += wh * y;
  s.gx += wh * x;
  s.gz += wh;
}

/// The Newton step dv = −H⁻¹ g of a cell, H = Σ_C K a aᵀ (symmetric: entries h00 h10 h11 h20 h21
/// h22 of the unscaled state v = (α, β, z)) and g = (g0, g1, g2), solved in the scaled state
/// ũ = D v, D = diag(L, L, 1) (il = 1/L; H̃ = D⁻¹ H D⁻¹, g̃ = D⁻¹ g) by the adjugate. Returns whether
/// H̃ is safely definite (positive leading minors, by Sylvester, and λ_min ≥ det / (tr/2)² above
/// kDefiniteTol · tr); dv means something only then. T is double (one cell: the result converts
/// to bool) or a vector of lanes (a cell per lane, core/lanes.hpp: the result is a lane mask), so
/// the one-frame route and the batched one (support_batch.cpp) take the same arithmetic.
template <class T>
[[gnu::always_inline]] inline auto cell_newton_step(T H00, T H10, T H11, T H20, T H21, T H22, T g0,
                                                    T g1, T g2, T il, T& d0, T& d1, T& d2) {
  const T h00 = H00 * il * il;
  const T h10 = H10 * il * il;
  const T h11 = H11 * il * il;
  const T h20 = H20 * il;
  const T h21 = H21 * il;
  const T h22 = H22;
  // Cofactors: all independent, one division (an LDLᵀ chains three, which cost more than the
  // rest of a step on small robots).
  const core::Sym3Adjugate<T> a = core::sym3_adjugate(h00, h10, h11, h20, h21, h22);
  const T tr = h00 + h11 + h22;
  const T b0 = -g0 * il;
  const T b1 = -g1 * il;
  const T b2 = -g2;
  const T inv = 1.0 / a.det;
  d0 = (a.c00 * b0 + a.c01 * b1 + a.c02 * b2) * inv * il;
  d1 = (a.c01 * b0 + a.c11 * b1 + a.c12 * b2) * inv * il;
  d2 = (a.c02 * b0 + a.c12 * b1 + a.c22 * b2) * inv;
  return (h00 > 0.0) & (a.c22 > 0.0) & (4.0 * a.det > kDefiniteTol * tr * tr * tr);
}

// A foot this many times the heights' rounding error or closer to its plane at the end may carry
// nothing at the balance and hold a tilt (a see-saw on a line of contacts with one foot exactly
// touching): the contact set is then not strictly complementary, the minimizer may not be unique,
// and the path search decides.
inline constexpr double kNearPlane = 1e3;

/// Tries the Newton route. Returns true when it certified the global minimizer of U: the contact
/// set read off the feet's heights did not change over the last step, ∇U = 0 to rounding on that
/// set, and the cell's Hessian is safely nonsingular (three or more contacts off a line), so the
/// minimizer is unique and equals the end of Alg. 1's path; it certifies only feet within
/// limits::kPosition (tested on its first pass: the caller's check_frame need not test q first).
/// Then frame.alpha, beta, z, contact, Fz and support.residual, iterations, newton_steps, route are
/// written (status kBalanced). Returns false otherwise (a cell with fewer than three contacts off a
/// line, a cycling contact set, too many steps, a foot at its plane at the end):
/// frame.support.newton_steps says how far it got; contact and Fz may be written, and all outputs
/// are the path search's to write. Uses frame.support_newton as scratch; does not allocate.
bool support_by_newton(const Robot& robot, Frame& frame);

/// The same from the state v0 = (α, β, z) of a previous balance (SupportOptions::warm_start): the
/// start cell is the feet below its plane there. Where that start does not certify, the cold
/// start above follows (support.newton_steps counts both).
bool support_by_newton_warm(const Robot& robot, Frame& frame, const Eigen::Vector3d& v0);

}  // namespace slipwalk::contact::detail
