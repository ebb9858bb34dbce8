#pragma once
// Boost.Odeint (1.74) as a backend of the hybrid layer (DESIGN.md: one hybrid description, many
// integrators): the Dormand–Prince 5(4) pair with step-size control and its dense output,
// stepped one accepted step at a time. Same interface as ExactBackend.
//
// Numerical choices.
//  - Stepper: make_dense_output(atol, rtol, runge_kutta_dopri5<std::array<double, 2N>>()),
//    advanced by do_step. std::array is odeint's plainest state type (array algebra, fixed
//    size): the stepper keeps all its stages inside the object, which lives on the stack of
//    advance(), so nothing is ever allocated on the heap.
//  - First step: the starting-step heuristic of Hairer, Nørsett & Wanner (Solving ODEs I, II.4)
//    from two evaluations of the field; the controller takes over from there.
//  - Guards: after each accepted step every guard is evaluated at the step end (g, and dg/dt
//    from the field there: dopri5 evaluates it anyway as its first-same-as-last stage, and the
//    field functor keeps that last evaluation). The step-end test shared by all numeric
//    backends then finds the first rising crossing in the step: a sign change of g, or a rise
//    hidden inside the step — a maximum (dg/dt from + to −) that reaches zero, or a minimum
//    (dg/dt from − to +) below zero followed by a rise — assuming dg/dt changes sign at most
//    once per step. Crossings and extrema are located on the step's dense-output interpolant
//    (calc_state, order 4) with TOMS 748 (boost::math::tools::toms748_solve, then bisection if
//    it runs out of iterations) to BackendOptions::event_tol (default 4ε·max(1, |t|)). The event
//    state is the interpolant at the upper end of the final bracket, where the guard is ≥ 0.
//    Ties between guards go to the last one, as in ExactBackend.
//  - The start of a segment mirrors first_rising_root at τ = 0: a guard that is ≥ 0 and rising
//    fires at t0 without a step; any other guard ≥ 0 at t0 does not fire there.
//  - Steps may run past t_end; the segment then ends on the interpolant at t_end.
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

class OdeintBackend {
 public:
  /// odeint's state type for N bodies: positions then velocities, (2N).
  template <int N>
  using Array = std::array<double, static_cast<std::size_t>(2 * N)>;

  static constexpr const char* kName = "odeint";

  explicit OdeintBackend(const BackendOptions& options = {}) : options_(options) {}

  /// Advances x from t0 in the mode `flow` until its first guard rises through zero or t_end.
  /// Throws core::ComputationError when the step-size control fails or the state blows up.
  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    namespace odeint = boost::numeric::odeint;
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

    auto stepper = odeint::make_dense_output(options_.atol, options_.rtol,
                                             odeint::runge_kutta_dopri5<Array<N>>());
    stepper.initialize(y, t0, std::min(initial_step(field, y, dy, t0), t_end - t0));
    Array<N> y_hi{};
    Array<N> dy_hi{};
    Array<N> y_in{};   // interpolated states inside a step
    Array<N> dy_in{};  // and the field there
    while (true) {
      std::pair<double, double> span;
      try {
        span = stepper.do_step(field);
      } catch (const std::exception& e) {
        throw core::ComputationError(std::string("odeint: ") + e.what());
      }
      ++stats_.steps;
      const double t_lo = span.first;
      const double t_hi = std::min(span.second, t_end);
      if (span.second <= t_end) {
        y_hi = stepper.current_state();
      } else {
        stepper.calc_state(t_hi, y_hi);
      }
      if (!std::all_of(y_hi.begin(), y_hi.end(), [](double v) { return std::isfinite(v); })) {
        throw core::ComputationError("odeint: the state is not finite at t = " +
                                     std::to_string(t_hi));
      }
      if (last.t == t_hi && last.y == y_hi) {
        dy_hi = last.dydt;  // the first-same-as-last stage of the accepted step
      } else {
        field(y_hi, dy_hi, t_hi);
      }
      // The step-end test on [t_lo, t_hi], the dense output giving g and dg/dt inside.
      double t_event = std::numeric_limits<double>::infinity();
      int event = -1;
      const double tol = guard_search::event_tolerance(options_, t_hi);
      for (int k = 0; k < flow.n_guards; ++k) {
        const AffineGuard<N>& guard = flow.guard[k];
        const GuardSample hi = sample(guard, y_hi, dy_hi);
        const double t_k = guard_search::first_rise(
            [&](double t) {
              stepper.calc_state(t, y_in);
              return sample(guard, y_in, dy_in).g;
            },
            [&](double t) {
              stepper.calc_state(t, y_in);
              field(y_in, dy_in, t);
              return sample(guard, y_in, dy_in).dg;
            },
            t_lo, t_hi, lo[k], hi, tol);
        if (std::isfinite(t_k) && t_k <= t_event) {
          t_event = t_k;
          event = k;
        }
        lo[k] = hi;
      }
      if (event >= 0) {
        if (t_event < t_hi) {
          stepper.calc_state(t_event, y_hi);
        }
        std::copy(y_hi.begin(), y_hi.end(), x.data());
        observe(t_event, x);
        return {t_event, event};
      }
      std::copy(y_hi.begin(), y_hi.end(), x.data());
      observe(t_hi, x);
      if (span.second >= t_end) {
        return {t_end, -1};
      }
    }
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }

 private:
  using GuardSample = guard_search::GuardSample;

  /// The field's last evaluation (after do_step: dopri5's last stage, at the step end).
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

  template <int N>
  GuardSample sample(const AffineGuard<N>& g, const Array<N>& y, const Array<N>& dy) {
    ++stats_.guard_evals;
    return guard_search::sample<N>(g, y.data(), dy.data());
  }

  /// Hairer–Nørsett–Wanner's starting step for an order-5 method in the controller's norm.
  template <int N, int G>
  double initial_step(const Field<N, G>& field, const Array<N>& y0, const Array<N>& f0,
                      double t0) const {
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
    const double h1 = d <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d, 1.0 / 6.0);
    return std::min(100.0 * h0, h1);
  }

  BackendOptions options_;
  BackendStats stats_;
};

}  // namespace slipwalk::events
