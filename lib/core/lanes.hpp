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
// the files that include this header (the .cpp files with passes over the feet, and the Coulomb
// solver's internal header, friction/coulomb_solver.hpp, for Lanes<2>).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

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
template <>
struct VectorTypes<2> {  // one SSE2 register: the Coulomb solver's passes, two feet at a time
  using V = double __attribute__((vector_size(16)));
  using M = std::int64_t __attribute__((vector_size(16)));
};

/// W doubles side by side (W = 4; another width is one more VectorTypes entry): unaligned loads and
/// stores, a broadcast, a masked select and the sum of the lanes, left to right. Always inlined: a
/// 32-byte vector passed to or returned from a call of the SSE2 clone goes through memory.
template <int W>
struct Lanes {
  using V = typename VectorTypes<W>::V;
  using M = typename VectorTypes<W>::M;
  [[gnu::always_inline]] static V load(const double* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  [[gnu::always_inline]] static void store(double* p, V v) { std::memcpy(p, &v, sizeof v); }
  [[gnu::always_inline]] static M load(const std::int64_t* p) {
    M m;
    std::memcpy(&m, p, sizeof m);
    return m;
  }
  [[gnu::always_inline]] static void store(std::int64_t* p, M m) { std::memcpy(p, &m, sizeof m); }
  [[gnu::always_inline]] static V splat(double x) { return V{} + x; }
  [[gnu::always_inline]] static V select(M mask, V x) {
    return std::bit_cast<V>(std::bit_cast<M>(x) & mask);
  }
  /// |x| lane by lane: the sign bit cleared (NaN stays NaN).
  [[gnu::always_inline]] static V abs(V x) {
    return std::bit_cast<V>(std::bit_cast<M>(x) & (M{} + std::numeric_limits<std::int64_t>::max()));
  }
  [[gnu::always_inline]] static double sum(V v) {
    double s = v[0];  // not 0.0 + v[0]: that add is kept (it turns −0 into +0)
    for (int i = 1; i < W; ++i) {
      s += v[i];
    }
    return s;
  }
};

/// The lane sums of four vectors, each left to right like Lanes::sum (the same rounding): lane i
/// of the result is the sum of the i-th argument. A 4 × 4 transpose in registers and three
/// lane-wise adds, eleven operations where four Lanes::sum take twenty-four; for the sums a pass
/// over the feet ends with, which sit on the serial path of every step.
[[gnu::always_inline]] inline Lanes<4>::V lane_sums(Lanes<4>::V a, Lanes<4>::V b, Lanes<4>::V c,
                                                    Lanes<4>::V d) {
  const Lanes<4>::V ab_even = __builtin_shufflevector(a, b, 0, 4, 2, 6);  // a0 b0 a2 b2
  const Lanes<4>::V ab_odd = __builtin_shufflevector(a, b, 1, 5, 3, 7);   // a1 b1 a3 b3
  const Lanes<4>::V cd_even = __builtin_shufflevector(c, d, 0, 4, 2, 6);
  const Lanes<4>::V cd_odd = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  const Lanes<4>::V lane0 = __builtin_shufflevector(ab_even, cd_even, 0, 1, 4, 5);
  const Lanes<4>::V lane1 = __builtin_shufflevector(ab_odd, cd_odd, 0, 1, 4, 5);
  const Lanes<4>::V lane2 = __builtin_shufflevector(ab_even, cd_even, 2, 3, 6, 7);
  const Lanes<4>::V lane3 = __builtin_shufflevector(ab_odd, cd_odd, 2, 3, 6, 7);
  return ((lane0 + lane1) + lane2) + lane3;
}

/// Whether any lane of the mask is set (the lanes ORed: no conversion, no per-lane branch).
[[gnu::always_inline]] inline bool any(Lanes<4>::M m) {
  const Lanes<4>::M halves = m | __builtin_shufflevector(m, m, 2, 3, 0, 1);
  return (halves[0] | halves[1]) != 0;
}

/// Whether |p_i| ≤ bound for all n values: a lane mask ANDed over the values, four at a time (a
/// comparison with NaN is false, so NaN and infinity fail without a test of their own), the last
/// four overlapping the ones before them (testing a value twice is harmless). Branch-free.
[[gnu::always_inline]] inline bool all_within(const double* p, std::ptrdiff_t n, double bound) {
  using L = Lanes<4>;
  using V = L::V;
  if (n < 4) {
    bool ok = true;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      ok = ok && (p[i] <= bound && -p[i] <= bound);
    }
    return ok;
  }
  const V limit = L::splat(bound);
  L::M ok = L::M{} - 1;  // every lane true
  for (std::ptrdiff_t i = 0; i + 4 <= n; i += 4) {
    ok &= L::abs(L::load(p + i)) <= limit;
  }
  ok &= L::abs(L::load(p + n - 4)) <= limit;
  return !any(~ok);  // every lane set (a lane is all ones or all zeros)
}

// Loading the feet of a pass four at a time, group j … j + 3 of n feet. Where the group is not
// full (the last, r = n − j < 4 feet), the loads never read past the end: for n ≥ 4 they read
// the group at n − 4 and shuffle its last r feet down to lanes 0 … r − 1 (one shuffle, on the
// count r that is fixed per robot); for n < 4 lane by lane. The other lanes are 0. (A tail read
// in a loop cost more than a whole group: GCC turns such loops into calls to memcpy.)

/// Lane i is all ones where j + i < n: the feet of a group, not its padding.
[[gnu::always_inline]] inline Lanes<4>::M lanes_below(std::ptrdiff_t j, std::ptrdiff_t n) {
  return Lanes<4>::M{0, 1, 2, 3} + j < n;
}

