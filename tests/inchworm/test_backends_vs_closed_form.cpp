// v_ss, the stroke period and the regime by event-driven simulation with each numeric backend
// (CVODE, Boost.Odeint, GSL) against the closed form of §2.4 (the oracle), over the thesis
// range and on the hard cases: the ends of the force range, the regime boundary, slow
// convergence at low friction and high force, and static friction above dynamic friction.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "events/cvode_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/odeint_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/simulate.hpp"
#include "support/inchworm_grid.hpp"

namespace slipwalk::inchworm {
namespace {

using testing::rel_diff;

/// Agreement asked of every backend and case.
constexpr double kAgree = 1e-9;

/// Step tolerances and convergence target, chosen by measurement over every case below: with
/// rtol = 1e-11 (atol = rtol × 1 cm) and target = 1e-11 the largest relative error in v_ss is
/// 1.3e-11 (CVODE) and 1.0e-11 (odeint, GSL), 75× inside kAgree. The Runge–Kutta pairs
/// reproduce a mode's quadratic motion to round-off whatever rtol is, so their error is the
/// simulation's remaining error (≤ target); CVODE's Adams restarts at order 1 on each segment
/// and is the one that needs rtol (at rtol = 1e-10 its worst case is 1.7e-10).
events::BackendOptions backend_options() {
  events::BackendOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  return o;
}
SimulationOptions simulation_options() {
  SimulationOptions o;
  o.target = 1e-11;
  return o;
}

std::string describe(const Params& p) {
  return "F=" + std::to_string(p.F) + " mu=" + std::to_string(p.mu) +
         " mu_s=" + std::to_string(p.static_mu());
}

/// Simulates p with a fresh backend and checks v_ss, c0, the period and the regime.
template <class Backend>
void expect_matches_closed_form(const Params& p, double tolerance = kAgree) {
  SCOPED_TRACE(describe(p));
  Backend backend(backend_options());
  const SimulationSummary sim = steady_state_by_simulation(p, backend, simulation_options());
  const SteadyState exact = steady_state_closed_form(p);
  ASSERT_TRUE(sim.converged) << sim.message;
  EXPECT_LT(rel_diff(sim.v_ss, exact.v_ss), tolerance);
  EXPECT_LT(rel_diff(sim.c0, exact.c0), tolerance);
  EXPECT_LT(rel_diff(sim.period, exact.period), tolerance);
  EXPECT_EQ(sim.regime, exact.regime);
  EXPECT_EQ(sim.regime, regime_of(p));
  EXPECT_GT(sim.stats.steps, sim.strokes);  // integrated, not solved in closed form
}

Params with(double mu, double force, double mu_s = std::nan("")) {
  Params p;
  p.mu = mu;
  p.mu_s = mu_s;
  p.F = force;
  return p;
}

/// μ ∈ {0.05, 0.2, 0.5, 1} × six forces in (μmg, 5Mg]: next to μmg, inside regime I, on both
/// sides of the regime boundary μMg, inside regime II and the top end 5Mg.
std::vector<Params> grid() {
  std::vector<Params> out;
  for (double mu : {0.05, 0.2, 0.5, 1.0}) {
    const Params base;
    const double lo = mu * base.m * base.g;
    const double boundary = mu * base.M * base.g;
    const double hi = 5.0 * base.M * base.g;
    for (double force : {lo * (1.0 + 1e-3), std::sqrt(lo * boundary), boundary * (1.0 - 1e-3),
                         boundary * (1.0 + 1e-3), std::sqrt(boundary * hi), hi}) {
      out.push_back(with(mu, force));
    }
  }
  return out;
}

template <class Backend>
class BackendVsClosedForm : public ::testing::Test {};

using Backends = ::testing::Types<events::CvodeBackend, events::OdeintBackend, events::GslBackend>;
TYPED_TEST_SUITE(BackendVsClosedForm, Backends);

TYPED_TEST(BackendVsClosedForm, AgreesOverTheThesisRange) {
  for (const Params& p : grid()) {
    expect_matches_closed_form<TypeParam>(p);
  }
}

TYPED_TEST(BackendVsClosedForm, ForceJustAboveTheSmallMassFriction) {
  // F = μmg(1 + 1e-9): m creeps forward at (F − μmg)/m ≈ 1e-8 m/s².
  const Params base;
  expect_matches_closed_form<TypeParam>(with(1.0, base.m * base.g * (1.0 + 1e-9)));
}

TYPED_TEST(BackendVsClosedForm, ForceAtTheRegimeBoundary) {
  // F = μMg(1 ∓ 1e-9): regime I just below (M held), regime II just above (M slides back at
  // ≈ 1e-8 m/s²); the regime must be classified on the right side.
  const Params base;
  const double boundary = base.M * base.g;
  const Params below = with(1.0, boundary * (1.0 - 1e-9));
  const Params above = with(1.0, boundary * (1.0 + 1e-9));
  ASSERT_EQ(regime_of(below), Regime::kOne);
  ASSERT_EQ(regime_of(above), Regime::kTwo);
  expect_matches_closed_form<TypeParam>(below);
  expect_matches_closed_form<TypeParam>(above);
}

TYPED_TEST(BackendVsClosedForm, SlowConvergenceAtLowFrictionAndHighForce) {
  // μ = 0.05: λ ≈ 0.9764 per cycle at F = 5Mg (≈ 2000 strokes) and ≈ 0.9976 at F = 50Mg
  // (≈ 20000 strokes); per-stroke errors are amplified by ~1/(1 − λ).
  const Params base;
  expect_matches_closed_form<TypeParam>(with(0.05, 5.0 * base.M * base.g));
  expect_matches_closed_form<TypeParam>(with(0.05, 50.0 * base.M * base.g));
}

TYPED_TEST(BackendVsClosedForm, StaticFrictionAboveDynamicFriction) {
  // μ_s = 1.3 μ: m starts only above μ_s m g; between μMg and μ_s M g static friction holds M
  // (regime I, where μ_s = μ would give regime II); above μ_s M g, M slides back (regime II).
  const Params base;
  for (double mu : {0.2, 1.0}) {
    const double mu_s = 1.3 * mu;
    for (double force : {mu_s * base.m * base.g * (1.0 + 1e-6), 1.15 * mu * base.M * base.g,
                         mu_s * base.M * base.g * (1.0 - 1e-9), mu_s * base.M * base.g * 1.5,
                         5.0 * base.M * base.g}) {
      expect_matches_closed_form<TypeParam>(with(mu, force, mu_s));
    }
  }
  const Params held = with(1.0, 1.15 * base.M * base.g, 1.3);
  EXPECT_EQ(regime_of(held), Regime::kOne);
}

}  // namespace
}  // namespace slipwalk::inchworm
