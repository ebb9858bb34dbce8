#pragma once
// Boost.Odeint (1.74) as a backend of the hybrid layer (DESIGN.md: one hybrid description, many
// integrators): an embedded Runge–Kutta pair with step-size control, stepped one accepted step
// at a time. Same interface as ExactBackend. Two steppers (OdeintStepper, chosen at
// construction), one event loop:
//  - kDopri5 (the default): make_dense_output(atol, rtol, runge_kutta_dopri5), the
//    Dormand–Prince 5(4) pair with its order-4 dense output (calc_state), advanced by do_step.
//  - kFehlberg78: make_controlled(atol, rtol, runge_kutta_fehlberg78), Fehlberg's 7(8) pair,
//    advanced by try_step (a rejected step is retried with the controller's smaller size).
//    Boost 1.74 has no dense output for it, so the state inside an accepted step is
//    RE-INTEGRATED from the step start with ONE fehlberg78 step of size τ (do_step from the
//    start state and the field there, which try_step was given): as accurate as the accepted
//    step itself, at 12 field evaluations per trial. (A cubic Hermite interpolant would cost
//    none but is only O(h⁴) in general; exact here, where a mode's motion is quadratic.)
//
// Numerical choices.
//  - State type std::array<double, 2N>, odeint's plainest (array algebra, fixed size): the
//    steppers keep all their stages inside the object, which lives on the stack of advance(),
//    so nothing is ever allocated on the heap.
//  - First step: the starting-step heuristic of Hairer, Nørsett & Wanner (Solving ODEs I, II.4)
//    from two evaluations of the field, for the stepper's order; the controller takes over.
//  - Guards: after each accepted step every guard is evaluated at the step end (g, and dg/dt
//    from the field there: dopri5 evaluates it anyway as its first-same-as-last stage and the
//    field functor keeps that last evaluation; fehlberg78 evaluates it once and hands it to the
//    next try_step as its start derivative). The step-end test shared by all numeric backends
//    then finds the first rising crossing in the step: a sign change of g, or a rise hidden
//    inside the step — a maximum (dg/dt from + to −) that reaches zero, or a minimum (dg/dt
//    from − to +) below zero followed by a rise — assuming dg/dt changes sign at most once per
//    step. Crossings and extrema are located on the dense output (dopri5) or by re-integration
//    (fehlberg78) with TOMS 748 (boost::math::tools::toms748_solve, then bisection if it runs
//    out of iterations) to BackendOptions::event_tol (default 4ε·max(1, |t|)). The event state
//    is the one at the upper end of the final bracket, where the guard is ≥ 0. Ties between
//    guards go to the last one, as in ExactBackend.
//  - The start of a segment mirrors first_rising_root at τ = 0: a guard that is ≥ 0 and rising
//    fires at t0 without a step; any other guard ≥ 0 at t0 does not fire there.
//  - dopri5's steps may run past t_end (the segment then ends on the interpolant at t_end);
//    fehlberg78's steps are clipped to end at t_end.
#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "events/guard_search.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

/// Which odeint stepper an OdeintBackend uses (see the top of this file).
enum class OdeintStepper {
  kDopri5,      ///< runge_kutta_dopri5, controlled, dense output
  kFehlberg78,  ///< runge_kutta_fehlberg78, controlled; guards located by re-integration
};

class OdeintBackend {
 public:
  /// odeint's state type for N bodies: positions then velocities, (2N).
  template <int N>
  using Array = std::array<double, static_cast<std::size_t>(2 * N)>;

  static constexpr const char* kName = "odeint";

  explicit OdeintBackend(const BackendOptions& options = {},
                         OdeintStepper stepper = OdeintStepper::kDopri5)
      : options_(options), stepper_(stepper) {}