/// The last r lanes of v (1 ≤ r ≤ 3) moved to lanes 0 … r − 1, zeros after them.
template <class T>
[[gnu::always_inline]] inline T tail_lanes(T v, std::ptrdiff_t r) {
  const T zero{};
  switch (r) {
    case 1:
      return __builtin_shufflevector(v, zero, 3, 4, 5, 6);
    case 2:
      return __builtin_shufflevector(v, zero, 2, 3, 4, 5);
    default:
      return __builtin_shufflevector(v, zero, 1, 2, 3, 4);
  }
}

/// Columns j … j + 3 of a 3 × n column-major matrix m (x y z x y z …, Eigen's Matrix3Xd) as
/// three lanes, columns at or beyond n as 0: three loads parted by shuffles.
[[gnu::always_inline]] inline void load_columns3(const double* m, std::ptrdiff_t n,
                                                 std::ptrdiff_t j, Lanes<4>::V& x, Lanes<4>::V& y,
                                                 Lanes<4>::V& z) {
  using L = Lanes<4>;
  using V = L::V;
  if (n < 4) {
    x = V{m[0], n > 1 ? m[3] : 0.0, n > 2 ? m[6] : 0.0, 0.0};
    y = V{m[1], n > 1 ? m[4] : 0.0, n > 2 ? m[7] : 0.0, 0.0};
    z = V{m[2], n > 1 ? m[5] : 0.0, n > 2 ? m[8] : 0.0, 0.0};
    return;
  }
  const std::ptrdiff_t at = j + 4 <= n ? j : n - 4;
  const V a = L::load(m + 3 * at);      // x0 y0 z0 x1
  const V b = L::load(m + 3 * at + 4);  // y1 z1 x2 y2
  const V c = L::load(m + 3 * at + 8);  // z2 x3 y3 z3
  x = __builtin_shufflevector(__builtin_shufflevector(a, b, 0, 3, 6, 6), c, 0, 1, 2, 5);
  y = __builtin_shufflevector(__builtin_shufflevector(a, b, 1, 4, 7, 7), c, 0, 1, 2, 6);
  z = __builtin_shufflevector(__builtin_shufflevector(a, b, 2, 5, 5, 5), c, 0, 1, 4, 7);
  if (at != j) {
    x = tail_lanes(x, n - j);
    y = tail_lanes(y, n - j);
    z = tail_lanes(z, n - j);
  }
}

/// Entries j … j + 3 of a vector of n doubles, entries at or beyond n as 0.
[[gnu::always_inline]] inline Lanes<4>::V load_padded(const double* p, std::ptrdiff_t n,
                                                      std::ptrdiff_t j) {
  if (n < 4) {
    return Lanes<4>::V{p[0], n > 1 ? p[1] : 0.0, n > 2 ? p[2] : 0.0, 0.0};
  }
  if (j + 4 <= n) {
    return Lanes<4>::load(p + j);
  }
  return tail_lanes(Lanes<4>::load(p + n - 4), n - j);
}

/// Lane i is all ones where flag p[j + i] (a char, j + i < n) is not 0. The four chars are read as
/// one 32-bit word, broadcast to the lanes and masked to byte i in lane i (a conversion of chars
/// to 64-bit lanes becomes a dozen scalar moves in GCC 12); the last group's word is shifted down
/// to its feet.
[[gnu::always_inline]] inline Lanes<4>::M load_flags(const char* p, std::ptrdiff_t n,
                                                     std::ptrdiff_t j) {
  static_assert(std::endian::native == std::endian::little, "byte i of the word is char p[j + i]");
  std::uint32_t word = 0;
  if (n < 4) {
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      word |= static_cast<std::uint32_t>(static_cast<unsigned char>(p[i])) << (8 * i);
    }
  } else if (j + 4 <= n) {
    std::memcpy(&word, p + j, sizeof word);
  } else {
    std::memcpy(&word, p + n - 4, sizeof word);
    word >>= 8 * (4 - (n - j));  // little-endian: the last n − j chars to the low bytes
  }
  using M = Lanes<4>::M;
  return ((M{} + static_cast<std::int64_t>(word)) & M{0xFF, 0xFF00, 0xFF0000, 0xFF000000}) != 0;
}

/// Stores lanes 0 … n − j − 1 of v (elements of type T) to p[j …]: all four at once where
/// j + 4 ≤ n, else one by one.
template <class T, class Vec>
[[gnu::always_inline]] inline void store_lanes(T* p, std::ptrdiff_t n, std::ptrdiff_t j, Vec v) {
  static_assert(sizeof v == 4 * sizeof(T));
  if (j + 4 <= n) {
    std::memcpy(p + j, &v, sizeof v);
    return;
  }
  p[j] = v[0];
  if (j + 1 < n) {
    p[j + 1] = v[1];
  }
  if (j + 2 < n) {
    p[j + 2] = v[2];
  }
}

/// Stores flags p[j …] (a char each: 1 where lane i of m is all ones, else 0), lanes
/// 0 … n − j − 1.
[[gnu::always_inline]] inline void store_flags(char* p, std::ptrdiff_t n, std::ptrdiff_t j,
                                               Lanes<4>::M m) {
  using Chars = char __attribute__((vector_size(4)));
  store_lanes(p, n, j, __builtin_convertvector(m & 1, Chars));
}

/// Stores lanes 0 … n − j − 1 of v to p[j …] (all four where j + 4 ≤ n).
[[gnu::always_inline]] inline void store_padded(double* p, std::ptrdiff_t n, std::ptrdiff_t j,
                                                Lanes<4>::V v) {
  store_lanes(p, n, j, v);
}

}  // namespace slipwalk::core
