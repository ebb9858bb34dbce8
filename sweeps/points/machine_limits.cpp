// machine_limits: what this machine's cores can do, measured, so the performance page can say how
// far from the physical limit each stage of the multi-legged model runs (thesis §3.5.3, §3.6: the
// thesis times its model but states no machine limit; the limit is ours).
//
// One point, one row, each number the median over `repeats` of one timed loop on the calling
// thread (thread CPU time, as legged_cost times the model; every loop sized to last at least
// `min_repeat_s`, so the clock's resolution does not matter):
//  * the core clock: a dependent chain of integer adds, one cycle each on every x86-64 core
//    since the Pentium Pro; adds per second = cycles per second (GHz while the thread ran);
//  * peak double-precision flops per cycle for scalar, 2-wide (SSE2), 4-wide (AVX2 without FMA,
//    the width of the spring support's AVX2 clone) and 4-wide with FMA (AVX2 + FMA): enough
//    independent accumulator chains (12 per loop) that the units' latency is hidden and only
//    their throughput counts; without FMA half the chains add and half multiply, so a core with
//    separate add and multiply units is measured at both; an FMA counts as 2 flops;
//  * latencies in cycles of a dependent double add, multiply, divide and square root; the divide
//    and the root run on operands with full mantissas (x ← c/x alternates between 1.3 and
//    1.7/1.3; x ← √(x + 1) sits at the golden ratio), since some dividers finish early on short
//    ones; the root's chain includes an add, whose measured latency is taken off.
// The AVX2 loops are compiled for AVX2 (and FMA) on their own functions and run only where
// __builtin_cpu_supports says the CPU has them; elsewhere, and on any target but x86-64 with
// GCC or Clang, the columns are NaN and `message` says why. The kind is timed: the runner runs
// it alone, so no other timed point shares its core.
// A virtual CPU need not retire one dependent add per cycle of any clock it has (one such VM's
// chain ran at 21.6 "GHz", another's made an add's latency 10 "cycles"): every per-cycle column
// is in units of the chain's rate, which `clock_plausible` (0.5-7 GHz, what x86-64 cores run at)
// and `message` flag. Ratios of two columns do not depend on that unit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/csv.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SLIPWALK_X86_LIMITS 1
#endif

// The 32-byte vectors below never cross a call between clones of different targets (each loop
// is one function), so GCC's note on their ABI without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace slipwalk::sweeps::points {

namespace {

const double kNaN = std::nan("");

const std::vector<std::string_view> kLimitKeys = {"repeats", "min_repeat_s"};

struct LimitInputs {
  long long repeats = 11;
  double min_repeat_s = 2e-3;
};

LimitInputs read_limits(const Point& point) {
  const Reader r(point, "machine_limits", kLimitKeys);
  LimitInputs in;
  in.repeats = r.integer("repeats", 11, 1, 1001);
  in.min_repeat_s = r.number("min_repeat_s", 2e-3, core::closed(1e-5, 0.1, "s"));
  // 8 measurements × repeats × 1.5 min_repeat_s (the loop and its clock), plus calibrations.
  r.limit_work("repeats", "12 · repeats · min_repeat_s [s]",
               12.0 * static_cast<double>(in.repeats) * in.min_repeat_s, 60.0);
  return in;
}

struct LimitRow {
  long long id = 0;
  std::string isa;               ///< "x86-64" or "portable"
  long long avx2 = 0;            ///< the CPU has AVX2
  long long fma = 0;             ///< the CPU has FMA
  long long repeats = 0;         ///
  double ghz = kNaN;             ///< core clock while the thread ran (integer add chain)
  double flops_scalar = kNaN;    ///< peak double flops per cycle, scalar (add + mul)
  double flops_sse2 = kNaN;      ///< 2-wide (add + mul)
  double flops_avx2 = kNaN;      ///< 4-wide without FMA (add + mul)
  double flops_avx2_fma = kNaN;  ///< 4-wide FMA (2 flops each)
  double latency_add = kNaN;     ///< cycles of a dependent double add
  double latency_mul = kNaN;
  double latency_div = kNaN;
  double latency_sqrt = kNaN;
  long long clock_plausible = 0;  ///< the add chain ran at 0.5-7 GHz (a core's clock)
  std::string message;

