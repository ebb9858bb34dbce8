#pragma once
// GSL odeiv2 (2.7) as a backend of the hybrid layer (DESIGN.md: one hybrid description, many
// integrators): a stepper with the standard control gsl_odeiv2_control_y_new(atol, rtol),
// advanced one accepted step at a time by gsl_odeiv2_evolve_apply. Same interface as
// ExactBackend. Three steppers (GslStepper, chosen at construction), one event loop:
//  - kRk8pd (the default): Prince–Dormand 8(9), gsl_odeiv2_step_rk8pd. At the tolerances this
//    project asks for (1e-10 and below) an eighth-order pair takes far fewer field evaluations
//    per unit time than a fourth-order one.
//  - kRkf45: Runge–Kutta–Fehlberg 4(5), gsl_odeiv2_step_rkf45, the general-purpose pair.
//  - kMsadams: gsl_odeiv2_step_msadams, variable-order (1–12) Adams in Nordsieck form with
//    functional iteration. It reads its error levels from the control object through a driver
//    (gsl_odeiv2_step_set_driver; without one its apply returns GSL_EFAULT), so every stepper is
//    allocated through gsl_odeiv2_driver_alloc_y_new, which sets the driver of the step,
//    control and evolve objects; the backend still calls gsl_odeiv2_evolve_apply itself (one
//    accepted step per call), not gsl_odeiv2_driver_apply, which would integrate to t_end
//    past the guards.
//
// Numerical choices.
//  - First step: the starting-step heuristic of Hairer, Nørsett & Wanner (II.4) from two
//    evaluations of the field, for the stepper's order after its reset (rk8pd 8, rkf45 5,
//    msadams 1: it restarts at order 1). GSL leaves the first step to the caller.
//  - Guards: after each accepted step every guard is evaluated at the step end (g, and dg/dt
//    from the field there, GSL's dydt_out). The step-end test shared by all numeric backends
//    then finds the first rising crossing in the step: a sign change of g, or a rise hidden
//    inside the step — a maximum (dg/dt from + to −) that reaches zero, or a minimum (dg/dt
//    from − to +) below zero followed by a rise — assuming dg/dt changes sign at most once per
//    step. GSL's steppers have no dense output; crossings and extrema are located by a
//    bracketing solve in time (TOMS 748, then bisection if it runs out of iterations) to
//    BackendOptions::event_tol (default 4ε·max(1, |t|)) on the state inside the step, which
//    comes from
//      rk8pd, rkf45: RE-INTEGRATION of the step from its start with ONE
//        gsl_odeiv2_step_apply of size τ (a step of size τ ≤ the accepted one is at least as
//        accurate; the field at the step start is evolve's dydt_in, so a trial costs the
//        remaining stages: 12 for rk8pd, 5 for rkf45);
//      msadams: the cubic Hermite interpolant of the step's end states and fields (a multistep
//        method cannot re-take a step without its history; the interpolant costs no field
//        evaluations, is O(h⁴) in general and exact here, where a mode's motion is quadratic;
//        dg/dt comes from its derivative).
//    The event state is the one at the upper end of the final bracket, where the guard is
//    ≥ 0. Ties between guards go to the last one, as in ExactBackend.
//  - The start of a segment mirrors first_rising_root at τ = 0: a guard that is ≥ 0 and rising
//    fires at t0 without a step; any other guard ≥ 0 at t0 does not fire there. Each segment
//    resets the stepper (msadams restarts its history at order 1: a mode change is a
//    discontinuity of the field).
//  - gsl_odeiv2_evolve_apply is given t_end as its end point and lands on it exactly.
//
// Memory. The driver (step, control and evolve objects) and the scratch vectors are allocated
// on the first advance() for a state of dimension 2N and reused by every later segment of that
// dimension (a call with another N reallocates them once). Nothing is allocated per step.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "events/guard_search.hpp"
#include "events/hybrid_system.hpp"

struct gsl_odeiv2_driver_struct;

namespace slipwalk::events {

/// Which GSL odeiv2 stepper a GslBackend uses (see the top of this file).
enum class GslStepper {
  kRk8pd,    ///< gsl_odeiv2_step_rk8pd, Prince–Dormand 8(9)
  kRkf45,    ///< gsl_odeiv2_step_rkf45, Runge–Kutta–Fehlberg 4(5)
  kMsadams,  ///< gsl_odeiv2_step_msadams, variable-order Adams (1–12)
};

class GslBackend {
 public:
  static constexpr const char* kName = "gsl";

  explicit GslBackend(const BackendOptions& options = {}, GslStepper stepper = GslStepper::kRk8pd);
  ~GslBackend();
  GslBackend(const GslBackend&) = delete;
  GslBackend& operator=(const GslBackend&) = delete;
  GslBackend(GslBackend&&) = delete;
  GslBackend& operator=(GslBackend&&) = delete;

