#pragma once
// A fixed-step integrator WITHOUT event location, as a backend of the hybrid layer: what a plain
// simulation script does (and, as far as its text tells, what the thesis did, §2.2.2). Same
// interface as ExactBackend; it exists to be measured against the backends that locate events
// (the cost-of-accuracy study), not to be used for results.
//
// Numerical choices.
//  - Method: classical Runge–Kutta 4 with the constant step h = BackendOptions::step (s),
//    started afresh at every segment (a mode change restarts the step grid at the event). RK4
//    reproduces a mode's motion exactly (it is quadratic in t, and RK4 is exact on polynomials
//    of degree ≤ 4), so every error this backend makes is an EVENT error.
//  - Guards: sampled at step ends only. A guard fires at the first step end where it is ≥ 0
//    after being < 0 at the previous one, and the reset is applied to the state THERE: no root
//    finding, so an event is late by up to h (an O(h) error in the state), and a guard that rises
//    through zero and falls back within one step is missed. Ties go to the last guard, as in
//    ExactBackend.
//  - The start of a segment mirrors first_rising_root at τ = 0 (shared with the other numeric
//    backends): a guard that is ≥ 0 and rising fires at t0 without a step; any other guard ≥ 0
//    at t0 must first fall below zero.
//  - The last step of a segment is shortened to land on t_end.
//  - A non-finite state ends the run (core::ComputationError) at the step that produced it.
//  - BackendOptions::max_steps (> 0) caps the steps over the backend's life: a run that would
//    take more throws core::BudgetExhausted (a budget, so that a study can ask for tiny steps
//    without running for hours; the stop is recorded, not hidden).
// Nothing is allocated.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "events/guard_search.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

class FixedStepBackend {
 public:
  static constexpr const char* kName = "fixed_rk4";

  /// Throws core::InputError when options.step is not a positive finite number.
  explicit FixedStepBackend(const BackendOptions& options = {}) : options_(options) {
    if (!(options.step > 0.0) || !std::isfinite(options.step)) {
      throw core::InputError("step", "the fixed step must be a positive number of seconds, got " +
                                         std::to_string(options.step));
    }
  }

  /// Advances x from t0 in the mode `flow` until a guard is found ≥ 0 at a step end, or t_end.
  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    ++stats_.segments;
    State<N> dx = field(flow, x);
    std::array<guard_search::GuardSample, G> lo{};
    stats_.guard_evals += flow.n_guards;
    if (const int fired = guard_search::fires_at_start(flow, x.data(), dx.data(), lo.data());
        fired >= 0) {
      return {t0, fired};
    }
    const double h = options_.step;
    // Integer step indices: no drift from repeated addition of h.
    for (long long k = 1;; ++k) {
      const double t_prev = t0 + static_cast<double>(k - 1) * h;
      double t = t0 + static_cast<double>(k) * h;
      const bool last = t >= t_end;
      if (last) {
        t = t_end;
      }
      if (options_.max_steps > 0 && stats_.steps >= options_.max_steps) {
        std::array<char, 32> step{};
        (void)std::snprintf(step.data(), step.size(), "%.3g", h);
        throw core::BudgetExhausted("fixed_rk4: step budget of " +
                                    std::to_string(options_.max_steps) +
                                    " steps (h = " + step.data() + " s) used up");
      }
      rk4_step(flow, x, dx, t - t_prev);
      ++stats_.steps;
      if (!all_finite(x)) {
        throw core::ComputationError("fixed_rk4: the state is not finite at t = " +
                                     std::to_string(t));
      }
      dx = field(flow, x);  // the next step's first stage
      int fired = -1;
      for (int g = 0; g < flow.n_guards; ++g) {
        const double value = guard_value(flow.guard[g], x);
        ++stats_.guard_evals;
        if (lo[g].g < 0.0 && value >= 0.0) {
          fired = g;
        }
        lo[g].g = value;
      }
      observe(t, x);
      if (fired >= 0) {
        return {t, fired};
      }
      if (last) {
        return {t_end, -1};
      }
    }
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }

 private:
  /// The mode's vector field [p; v]' = [v; a]: all a backend knows of the flow.
  template <int N, int G>
  State<N> field(const ModeFlow<N, G>& flow, const State<N>& x) {
    ++stats_.rhs_evals;
    State<N> d;
    d.template head<N>() = x.template tail<N>();
    d.template tail<N>() = flow.accel;
    return d;
  }

  /// One classical RK4 step of size h from x (whose field is k1).
  template <int N, int G>
  void rk4_step(const ModeFlow<N, G>& flow, State<N>& x, const State<N>& k1, double h) {
    const State<N> k2 = field(flow, State<N>(x + 0.5 * h * k1));
    const State<N> k3 = field(flow, State<N>(x + 0.5 * h * k2));
    const State<N> k4 = field(flow, State<N>(x + h * k3));
    x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }

  BackendOptions options_;
  BackendStats stats_;
};

}  // namespace slipwalk::events
