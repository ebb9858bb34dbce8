// The closed form of §2.4 against independent routes: the GSL fixed point of the stroke map,
// one stroke integrated by the exact event-driven backend, and finite differences.
#include <gtest/gtest.h>

#include "events/exact_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/simulate.hpp"
#include "support/inchworm_grid.hpp"

namespace slipwalk::inchworm {
namespace {

using testing::rel_diff;

TEST(ClosedForm, AgreesWithGslFixedPointOfTheStrokeMap) {
  for (const Params& p : testing::thesis_grid()) {
    const SteadyState closed = steady_state_closed_form(p);
    const SteadyState root = steady_state_fixed_point(p);
    // Brent resolves c0 to ~eps/(1 − λ); λ ≤ 0.99 on this grid.
    EXPECT_LT(rel_diff(root.v_ss, closed.v_ss), 1e-12) << "F=" << p.F << " mu=" << p.mu;
    EXPECT_LT(rel_diff(root.c0, closed.c0), 1e-12) << "F=" << p.F << " mu=" << p.mu;
    EXPECT_LT(rel_diff(root.period, closed.period), 1e-12);
    EXPECT_EQ(root.regime, closed.regime);
  }
}

TEST(ClosedForm, IsAFixedPointOfTheStrokeMap) {
  for (const Params& p : testing::thesis_grid()) {
    const SteadyState s = steady_state_closed_form(p);
    const Stroke st = stroke_map(p, s.c0);
    EXPECT_LT(rel_diff(st.c_next, s.c0), 1e-14) << "F=" << p.F << " mu=" << p.mu;
    EXPECT_LT(rel_diff(st.duration, s.period), 1e-14);
    EXPECT_FALSE(st.ends_before_M_stops);
    // v_ss from the stroke's own displacement: (2 D + ρ ΔL) / (2 T), eq. 2.5 over one cycle.
    const double v = (2.0 * st.displacement + p.swap_ratio() * p.stroke()) / (2.0 * st.duration);
    EXPECT_LT(rel_diff(v, s.v_ss), 1e-13);
  }
}

TEST(ClosedForm, ContractionMatchesFiniteDifferenceOfTheMap) {
  for (const Params& p : testing::thesis_grid()) {
    const SteadyState s = steady_state_closed_form(p);
    const double h = 1e-6 * s.c0;
    const double fd = (stroke_map(p, s.c0 + h).c_next - stroke_map(p, s.c0 - h).c_next) / (2.0 * h);
    EXPECT_NEAR(s.contraction, fd, 1e-7) << "F=" << p.F << " mu=" << p.mu;
    EXPECT_GT(s.contraction, 0.0);
    EXPECT_LT(s.contraction, 1.0);
  }
}

// One stroke of the map against the exact event-driven integration of the hybrid system,
// including strokes that end before M stops (large c0) and strokes from rest (c0 = 0).
TEST(StrokeMap, MatchesOneIntegratedStroke) {
  for (const Params& p : testing::thesis_grid(4, 5)) {
    const InstantSwapSystem sys(p);
    for (double c0 : {0.0, 0.3, 1.0, 3.0, 10.0}) {
      InstantSwapSystem::StateType x = sys.rest_state();
      x(2) = c0;
      x(3) = c0;
      auto mode = sys.mode_of(x, 1);
      events::ExactBackend backend;
      const HalfCycleRecord rec = simulate_half_cycle(sys, backend, mode, x);
      const Stroke st = stroke_map(p, c0);
      const double jump = p.swap_ratio() * p.L_max;
      EXPECT_NEAR(sys.com_velocity(x), st.c_next, 1e-13 * (1.0 + std::abs(c0)))
          << "F=" << p.F << " mu=" << p.mu << " c0=" << c0;
      EXPECT_LT(rel_diff(rec.duration, st.duration), 1e-12);
      EXPECT_NEAR(rec.displacement - jump, st.displacement, 1e-13);
    }
  }
}

TEST(StrokeMap, CoversAStrokeThatEndsBeforeMStops) {
  Params p;
  p.F = 45.0;
  const Stroke st = stroke_map(p, 10.0);
  EXPECT_TRUE(st.ends_before_M_stops);
  EXPECT_LT(st.c_next, 10.0);  // only phase 1: the CoM decelerates at μg throughout
  EXPECT_DOUBLE_EQ(st.c_next, 10.0 - p.mu * p.g * st.duration);
  EXPECT_THROW((void)stroke_map(p, -1.0), std::exception);
}

TEST(ClosedForm, RegimesFollowStaticFrictionOfTheLargeMass) {
  Params p;
  p.mu = 1.0;
  const double boundary = p.mu * p.M * p.g;
  p.F = boundary * (1.0 - 1e-9);
  const SteadyState below = steady_state_closed_form(p);
  p.F = boundary * (1.0 + 1e-9);
  const SteadyState above = steady_state_closed_form(p);
  EXPECT_EQ(below.regime, Regime::kOne);
  EXPECT_EQ(above.regime, Regime::kTwo);
  // At F = μMg the sliding M has zero acceleration: both regimes give the same stroke, so v_ss
  // is continuous across the boundary (its slope is not).
  EXPECT_LT(rel_diff(below.v_ss, above.v_ss), 1e-8);
  // With μ_s > μ, M sticks up to μ_s M g: regime I extends past μMg.
  p.mu_s = 1.3;
  p.F = 1.2 * boundary;
  EXPECT_EQ(steady_state_closed_form(p).regime, Regime::kOne);
}

TEST(ClosedForm, HardCasesStayFiniteAndAgree) {
  Params near_threshold;  // F barely above μmg: a slow stroke lasting hours
  near_threshold.F = near_threshold.mu * near_threshold.m * near_threshold.g * (1.0 + 1e-9);
  Params slow;  // μ = 0.05, F = 5Mg: λ close to 1
  slow.mu = 0.05;
  slow.F = 5.0 * slow.M * slow.g;
  Params strong;  // F = 50 Mg
  strong.mu = 0.05;
  strong.F = 50.0 * strong.M * strong.g;
  for (const Params& p : {near_threshold, slow, strong}) {
    const SteadyState a = steady_state_closed_form(p);
    const SteadyState b = steady_state_fixed_point(p);
    ASSERT_TRUE(std::isfinite(a.v_ss));
    EXPECT_GT(a.v_ss, 0.0);
    EXPECT_LT(rel_diff(b.v_ss, a.v_ss), 1e-12) << "F=" << p.F << " mu=" << p.mu;
  }
  // Near the threshold v_ss → 0: the stroke takes ~sqrt(2ΔL/a_x) with a_x = 1e-9 μg.
  const SteadyState s = steady_state_closed_form(near_threshold);
  EXPECT_LT(s.v_ss, 1e-3);
  EXPECT_GT(s.period, 1e3);
}

// Every acceleration of the model is μg times a function of F/(μg) (a_x = μg(f − m)/m, b =
// μg(f + M)/M, r1 = μg f(1/m + 1/M), a2 = μgρ or μg(f − m)/(m + M), κ = f/(f + M) with
// f = F/(μg)), so c0 ∝ √μ and T ∝ 1/√μ at fixed F/μ: v_ss(F, μ) = √μ · v_ss(F/μ, 1). An exact
// oracle that the closed form, the fixed point and the simulation must all obey.
TEST(ScalingLaw, SpeedScalesWithRootMuAtFixedForcePerMu) {
  for (const Params& p : testing::thesis_grid()) {
    Params unit = p;
    unit.mu = 1.0;
    unit.F = p.F / p.mu;
    const SteadyState s = steady_state_closed_form(p);
    const SteadyState u = steady_state_closed_form(unit);
    // Rounding F/μ is amplified by the condition number of F − μmg near the threshold.
    const double tol = 16.0 * 2.2e-16 * p.F / (p.F - p.mu * p.m * p.g);
    EXPECT_LT(rel_diff(s.v_ss, std::sqrt(p.mu) * u.v_ss), tol) << "F=" << p.F;
    EXPECT_LT(rel_diff(s.period, u.period / std::sqrt(p.mu)), tol);
    EXPECT_NEAR(s.contraction, u.contraction, 1e-14);  // the contraction depends on F/μ alone
    events::ExactBackend backend;
    const SimulationSummary sim = steady_state_by_simulation(unit, backend);
    EXPECT_LT(rel_diff(std::sqrt(p.mu) * sim.v_ss, s.v_ss), 1e-10);
  }
}

TEST(GoverningLaw, Eq26IsTheThesisFormula) {
  // ṽ = 0.073μ(1 − 0.178μ²) f̃ + 0.11μ + 0.20 (eq. 2.6), evaluated by hand at μ = 1, f̃ = 5.
  EXPECT_DOUBLE_EQ(governing_law_eq_2_6(1.0, 5.0), 0.073 * 0.822 * 5.0 + 0.31);
  // And it is within the thesis' 5 % of the exact solution there (v = ṽ sqrt(L_max g)).
  Params p;
  p.F = 5.0 * p.M * p.g;
  const double v = governing_law_eq_2_6(p.mu, p.F / (p.mu * p.M * p.g)) * std::sqrt(p.L_max * p.g);
  EXPECT_LT(rel_diff(v, steady_state_closed_form(p).v_ss), 0.05);
}

}  // namespace
}  // namespace slipwalk::inchworm
