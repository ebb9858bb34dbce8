#include "inchworm/vss.hpp"

#include <array>
#include <chrono>
#include <utility>

#include "core/error.hpp"
#include "events/cvode_backend.hpp"
#include "events/exact_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/odeint_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/mass_swap_closed_form.hpp"

namespace slipwalk::inchworm {

namespace {

constexpr std::array<std::pair<Method, const char*>, 6> kMethods{{
    {Method::kExact, "exact"},
    {Method::kRootfind, "rootfind"},
    {Method::kAnalytic, "analytic"},
    {Method::kCvode, "cvode"},
    {Method::kOdeint, "odeint"},
    {Method::kGsl, "gsl"},
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

template <class Backend>
VssResult simulate(const Params& p, Method method, const VssOptions& opt) {
  events::BackendOptions bo;
  bo.rtol = opt.rtol;
  bo.atol = opt.rtol * 1e-2;
  Backend backend(bo);
  SimulationOptions so;
  so.target = opt.rtol;
  so.stop = opt.stop;
  so.estimator = opt.estimator;
  so.max_strokes = opt.max_strokes;
  const SimulationSummary s = steady_state_by_simulation(p, backend, so);
  VssResult r;
  r.method = method;
  r.converged = s.converged;
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

const char* method_names() { return "exact|rootfind|analytic|cvode|odeint|gsl"; }

VssResult solve_vss(const Params& p, Method method, const VssOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
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
      case Method::kAnalytic:
        r = simulate<events::ExactBackend>(p, method, opt);
        break;
      // numeric backends:
      case Method::kCvode:
        r = simulate<events::CvodeBackend>(p, method, opt);
        break;
      case Method::kOdeint:
        r = simulate<events::OdeintBackend>(p, method, opt);
        break;
      case Method::kGsl:
        r = simulate<events::GslBackend>(p, method, opt);
        break;
      default:
        r.method = method;
        r.converged = false;
        r.message = std::string("method ") + method_name(method) + " is not built";
        break;
    }
  } catch (const std::exception& e) {
    r.method = method;
    r.converged = false;
    r.message = e.what();
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace slipwalk::inchworm
