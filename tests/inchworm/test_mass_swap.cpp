// Invariants of the realistic-swap ("dm") hybrid system (thesis §2.5): the stroke is the
// instant-swap stroke, internal forces never move the CoM, impacts keep momentum, static friction
// and the held mode decide the swap's modes.
#include <gtest/gtest.h>

#include "events/exact_backend.hpp"
#include "inchworm/instant_swap.hpp"
#include "inchworm/mass_swap.hpp"
#include "inchworm/simulate.hpp"

namespace slipwalk::inchworm {
namespace {

using Sys = MassSwapSystem;

Params dm_params(double F, double mu, double alpha) {
  Params p;
  p.F = F;
  p.mu = mu;
  p.model = SwapModel::kMass;
  p.alpha = alpha;
  return p;
}

std::int8_t i8(int v) { return static_cast<std::int8_t>(v); }

TEST(MassSwap, StrokeIsTheInstantSwapStrokeWithDmRidingOnY) {
  const Params p = dm_params(20.0, 0.7, 1.0);
  const Sys dm(p);
  const InstantSwapSystem instant(p);
  for (int sx : {-1, 0, 1}) {
    for (int sy : {-1, 0, 1}) {
      for (int side : {-1, 1}) {
        const auto f = dm.flow({Sys::kStroke, i8(sx), i8(sy), i8(side), 0});
        const auto g = instant.flow({i8(sx), i8(sy), i8(side)});
        EXPECT_EQ(f.accel(0), g.accel(0));
        EXPECT_EQ(f.accel(1), g.accel(1));
        EXPECT_EQ(f.accel(2), f.accel(1));  // Δm locked on y
        EXPECT_EQ(f.n_guards, g.n_guards);
      }
    }
  }
}

// Internal forces (actuator, F_Δm, the held contact) cancel: the CoM accelerates only by the
// friction on the ground, in every mode of both phases.
TEST(MassSwap, OnlyGroundFrictionAcceleratesTheCoM) {
  const Params p = dm_params(20.0, 0.7, 3.0);
  const Sys sys(p);
  const double total = 2.0 * p.m + p.moving_mass();
  for (int side : {-1, 1}) {
    for (int s : {-1, 0, 1}) {
      for (int held : {0, 1}) {
        if (held == 1 && s == 0) {
          continue;  // held only while sliding
        }
        const auto f = sys.flow({Sys::kSwap, 0, i8(s), i8(side), i8(held)});
        const double com_accel =
            (p.m * (f.accel(0) + f.accel(1)) + p.moving_mass() * f.accel(2)) / total;
        // Sliding: friction −s μ g (2m + Δm); stuck: static friction balances −side·αF exactly,
        // which the flow represents as zero body acceleration with Δm still pushed.
        const double expected = s != 0 ? -s * p.mu * p.g : side * p.alpha * p.F / total;
        EXPECT_NEAR(com_accel, expected, 1e-13) << "side " << side << " s " << s;
        EXPECT_EQ(f.accel(0), f.accel(1));  // the ends move as one body
      }
    }
  }
}

TEST(MassSwap, StrokeCollisionStartsTheSwapWithMomentumKept) {
  const Params p = dm_params(20.0, 1.0, 1.0);
  const Sys sys(p);
  Sys::StateType x;
  x << 0.5, 0.0, 0.0, 1.2, -0.1, -0.1;  // x − y = L_max, Δm on y
  const double v = sys.com_velocity(x);
  const auto mode = sys.reset({Sys::kStroke, 1, 1, 1, 0}, Sys::kLengthLimit, x);
  EXPECT_EQ(mode.phase, Sys::kSwap);
  EXPECT_EQ(mode.side, 1);  // Δm now travels forward, toward x
  EXPECT_NEAR(x(3), v, 1e-15);
  EXPECT_EQ(x(3), x(4));
  EXPECT_EQ(x(4), x(5));
  EXPECT_EQ(mode.slide_y, v > 0 ? 1 : -1);
  EXPECT_EQ(mode.held, 0);
}

TEST(MassSwap, ArrivalKeepsMomentumAndRelabelsTheEnds) {
  const Params p = dm_params(20.0, 1.0, 5.0);
  const Sys sys(p);
  Sys::StateType x;
  x << 0.5, 0.0, 0.5, -0.3, -0.3, 2.0;  // Δm arrived at x, the body sliding back
  const double v = sys.com_velocity(x);
  const double c = sys.com(x);
  const auto mode = sys.reset({Sys::kSwap, 0, -1, 1, 0}, Sys::kArrival, x);
  EXPECT_EQ(mode.phase, Sys::kStroke);
  EXPECT_EQ(mode.side, -1);  // a contraction stroke follows an extension
  EXPECT_DOUBLE_EQ(x(0), 0.0);
  EXPECT_DOUBLE_EQ(x(1), 0.5);  // Δm's new carrier
  EXPECT_DOUBLE_EQ(x(2), 0.5);
  EXPECT_NEAR(sys.com_velocity(x), v, 1e-15);
  EXPECT_NEAR(sys.com(x), c, 1e-15);  // no jump: Δm really travelled
}

TEST(MassSwap, StaticFrictionOfTheBodyDecidesAtRest) {
  // αF ≤ μ_s g (2m + Δm) = 24.525 N at μ = 1: the body stays stuck.
  Sys::StateType x = Sys::StateType::Zero();
  x(0) = 0.5;
  const Sys holds(dm_params(20.0, 1.0, 1.0));
  EXPECT_EQ(holds.reset({Sys::kSwap, 0, 1, 1, 0}, Sys::kBodyStops, x).slide_y, 0);
  // αF = 100 N: pushed out of its friction cone, backward after an extension (side +1) ...
  const Sys breaks(dm_params(20.0, 1.0, 5.0));
  EXPECT_EQ(breaks.reset({Sys::kSwap, 0, 1, 1, 0}, Sys::kBodyStops, x).slide_y, -1);
  // ... and forward after a contraction (side −1).
  EXPECT_EQ(breaks.reset({Sys::kSwap, 0, -1, -1, 0}, Sys::kBodyStops, x).slide_y, 1);
  // μ_s > μ: static friction alone holds it although αF exceeds the sliding friction.
  Params sticky = dm_params(26.0, 1.0, 1.0);
  sticky.mu_s = 1.3;
  EXPECT_EQ(Sys(sticky).reset({Sys::kSwap, 0, 1, 1, 0}, Sys::kBodyStops, x).slide_y, 0);
}

// After a contraction stroke Δm is pushed backward while the body slides forward; with
// αF < μ g Δm the free Δm would decelerate less than the body and press into the end it left.
TEST(MassSwap, HeldModeWhenDmWouldPressIntoItsStart) {
  const double mu = 1.0;
  const double F = 12.0;
  const double alpha = 0.3;  // αF = 3.6 N < μ g Δm = 4.905 N
  const Sys sys(dm_params(F, mu, alpha));
  Sys::StateType x;
  x << 0.0, 0.02, 0.02, 0.4, 0.4, 0.4;  // after a contraction: x − y = −L_min
  const auto mode = sys.reset({Sys::kStroke, 1, 1, -1, 0}, Sys::kLengthLimit, x);
  ASSERT_EQ(mode.held, 1);
  const auto f = sys.flow(mode);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.accel(i), -mu * 9.81, 1e-13);  // all three slide together
  }
  // When the body stops, Δm is released (at rest it is free to move toward x).
  const auto after = sys.reset(mode, Sys::kBodyStops, x);
  EXPECT_EQ(after.held, 0);
  EXPECT_EQ(x(5), 0.0);
  // With a larger push the same start is free.
  const Sys free_sys(dm_params(F, mu, 1.0));
  x << 0.0, 0.02, 0.02, 0.4, 0.4, 0.4;
  EXPECT_EQ(free_sys.reset({Sys::kStroke, 1, 1, -1, 0}, Sys::kLengthLimit, x).held, 0);
}

// Fig. 2.6 (F = 20 N, μ = 1): at α = 1 the m–m body stops and stands still during the swap; at
// α = 5 and 10 it does not stop.
TEST(MassSwap, SwapStopRegimeFollowsTheSwapForce) {
  for (double alpha : {1.0, 5.0, 10.0}) {
    events::ExactBackend backend;
    const SimulationSummary s =
        steady_state_by_simulation(Sys(dm_params(20.0, 1.0, alpha)), backend);
    ASSERT_TRUE(s.converged) << s.message;
    EXPECT_EQ(s.swap_stopped, alpha == 1.0) << "alpha " << alpha;
    EXPECT_EQ(s.regime, Regime::kTwo);  // F = 20 > μMg = 14.7
  }
}

}  // namespace
}  // namespace slipwalk::inchworm
