#include "inchworm/trace.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "events/hybrid_run.hpp"
#include "inchworm/backends.hpp"
#include "inchworm/instant_swap.hpp"
#include "inchworm/mass_swap.hpp"

namespace slipwalk::inchworm {

namespace {

/// Bytes of one row, measured on the default trace: nine numbers at full precision (~17
/// digits), the modes and an event name.
constexpr double kBytesPerRow = 170.0;

/// The CSV and its row bound.
struct Rows {
  core::CsvWriter csv;
  long long written = 0;
  long long max_rows;
};

/// One row: both systems write the same columns; the instant model has no separate Δm, so its
/// z is y (Δm "is" in M) and its phase is always the stroke.
template <class System>
void row(Rows& rows, const System& sys, double t, const typename System::StateType& x,
         typename System::Mode mode, const char* event) {
  if (rows.written >= rows.max_rows) {
    throw core::ComputationError("the row bound of " + std::to_string(rows.max_rows) +
                                 " rows is reached (raise --max-rows or --dt)");
  }
  ++rows.written;
  core::CsvWriter& csv = rows.csv;
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

/// `samples`: the backend reports states on the dt grid itself (the exact one): every state it
/// reports is a row. Otherwise (integrators, whose accepted steps are as many as their step
/// control or fixed step makes them) a step is a row only if it is the first at or after the
/// next grid time, so a trace has at most one sample row per dt whatever the method.
template <class System, class Backend>
void run_trace(const System& sys, Backend& backend, const TraceOptions& opt, bool samples,
               std::ostream& out) {
  Rows rows{core::CsvWriter(out, {"t", "x", "y", "z", "com", "xdot", "ydot", "zdot", "comdot",
                                  "phase", "slide_x", "slide_y", "side", "event"}),
            0, opt.max_rows};
  auto x = sys.rest_state();
  auto mode = sys.initial_mode(x);
  double t = 0.0;
  double next_sample = opt.sample_dt;
  row(rows, sys, t, x, mode, "start");
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
        row(rows, sys, ev.t, ev.x_before, ev.mode_before,
            impact ? (name + "_before").c_str() : name.c_str());
        if (impact) {
          row(rows, sys, ev.t, ev.x_after, ev.mode_after, (name + "_after").c_str());
        }
        if (ev.guard_id == System::kHalfCycleEnd) {
          ++half_cycles;
        }
        return half_cycles < wanted;
      },
      [&](double ts, const typename System::StateType& xs) {
        if (samples) {
          row(rows, sys, ts, xs, mode, "");
        } else if (ts >= next_sample) {
          row(rows, sys, ts, xs, mode, "");
          next_sample = (std::floor(ts / opt.sample_dt) + 1.0) * opt.sample_dt;
        }
      });
  if (summary.status != events::RunStatus::kObserverStopped) {
    throw core::ComputationError("trace stopped early: " + summary.message);
  }
}

template <class Backend>
void run_trace(const Params& p, Backend& backend, const TraceOptions& opt, bool samples,
               std::ostream& out) {
  if (p.model == SwapModel::kMass) {
    run_trace(MassSwapSystem(p), backend, opt, samples, out);
  } else {
    run_trace(InstantSwapSystem(p), backend, opt, samples, out);
  }
}

}  // namespace

TraceSize estimate_trace_size(const Params& p, const TraceOptions& opt) {
  const double rows = 2.0 * opt.cycles * (steady_period(p) / opt.sample_dt + 8.0) + 1.0;
  return {rows, rows * kBytesPerRow};
}

void check_trace_size(const Params& p, Method method, const TraceOptions& opt) {
  const TraceSize size = estimate_trace_size(p, opt);
  if (size.rows > static_cast<double>(opt.max_rows)) {
    throw core::InputError("--dt", "--cycles " + std::to_string(opt.cycles) + " at --dt " +
                                       core::format_double(opt.sample_dt) +
                                       " s would write about " + core::format_approx(size.rows) +
                                       " rows (~" + core::format_approx(size.bytes / 1e6) +
                                       " MB; stroke period " +
                                       core::format_approx(steady_period(p)) +
                                       " s), more than --max-rows " + std::to_string(opt.max_rows) +
                                       ": raise --dt, lower --cycles or raise --max-rows");
  }
  VssOptions vo;
  vo.rtol = opt.rtol;
  vo.max_steps = opt.max_steps;
  check_fixed_step_budget(p, method, vo, 2.0 * opt.cycles, "--rtol");
}

void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out) {
  VssOptions vo;
  vo.rtol = opt.rtol;
  vo.max_steps = opt.max_steps;
  // The closed forms have no time series: they are traced by the exact event-driven method.
  const Method traced = is_simulation(method) ? method : Method::kAnalytic;
  if (!with_backend(traced, backend_options(vo), [&](auto& backend) {
        bool samples = false;
        if constexpr (requires { backend.set_sample_interval(opt.sample_dt); }) {
          backend.set_sample_interval(opt.sample_dt);
          samples = true;
        }
        run_trace(p, backend, opt, samples, out);
      })) {
    throw core::ComputationError(std::string("trace: unknown method ") + method_name(method));
  }
}

}  // namespace slipwalk::inchworm
