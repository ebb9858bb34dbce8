#pragma once
// Fixed-width vectors of doubles for passes over many feet at once (the structure-of-arrays rows
// of contact/robot.hpp, FootRow): GCC/Clang vector extensions rather than Eigen arrays, because
// per-foot tests are lane masks (Eigen 3.4 does not vectorize select()).
//
// Function multiversioning (GCC on x86-64): a function marked SLIPWALK_CLONES gets an AVX2 clone
// beside the portable default, chosen at load time; other compilers and targets get the default
// only. Not x86-64-v3: its FMA would contract a·b + c and round differently from the default
// clone. Lanes<4> is then one AVX register in the AVX2 clone and two SSE2 registers in the
// default one: the same operations, hence the same rounding, on every x86-64 machine.
//
// The vectors never cross a call boundary between translation units (helpers are inlined), so
// GCC's note that passing them without AVX would change the ABI does not apply: it is silenced for
// the files that include this header (only .cpp files with passes over the feet do).
#include <bit>
#include <cstdint>
#include <cstring>

#pragma GCC diagnostic ignored "-Wpsabi"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SLIPWALK_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SLIPWALK_CLONES
#endif

namespace slipwalk::core {

template <int W>
struct VectorTypes;
template <>
struct VectorTypes<4> {
  using V = double __attribute__((vector_size(32)));
  using M = std::int64_t __attribute__((vector_size(32)));
};

/// W doubles side by side (W = 4; another width is one more VectorTypes entry): unaligned loads and
/// stores, a broadcast, a masked select and the sum of the lanes, left to right.
template <int W>
struct Lanes {
  using V = typename VectorTypes<W>::V;
  using M = typename VectorTypes<W>::M;
  static V load(const double* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  static void store(double* p, V v) { std::memcpy(p, &v, sizeof v); }
  static V splat(double x) { return V{} + x; }
  static V select(M mask, V x) { return std::bit_cast<V>(std::bit_cast<M>(x) & mask); }
  static double sum(V v) {
    double s = 0.0;
    for (int i = 0; i < W; ++i) {
      s += v[i];
    }
    return s;
  }
};

}  // namespace slipwalk::core
