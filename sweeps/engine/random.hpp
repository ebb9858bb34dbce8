#pragma once
// A deterministic random stream for sweep points: the same numbers on every platform and thread
// count (the standard library's distributions are implementation-defined, so they are written
// out here).
#include <cmath>
#include <cstdint>
#include <numbers>

namespace slipwalk::sweeps {

/// SplitMix64 (Steele, Lea & Flood 2014): seeds of (seed, trial) give independent streams.
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t trial) : state_(seed * 0x9E3779B97F4A7C15ULL) {
    state_ ^= mix(trial + 0x632BE59BD9B4E019ULL);
  }
  /// Uniform in [0, 1), 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Standard normal (Box–Muller; one draw per call).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  /// Exponential with mean 1.
  double exponential() { return -std::log(1.0 - uniform()); }

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    return mix(state_);
  }
  std::uint64_t state_;
};

}  // namespace slipwalk::sweeps