  static std::vector<Column<LimitRow>> columns() {
    using R = LimitRow;
    return {value("id", &R::id),
            value("isa", &R::isa),
            value("avx2", &R::avx2),
            value("fma", &R::fma),
            value("repeats", &R::repeats),
            timing("ghz", &R::ghz, "GHz"),
            timing("flops_per_cycle_scalar", &R::flops_scalar, "flop/cycle"),
            timing("flops_per_cycle_sse2", &R::flops_sse2, "flop/cycle"),
            timing("flops_per_cycle_avx2", &R::flops_avx2, "flop/cycle"),
            timing("flops_per_cycle_avx2_fma", &R::flops_avx2_fma, "flop/cycle"),
            timing("latency_add_cycles", &R::latency_add, "cycle"),
            timing("latency_mul_cycles", &R::latency_mul, "cycle"),
            timing("latency_div_cycles", &R::latency_div, "cycle"),
            timing("latency_sqrt_cycles", &R::latency_sqrt, "cycle"),
            value("clock_plausible", &R::clock_plausible),
            value("message", &R::message)};
  }
};

// A loop of `n` iterations, each doing a known number of the measured operations; returns a
// value so that nothing is dead.
using Loop = double (*)(std::int64_t n);

/// Seconds of thread CPU time that `n` iterations of `loop` take.
double seconds_of(Loop loop, std::int64_t n) {
  static volatile double sink = 0.0;
  const double t0 = thread_cpu_seconds();
  sink = sink + loop(n);
  return thread_cpu_seconds() - t0;
}

/// Iterations of `loop` that last about `seconds` (grown from 1000 until a run lasts a tenth of
/// that, then scaled).
std::int64_t iterations_for(Loop loop, double seconds) {
  std::int64_t n = 1000;
  for (;;) {
    const double t = seconds_of(loop, n);
    if (t >= 0.1 * seconds || n > (std::int64_t{1} << 40)) {
      return std::max<std::int64_t>(n, static_cast<std::int64_t>(std::ceil(
                                           static_cast<double>(n) * seconds / std::max(t, 1e-9))));
    }
    n *= 8;
  }
}

#ifdef SLIPWALK_X86_LIMITS

// --- the clock: 16 dependent integer adds per iteration ------------------------------------------

// The empty asm tells the compiler x may have changed, so the 16 adds stay 16 dependent adds
// (without it they fold into one add of 16).
#define SLIPWALK_ADD1 \
  x += 1;             \
  asm volatile("" : "+r"(x))
#define SLIPWALK_ADD4 \
  SLIPWALK_ADD1;      \
  SLIPWALK_ADD1;      \
  SLIPWALK_ADD1;      \
  SLIPWALK_ADD1

double add_chain(std::int64_t n) {
  std::int64_t x = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    SLIPWALK_ADD4;
    SLIPWALK_ADD4;
    SLIPWALK_ADD4;
    SLIPWALK_ADD4;
  }
  return static_cast<double>(x);
}
constexpr double kAddsPerIteration = 16.0;

// --- throughput: 12 independent chains ---------------------------------------------------------

// Makes a register's value unknown to the compiler, so that x·1 and x + c are not folded away.
// A macro, not a function: the 4-wide loops' registers exist only inside their AVX2 functions.
#define SLIPWALK_OPAQUE(v) asm volatile("" : "+x"(v))
// Twelve accumulators a0…a5, m0…m5 of type T (set by `set`), each a different opaque value: equal
// starting values would let the compiler merge chains that then compute the same thing.
#define SLIPWALK_CHAINS(T, set)                                                     \
  T a0 = set(1e-9), a1 = set(2e-9), a2 = set(3e-9), a3 = set(4e-9), a4 = set(5e-9); \
  T a5 = set(6e-9), m0 = set(1.0), m1 = set(1.1), m2 = set(1.2), m3 = set(1.3);     \
  T m4 = set(1.4), m5 = set(1.5);                                                   \
  SLIPWALK_OPAQUE(a0);                                                              \
  SLIPWALK_OPAQUE(a1);                                                              \
  SLIPWALK_OPAQUE(a2);                                                              \
  SLIPWALK_OPAQUE(a3);                                                              \
  SLIPWALK_OPAQUE(a4);                                                              \
  SLIPWALK_OPAQUE(a5);                                                              \
  SLIPWALK_OPAQUE(m0);                                                              \
  SLIPWALK_OPAQUE(m1);                                                              \
  SLIPWALK_OPAQUE(m2);                                                              \
  SLIPWALK_OPAQUE(m3);                                                              \
  SLIPWALK_OPAQUE(m4);                                                              \
  SLIPWALK_OPAQUE(m5)

