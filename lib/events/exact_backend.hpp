#pragma once
// The exact piecewise integrator: within a mode the accelerations are constant, so positions are
// quadratics in t and each affine guard is a quadratic g(τ) = c0 + c1 τ + c2 τ²; the segment ends
// at the smallest τ ≥ 0 where g rises through zero. No step size, no tolerance.
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

/// First τ ≥ 0 at which c0 + c1 τ + c2 τ² rises through zero, or +inf if it never does.
/// Roots come from the cancellation-free quadratic formula. At τ = 0 a guard fires only if it is
/// on or above zero and rising (c0 ≥ 0, c1 > 0): a guard just reset to zero and falling does not
/// re-fire, and an inconsistent start above a rising guard fires at once instead of being missed.
double first_rising_root(double c0, double c1, double c2);

template <int N>
[[nodiscard]] inline State<N> constant_acceleration_state(const State<N>& x, const Vec<N>& a,
                                                          double tau) {
  State<N> out;
  out.template head<N>() =
      x.template head<N>() + tau * x.template tail<N>() + (0.5 * tau * tau) * a;
  out.template tail<N>() = x.template tail<N>() + tau * a;
  return out;
}

class ExactBackend {
 public:
  static constexpr const char* kName = "analytic";
  /// Only BackendOptions::max_steps applies (a budget of segments).
  explicit ExactBackend(const BackendOptions& options = {}) : max_steps_(options.max_steps) {}

  /// Advances x from t0 in the mode `flow` until its first guard fires or t_end.
  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    if (max_steps_ > 0 && stats_.steps >= max_steps_) {
      throw core::BudgetExhausted(step_budget_message(kName, max_steps_));
    }
    ++stats_.segments;
    double tau_min = t_end - t0;
    int fired = -1;
    for (int k = 0; k < flow.n_guards; ++k) {
      const AffineGuard<N>& g = flow.guard[k];
      const double c0 = guard_value(g, x);
      const double c1 = g.wp.dot(x.template tail<N>()) + g.wv.dot(flow.accel);
      const double c2 = 0.5 * g.wp.dot(flow.accel);
      ++stats_.guard_evals;
      const double tau = first_rising_root(c0, c1, c2);
      if (tau <= tau_min) {
        tau_min = tau;
        fired = k;
      }
    }
    // Dense output for traces: the exact solution at every multiple of the sample interval.
    if (sample_interval_ > 0.0) {
      // Integer sample indices: no drift from repeated addition.
      const auto first = static_cast<long long>(std::ceil(t0 / sample_interval_));
      for (long long k = first;; ++k) {
        const double ts = static_cast<double>(k) * sample_interval_;
        if (ts >= t0 + tau_min) {
          break;
        }
        if (ts > t0) {
          observe(ts, constant_acceleration_state<N>(x, flow.accel, ts - t0));
        }
      }
    }
    x = constant_acceleration_state<N>(x, flow.accel, tau_min);
    ++stats_.steps;
    observe(t0 + tau_min, x);
    return {t0 + tau_min, fired};
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }
  /// Makes advance() also report the exact state at every multiple of `dt` (0 = off).
  void set_sample_interval(double dt) { sample_interval_ = dt; }

 private:
  BackendStats stats_;
  long long max_steps_ = 0;
  double sample_interval_ = 0.0;
};

}  // namespace slipwalk::events
