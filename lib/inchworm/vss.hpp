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
  kExact,        ///< the algebraic closed form of the fixed point (closed_form.hpp)
  kRootfind,     ///< the fixed point of the stroke map by GSL's Brent solver
  kAnalytic,     ///< exact event-driven integration (events::ExactBackend)
  kCvode,        ///< SUNDIALS CVODE, Adams (fixed-point corrector), with rootfinding
  kOdeint,       ///< Boost.Odeint dense-output Dormand–Prince 5(4) with guard location
  kGsl,          ///< GSL odeiv2 Prince–Dormand 8(9) (rk8pd) with guard location
  kCvodeBdf,     ///< SUNDIALS CVODE, BDF (Newton, dense direct solver), with rootfinding
  kOdeintRkf78,  ///< Boost.Odeint controlled Fehlberg 7(8), guards by re-integration
  kGslRkf45,     ///< GSL odeiv2 Runge–Kutta–Fehlberg 4(5) with guard location
  kGslMsadams,   ///< GSL odeiv2 variable-order Adams (msadams), guards on a Hermite interpolant
  kFixedRk4,     ///< classical RK4 with a fixed step and NO event location (a plain script)
};

[[nodiscard]] std::optional<Method> parse_method(std::string_view name);
[[nodiscard]] const char* method_name(Method m);
/// "exact|rootfind|analytic|cvode|odeint|gsl|cvode_bdf|...", for help texts and error messages.
[[nodiscard]] const char* method_names();
[[nodiscard]] inline bool is_simulation(Method m) {
  return m != Method::kExact && m != Method::kRootfind;
}

struct VssOptions {
  /// Integrators: the relative step tolerance (absolute: rtol × 1 cm) and, unless `target` is
  /// set, the convergence target of the simulation. Closed forms ignore it. fixed_rk4 has no
  /// tolerance: its step is `step`, or rtol read as seconds when `step` is 0 (so --rtol sets it).
  double rtol = 1e-10;
  double target = 0.0;  ///< convergence target of the simulation (see StopRule); 0 = rtol
  StopRule stop = StopRule::kEstimatedError;
  Estimator estimator = Estimator::kCycleAverage;
  long long max_strokes = 4'000'000;
  double event_tol = 0.0;  ///< s, guard location tolerance; 0 = 4ε·max(1, |t|)
  double step = 0.0;       ///< s, fixed_rk4's step; 0 = rtol s
  /// Integrators: fail (not converged, "step budget ... used up") after this many accepted
  /// steps in all; 0 = kDefaultMaxSteps (params.hpp, where the choice is argued).
  long long max_steps = 0;
  /// Integration error only: the events at the exact times (events::ExactEventTimes; a study
  /// of error sources, not a method).
  bool exact_event_times = false;
};

/// The backend settings of a solve: rtol, atol = rtol × 1 cm, event_tol, step, max_steps.
[[nodiscard]] events::BackendOptions backend_options(const VssOptions& opt);

struct VssResult {
  Method method = Method::kExact;
  bool converged = true;
  Budget budget = Budget::kNone;  ///< not converged: the budget that ended it, if one did
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
  double cpu_s = 0.0;   ///< CPU time of this solve (the calling thread's)
};

/// Solves for v_ss. Parameters must be valid (see validate()); numerical trouble is reported in
/// the result (converged = false, message), never thrown. A result whose v_ss, period, c0,
/// est_error or contraction is not finite is never converged (a simulation's contraction may be
/// NaN: not estimable once its differences reach the noise floor).
[[nodiscard]] VssResult solve_vss(const Params& p, Method method, const VssOptions& opt = {});

/// The steady stroke period (s) by the closed form (instant swap: §2.4; dm: half the cycle of
/// the cycle map's fixed point, §2.5), or NaN where it has none: the time scale for estimating
/// a run's steps and a trace's rows before starting.
[[nodiscard]] double steady_period(const Params& p);

/// fixed_rk4 only: throws core::InputError naming `option` (the option that set the step) when
/// `strokes` steady strokes at the step backend_options(opt).step would take more steps than
/// the budget (VssOptions::max_steps): a run refused up front instead of failing after seconds.
void check_fixed_step_budget(const Params& p, Method method, const VssOptions& opt, double strokes,
                             const char* option);

}  // namespace slipwalk::inchworm
