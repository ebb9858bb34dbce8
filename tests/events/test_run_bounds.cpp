// Bounds that hold for any input: a state that blows up ends a hybrid run with a backend
// failure (never an endless integration towards t_end), whatever the backend, and every
// backend stops at its step budget, saying so.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "events/cvode_backend.hpp"
#include "events/exact_backend.hpp"
#include "events/fixed_step_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/hybrid_run.hpp"
#include "events/odeint_backend.hpp"

namespace slipwalk::events {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// One body under a constant acceleration `a` with one guard p ≥ wall (never, for an infinite
/// wall); the reset puts it back at the start.
struct Falling {
  static constexpr int kBodies = 1;
  static constexpr int kMaxGuards = 1;
  using Mode = int;
  double a;
  double wall;
  [[nodiscard]] ModeFlow<1, 1> flow(Mode /*mode*/) const {
    ModeFlow<1, 1> f;
    f.accel << a;
    f.guard[0].wp << (std::isinf(wall) ? 0.0 : 1.0);
    f.guard[0].w0 = std::isinf(wall) ? -1.0 : -wall;
    f.n_guards = 1;
    return f;
  }
  Mode reset(Mode mode, int /*id*/, State<1>& x) const {
    x(0) = 0.0;  // back to the start: the run goes on until the observer stops it
    return mode;
  }
};

template <class Backend>
class RunBounds : public ::testing::Test {};
using Backends =
    ::testing::Types<ExactBackend, FixedStepBackend, CvodeBackend, OdeintBackend, GslBackend>;
TYPED_TEST_SUITE(RunBounds, Backends);

BackendOptions options(long long max_steps) {
  BackendOptions o;
  o.rtol = 1e-6;
  o.atol = 1e-8;
  o.step = 1e-2;
  o.max_steps = max_steps;
  return o;
}

TYPED_TEST(RunBounds, AStateThatOverflowsEndsTheRunWithABackendFailure) {
  // a = ±1e308 and a guard that never fires: positions overflow within the first second.
  for (const double a : {1e308, -1e308}) {
    const Falling sys{a, kInf};
    TypeParam backend(options(0));
    State<1> x(0.0, 0.0);
    double t = 0.0;
    int mode = 0;
    RunLimits limits;
    limits.t_end = 1e3;
    RunSummary s;
    try {
      s = run_hybrid(sys, backend, t, mode, x, limits, [](const auto&) { return true; });
    } catch (const core::ComputationError& e) {
      s.status = RunStatus::kBackendFailure;  // a backend may also refuse by throwing
      s.message = e.what();
    }
    EXPECT_EQ(s.status, RunStatus::kBackendFailure) << TypeParam::kName << " " << s.message;
    EXPECT_FALSE(s.message.empty()) << TypeParam::kName;
    EXPECT_LT(backend.stats().steps, 10'000) << TypeParam::kName;
  }
}

TYPED_TEST(RunBounds, EveryBackendStopsAtItsStepBudgetAndSaysWhich) {
  // Endless bouncing: every segment ends at the wall and restarts; only the budget stops it.
  const Falling sys{1.0, 0.5};
  TypeParam backend(options(50));
  State<1> x(0.0, 0.0);
  double t = 0.0;
  int mode = 0;
  const RunSummary s =
      run_hybrid(sys, backend, t, mode, x, RunLimits{}, [](const auto&) { return true; });
  EXPECT_EQ(s.status, RunStatus::kStepBudget) << TypeParam::kName;
  EXPECT_NE(s.message.find("step budget of 50 steps"), std::string::npos) << s.message;
  EXPECT_LE(backend.stats().steps, 51) << TypeParam::kName;
}

}  // namespace
}  // namespace slipwalk::events
