#include "inchworm/vss.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "core/clock.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "events/exact_event_times.hpp"
#include "inchworm/backends.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/mass_swap_closed_form.hpp"

namespace slipwalk::inchworm {

namespace {

constexpr std::array<std::pair<Method, const char*>, 11> kMethods{{
    {Method::kExact, "exact"},
    {Method::kRootfind, "rootfind"},
    {Method::kAnalytic, "analytic"},
    {Method::kCvode, "cvode"},
    {Method::kOdeint, "odeint"},
    {Method::kGsl, "gsl"},
    {Method::kCvodeBdf, "cvode_bdf"},
    {Method::kOdeintRkf78, "odeint_rkf78"},
    {Method::kGslRkf45, "gsl_rkf45"},
    {Method::kGslMsadams, "gsl_msadams"},
    {Method::kFixedRk4, "fixed_rk4"},
}};

VssResult from_steady_state(Method method, const SteadyState& s) {
  VssResult r;
  r.method = method;
  r.message = "closed form";
  r.v_ss = s.v_ss;
  r.period = s.period;
  r.c0 = s.c0;
  r.regime = s.regime;
  r.contraction = s.contraction * s.contraction;  // two strokes per cycle
  return r;
}

/// v_ss by simulation with `backend` (or, for exact_event_times, with its integration alone).
template <class Backend>
VssResult simulate(const Params& p, Method method, const VssOptions& opt, Backend& backend) {
  SimulationOptions so;
  so.target = opt.target > 0.0 ? opt.target : opt.rtol;
  so.stop = opt.stop;
  so.estimator = opt.estimator;
  so.max_strokes = opt.max_strokes;
  SimulationSummary s;
  if (opt.exact_event_times) {
    events::ExactEventTimes<Backend> integration_only(backend);
    s = steady_state_by_simulation(p, integration_only, so);
  } else {
    s = steady_state_by_simulation(p, backend, so);
  }
  VssResult r;
  r.method = method;
  r.converged = s.converged;
  r.budget = s.budget;
  r.message = s.message;
  r.v_ss = s.v_ss;
  r.period = s.period;
  r.c0 = s.c0;
  r.regime = s.regime;
  r.swap_stopped = s.swap_stopped;
  r.est_error = s.est_error;
  r.last_difference = s.last_difference;
  r.contraction = s.contraction;
  r.strokes = s.strokes;
  r.stats = s.stats;
  return r;
}

/// A converged result must be made of numbers: the first non-finite one makes it not converged,
/// saying which. A simulation's contraction may be NaN (its differences reached the noise
/// floor: not estimable), never infinite.
void refuse_non_finite(Method method, VssResult& r) {
  if (!r.converged) {
    return;
  }
  const bool nan_contraction_ok = is_simulation(method) && std::isnan(r.contraction);
  const std::pair<const char*, double> values[] = {
      {"v_ss", r.v_ss},
      {"period", r.period},
      {"c0", r.c0},
      {"est_error", r.est_error},
      {"contraction", nan_contraction_ok ? 0.0 : r.contraction}};
  for (const auto& [name, value] : values) {
    if (!std::isfinite(value)) {
      r.converged = false;
      r.message = std::string(name) + " became non-finite (" + core::format_double(value) +
                  "): the parameters are beyond what double precision resolves";
      return;
    }
  }
}

}  // namespace

std::optional<Method> parse_method(std::string_view name) {
  for (const auto& [m, n] : kMethods) {
    if (name == n) {
      return m;
    }
  }
  return std::nullopt;
}

const char* method_name(Method m) {
  for (const auto& [mm, n] : kMethods) {
    if (mm == m) {
      return n;
    }
  }
  return "?";
}

const char* method_names() {
  return "exact|rootfind|analytic|cvode|odeint|gsl|cvode_bdf|odeint_rkf78|gsl_rkf45|gsl_msadams|"
         "fixed_rk4";
}

events::BackendOptions backend_options(const VssOptions& opt) {
  events::BackendOptions bo;
  bo.rtol = opt.rtol;
  bo.atol = opt.rtol * 1e-2;  // 1 cm: the scale of the inchworm's lengths
  bo.event_tol = opt.event_tol;
  bo.step = opt.step > 0.0 ? opt.step : opt.rtol;
  bo.max_steps = opt.max_steps > 0 ? opt.max_steps : kDefaultMaxSteps;
  return bo;
}

double steady_period(const Params& p) {
  try {
    const double period = p.model == SwapModel::kMass ? dm_steady_state(p).period
                                                      : steady_state_closed_form(p).period;
    return std::isfinite(period) && period > 0.0 ? period : std::nan("");
  } catch (const std::exception&) {
    return std::nan("");
  }
}

void check_fixed_step_budget(const Params& p, Method method, const VssOptions& opt, double strokes,
                             const char* option) {
  if (method != Method::kFixedRk4) {
    return;
  }
  const events::BackendOptions bo = backend_options(opt);
  const double period = steady_period(p);
  const double steps = strokes * period / bo.step;
  if (std::isfinite(period) && steps > static_cast<double>(bo.max_steps)) {
    throw core::InputError(
        option, "fixed_rk4's step h = " + core::format_double(bo.step) + " s takes about " +
                    core::format_approx(period / bo.step) + " steps per stroke (period " +
                    core::format_approx(period) + " s), about " + core::format_approx(steps) +
                    " for " + core::format_approx(strokes) +
                    " strokes: more than the step budget of " + std::to_string(bo.max_steps) +
                    " (raise the step or --max-steps)");
  }
}

VssResult solve_vss(const Params& p, Method method, const VssOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = core::thread_cpu_seconds();
  VssResult r;
  try {
    switch (method) {
      case Method::kExact:
      case Method::kRootfind:
        if (p.model == SwapModel::kMass) {
          // The dm model has no algebraic form of its fixed point: both methods return the GSL
          // Brent fixed point of the hand-derived cycle map (mass_swap_closed_form.hpp).
          const DmSteadyState s = dm_steady_state(p);
          r.method = method;
          r.message = "closed form (fixed point of the cycle map)";
          r.v_ss = s.v_ss;
          r.period = s.period;
          r.c0 = s.c0;
          r.regime = s.regime;
          r.swap_stopped = s.swap_stopped;
          r.contraction = s.contraction;  // per cycle: the cycle map's slope
          break;
        }
        r = from_steady_state(method, method == Method::kExact ? steady_state_closed_form(p)
                                                               : steady_state_fixed_point(p));
        break;
      default:
        // The simulation methods: the backend of each is chosen in backends.hpp.
        (void)with_backend(method, backend_options(opt),
                           [&](auto& backend) { r = simulate(p, method, opt, backend); });
        break;
    }
  } catch (const core::BudgetExhausted& e) {
    r.method = method;
    r.converged = false;
    r.budget = Budget::kSteps;
    r.message = e.what();
  } catch (const std::exception& e) {
    r.method = method;
    r.converged = false;
    r.budget = Budget::kNone;
    r.message = e.what();
  }
  refuse_non_finite(method, r);
  r.wall_s = core::seconds_since(start);
  r.cpu_s = core::thread_cpu_seconds() - cpu_start;
  return r;
}

}  // namespace slipwalk::inchworm