double scalar_chains(std::int64_t n) {
  __m128d one = _mm_set_sd(1.0);
  __m128d inc = _mm_set_sd(1e-9);
  SLIPWALK_OPAQUE(one);
  SLIPWALK_OPAQUE(inc);
  SLIPWALK_CHAINS(__m128d, _mm_set_sd);
  for (std::int64_t i = 0; i < n; ++i) {
    a0 = _mm_add_sd(a0, inc);
    m0 = _mm_mul_sd(m0, one);
    a1 = _mm_add_sd(a1, inc);
    m1 = _mm_mul_sd(m1, one);
    a2 = _mm_add_sd(a2, inc);
    m2 = _mm_mul_sd(m2, one);
    a3 = _mm_add_sd(a3, inc);
    m3 = _mm_mul_sd(m3, one);
    a4 = _mm_add_sd(a4, inc);
    m4 = _mm_mul_sd(m4, one);
    a5 = _mm_add_sd(a5, inc);
    m5 = _mm_mul_sd(m5, one);
  }
  const __m128d s = _mm_add_sd(_mm_add_sd(_mm_add_sd(a0, a1), _mm_add_sd(a2, a3)),
                               _mm_add_sd(_mm_add_sd(a4, a5), _mm_add_sd(m0, m5)));
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_add_sd(_mm_add_sd(m1, m2), _mm_add_sd(m3, m4))));
}
constexpr double kScalarFlops = 12.0;

double sse2_chains(std::int64_t n) {
  __m128d one = _mm_set1_pd(1.0);
  __m128d inc = _mm_set1_pd(1e-9);
  SLIPWALK_OPAQUE(one);
  SLIPWALK_OPAQUE(inc);
  SLIPWALK_CHAINS(__m128d, _mm_set1_pd);
  for (std::int64_t i = 0; i < n; ++i) {
    a0 = _mm_add_pd(a0, inc);
    m0 = _mm_mul_pd(m0, one);
    a1 = _mm_add_pd(a1, inc);
    m1 = _mm_mul_pd(m1, one);
    a2 = _mm_add_pd(a2, inc);
    m2 = _mm_mul_pd(m2, one);
    a3 = _mm_add_pd(a3, inc);
    m3 = _mm_mul_pd(m3, one);
    a4 = _mm_add_pd(a4, inc);
    m4 = _mm_mul_pd(m4, one);
    a5 = _mm_add_pd(a5, inc);
    m5 = _mm_mul_pd(m5, one);
  }
  const __m128d s = _mm_add_pd(_mm_add_pd(_mm_add_pd(a0, a1), _mm_add_pd(a2, a3)),
                               _mm_add_pd(_mm_add_pd(a4, a5), _mm_add_pd(m0, m5)));
  const __m128d t = _mm_add_pd(s, _mm_add_pd(_mm_add_pd(m1, m2), _mm_add_pd(m3, m4)));
  return _mm_cvtsd_f64(_mm_add_pd(t, _mm_unpackhi_pd(t, t)));
}
constexpr double kSse2Flops = 24.0;

__attribute__((target("avx2"))) double avx2_chains(std::int64_t n) {
  __m256d one = _mm256_set1_pd(1.0);
  __m256d inc = _mm256_set1_pd(1e-9);
  SLIPWALK_OPAQUE(one);
  SLIPWALK_OPAQUE(inc);
  SLIPWALK_CHAINS(__m256d, _mm256_set1_pd);
  for (std::int64_t i = 0; i < n; ++i) {
    a0 = _mm256_add_pd(a0, inc);
    m0 = _mm256_mul_pd(m0, one);
    a1 = _mm256_add_pd(a1, inc);
    m1 = _mm256_mul_pd(m1, one);
    a2 = _mm256_add_pd(a2, inc);
    m2 = _mm256_mul_pd(m2, one);
    a3 = _mm256_add_pd(a3, inc);
    m3 = _mm256_mul_pd(m3, one);
    a4 = _mm256_add_pd(a4, inc);
    m4 = _mm256_mul_pd(m4, one);
    a5 = _mm256_add_pd(a5, inc);
    m5 = _mm256_mul_pd(m5, one);
  }
  const __m256d s = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(a0, a1), _mm256_add_pd(a2, a3)),
                                  _mm256_add_pd(_mm256_add_pd(a4, a5), _mm256_add_pd(m0, m5)));
  const __m256d t = _mm256_add_pd(s, _mm256_add_pd(_mm256_add_pd(m1, m2), _mm256_add_pd(m3, m4)));
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, t);
  return lanes[0] + lanes[1] + lanes[2] + lanes[3];
}
constexpr double kAvx2Flops = 48.0;

