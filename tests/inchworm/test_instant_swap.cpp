// Invariants of the instant-swap hybrid system (§2.2): Newton's law per mode, the plastic
// collision and the swap, static friction as a mode.
#include <gtest/gtest.h>

#include "inchworm/instant_swap.hpp"

namespace slipwalk::inchworm {
namespace {

using Sys = InstantSwapSystem;

Params thesis_params(double F, double mu) {
  Params p;
  p.F = F;
  p.mu = mu;
  return p;
}

TEST(InstantSwap, AccelerationsAreNewtonWithCoulombFriction) {
  const Params p = thesis_params(45.0, 0.7);
  const Sys sys(p);
  for (int sm : {-1, 0, 1}) {
    for (int sM : {-1, 0, 1}) {
      const auto f = sys.flow({static_cast<std::int8_t>(sm), static_cast<std::int8_t>(sM), 1});
      // eqs. 2.1–2.2 with F_t sgn(x − y) = F: m ẍ = F − μ m g sgn(ẋ), M ÿ = −F − μ M g sgn(ẏ).
      const double am = sm == 0 ? 0.0 : (p.F - sm * p.mu * p.m * p.g) / p.m;
      const double aM = sM == 0 ? 0.0 : (-p.F - sM * p.mu * p.M * p.g) / p.M;
      EXPECT_NEAR(f.accel(0), am, 1e-13);
      EXPECT_NEAR(f.accel(1), aM, 1e-13);
      // One velocity guard per sliding mass, plus the length limit.
      EXPECT_EQ(f.n_guards, (sm != 0) + (sM != 0) + 1);
    }
  }
}

TEST(InstantSwap, CollisionKeepsCoMVelocityAndSwapJumpsCoMByRhoD) {
  const Params p = thesis_params(45.0, 1.0);
  const Sys sys(p);
  Sys::StateType x;
  x << 0.7, 0.2, 1.9, -0.4;  // x − y = 0.5 = L_max, m faster than M
  const double c_before = sys.com(x);
  const double v_before = sys.com_velocity(x);
  const double d = x(0) - x(1);
  const auto mode = sys.reset(sys.mode_of(x, 1), Sys::kLengthLimit, x);
  // eq. 2.4: momentum is kept and both masses share the CoM velocity.
  EXPECT_DOUBLE_EQ(x(2), v_before);
  EXPECT_DOUBLE_EQ(x(3), v_before);
  EXPECT_NEAR(sys.com_velocity(x), v_before, 1e-15);
  // The swap moves the CoM by (M − m)/(M + m) · d.
  EXPECT_NEAR(sys.com(x) - c_before, p.swap_ratio() * d, 1e-15);
  EXPECT_DOUBLE_EQ(x(0), 0.2);
  EXPECT_DOUBLE_EQ(x(1), 0.7);
  EXPECT_EQ(mode.side, -1);
  EXPECT_EQ(mode.slide_m, 1);  // common velocity > 0: both slide forward
  EXPECT_EQ(mode.slide_M, 1);
}

TEST(InstantSwap, StaticFrictionDecidesAtRest) {
  // Regime I: F ≤ μ M g, so M at rest stays stuck; m always leaves static friction.
  const Sys weak(thesis_params(12.0, 1.0));
  auto x = weak.rest_state();
  auto mode = weak.mode_of(x, 1);
  EXPECT_EQ(mode.slide_m, 1);
  EXPECT_EQ(mode.slide_M, 0);
  // Regime II: M is pushed out of its friction cone backward.
  const Sys strong(thesis_params(20.0, 1.0));
  mode = strong.mode_of(strong.rest_state(), 1);
  EXPECT_EQ(mode.slide_M, -1);
  // μ_s > μ: at F = 1.2 μMg, M stays stuck although sliding friction would be exceeded.
  Params p = thesis_params(1.2 * 1.5 * 9.81, 1.0);
  p.mu_s = 1.3;
  const Sys sticky(p);
  EXPECT_EQ(sticky.mode_of(sticky.rest_state(), 1).slide_M, 0);
}

TEST(InstantSwap, VelocityGuardSnapsToRestAndSwitchesMode) {
  const Sys sys(thesis_params(20.0, 1.0));
  Sys::StateType x;
  x << 0.1, 0.0, 0.8, 1e-17;  // M has just stopped (round-off left)
  const auto mode = sys.reset({1, 1, 1}, Sys::kLargeStops, x);
  EXPECT_EQ(x(3), 0.0);
  EXPECT_EQ(mode.slide_M, -1);  // F = 20 > μMg = 14.7: slides back
  EXPECT_EQ(mode.slide_m, 1);
}

TEST(InstantSwap, LengthGuardTargetsBothStrokes) {
  const Params p = thesis_params(20.0, 1.0);
  const Sys sys(p);
  Sys::StateType x = Sys::StateType::Zero();
  x(0) = p.L_max;  // x − y = L_max: the extension guard is at zero
  auto f = sys.flow({1, 1, 1});
  EXPECT_NEAR(events::guard_value(f.guard[f.n_guards - 1], x), 0.0, 1e-16);
  x(0) = -p.L_min;  // x − y = −L_min: the contraction guard is at zero
  f = sys.flow({1, 1, -1});
  EXPECT_NEAR(events::guard_value(f.guard[f.n_guards - 1], x), 0.0, 1e-16);
}

TEST(InstantSwap, RestStateStartsAtLminWithCoMAtOrigin) {
  const Params p = thesis_params(20.0, 1.0);
  const Sys sys(p);
  const auto x = sys.rest_state();
  EXPECT_NEAR(x(0) - x(1), p.L_min, 1e-17);
  EXPECT_NEAR(sys.com(x), 0.0, 1e-17);
}

}  // namespace
}  // namespace slipwalk::inchworm