  /// Advances x from t0 in the mode `flow` until its first guard rises through zero or t_end.
  /// Throws core::ComputationError when the step-size control fails or the state blows up.
  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    ++stats_.segments;
    LastEvaluation<N> last;
    const Field<N, G> field{&flow, &stats_.rhs_evals, &last};
    Array<N> y{};
    std::copy(x.data(), x.data() + 2 * N, y.begin());
    Array<N> dy{};
    field(y, dy, t0);
    // g and dg/dt of every guard at t0; a guard on or above zero and rising fires at once.
    std::array<GuardSample, G> lo{};
    stats_.guard_evals += flow.n_guards;
    if (const int fired = guard_search::fires_at_start(flow, y.data(), dy.data(), lo.data());
        fired >= 0) {
      return {t0, fired};
    }
    if (!(t_end > t0)) {
      return {t0, -1};
    }
    if (stepper_ == OdeintStepper::kFehlberg78) {
      Fehlberg78Steps<N> steps(options_);
      steps.start(y, dy, t0, std::min(initial_step(field, y, dy, t0, 7), t_end - t0));
      return integrate(flow, field, steps, lo.data(), x, t_end, observe);
    }
    Dopri5Steps<N> steps(options_);
    steps.start(y, dy, t0, std::min(initial_step(field, y, dy, t0, 5), t_end - t0));
    return integrate(flow, field, steps, lo.data(), x, t_end, observe);
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }

 private:
  using GuardSample = guard_search::GuardSample;

  /// The field's last evaluation (after dopri5's do_step: its last stage, at the step end).
  template <int N>
  struct LastEvaluation {
    double t = std::numeric_limits<double>::quiet_NaN();
    Array<N> y{};
    Array<N> dydt{};
  };

  /// The mode's vector field [p; v]' = [v; a] in odeint's calling convention: all a backend
  /// knows of the flow.
  template <int N, int G>
  struct Field {
    const ModeFlow<N, G>* flow;
    long long* evals;
    LastEvaluation<N>* last;
    void operator()(const Array<N>& y, Array<N>& dydt, double t) const {
      for (int i = 0; i < N; ++i) {
        dydt[i] = y[N + i];
        dydt[N + i] = flow->accel(i);
      }
      ++*evals;
      last->t = t;
      last->y = y;
      last->dydt = dydt;
    }
  };

  /// One accepted step: [t_lo, t_hi] (t_hi ≤ t_end); `at_end` once the segment reached t_end.
  struct Span {
    double t_lo;
    double t_hi;
    bool at_end;
  };

  /// Dormand–Prince 5(4) with dense output. After step(): y_hi, dy_hi at t_hi.
  template <int N>
  struct Dopri5Steps {
    using Stepper = decltype(boost::numeric::odeint::make_dense_output(
        1.0, 1.0, boost::numeric::odeint::runge_kutta_dopri5<Array<N>>()));
    Stepper stepper;
    Array<N> y_hi{};
    Array<N> dy_hi{};

    explicit Dopri5Steps(const BackendOptions& o)
        : stepper(boost::numeric::odeint::make_dense_output(
              o.atol, o.rtol, boost::numeric::odeint::runge_kutta_dopri5<Array<N>>())) {}

    void start(const Array<N>& y, const Array<N>& /*dy*/, double t0, double h0) {
      stepper.initialize(y, t0, h0);
    }

    template <class F>
    Span step(const F& field, double t_end) {
      const std::pair<double, double> span = stepper.do_step(field);
      const double t_hi = std::min(span.second, t_end);
      if (span.second <= t_end) {
        y_hi = stepper.current_state();
      } else {
        stepper.calc_state(t_hi, y_hi);
      }
      if (field.last->t == t_hi && field.last->y == y_hi) {
        dy_hi = field.last->dydt;  // the first-same-as-last stage of the accepted step
      } else {
        field(y_hi, dy_hi, t_hi);
      }
      return {span.first, t_hi, span.second >= t_end};
    }

    /// The state at t inside the last step, from the dense output.
    template <class F>
    void state_at(const F& /*field*/, double t, Array<N>& out) {
      stepper.calc_state(t, out);
    }
  };

  /// Fehlberg 7(8), controlled, without dense output. After step(): y_hi, dy_hi at t_hi.
  template <int N>
  struct Fehlberg78Steps {
    using Stepper = boost::numeric::odeint::controlled_runge_kutta<
        boost::numeric::odeint::runge_kutta_fehlberg78<Array<N>>>;
    /// Rejected tries of one step before the backend gives up (the step has shrunk by far more
    /// than any double can resolve by then).
    static constexpr int kMaxTries = 200;
    Stepper stepper;
    double t = 0.0;   ///< end of the last accepted step
    double dt = 0.0;  ///< the controller's proposal for the next step
    double t_lo = 0.0;
    Array<N> y_lo{};  ///< the state and the field at the start of the last step
    Array<N> dy_lo{};
    Array<N> y_hi{};  ///< and at its end
    Array<N> dy_hi{};

// make_controlled copies a fresh fehlberg78 stepper whose stage buffers are not initialised yet
// (they are written before they are read); GCC warns about the copy.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
    explicit Fehlberg78Steps(const BackendOptions& o)
        : stepper(boost::numeric::odeint::make_controlled(
              o.atol, o.rtol, boost::numeric::odeint::runge_kutta_fehlberg78<Array<N>>())) {}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

    void start(const Array<N>& y, const Array<N>& dy, double t0, double h0) {
      t = t0;
      dt = h0;
      y_hi = y;
      dy_hi = dy;
    }

    template <class F>
    Span step(const F& field, double t_end) {
      t_lo = t;
      y_lo = y_hi;
      dy_lo = dy_hi;
      for (int tries = 0;; ++tries) {
        if (tries == kMaxTries) {
          throw core::ComputationError("odeint: fehlberg78 rejected " + std::to_string(kMaxTries) +
                                       " tries of one step at t = " + std::to_string(t_lo));
        }
        const bool clipped = dt >= t_end - t_lo;
        double h = clipped ? t_end - t_lo : dt;
        double tt = t_lo;
        if (stepper.try_step(field, y_lo, dy_lo, tt, y_hi, h) == boost::numeric::odeint::success) {
          t = clipped ? t_end : tt;
          dt = h;
          break;
        }
        dt = h;  // the controller's smaller size
      }
      field(y_hi, dy_hi, t);
      return {t_lo, t, t >= t_end};
    }

    /// The state at t inside the last step: one fehlberg78 step of size t − t_lo from its start.
    template <class F>
    void state_at(const F& field, double tt, Array<N>& out) {
      stepper.stepper().do_step(field, y_lo, dy_lo, t_lo, out, tt - t_lo);
    }
  };

  /// The event loop of one segment over accepted steps of `steps`, after the start test.
  template <int N, int G, class Steps, class Observer>
  SegmentEnd integrate(const ModeFlow<N, G>& flow, const Field<N, G>& field, Steps& steps,
                       GuardSample* lo, State<N>& x, double t_end, Observer& observe) {
    Array<N> y_in{};   // states inside a step
    Array<N> dy_in{};  // and the field there
    while (true) {
      Span span{};
      try {
        span = steps.step(field, t_end);
      } catch (const core::ComputationError&) {
        throw;
      } catch (const std::exception& e) {
        throw core::ComputationError(std::string("odeint: ") + e.what());
      }
      if (options_.max_steps > 0 && stats_.steps >= options_.max_steps) {
        throw core::BudgetExhausted(step_budget_message(kName, options_.max_steps));
      }
      ++stats_.steps;
      const Array<N>& y_hi = steps.y_hi;
      if (!std::all_of(y_hi.begin(), y_hi.end(), [](double v) { return std::isfinite(v); })) {
        throw core::ComputationError("odeint: the state is not finite at t = " +
                                     std::to_string(span.t_hi));
      }
      if (!(span.t_hi > span.t_lo)) {  // a step shrunk to nothing would repeat forever
        throw core::ComputationError("odeint: no progress at t = " + std::to_string(span.t_lo));
      }
      // The step-end test on [t_lo, t_hi], the stepper's state inside giving g and dg/dt.
      double t_event = std::numeric_limits<double>::infinity();
      int event = -1;
      const double tol = guard_search::event_tolerance(options_, span.t_hi);
      for (int k = 0; k < flow.n_guards; ++k) {
        const AffineGuard<N>& guard = flow.guard[k];
        const GuardSample hi = sample(guard, y_hi, steps.dy_hi);
        const double t_k = guard_search::first_rise(
            [&](double t) {
              steps.state_at(field, t, y_in);
              return sample(guard, y_in, dy_in).g;
            },
            [&](double t) {
              steps.state_at(field, t, y_in);
              field(y_in, dy_in, t);
              return sample(guard, y_in, dy_in).dg;
            },
            span.t_lo, span.t_hi, lo[k], hi, tol);
        if (std::isfinite(t_k) && t_k <= t_event) {
          t_event = t_k;
          event = k;
        }
        lo[k] = hi;
      }
      if (event >= 0) {
        if (t_event < span.t_hi) {
          steps.state_at(field, t_event, y_in);
        } else {
          y_in = y_hi;
        }
        std::copy(y_in.begin(), y_in.end(), x.data());
        observe(t_event, x);
        return {t_event, event};
      }
      std::copy(y_hi.begin(), y_hi.end(), x.data());
      observe(span.t_hi, x);
      if (span.at_end) {
        return {t_end, -1};
      }
    }
  }

  template <int N>
  GuardSample sample(const AffineGuard<N>& g, const Array<N>& y, const Array<N>& dy) {
    ++stats_.guard_evals;
    return guard_search::sample<N>(g, y.data(), dy.data());
  }

  /// Hairer–Nørsett–Wanner's starting step for a method of order `order` in the controller's
  /// norm.
  template <int N, int G>
  double initial_step(const Field<N, G>& field, const Array<N>& y0, const Array<N>& f0, double t0,
                      int order) const {
    auto norm = [&](auto&& component) {
      double s = 0.0;
      for (int i = 0; i < 2 * N; ++i) {
        const double c = component(i) / (options_.atol + options_.rtol * std::abs(y0[i]));
        s += c * c;
      }
      return std::sqrt(s / (2 * N));
    };
    const double d0 = norm([&](int i) { return y0[i]; });
    const double d1 = norm([&](int i) { return f0[i]; });
    const double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    Array<N> y1;
    Array<N> f1;
    for (int i = 0; i < 2 * N; ++i) {
      y1[i] = y0[i] + h0 * f0[i];
    }
    field(y1, f1, t0 + h0);
    const double d2 = norm([&](int i) { return f1[i] - f0[i]; }) / h0;
    const double d = std::max(d1, d2);
    const double h1 = d <= 1e-15 ? std::max(1e-6, h0 * 1e-3)
                                 : std::pow(0.01 / d, 1.0 / static_cast<double>(order + 1));
    return std::min(100.0 * h0, h1);
  }

  BackendOptions options_;
  OdeintStepper stepper_;
  BackendStats stats_;
};

}  // namespace slipwalk::events