__attribute__((target("avx2,fma"))) double fma_chains(std::int64_t n) {
  __m256d one = _mm256_set1_pd(1.0);
  __m256d inc = _mm256_set1_pd(1e-9);
  SLIPWALK_OPAQUE(one);
  SLIPWALK_OPAQUE(inc);
  SLIPWALK_CHAINS(__m256d, _mm256_set1_pd);
  __m256d a6 = m0, a7 = m1, a8 = m2, a9 = m3, a10 = m4, a11 = m5;
  for (std::int64_t i = 0; i < n; ++i) {  // a ← a·1 + inc: one FMA, 2 flops per lane
    a0 = _mm256_fmadd_pd(a0, one, inc);
    a1 = _mm256_fmadd_pd(a1, one, inc);
    a2 = _mm256_fmadd_pd(a2, one, inc);
    a3 = _mm256_fmadd_pd(a3, one, inc);
    a4 = _mm256_fmadd_pd(a4, one, inc);
    a5 = _mm256_fmadd_pd(a5, one, inc);
    a6 = _mm256_fmadd_pd(a6, one, inc);
    a7 = _mm256_fmadd_pd(a7, one, inc);
    a8 = _mm256_fmadd_pd(a8, one, inc);
    a9 = _mm256_fmadd_pd(a9, one, inc);
    a10 = _mm256_fmadd_pd(a10, one, inc);
    a11 = _mm256_fmadd_pd(a11, one, inc);
  }
  const __m256d s = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(a0, a1), _mm256_add_pd(a2, a3)),
                                  _mm256_add_pd(_mm256_add_pd(a4, a5), _mm256_add_pd(a6, a7)));
  const __m256d t = _mm256_add_pd(s, _mm256_add_pd(_mm256_add_pd(a8, a9), _mm256_add_pd(a10, a11)));
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, t);
  return lanes[0] + lanes[1] + lanes[2] + lanes[3];
}
constexpr double kFmaFlops = 12.0 * 4.0 * 2.0;

// --- latency: one dependent chain, 8 operations per iteration ----------------------------------

double add_latency(std::int64_t n) {
  double x = 0.0;
  double inc = 1e-9;
  SLIPWALK_OPAQUE(inc);
  for (std::int64_t i = 0; i < n; ++i) {
    x += inc;
    x += inc;
    x += inc;
    x += inc;
    x += inc;
    x += inc;
    x += inc;
    x += inc;
  }
  return x;
}

double mul_latency(std::int64_t n) {
  double x = 1.3;
  double one = 1.0;
  SLIPWALK_OPAQUE(one);
  for (std::int64_t i = 0; i < n; ++i) {
    x *= one;
    x *= one;
    x *= one;
    x *= one;
    x *= one;
    x *= one;
    x *= one;
    x *= one;
  }
  return x;
}

double div_latency(std::int64_t n) {
  double x = 1.3;
  double c = 1.7;
  SLIPWALK_OPAQUE(c);
  for (std::int64_t i = 0; i < n; ++i) {  // 1.3, 1.7/1.3, 1.3, ...: full mantissas
    x = c / x;
    x = c / x;
    x = c / x;
    x = c / x;
    x = c / x;
    x = c / x;
    x = c / x;
    x = c / x;
  }
  return x;
}

double sqrt_add_latency(std::int64_t n) {
  double x = 1.6;
  double one = 1.0;
  SLIPWALK_OPAQUE(one);
  for (std::int64_t i = 0; i < n; ++i) {  // → the golden ratio: a full mantissa
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
    x = std::sqrt(x + one);
  }
  return x;
}
constexpr double kChainOps = 8.0;

