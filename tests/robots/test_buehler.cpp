// robots::clock_at: the Buehler clock (thesis §3.5.1.4) and the metachronal gait's cubic-stance
// clock (§3.5.1.5). Oracles: the defining formulas at the breakpoints, monotonicity, continuity,
// period one, the time spent in stance, and the rate against differences of the unwrapped angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "robots/buehler.hpp"

namespace slipwalk::robots {
namespace {

std::vector<ClockShape> shapes() {
  return {{0.55, 0.35, 0.0, false},     {0.5, 0.2, 0.3, false}, {0.7, 0.6, -0.1, false},
          {2.0 / 3.0, 0.35, 0.0, true}, {0.6, 0.0, 0.0, false}, {0.3, 0.9, 0.45, true}};
}

double max_rate(const ClockShape& c) {
  return std::max(c.cubic ? 1.5 * c.sweep / c.duty : c.sweep / c.duty,
                  (1.0 - c.sweep) / (1.0 - c.duty));
}

TEST(Clock, MonotoneContinuousAndOneTurnPerCycle) {
  for (const ClockShape& c : shapes()) {
    const int n = 20000;
    const double ds = 4.0 / n;
    double previous = clock_unwrapped(c, -2.0);
    for (int k = 1; k <= n; ++k) {
      const double s = -2.0 + k * ds;
      const double phi = clock_unwrapped(c, s);
      EXPECT_GE(phi, previous - 1e-15) << "s " << s;               // monotone
      EXPECT_LE(phi - previous, max_rate(c) * ds + 1e-12) << s;    // continuous (Lipschitz)
      EXPECT_NEAR(clock_unwrapped(c, s + 1.0), phi + 1.0, 1e-12);  // period one
      const ClockState st = clock_at(c, s);
      EXPECT_GE(st.phi, 0.0);
      EXPECT_LT(st.phi, 1.0);
      EXPECT_NEAR(st.phi, phi - std::floor(phi), 1e-12);
      previous = phi;
    }
    EXPECT_NEAR(clock_unwrapped(c, 0.0), c.center, 1e-15);  // s = 0 is mid-stance
  }
}

TEST(Clock, StanceSweepsSigmaInDutyOfTheCycle) {
  for (const ClockShape& c : shapes()) {
    // The stance starts at s = −D/2 with φ = φ_c − Σ/2 and ends at s = D/2 with φ_c + Σ/2.
    EXPECT_NEAR(clock_unwrapped(c, -0.5 * c.duty), c.center - 0.5 * c.sweep, 1e-14);
    EXPECT_NEAR(clock_unwrapped(c, 0.5 * c.duty), c.center + 0.5 * c.sweep, 1e-14);
    // Fraction of the cycle flagged as stance.
    const int n = 100000;
    int stance = 0;
    for (int k = 0; k < n; ++k) {
      stance += clock_at(c, (k + 0.5) / n).stance ? 1 : 0;
    }
    EXPECT_NEAR(static_cast<double>(stance) / n, c.duty, 1.0 / n);
    if (!c.cubic) {
      // Buehler: slow stance (Σ/D), fast return ((1 − Σ)/(1 − D)) whenever Σ < D.
      EXPECT_NEAR(clock_at(c, 0.1 * c.duty).rate, c.sweep / c.duty, 1e-14);
      EXPECT_NEAR(clock_at(c, 0.5).rate, (1.0 - c.sweep) / (1.0 - c.duty), 1e-14);
      if (c.sweep < c.duty) {
        EXPECT_LT(clock_at(c, 0.0).rate, clock_at(c, 0.5).rate);
      }
    } else {
      // Cubic stance: at rest at touchdown and lift-off, fastest (1.5 Σ/D) at mid-stance.
      EXPECT_NEAR(clock_at(c, -0.5 * c.duty + 1e-12).rate, 0.0, 1e-9);
      EXPECT_NEAR(clock_at(c, 0.0).rate, 1.5 * c.sweep / c.duty, 1e-14);
      // τ = 1/4: φ = φ_c − Σ/2 + Σ(3/16 − 2/64) = φ_c − Σ/2 + 5Σ/32.
      EXPECT_NEAR(clock_unwrapped(c, -0.25 * c.duty), c.center - 0.5 * c.sweep + 5.0 * c.sweep / 32,
                  1e-14);
    }
  }
}

TEST(Clock, RateIsTheDerivativeOfTheAngle) {
  const double h = 1e-7;
  for (const ClockShape& c : shapes()) {
    for (int k = 0; k < 997; ++k) {
      const double s = -1.0 + 2.0 * (k + 0.5) / 997.0;
      // Skip the breakpoints (touchdown and lift-off), where the rate jumps.
      const double w = s + 0.5 * c.duty;
      const double f = w - std::floor(w);
      if (f < 2 * h || std::abs(f - c.duty) < 2 * h || f > 1.0 - 2 * h) {
        continue;
      }
      const double fd = (clock_unwrapped(c, s + h) - clock_unwrapped(c, s - h)) / (2 * h);
      EXPECT_NEAR(fd, clock_at(c, s).rate, 1e-6 * max_rate(c)) << "s " << s;
    }
  }
}

TEST(Clock, ValidationNamesTheField) {
  auto where = [](ClockShape c) {
    try {
      validate(c, "gait");
    } catch (const core::InputError& e) {
      return e.where();
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(where({0.55, 0.35, 0.0, false}), "(no error)");
  EXPECT_EQ(where({0.0, 0.35, 0.0, false}), "gait.duty");
  EXPECT_EQ(where({1.0, 0.35, 0.0, false}), "gait.duty");
  EXPECT_EQ(where({0.5, 1.0, 0.0, false}), "gait.sweep");
  EXPECT_EQ(where({0.5, -0.1, 0.0, false}), "gait.sweep");
  EXPECT_EQ(where({0.5, 0.3, std::nan(""), false}), "gait.center");
}

}  // namespace
}  // namespace slipwalk::robots
