#include "inchworm/trace.hpp"

#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "events/cvode_backend.hpp"
#include "events/exact_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/hybrid_run.hpp"
#include "events/odeint_backend.hpp"
#include "inchworm/instant_swap.hpp"

namespace slipwalk::inchworm {

namespace {

using Sys = InstantSwapSystem;

void row(core::CsvWriter& csv, const Sys& sys, double t, const Sys::StateType& x, Sys::Mode mode,
         const char* event) {
  csv.cell(t).cell(x(0)).cell(x(1)).cell(sys.com(x)).cell(x(2)).cell(x(3));
  csv.cell(sys.com_velocity(x)).cell(int{mode.slide_m}).cell(int{mode.slide_M});
  csv.cell(int{mode.side}).cell(event);
  csv.end_row();
}

const char* event_name(int guard_id) {
  switch (guard_id) {
    case Sys::kSmallStops:
      return "m_stops";
    case Sys::kLargeStops:
      return "M_stops";
    default:
      return "collision";
  }
}

template <class Backend>
void run_trace(const Params& p, Backend& backend, const TraceOptions& opt, std::ostream& out) {
  const Sys sys(p);
  core::CsvWriter csv(
      out, {"t", "x", "y", "com", "xdot", "ydot", "comdot", "slide_m", "slide_M", "side", "event"});
  auto x = sys.rest_state();
  auto mode = sys.mode_of(x, 1);
  double t = 0.0;
  row(csv, sys, t, x, mode, "start");
  long long strokes = 0;
  const long long wanted = 2LL * opt.cycles;
  events::RunLimits limits;
  limits.max_events = 64 * (wanted + 1);
  const auto summary = events::run_hybrid(
      sys, backend, t, mode, x, limits,
      [&](const events::Event<Sys>& ev) {
        const bool collision = ev.guard_id == Sys::kLengthLimit;
        row(csv, sys, ev.t, ev.x_before, ev.mode_before,
            collision ? "collision_before" : event_name(ev.guard_id));
        if (collision) {
          row(csv, sys, ev.t, ev.x_after, ev.mode_after, "collision_after");
          ++strokes;
        }
        return strokes < wanted;
      },
      [&](double ts, const Sys::StateType& xs) { row(csv, sys, ts, xs, mode, ""); });
  if (summary.status != events::RunStatus::kObserverStopped) {
    throw core::ComputationError("trace stopped early: " + summary.message);
  }
}

}  // namespace

void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out) {
  events::BackendOptions bo;
  bo.rtol = opt.rtol;
  bo.atol = opt.rtol * 1e-2;
  switch (method) {
    case Method::kExact:
    case Method::kRootfind:
    case Method::kAnalytic: {
      events::ExactBackend backend(bo);
      backend.set_sample_interval(opt.sample_dt);
      run_trace(p, backend, opt, out);
      return;
    }
    case Method::kCvode: {
      events::CvodeBackend backend(bo);
      run_trace(p, backend, opt, out);
      return;
    }
    case Method::kOdeint: {
      events::OdeintBackend backend(bo);
      run_trace(p, backend, opt, out);
      return;
    }
    case Method::kGsl: {
      events::GslBackend backend(bo);
      run_trace(p, backend, opt, out);
      return;
    }
  }
  throw core::ComputationError(std::string("trace: unknown method ") + method_name(method));
}

}  // namespace slipwalk::inchworm
