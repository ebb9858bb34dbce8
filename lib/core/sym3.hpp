#pragma once
// The adjugate of a symmetric 3 × 3 matrix, for the small systems on the serial path of a Newton
// step: the spring support's cell (contact/support_newton.hpp), the Coulomb solver's steps
// (friction/coulomb.cpp) and the viscous balance's LDLᵀ (friction/balance.cpp, Psd3), which all
// solve by cofactors or test definiteness by leading minors because their six products are
// independent, where an elimination chains them and its divisions.

namespace slipwalk::core {

/// adj(A) (symmetric: c00 c01 c02 c11 c12 c22) and det A = a00 c00 + a10 c01 + a20 c02, so that
/// A⁻¹ = adj(A) / det A. Its leading minors are a00, c22 (= a00 a11 − a10²) and det A. T is a
/// double or a vector of lanes (core/lanes.hpp), the same operations either way.
template <class T>
struct Sym3Adjugate {
  T c00, c01, c02, c11, c12, c22, det;
};

/// Of the matrix with lower triangle a00; a10 a11; a20 a21 a22.
template <class T>
[[gnu::always_inline]] inline Sym3Adjugate<T> sym3_adjugate(T a00, T a10, T a11, T a20, T a21,
                                                            T a22) {
  const T c00 = a11 * a22 - a21 * a21;
  const T c01 = a21 * a20 - a10 * a22;
  const T c02 = a10 * a21 - a11 * a20;
  const T c11 = a00 * a22 - a20 * a20;
  const T c12 = a10 * a20 - a00 * a21;
  const T c22 = a00 * a11 - a10 * a10;
  return {c00, c01, c02, c11, c12, c22, a00 * c00 + a10 * c01 + a20 * c02};
}

}  // namespace slipwalk::core