  /// Advances x from t0 in the mode `flow` until its first guard rises through zero or t_end.
  /// Throws core::ComputationError when GSL fails or the state blows up.
  template <int N, int G, class Observer = NoStepObserver>
  SegmentEnd advance(const ModeFlow<N, G>& flow, double t0, State<N>& x, double t_end,
                     Observer&& observe = {}) {
    ++stats_.segments;
    // g and dg/dt of every guard at t0; a guard on or above zero and rising fires at once.
    std::array<GuardSample, G> lo{};
    {
      State<N> dx;
      flow_rhs<N, G>(&flow, x.data(), dx.data());
      ++stats_.rhs_evals;
      stats_.guard_evals += flow.n_guards;
      if (const int fired = guard_search::fires_at_start(flow, x.data(), dx.data(), lo.data());
          fired >= 0) {
        return {t0, fired};
      }
    }
    if (!(t_end > t0)) {
      return {t0, -1};
    }
    flow_ = &flow;
    rhs_ = &flow_rhs<N, G>;
    start_segment(2 * N, x.data());
    double t = t0;
    while (true) {
      const double t_lo = t;
      step(t, t_end);  // y_ now holds the state at t (and y_start_ the one at t_lo)
      const double t_hi = t;
      // The step-end test on [t_lo, t_hi]; inside the step g and dg/dt come from re-integrating
      // from the step start.
      double t_event = std::numeric_limits<double>::infinity();
      int event = -1;
      const double tol = guard_search::event_tolerance(options_, t_hi);
      for (int k = 0; k < flow.n_guards; ++k) {
        const AffineGuard<N>& guard = flow.guard[k];
        const GuardSample hi = sample(guard, y_.data(), step_end_derivative());
        const double t_k = guard_search::first_rise(
            [&](double tt) { return sample(guard, state_at(t_lo, t_hi, tt), dy_try_.data()).g; },
            [&](double tt) {
              const double* y = state_at(t_lo, t_hi, tt);
              if (!interpolates()) {
                rhs_(flow_, y, dy_try_.data());  // (Hermite: state_at set dy_try_ already)
                ++stats_.rhs_evals;
              }
              return sample(guard, y, dy_try_.data()).dg;
            },
            t_lo, t_hi, lo[k], hi, tol);
        if (std::isfinite(t_k) && t_k <= t_event) {
          t_event = t_k;
          event = k;
        }
        lo[k] = hi;
      }
      if (event >= 0) {
        const double* y = t_event < t_hi ? state_at(t_lo, t_hi, t_event) : y_.data();
        x = Eigen::Map<const State<N>>(y);
        observe(t_event, x);
        return {t_event, event};
      }
      x = Eigen::Map<const State<N>>(y_.data());
      observe(t_hi, x);
      if (t_hi >= t_end) {
        return {t_end, -1};
      }
    }
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }

 private:
  using GuardSample = guard_search::GuardSample;
  using RhsFn = void (*)(const void* flow, const double* y, double* dydt);

  /// The mode's vector field [p; v]' = [v; a]: all a backend knows of the flow.
  template <int N, int G>
  static void flow_rhs(const void* flow, const double* y, double* dydt) {
    const auto& f = *static_cast<const ModeFlow<N, G>*>(flow);
    for (int i = 0; i < N; ++i) {
      dydt[i] = y[N + i];
      dydt[N + i] = f.accel(i);
    }
  }

  template <int N>
  GuardSample sample(const AffineGuard<N>& g, const double* y, const double* dy) {
    ++stats_.guard_evals;
    return guard_search::sample<N>(g, y, dy);
  }

  // Implemented in gsl_backend.cpp.
  void ensure_memory(int n_state);
  void free_memory();
  void start_segment(int n_state, const double* x0);
  void step(double& t, double t_end);
  /// The field at the end of the last accepted step (GSL's dydt_out).
  [[nodiscard]] const double* step_end_derivative() const;
  /// True when states inside a step come from the Hermite interpolant (msadams).
  [[nodiscard]] bool interpolates() const { return stepper_ == GslStepper::kMsadams; }
  /// The state at t in the last step [t_lo, t_hi] (into y_try_): re-integrated (rk8pd,
  /// rkf45) or interpolated (msadams, which also writes the interpolant's derivative to
  /// dy_try_).
  const double* state_at(double t_lo, double t_hi, double t);
  double initial_step();
  struct Callbacks;  // the C callback handed to GSL
  friend struct Callbacks;

  BackendOptions options_;
  GslStepper stepper_;
  BackendStats stats_;

  // The mode being integrated (valid during advance()).
  const void* flow_ = nullptr;
  RhsFn rhs_ = nullptr;

  gsl_odeiv2_driver_struct* driver_ = nullptr;  ///< owns the step, control and evolve objects
  int n_state_ = 0;
  double h_ = 0.0;                ///< GSL's proposal for the next step size
  std::vector<double> y_;         ///< (n_state_) the state GSL advances
  std::vector<double> y_start_;   ///< (n_state_) the state at the start of the last step
  std::vector<double> dy_start_;  ///< (n_state_) the field there
  std::vector<double> y_try_;     ///< (n_state_) a state inside the last step
  std::vector<double> dy_try_;    ///< (n_state_) the field there
  std::vector<double> y_err_;     ///< (n_state_) GSL's error estimate (unused)
  std::vector<double> work_;      ///< (3 n_state_) scratch of the starting-step heuristic
  void* system_ = nullptr;        ///< the gsl_odeiv2_system the driver points to (with driver_)
};

}  // namespace slipwalk::events
