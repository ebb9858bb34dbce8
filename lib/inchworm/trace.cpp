#include "inchworm/trace.hpp"

#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "events/hybrid_run.hpp"
#include "inchworm/backends.hpp"
#include "inchworm/instant_swap.hpp"
#include "inchworm/mass_swap.hpp"

namespace slipwalk::inchworm {

namespace {

/// One row: both systems write the same columns; the instant model has no separate Δm, so its
/// z is y (Δm "is" in M) and its phase is always the stroke.
template <class System>
void row(core::CsvWriter& csv, const System& sys, double t, const typename System::StateType& x,
         typename System::Mode mode, const char* event) {
  constexpr int n = System::kBodies;
  const double z = n == 3 ? x(2) : x(1);
  csv.cell(t).cell(x(0)).cell(x(1)).cell(z).cell(sys.com(x));
  csv.cell(x(n)).cell(x(n + 1)).cell(n == 3 ? x(n + 2) : x(n + 1)).cell(sys.com_velocity(x));
  if constexpr (requires { mode.phase; }) {
    csv.cell(int{mode.phase}).cell(int{mode.slide_x}).cell(int{mode.slide_y});
  } else {
    csv.cell(0).cell(int{mode.slide_m}).cell(int{mode.slide_M});
  }
  csv.cell(int{mode.side}).cell(event);
  csv.end_row();
}

const char* event_name(int guard_id) {
  // The two systems share the ids 0–2 (kSmallStops, kLargeStops, kLengthLimit).
  switch (guard_id) {
    case InstantSwapSystem::kSmallStops:
      return "m_stops";
    case InstantSwapSystem::kLargeStops:
      return "M_stops";
    case InstantSwapSystem::kLengthLimit:
      return "collision";
    case MassSwapSystem::kBodyStops:
      return "body_stops";
    default:
      return "arrival";
  }
}

template <class System, class Backend>
void run_trace(const System& sys, Backend& backend, const TraceOptions& opt, std::ostream& out) {
  core::CsvWriter csv(out, {"t", "x", "y", "z", "com", "xdot", "ydot", "zdot", "comdot", "phase",
                            "slide_x", "slide_y", "side", "event"});
  auto x = sys.rest_state();
  auto mode = sys.initial_mode(x);
  double t = 0.0;
  row(csv, sys, t, x, mode, "start");
  long long half_cycles = 0;
  const long long wanted = 2LL * opt.cycles;
  events::RunLimits limits;
  limits.max_events = 64 * (wanted + 1);
  const auto summary = events::run_hybrid(
      sys, backend, t, mode, x, limits,
      [&](const events::Event<System>& ev) {
        // A collision or an arrival changes velocities (and labels): a row before and after.
        const bool impact = ev.guard_id == InstantSwapSystem::kLengthLimit ||
                            ev.guard_id == MassSwapSystem::kArrival;
        const std::string name = event_name(ev.guard_id);
        row(csv, sys, ev.t, ev.x_before, ev.mode_before,
            impact ? (name + "_before").c_str() : name.c_str());
        if (impact) {
          row(csv, sys, ev.t, ev.x_after, ev.mode_after, (name + "_after").c_str());
        }
        if (ev.guard_id == System::kHalfCycleEnd) {
          ++half_cycles;
        }
        return half_cycles < wanted;
      },
      [&](double ts, const typename System::StateType& xs) { row(csv, sys, ts, xs, mode, ""); });
  if (summary.status != events::RunStatus::kObserverStopped) {
    throw core::ComputationError("trace stopped early: " + summary.message);
  }
}

template <class Backend>
void run_trace(const Params& p, Backend& backend, const TraceOptions& opt, std::ostream& out) {
  if (p.model == SwapModel::kMass) {
    run_trace(MassSwapSystem(p), backend, opt, out);
  } else {
    run_trace(InstantSwapSystem(p), backend, opt, out);
  }
}

}  // namespace

void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out) {
  VssOptions vo;
  vo.rtol = opt.rtol;
  // The closed forms have no time series: they are traced by the exact event-driven method.
  const Method traced = is_simulation(method) ? method : Method::kAnalytic;
  if (!with_backend(traced, backend_options(vo), [&](auto& backend) {
        if constexpr (requires { backend.set_sample_interval(opt.sample_dt); }) {
          backend.set_sample_interval(opt.sample_dt);
        }
        run_trace(p, backend, opt, out);
      })) {
    throw core::ComputationError(std::string("trace: unknown method ") + method_name(method));
  }
}

}  // namespace slipwalk::inchworm
