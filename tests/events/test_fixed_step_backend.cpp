// The fixed-step backend without event location, and the exact-event-times wrapper, on single
// segments of one body with constant acceleration, against the closed form
// p(τ) = p0 + v0 τ + a τ²/2.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "events/exact_event_times.hpp"
#include "events/fixed_step_backend.hpp"
#include "events/odeint_backend.hpp"

namespace slipwalk::events {
namespace {

/// One body with acceleration a and up to two guards g = wp p + wv v + w0.
struct OneBody {
  ModeFlow<1, 2> flow;
  explicit OneBody(double a) { flow.accel << a; }
  OneBody& guard(double wp, double wv, double w0) {
    AffineGuard<1>& g = flow.guard[flow.n_guards];
    g.wp << wp;
    g.wv << wv;
    g.w0 = w0;
    g.id = 10 + flow.n_guards;
    ++flow.n_guards;
    return *this;
  }
};

State<1> state(double p, double v) {
  State<1> x;
  x << p, v;
  return x;
}

BackendOptions with_step(double h) {
  BackendOptions o;
  o.step = h;
  return o;
}

TEST(FixedStepBackend, FindsTheGuardAtTheFirstStepEndAfterTheCrossing) {
  // Sliding at v0 = 1 against a = −2: g = −v crosses at τ = 0.5. With h = 0.03 the first step
  // end at or after it is 17 h = 0.51, where RK4's state is the exact one (it integrates a
  // quadratic exactly), the guard already past zero.
  const OneBody sys = OneBody(-2.0).guard(0.0, -1.0, 0.0);
  State<1> x = state(0.0, 1.0);
  FixedStepBackend backend(with_step(0.03));
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 17 * 0.03, 1e-15);
  EXPECT_NEAR(x(0), 0.51 - 0.51 * 0.51, 1e-14);
  EXPECT_NEAR(x(1), 1.0 - 2.0 * 0.51, 1e-14);
  EXPECT_EQ(backend.stats().steps, 17);
  EXPECT_EQ(backend.stats().rhs_evals, 1 + 4 * 17);  // the start, then 4 per step
}

TEST(FixedStepBackend, MissesACrossingThatRisesAndFallsWithinOneStep) {
  // g = p − 0.2499 with p = τ − τ²: above zero on τ ∈ (0.4900, 0.5100) only, inside one step of
  // h = 0.3 (step ends 0.3, 0.6): no step end sees it. t_end ends the segment.
  const OneBody sys = OneBody(-2.0).guard(1.0, 0.0, -0.2499);
  State<1> x = state(0.0, 1.0);
  FixedStepBackend backend(with_step(0.3));
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 2.0);
  EXPECT_EQ(end.guard, -1);
  EXPECT_EQ(end.t, 2.0);  // the last step shortened to land on t_end
  EXPECT_NEAR(x(0), 2.0 - 4.0, 1e-13);
}

TEST(FixedStepBackend, AGuardOnZeroAndRisingFiresAtOnce) {
  const OneBody sys = OneBody(1.0).guard(0.0, 1.0, 0.0);
  State<1> x = state(0.0, 0.0);
  FixedStepBackend backend(with_step(0.1));
  const SegmentEnd end = backend.advance(sys.flow, 4.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_EQ(end.t, 4.0);
}

TEST(FixedStepBackend, RejectsABadStepAndHonoursTheStepBudget) {
  EXPECT_THROW(FixedStepBackend(with_step(0.0)), core::InputError);
  EXPECT_THROW(FixedStepBackend(with_step(std::nan(""))), core::InputError);
  BackendOptions o = with_step(1e-3);
  o.max_steps = 100;
  FixedStepBackend backend(o);
  const OneBody sys = OneBody(1.0).guard(1.0, 0.0, -1e6);  // far away
  State<1> x = state(0.0, 0.0);
  EXPECT_THROW((void)backend.advance(sys.flow, 0.0, x, 10.0), core::ComputationError);
  EXPECT_EQ(backend.stats().steps, 100);
}

TEST(ExactEventTimes, EndsAtTheExactTimeWithTheWrappedBackendsState) {
  // The crossing time comes from the exact solution; the state from the wrapped integrator
  // (here a fixed step that would otherwise overshoot by up to h).
  const OneBody sys = OneBody(-2.0).guard(0.0, -1.0, 0.0);
  State<1> x = state(0.0, 1.0);
  FixedStepBackend inner(with_step(0.03));
  ExactEventTimes<FixedStepBackend> backend(inner);
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_EQ(end.t, 0.5);
  EXPECT_NEAR(x(0), 0.25, 1e-14);
  EXPECT_NEAR(x(1), 0.0, 1e-14);
  EXPECT_EQ(backend.stats().segments, 1);
  EXPECT_EQ(backend.stats().guard_evals, 0);  // the wrapped backend sees no guards
}

TEST(ExactEventTimes, WrapsALocatingBackendToo) {
  const OneBody sys = OneBody(1.7).guard(1.0, 0.0, -1.0);
  const double tau = 2.0 / (0.3 + std::sqrt(0.09 + 2.0 * 1.7));
  State<1> x = state(0.0, 0.3);
  OdeintBackend inner;
  ExactEventTimes<OdeintBackend> backend(inner);
  const SegmentEnd end = backend.advance(sys.flow, 2.5, x, 100.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 2.5 + tau, 1e-15 * (2.5 + tau));
  EXPECT_NEAR(x(0), 1.0, 1e-12);
}

}  // namespace
}  // namespace slipwalk::events
