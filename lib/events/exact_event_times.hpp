#pragma once
// A numeric backend with its event location switched off: the exact piecewise integrator
// decides WHEN a segment ends and WHICH guard fired (from the current, numerically integrated
// state), and the wrapped backend integrates the mode, without guards, to exactly that time.
// What remains of a numeric backend's error is its INTEGRATION error alone; the cost-of-accuracy
// study uses it to separate integration from event location. Not a method for results: it needs
// the exact solution it is measured against.
//
// The reset is applied to the numerically integrated state at the exact time, where the guard
// is zero only up to the integration error; the system's resets (velocities set, masses merged)
// do not depend on the guard being exactly zero.
#include "events/exact_backend.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

template <class Backend>
class ExactEventTimes {
 public:
  static constexpr const char* kName = Backend::kName;

  explicit ExactEventTimes(Backend& backend) : backend_(backend) {}

  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    State<N> exact = x;
    const SegmentEnd end = exact_.advance(flow, t0, exact, t_end);
    if (end.t > t0) {
      ModeFlow<N, G> unguarded = flow;
      unguarded.n_guards = 0;
      (void)backend_.advance(unguarded, t0, x, end.t, observe);
    }
    return end;
  }

  /// The wrapped backend's work (the exact integrator's is not counted).
  [[nodiscard]] const BackendStats& stats() const { return backend_.stats(); }

 private:
  Backend& backend_;
  ExactBackend exact_;
};

}  // namespace slipwalk::events
