#pragma once
// v_ss by any method: the one entry point of the command line and the sweeps.
#include <optional>
#include <string>
#include <string_view>

#include "events/hybrid_system.hpp"
#include "inchworm/params.hpp"
#include "inchworm/simulate.hpp"

namespace slipwalk::inchworm {

enum class Method {
  kExact,     ///< the algebraic closed form of the fixed point (closed_form.hpp)
  kRootfind,  ///< the fixed point of the stroke map by GSL's Brent solver
  kAnalytic,  ///< exact event-driven integration (events::ExactBackend)
  kCvode,     ///< SUNDIALS CVODE with rootfinding
  kOdeint,    ///< Boost.Odeint dense-output Dormand–Prince with guard location
  kGsl,       ///< GSL odeiv2 with guard location
};

[[nodiscard]] std::optional<Method> parse_method(std::string_view name);
[[nodiscard]] const char* method_name(Method m);
/// "exact|rootfind|analytic|cvode|odeint|gsl", for help texts and error messages.
[[nodiscard]] const char* method_names();
[[nodiscard]] inline bool is_simulation(Method m) {
  return m != Method::kExact && m != Method::kRootfind;
}

struct VssOptions {
  /// Integrators: the relative step tolerance (absolute: rtol × 1 cm) and the convergence
  /// target of the simulation. Closed forms ignore it.
  double rtol = 1e-10;
  StopRule stop = StopRule::kEstimatedError;
  Estimator estimator = Estimator::kCycleAverage;
  long long max_strokes = 4'000'000;
};

struct VssResult {
  Method method = Method::kExact;
  bool converged = true;
  std::string message;
  double v_ss = 0.0;    ///< m/s
  double period = 0.0;  ///< s, one stroke
  double c0 = 0.0;      ///< m/s, CoM velocity at the start of a steady stroke
  Regime regime = Regime::kOne;
  bool swap_stopped = false;  ///< dm model: the m–m body stopped and stuck during a swap
  double est_error = 0.0;     ///< estimated remaining relative error (0 for closed forms)
  double last_difference = 0.0;
  double contraction = 0.0;  ///< per-cycle contraction λ (closed forms: exact; else estimated)
  long long strokes = 0;
  events::BackendStats stats;
  double wall_s = 0.0;  ///< wall time of this solve
};

/// Solves for v_ss. Parameters must be valid (see validate()); numerical trouble is reported in
/// the result (converged = false, message), never thrown.
[[nodiscard]] VssResult solve_vss(const Params& p, Method method, const VssOptions& opt = {});

}  // namespace slipwalk::inchworm
