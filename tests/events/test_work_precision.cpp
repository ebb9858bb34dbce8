// Work–precision on small cases (the cost-of-accuracy study, studies/cost_of_accuracy): for every
// simulation method, the error of v_ss against the closed form shrinks as its tolerance tightens —
// monotone within a factor — and the fixed-step method's shrinks about linearly in its step.
// Also the error sources the study separates: with the events at the exact times the
// Runge–Kutta methods make no integration error at all, and our stopping rule meets its target
// where the thesis' rule on the running mean does not. Timings stay out of the tests.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "inchworm/params.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {
namespace {

/// One small case per model: fast convergence (tens of strokes).
struct Case {
  const char* name;
  Params p;
};

std::vector<Case> cases() {
  Params instant;
  instant.F = 45.0;
  instant.mu = 1.0;
  Params dm;
  dm.model = SwapModel::kMass;
  dm.alpha = 10.0;
  dm.F = 20.0;
  dm.mu = 1.0;
  return {{"instant F=45 mu=1", instant}, {"dm F=20 mu=1 alpha=10", dm}};
}

double exact_v_ss(const Params& p) {
  const VssResult r = solve_vss(p, Method::kExact);
  EXPECT_TRUE(r.converged) << r.message;
  return r.v_ss;
}

/// |v_ss − exact| / exact of one solve; fails the test if the solve did not converge.
double error_of(const Params& p, Method m, const VssOptions& opt, double exact) {
  const VssResult r = solve_vss(p, m, opt);
  EXPECT_TRUE(r.converged) << method_name(m) << ": " << r.message;
  return std::abs(r.v_ss - exact) / exact;
}

/// Below this an error is round-off: "shrinks" stops making sense there.
constexpr double kFloor = 1e-13;

const std::vector<Method> kIntegrators = {
    Method::kAnalytic,    Method::kCvode, Method::kCvodeBdf, Method::kOdeint,
    Method::kOdeintRkf78, Method::kGsl,   Method::kGslRkf45, Method::kGslMsadams,
};

TEST(WorkPrecision, EveryMethodsErrorShrinksAsItsToleranceTightens) {
  const std::vector<double> tolerances = {1e-3, 1e-5, 1e-7, 1e-9};
  for (const Case& c : cases()) {
    const double exact = exact_v_ss(c.p);
    for (const Method m : kIntegrators) {
      SCOPED_TRACE(std::string(c.name) + ", " + method_name(m));
      std::vector<double> err;
      for (const double tol : tolerances) {
        VssOptions opt;
        opt.rtol = tol;
        err.push_back(error_of(c.p, m, opt, exact));
        // the tolerance is a fair promise of the error
        EXPECT_LE(err.back(), 5.0 * tol) << "rtol " << tol;
      }
      for (std::size_t k = 1; k < err.size(); ++k) {
        // monotone within a factor of 3 (the stopping rule works in whole cycles)
        EXPECT_LE(err[k], 3.0 * err[k - 1] + kFloor) << "rtol " << tolerances[k];
      }
      // and six decades of tolerance buy at least two of error
      EXPECT_LE(err.back(), 1e-2 * err.front() + kFloor);
    }
  }
}

TEST(WorkPrecision, FixedStepErrorShrinksAboutLinearlyInTheStep) {
  // RK4 integrates a mode exactly; its error is that of events found at step ends: O(h).
  const std::vector<double> steps = {1e-3, 1e-4, 1e-5};
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const double exact = exact_v_ss(c.p);
    std::vector<double> err;
    for (const double h : steps) {
      VssOptions opt;
      opt.step = h;
      opt.target = 1e-10;  // far below the step's error
      err.push_back(error_of(c.p, Method::kFixedRk4, opt, exact));
      EXPECT_LE(err.back(), 100.0 * h) << "h " << h;  // O(h), 100 s⁻¹ the constant
    }
    for (std::size_t k = 1; k < err.size(); ++k) {
      EXPECT_LT(err[k], err[k - 1]) << "h " << steps[k];
    }
    // least-squares slope of log err against log h: about 1
    double sx = 0.0;
    double sy = 0.0;
    double sxx = 0.0;
    double sxy = 0.0;
    const auto n = static_cast<double>(steps.size());
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const double x = std::log10(steps[k]);
      const double y = std::log10(err[k]);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    EXPECT_GT(slope, 0.5);
    EXPECT_LT(slope, 1.5);
  }
}

TEST(WorkPrecision, FixedStepTakesRtolAsItsStepWhenNoneIsGiven) {
  // What `slipwalk inchworm vss --method fixed_rk4 --rtol 1e-3` does: h = 1e-3 s.
  const Params p = cases().front().p;
  VssOptions by_rtol;
  by_rtol.rtol = 1e-3;
  VssOptions by_step = by_rtol;
  by_step.step = 1e-3;
  const VssResult a = solve_vss(p, Method::kFixedRk4, by_rtol);
  const VssResult b = solve_vss(p, Method::kFixedRk4, by_step);
  ASSERT_TRUE(a.converged) << a.message;
  EXPECT_EQ(a.v_ss, b.v_ss);
  EXPECT_EQ(a.stats.steps, b.stats.steps);
}

TEST(WorkPrecision, WithExactEventTimesRungeKuttaMakesNoIntegrationError) {
  // A mode's motion is quadratic in t; every Runge–Kutta pair here (and RK4) reproduces it to
  // round-off whatever its tolerance. The multistep methods restart at order 1 in each segment
  // and make an integration error that shrinks with rtol.
  const Case c = cases().front();
  const double exact = exact_v_ss(c.p);
  VssOptions opt;
  opt.exact_event_times = true;
  opt.target = 1e-13;
  for (const Method m : {Method::kOdeint, Method::kOdeintRkf78, Method::kGsl, Method::kGslRkf45,
                         Method::kFixedRk4}) {
    SCOPED_TRACE(method_name(m));
    opt.rtol = 1e-3;  // (fixed_rk4: h = 1e-3 s)
    EXPECT_LT(error_of(c.p, m, opt, exact), 1e-11);
  }
  for (const Method m : {Method::kCvode, Method::kCvodeBdf, Method::kGslMsadams}) {
    SCOPED_TRACE(method_name(m));
    opt.rtol = 1e-3;
    const double loose = error_of(c.p, m, opt, exact);
    opt.rtol = 1e-9;
    const double tight = error_of(c.p, m, opt, exact);
    EXPECT_LT(tight, 1e-2 * loose + kFloor);
    EXPECT_LT(tight, 1e-8);
  }
}

TEST(WorkPrecision, OurStoppingRuleMeetsItsTargetTheThesisRunningMeanDoesNot) {
  // The slow-converging case (contraction 0.976 per cycle), exact event-driven integration: no
  // integration or location error, only the stopping rule's.
  Params p;
  p.F = 5.0 * p.M * p.g;
  p.mu = 0.05;
  const double exact = exact_v_ss(p);
  VssOptions ours;
  ours.target = 1e-6;
  EXPECT_LT(error_of(p, Method::kAnalytic, ours, exact), 2e-6);
  VssOptions thesis = ours;
  thesis.stop = StopRule::kConsecutiveDifference;
  thesis.estimator = Estimator::kRunningMean;
  EXPECT_GT(error_of(p, Method::kAnalytic, thesis, exact), 100.0 * 1e-6);
}

}  // namespace
}  // namespace slipwalk::inchworm
