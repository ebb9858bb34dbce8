// v_ss by exact event-driven simulation against the closed form, the honesty of the remaining-
// error estimate, the thesis' stopping protocol, determinism and hard cases (regime boundaries,
// slow convergence, strong actuators).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "events/exact_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/simulate.hpp"
#include "inchworm/vss.hpp"
#include "support/inchworm_grid.hpp"

namespace slipwalk::inchworm {
namespace {

using testing::rel_diff;

SimulationSummary simulate_exact(const Params& p, SimulationOptions opt = {}) {
  events::ExactBackend backend;
  return steady_state_by_simulation(p, backend, opt);
}

TEST(Simulation, ExactIntegrationMatchesTheClosedFormOverTheThesisRange) {
  for (const Params& p : testing::thesis_grid()) {
    const SteadyState exact = steady_state_closed_form(p);
    const SimulationSummary sim = simulate_exact(p);
    ASSERT_TRUE(sim.converged) << sim.message << " F=" << p.F << " mu=" << p.mu;
    EXPECT_LT(rel_diff(sim.v_ss, exact.v_ss), 1e-10) << "F=" << p.F << " mu=" << p.mu;
    EXPECT_LT(rel_diff(sim.period, exact.period), 1e-10);
    EXPECT_LT(rel_diff(sim.c0, exact.c0), 1e-10);
    EXPECT_EQ(sim.regime, exact.regime);
  }
}

// The estimate must bound the true error (within a small factor), also where convergence is
// slow and the last difference alone would understate the error by λ/(1 − λ).
TEST(Simulation, RemainingErrorEstimateIsHonest) {
  for (const Params& p : testing::thesis_grid(4, 5)) {
    for (double target : {1e-6, 1e-9, 1e-12}) {
      SimulationOptions opt;
      opt.target = target;
      const SimulationSummary sim = simulate_exact(p, opt);
      const double truth = rel_diff(sim.v_ss, steady_state_closed_form(p).v_ss);
      ASSERT_TRUE(sim.converged);
      EXPECT_LE(truth, 3.0 * sim.est_error + 1e-14)
          << "F=" << p.F << " mu=" << p.mu << " target=" << target;
      EXPECT_LE(truth, 3.0 * target + 1e-14);
    }
  }
}

TEST(Simulation, EstimatedContractionIsTheSquareOfTheStrokeMapSlope) {
  Params p;
  p.mu = 0.05;
  p.F = 5.0 * p.M * p.g;
  SimulationOptions opt;
  opt.target = 1e-9;  // stop while the differences are far above round-off
  const SimulationSummary sim = simulate_exact(p, opt);
  const double lambda = steady_state_closed_form(p).contraction;
  EXPECT_NEAR(sim.contraction, lambda * lambda, 1e-6);
}

// The thesis stopped when consecutive averages differed by 1e-4 (§2.2.2). Averaging from rest
// converges like 1/N and leaves a visible gap; the last-cycle average does not.
TEST(Simulation, ThesisRunningMeanProtocolLeavesAVisibleGap) {
  Params p;
  p.F = 45.0;
  SimulationOptions thesis;
  thesis.target = 1e-4;
  thesis.stop = StopRule::kConsecutiveDifference;
  thesis.estimator = Estimator::kRunningMean;
  SimulationOptions cycle = thesis;
  cycle.estimator = Estimator::kCycleAverage;
  const double exact = steady_state_closed_form(p).v_ss;
  const SimulationSummary running = simulate_exact(p, thesis);
  const SimulationSummary last = simulate_exact(p, cycle);
  EXPECT_GT(rel_diff(running.v_ss, exact), 1e-3);
  EXPECT_LT(running.v_ss, exact);  // the transient from rest is slower than the limit cycle
  EXPECT_LT(rel_diff(last.v_ss, exact), 1e-4);
}

// The thesis' protocol (§2.2.2: from rest, the running mean, stopped when two consecutive
// means differ by less than a tolerance) is a consistent estimator of the limit cycle's speed:
// the running mean's error decays like 1/N and the consecutive differences like 1/N², so the
// error left at stopping shrinks like the square root of the tolerance and goes to zero with it.
TEST(Simulation, TheThesisProtocolConvergesToTheClosedFormAsItsToleranceGoesToZero) {
  for (const double mu : {1.0, 0.2}) {
    Params p;
    p.mu = mu;
    p.F = 45.0 * mu;
    const double exact = steady_state_closed_form(p).v_ss;
    double previous = 1.0;
    for (const double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      SimulationOptions thesis;
      thesis.target = tol;
      thesis.stop = StopRule::kConsecutiveDifference;
      thesis.estimator = Estimator::kRunningMean;
      thesis.max_strokes = 100'000'000;
      const SimulationSummary s = simulate_exact(p, thesis);
      ASSERT_TRUE(s.converged) << "mu = " << mu << ", tol = " << tol;
      const double gap = rel_diff(s.v_ss, exact);
      EXPECT_LT(gap, previous / 5.0) << "mu = " << mu << ", tol = " << tol;
      EXPECT_LT(gap, 30.0 * std::sqrt(tol)) << "mu = " << mu << ", tol = " << tol;
      previous = gap;
    }
    EXPECT_LT(previous, 1e-4) << "mu = " << mu;
  }
}

// The same protocol on a fixed RK4 step (the thesis' other reading of its integrator, §2.2.2):
// its error has two parts, the step's O(h) and the stopping rule's O(√tol), and goes to zero as
// both shrink together.
TEST(Simulation, TheThesisProtocolOnAFixedStepConvergesAsTheStepAndToleranceShrink) {
  Params p;
  p.F = 45.0;
  const double exact = steady_state_closed_form(p).v_ss;
  double previous = 1.0;
  for (const auto& [h, tol] :
       {std::pair{1e-3, 1e-4}, std::pair{1e-4, 1e-6}, std::pair{2e-5, 1e-7}}) {
    VssOptions opt;
    opt.step = h;
    opt.target = tol;
    opt.stop = StopRule::kConsecutiveDifference;
    opt.estimator = Estimator::kRunningMean;
    const VssResult r = solve_vss(p, Method::kFixedRk4, opt);
    ASSERT_TRUE(r.converged) << "h = " << h << ": " << r.message;
    const double gap = rel_diff(r.v_ss, exact);
    EXPECT_LT(gap, previous / 3.0) << "h = " << h << ", tol = " << tol;
    previous = gap;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST(Simulation, IsDeterministic) {
  Params p;
  p.F = 30.0;
  p.mu = 0.3;
  const SimulationSummary a = simulate_exact(p);
  const SimulationSummary b = simulate_exact(p);
  EXPECT_EQ(a.v_ss, b.v_ss);
  EXPECT_EQ(a.strokes, b.strokes);
}

// Hard cases (regime boundaries, slow convergence at low friction, strong actuators, static
// friction above sliding): each converges and matches the closed form to 1e-9.
struct HardCase {
  const char* name;
  double F_over_Mg;  // if > 0, F = F_over_Mg M g
  double F_factor;   // else F = F_factor × (μ m g or μ M g, see on_large)
  bool on_large;
  double mu;
  double mu_s;
};

class HardCases : public ::testing::TestWithParam<HardCase> {};

TEST_P(HardCases, ConvergeAndMatchTheClosedForm) {
  const HardCase& hc = GetParam();
  Params p;
  p.mu = hc.mu;
  if (hc.mu_s > 0.0) {
    p.mu_s = hc.mu_s;
  }
  p.F = hc.F_over_Mg > 0.0 ? hc.F_over_Mg * p.M * p.g
                           : hc.F_factor * p.mu * (hc.on_large ? p.M : p.m) * p.g;
  for (Method method : {Method::kExact, Method::kRootfind, Method::kAnalytic}) {
    const VssResult r = solve_vss(p, method, VssOptions{.rtol = 1e-11});
    ASSERT_TRUE(r.converged) << method_name(method) << ": " << r.message;
    ASSERT_TRUE(std::isfinite(r.v_ss));
    EXPECT_LT(rel_diff(r.v_ss, steady_state_closed_form(p).v_ss), 1e-9) << method_name(method);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Inchworm, HardCases,
    ::testing::Values(HardCase{"JustAboveSmallMassFriction", 0, 1 + 1e-9, false, 1.0, 0},
                      HardCase{"RegimeBoundaryBelow", 0, 1 - 1e-9, true, 1.0, 0},
                      HardCase{"RegimeBoundaryAbove", 0, 1 + 1e-9, true, 1.0, 0},
                      HardCase{"SlowConvergenceLowFriction", 5.0, 0, false, 0.05, 0},
                      HardCase{"VeryStrongActuator", 50.0, 0, false, 0.05, 0},
                      HardCase{"StaticAboveDynamic", 0, 1.2, true, 1.0, 1.3}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace slipwalk::inchworm
