// The numeric backends (CVODE, Boost.Odeint, GSL) on single segments of tiny hand-made systems
// whose event times are known in closed form: one body, constant acceleration, affine guards.
// Oracles are the closed-form solutions p(τ) = p0 + v0 τ + a τ²/2, never stored outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "events/cvode_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/odeint_backend.hpp"

// Allocation counting needs glibc and no sanitizer (which brings its own malloc).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define SLIPWALK_SANITIZED_MALLOC 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define SLIPWALK_SANITIZED_MALLOC 1
#endif
#if defined(__GLIBC__) && !defined(SLIPWALK_SANITIZED_MALLOC)
#define SLIPWALK_COUNT_ALLOCATIONS 1
#endif

#if defined(SLIPWALK_COUNT_ALLOCATIONS)
#include <atomic>
#include <cstdlib>

// Counts heap allocations made while `g_count_allocations` is set: glibc lets the executable
// interpose malloc/calloc/realloc and forward them to the real allocator (operator new ends in
// malloc as well). Used to check that the backends do not allocate per step or per segment.
// glibc's own entry points to its allocator (reserved names, but that is what they are called).
extern "C" {
void* __libc_malloc(std::size_t);               // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(std::size_t, std::size_t);  // NOLINT(bugprone-reserved-identifier)
void* __libc_realloc(void*, std::size_t);       // NOLINT(bugprone-reserved-identifier)
}
namespace {
std::atomic<bool> g_count_allocations{false};
std::atomic<long> g_allocations{0};
}  // namespace
extern "C" {
void* malloc(std::size_t n) {
  if (g_count_allocations.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  if (g_count_allocations.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  if (g_count_allocations.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_realloc(p, n);
}
}
#endif

namespace slipwalk::events {
namespace {

/// Tight step tolerances: the event time and state must then agree with the closed form to 1e-9.
BackendOptions tight() {
  BackendOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  return o;
}

constexpr double kAgree = 1e-9;

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

// The other variants of the three libraries' backends, as types for the typed tests.
struct CvodeBdf : CvodeBackend {
  explicit CvodeBdf(const BackendOptions& o) : CvodeBackend(o, CvodeMethod::kBdf) {}
};
struct OdeintFehlberg78 : OdeintBackend {
  explicit OdeintFehlberg78(const BackendOptions& o)
      : OdeintBackend(o, OdeintStepper::kFehlberg78) {}
};
struct GslRkf45 : GslBackend {
  explicit GslRkf45(const BackendOptions& o) : GslBackend(o, GslStepper::kRkf45) {}
};
struct GslMsadams : GslBackend {
  explicit GslMsadams(const BackendOptions& o) : GslBackend(o, GslStepper::kMsadams) {}
};

/// The agreement asked of a backend where it must resolve a crossing inside its very first
/// step: msadams restarts at order 1 in every segment (a multistep method has no history
/// across a mode change), so there its state, and with it the crossing, is good to ~2e-9.
template <class Backend>
constexpr double kAgreeFirstStep = kAgree;
template <>
constexpr double kAgreeFirstStep<GslMsadams> = 3e-9;

template <class Backend>
class NumericBackend : public ::testing::Test {};

using Backends = ::testing::Types<CvodeBackend, OdeintBackend, GslBackend, CvodeBdf,
                                  OdeintFehlberg78, GslRkf45, GslMsadams>;
TYPED_TEST_SUITE(NumericBackend, Backends);

TYPED_TEST(NumericBackend, PositionGuardFiresAtTheClosedFormTime) {
  // p0 = 0, v0 = 0.3, a = 1.7; guard p − 1 rises through zero at the positive root of
  // a τ²/2 + v0 τ − 1 = 0, from t0 = 2.5.
  const double a = 1.7;
  const double v0 = 0.3;
  const OneBody sys = OneBody(a).guard(1.0, 0.0, -1.0);
  const double tau = 2.0 / (v0 + std::sqrt(v0 * v0 + 2.0 * a));  // cancellation-free root
  State<1> x = state(0.0, v0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 2.5, x, 100.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 2.5 + tau, kAgree * (2.5 + tau));
  EXPECT_NEAR(x(0), 1.0, kAgree);
  EXPECT_NEAR(x(1), v0 + a * tau, kAgree);
  EXPECT_GE(x(0) - 1.0, -kAgree);  // the returned state is where the guard has fired
}

TYPED_TEST(NumericBackend, VelocityGuardFiresWhenTheBodyStops) {
  // Sliding forward at v0 = 1 against a deceleration of 2: g = −v rises through 0 at τ = 0.5,
  // where p = 0.25.
  const OneBody sys = OneBody(-2.0).guard(0.0, -1.0, 0.0);
  State<1> x = state(0.0, 1.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 0.5, kAgree);
  EXPECT_NEAR(x(0), 0.25, kAgree);
  EXPECT_NEAR(x(1), 0.0, kAgree);
}

TYPED_TEST(NumericBackend, TheEarlierOfTwoGuardsFires) {
  // v0 = 1, a = −2: guard 0 (p − 0.2) crosses at τ = (1 − √0.2)/2 ≈ 0.276, guard 1 (−v) at 0.5.
  const OneBody sys = OneBody(-2.0).guard(1.0, 0.0, -0.2).guard(0.0, -1.0, 0.0);
  State<1> x = state(0.0, 1.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  const double tau = 0.4 / (1.0 + std::sqrt(0.2));  // cancellation-free form
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, tau, kAgree);
  EXPECT_NEAR(x(0), 0.2, kAgree);
  EXPECT_NEAR(x(1), 1.0 - 2.0 * tau, kAgree);
}

TYPED_TEST(NumericBackend, AGuardAtZeroAndFallingDoesNotFire) {
  // The velocity was just reset to zero and the body starts sliding backward: g = v is 0 at t0
  // and falling, so it must not fire (first_rising_root(0, −1, 0) = never); t_end ends the run.
  const OneBody sys = OneBody(-1.0).guard(0.0, 1.0, 0.0);
  State<1> x = state(0.0, 0.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 3.0);
  EXPECT_EQ(end.guard, -1);
  EXPECT_EQ(end.t, 3.0);
  EXPECT_NEAR(x(0), -4.5, kAgree * 4.5);
  EXPECT_NEAR(x(1), -3.0, kAgree * 3.0);
}

TYPED_TEST(NumericBackend, AGuardAtZeroThatDipsAndRisesFiresLater) {
  // g = p with p0 = 0, v0 = −1, a = 2: g = τ² − τ falls below zero, then rises through it at 1.
  const OneBody sys = OneBody(2.0).guard(1.0, 0.0, 0.0);
  State<1> x = state(0.0, -1.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 1.0, kAgree);
  EXPECT_NEAR(x(0), 0.0, kAgree);
  EXPECT_NEAR(x(1), 1.0, kAgree);
}

TYPED_TEST(NumericBackend, AGuardAboveZeroAndFallingFiresOnlyWhenItRisesAgain) {
  // g = p − 1 with p0 = 2, v0 = −1, a = 0.4: g = 1 − τ + 0.2 τ² falls through zero at
  // τ = (1 − √0.2)/0.4 (not an event) and rises through it at τ = (1 + √0.2)/0.4.
  const OneBody sys = OneBody(0.4).guard(1.0, 0.0, -1.0);
  State<1> x = state(2.0, -1.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  const double tau = (1.0 + std::sqrt(0.2)) / 0.4;
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, tau, kAgree * tau);
  EXPECT_NEAR(x(0), 1.0, kAgree);
  EXPECT_NEAR(x(1), -1.0 + 0.4 * tau, kAgree);
}

TYPED_TEST(NumericBackend, AGuardAtZeroAndRisingFiresAtOnce) {
  // first_rising_root(0, +1, ·) = 0: on the guard and rising fires at t0, state untouched.
  const OneBody sys = OneBody(1.0).guard(1.0, 0.0, -5.0).guard(0.0, 1.0, 0.0);
  State<1> x = state(0.0, 0.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 4.0, x, 10.0);
  EXPECT_EQ(end.guard, 1);
  EXPECT_EQ(end.t, 4.0);
  EXPECT_EQ(x(0), 0.0);
  EXPECT_EQ(x(1), 0.0);
}

TYPED_TEST(NumericBackend, ReachesTEndWhenNoGuardFires) {
  // Guard p − 100 is far away: the segment ends at t_end with the closed-form state.
  const OneBody sys = OneBody(0.5).guard(1.0, 0.0, -100.0);
  State<1> x = state(1.0, -2.0);
  TypeParam backend(tight());
  const SegmentEnd end = backend.advance(sys.flow, 1.0, x, 3.0);
  EXPECT_EQ(end.guard, -1);
  EXPECT_EQ(end.t, 3.0);
  EXPECT_NEAR(x(0), 1.0 - 2.0 * 2.0 + 0.25 * 4.0, kAgree);
  EXPECT_NEAR(x(1), -2.0 + 0.5 * 2.0, kAgree);
}

TYPED_TEST(NumericBackend, StatsCountStepsAndTheObserverSeesEachOne) {
  const OneBody sys = OneBody(1.7).guard(1.0, 0.0, -1.0);
  State<1> x = state(0.0, 0.3);
  TypeParam backend(tight());
  std::vector<double> times;
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 100.0,
                                         [&](double t, const State<1>&) { times.push_back(t); });
  const BackendStats& s = backend.stats();
  EXPECT_EQ(s.segments, 1);
  EXPECT_GE(s.steps, 2);  // adaptive steps from a small first step
  EXPECT_EQ(static_cast<long long>(times.size()), s.steps);
  EXPECT_GE(s.rhs_evals, s.steps);
  EXPECT_GE(s.guard_evals, s.steps);
  for (std::size_t i = 1; i < times.size(); ++i) {
    EXPECT_GT(times[i], times[i - 1]);
  }
  EXPECT_EQ(times.back(), end.t);
  // A second segment adds to the counters.
  const BackendStats first = s;
  x = state(0.0, 0.3);
  (void)backend.advance(sys.flow, 0.0, x, 100.0);
  EXPECT_EQ(backend.stats().segments, 2);
  EXPECT_EQ(backend.stats().steps, 2 * first.steps);  // the same segment costs the same
  EXPECT_EQ(backend.stats().rhs_evals, 2 * first.rhs_evals);
}

TYPED_TEST(NumericBackend, AZeroGuardWithZeroSlopeDoesNotLeakIntoTheNextSegment) {
  // Segment 1: a resting body with guard g = v (0 with zero slope: never fires). CVODE leaves
  // such a root function disarmed; the next segment, a new mode, must see all guards armed.
  const OneBody rest = OneBody(0.0).guard(0.0, 1.0, 0.0);
  State<1> x = state(0.0, 0.0);
  TypeParam backend(tight());
  SegmentEnd end = backend.advance(rest.flow, 0.0, x, 1.0);
  EXPECT_EQ(end.guard, -1);
  EXPECT_EQ(end.t, 1.0);
  // Segment 2: from rest at a = 2, p − 1e-6 rises through zero at τ = 1e-3, inside CVODE's
  // first step.
  const OneBody push = OneBody(2.0).guard(1.0, 0.0, -1e-6);
  end = backend.advance(push.flow, 1.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 1.001, kAgreeFirstStep<TypeParam>);
}

TYPED_TEST(NumericBackend, EventToleranceIsHonoured) {
  // A loose event tolerance locates the same crossing less precisely, but within that tolerance.
  const OneBody sys = OneBody(-2.0).guard(0.0, -1.0, 0.0);
  BackendOptions o = tight();
  o.event_tol = 1e-6;
  State<1> x = state(0.0, 1.0);
  TypeParam backend(o);
  const SegmentEnd end = backend.advance(sys.flow, 0.0, x, 10.0);
  EXPECT_EQ(end.guard, 0);
  EXPECT_NEAR(end.t, 0.5, 1e-6);
  EXPECT_GE(end.t, 0.5 - 1e-12);  // the upper end of the bracket: the guard has fired
}

#if defined(SLIPWALK_COUNT_ALLOCATIONS)
TYPED_TEST(NumericBackend, DoesNotAllocateAfterTheFirstSegment) {
  const OneBody sys = OneBody(-2.0).guard(1.0, 0.0, -0.2).guard(0.0, -1.0, 0.0);
  TypeParam backend(tight());
  State<1> x = state(0.0, 1.0);
  (void)backend.advance(sys.flow, 0.0, x, 10.0);  // lazily sizes the solver memory
  long steps_before = static_cast<long>(backend.stats().steps);
  g_allocations = 0;
  g_count_allocations = true;
  for (int i = 0; i < 20; ++i) {
    x = state(0.0, 1.0);
    (void)backend.advance(sys.flow, 0.0, x, 10.0);
  }
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_GT(static_cast<long>(backend.stats().steps), steps_before);
}
#endif

}  // namespace
}  // namespace slipwalk::events