/// Cycles per operation of `loop` (`ops` per iteration): each repeat times the clock's add chain
/// and then the loop, back to back, and takes the ratio, so a clock that drifts between repeats
/// (turbo, a neighbour on the core) cancels; the median over the repeats. `ghz`, when given,
/// gets the median clock.
double cycles_per_op(Loop loop, double ops, const LimitInputs& in, double* ghz = nullptr) {
  const std::int64_t n_clock = iterations_for(add_chain, 0.5 * in.min_repeat_s);
  const std::int64_t n = iterations_for(loop, in.min_repeat_s);
  std::vector<double> ratio;
  std::vector<double> clock;
  for (long long r = 0; r < in.repeats; ++r) {
    const double cycle =
        seconds_of(add_chain, n_clock) / (static_cast<double>(n_clock) * kAddsPerIteration);
    const double per_op = seconds_of(loop, n) / (static_cast<double>(n) * ops);
    ratio.push_back(per_op / cycle);
    clock.push_back(1e-9 / cycle);
  }
  if (ghz != nullptr) {
    *ghz = median(clock);
  }
  return median(ratio);
}

/// The add chain's rate is a core's clock only where it lies where x86-64 cores run; elsewhere
/// the CPU is virtual or throttled in a way the chain does not see, and the message says that
/// the per-cycle columns are in units of the chain, not of a clock.
void flag_clock(LimitRow& row) {
  constexpr double kLowestGhz = 0.5;
  constexpr double kHighestGhz = 7.0;
  row.clock_plausible = row.ghz >= kLowestGhz && row.ghz <= kHighestGhz ? 1 : 0;
  if (row.clock_plausible == 0) {
    std::string what = "the integer-add chain ran at " + core::format_double(row.ghz) +
                       " GHz, outside the 0.5-7 GHz of x86-64 cores: this CPU does not retire "
                       "one dependent add per clock cycle, so every per-cycle column counts "
                       "that chain's steps, not cycles";
    row.message = row.message.empty() ? what : row.message + "; " + what;
  }
}

void measure(const LimitInputs& in, LimitRow& row) {
  row.isa = "x86-64";
  __builtin_cpu_init();
  row.avx2 = __builtin_cpu_supports("avx2") ? 1 : 0;
  row.fma = __builtin_cpu_supports("fma") ? 1 : 0;
  row.flops_scalar = kScalarFlops / cycles_per_op(scalar_chains, 1.0, in, &row.ghz);
  row.flops_sse2 = kSse2Flops / cycles_per_op(sse2_chains, 1.0, in);
  if (row.avx2 != 0) {
    row.flops_avx2 = kAvx2Flops / cycles_per_op(avx2_chains, 1.0, in);
  }
  if (row.avx2 != 0 && row.fma != 0) {
    row.flops_avx2_fma = kFmaFlops / cycles_per_op(fma_chains, 1.0, in);
  } else {
    row.message = "no AVX2 + FMA on this CPU: its 4-wide columns are NaN";
  }
  row.latency_add = cycles_per_op(add_latency, kChainOps, in);
  row.latency_mul = cycles_per_op(mul_latency, kChainOps, in);
  row.latency_div = cycles_per_op(div_latency, kChainOps, in);
  row.latency_sqrt = cycles_per_op(sqrt_add_latency, kChainOps, in) - row.latency_add;
  flag_clock(row);
}

#else

void measure(const LimitInputs& /*in*/, LimitRow& row) {
  row.isa = "portable";
  row.message =
      "not measured: the loops are written for x86-64 (GCC or Clang); every limit column is NaN";
}

#endif

Rows<LimitRow> run_limits(const Point& point) {
  const LimitInputs in = read_limits(point);
  LimitRow row;
  row.id = point.id;
  row.repeats = in.repeats;
  measure(in, row);
  Rows<LimitRow> out;
  out.rows.push_back(row);
  return out;
}

}  // namespace

std::vector<PointKind> machine_limit_kinds() {
  return {make_point_kind<LimitRow>(
      "machine_limits",
      "§3.5.3, §3.6 (ours): this machine's core clock (integer add chain), peak double flops per "
      "cycle scalar, SSE2, AVX2 and AVX2+FMA, and the latency in cycles of a double add, "
      "multiply, divide and square root (one row per point)",
      Timed::kYes, [](const Point& p) { (void)read_limits(p); }, run_limits)};
}

}  // namespace slipwalk::sweeps::points
