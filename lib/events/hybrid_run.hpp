#pragma once
// The event loop shared by every backend: integrate the current mode until a guard fires, apply
// the system's reset, tell the observer, repeat. The backend only integrates one mode at a time,
// so all backends see exactly the same modes, guards and resets.
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

/// Why a run stopped.
enum class RunStatus {
  kObserverStopped,  ///< the event observer asked to stop (the normal end)
  kTimeLimit,        ///< t reached t_end
  kEventLimit,       ///< too many events: a Zeno sequence or a run far longer than planned
  kBackendFailure,   ///< the backend could not integrate (message in RunSummary::message)
  kStepBudget,       ///< the backend's step budget ran out (core::BudgetExhausted; message)
};

struct RunLimits {
  double t_end = 1e9;                 ///< stop at this time
  long long max_events = 10'000'000;  ///< stop after this many events
};

struct RunSummary {
  RunStatus status = RunStatus::kObserverStopped;
  long long events = 0;
  std::string message;
};

/// What the event observer sees: the guard that fired (the system's id), the time, and the mode
/// and state just before and just after the reset.
template <class System>
struct Event {
  double t;
  int guard_id;
  typename System::Mode mode_before;
  State<System::kBodies> x_before;
  typename System::Mode mode_after;
  State<System::kBodies> x_after;
};

/// Runs `system` from (t, mode, x) with `backend` until `on_event` returns false or a limit is
/// hit. `on_event(const Event<System>&) -> bool` is called after each reset; `observe_step(t, x)`
/// after each accepted backend step (for traces). t, mode and x hold the final values.
template <PiecewiseConstantAccelerationSystem System, class Backend, class EventObserver,
          class StepObserver = NoStepObserver>
RunSummary run_hybrid(const System& system, Backend& backend, double& t,
                      typename System::Mode& mode, State<System::kBodies>& x,
                      const RunLimits& limits, EventObserver&& on_event,
                      StepObserver&& observe_step = {}) {
  RunSummary summary;
  while (true) {
    if (summary.events >= limits.max_events) {
      summary.status = RunStatus::kEventLimit;
      summary.message = "event limit of " + std::to_string(limits.max_events) + " reached";
      return summary;
    }
    const auto flow = system.flow(mode);
    SegmentEnd end;
    try {
      end = backend.advance(flow, t, x, limits.t_end, observe_step);
    } catch (const core::BudgetExhausted& e) {
      summary.status = RunStatus::kStepBudget;
      summary.message = e.what();
      return summary;
    } catch (const std::exception& e) {
      summary.status = RunStatus::kBackendFailure;
      summary.message = e.what();
      return summary;
    }
    t = end.t;
    // A state that blew up (every guard NaN) would otherwise integrate on to t_end.
    if (!std::isfinite(t) || !all_finite(x)) {
      summary.status = RunStatus::kBackendFailure;
      summary.message = "the state became non-finite at t = " + std::to_string(t);
      return summary;
    }
    if (end.guard < 0) {
      summary.status = RunStatus::kTimeLimit;
      return summary;
    }
    Event<System> event{t, flow.guard[end.guard].id, mode, x, mode, x};
    mode = system.reset(mode, event.guard_id, x);
    event.mode_after = mode;
    event.x_after = x;
    ++summary.events;
    if (!on_event(event)) {
      summary.status = RunStatus::kObserverStopped;
      return summary;
    }
  }
}

}  // namespace slipwalk::events
