// The exact piecewise integrator: roots of the guard quadratics and one constant-acceleration
// segment against hand-computed answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "events/exact_backend.hpp"

namespace slipwalk::events {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

TEST(FirstRisingRoot, LinearGuards) {
  EXPECT_DOUBLE_EQ(first_rising_root(-2.0, 4.0, 0.0), 0.5);
  EXPECT_EQ(first_rising_root(-2.0, -4.0, 0.0), kNever);  // falling away
  EXPECT_EQ(first_rising_root(0.0, -1.0, 0.0), kNever);   // just reset to zero, falling
  EXPECT_EQ(first_rising_root(0.0, 1.0, 0.0), 0.0);       // on the guard and rising: fire now
}

TEST(FirstRisingRoot, QuadraticGuards) {
  // g = −1 + τ²: rises through zero at τ = 1.
  EXPECT_DOUBLE_EQ(first_rising_root(-1.0, 0.0, 1.0), 1.0);
  // g = −(τ − 1)(τ − 3) = −3 + 4τ − τ²: rises at τ = 1 (then falls at 3).
  EXPECT_DOUBLE_EQ(first_rising_root(-3.0, 4.0, -1.0), 1.0);
  // g = −1 − τ²: never.
  EXPECT_EQ(first_rising_root(-1.0, 0.0, -1.0), kNever);
  // Tangency g = −(τ − 1)²: touches zero without rising through it.
  EXPECT_EQ(first_rising_root(-1.0, 2.0, -1.0), kNever);
  // g = τ² − τ from zero: dips below, rises through zero at τ = 1.
  EXPECT_DOUBLE_EQ(first_rising_root(0.0, -1.0, 1.0), 1.0);
  // Cancellation-prone: tiny c0 with large c1 keeps full relative precision.
  EXPECT_NEAR(first_rising_root(-1e-12, 1e4, 1.0), 1e-16, 1e-31);
}

// Random quadratics with known roots r1 < r2, g(τ) = c2 (τ − r1)(τ − r2): the first rising
// crossing at τ > 0 is the smallest root r > 0 with g'(r) = c2 (2r − r1 − r2) > 0.
TEST(FirstRisingRoot, RandomQuadraticsAgainstTheirConstructedRoots) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> root(-10.0, 10.0);
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  int checked = 0;
  for (int i = 0; i < 100000; ++i) {
    double r1 = root(rng);
    double r2 = root(rng);
    if (r1 > r2) {
      std::swap(r1, r2);
    }
    if (r2 - r1 < 1e-6 * (std::abs(r1) + std::abs(r2))) {
      continue;  // nearly a double root: the crossing is ill-conditioned
    }
    const double c2 = ((rng() & 1U) ? 1.0 : -1.0) * std::pow(10.0, log_scale(rng));
    const double c1 = -c2 * (r1 + r2);
    const double c0 = c2 * r1 * r2;
    // A guard already on or above zero and rising fires at once (an inconsistent start is not
    // silently skipped); otherwise the first rising root.
    double expected = c0 >= 0.0 && c1 > 0.0 ? 0.0 : kNever;
    for (double r : {r1, r2}) {
      if (r > 0.0 && c2 * (2.0 * r - r1 - r2) > 0.0) {
        expected = std::min(expected, r);
      }
    }
    const double got = first_rising_root(c0, c1, c2);
    if (expected == kNever) {
      EXPECT_EQ(got, kNever) << c0 << " " << c1 << " " << c2;
    } else {
      // Rounding the constructed coefficients moves a root by about ε |r1 r2 + (r1 + r2) r| /
      // |g'(r)/c2| — the conditioning of a root at distance r2 − r1 from the other.
      const double scale = std::abs(r1) + std::abs(r2) + 1.0;
      const double tol = 16.0 * 2.2e-16 * scale * scale / (r2 - r1);
      EXPECT_NEAR(got, expected, tol) << c0 << " " << c1 << " " << c2;
    }
    ++checked;
  }
  EXPECT_GT(checked, 90000);
}

TEST(ExactBackend, ConstantAccelerationSegment) {
  // One body from x = 0, v = 2, a = −1; guard: position reaches 1.5 (g = p − 1.5).
  // p(τ) = 2τ − τ²/2 = 1.5 at τ = 1 (and 3); first rising crossing τ = 1.
  ModeFlow<1, 1> flow;
  flow.accel << -1.0;
  flow.guard[0].wp << 1.0;
  flow.guard[0].w0 = -1.5;
  flow.guard[0].id = 7;
  flow.n_guards = 1;
  State<1> x;
  x << 0.0, 2.0;
  ExactBackend backend;
  const SegmentEnd end = backend.advance(flow, 10.0, x, 100.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_DOUBLE_EQ(end.t, 11.0);
  EXPECT_DOUBLE_EQ(x(0), 1.5);
  EXPECT_DOUBLE_EQ(x(1), 1.0);
  EXPECT_EQ(backend.stats().segments, 1);
}

TEST(ExactBackend, ReachesTheEndTimeWhenNoGuardFires) {
  ModeFlow<1, 1> flow;
  flow.accel << 0.0;
  flow.guard[0].wv << 1.0;  // velocity rises through zero: never, it is constant −1
  flow.n_guards = 1;
  State<1> x;
  x << 0.0, -1.0;
  ExactBackend backend;
  const SegmentEnd end = backend.advance(flow, 0.0, x, 2.5);
  EXPECT_EQ(end.guard, -1);
  EXPECT_DOUBLE_EQ(end.t, 2.5);
  EXPECT_DOUBLE_EQ(x(0), -2.5);
}

TEST(ExactBackend, SamplesTheExactSolutionOnAGrid) {
  ModeFlow<1, 1> flow;
  flow.accel << 2.0;
  flow.n_guards = 0;
  State<1> x;
  x << 0.0, 0.0;
  ExactBackend backend;
  backend.set_sample_interval(0.25);
  int samples = 0;
  (void)backend.advance(flow, 0.0, x, 1.0, [&](double t, const State<1>& s) {
    ++samples;
    EXPECT_NEAR(s(0), t * t, 1e-15);  // p = ½ a t²
  });
  EXPECT_EQ(samples, 4);  // 0.25, 0.5, 0.75 on the grid, then the segment end at 1.0
}

}  // namespace
}  // namespace slipwalk::events
