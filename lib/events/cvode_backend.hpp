#pragma once
// SUNDIALS CVODE (6.4) as a backend of the hybrid layer (DESIGN.md: one hybrid description, many
// integrators). It integrates a mode's flow as the ODE [p; v]' = [v; a] with CVODE's own
// rootfinding on the mode's guards and has exactly the interface of ExactBackend.
//
// Numerical choices.
//  - Method (CvodeMethod, chosen at construction):
//    kAdams (the default): Adams–Moulton (CV_ADAMS, orders 1–12) with CVODE's fixed-point
//    (functional) corrector. The mechanical flows of this layer are not stiff (friction is a
//    mode, not a stiff force); high-order Adams takes the longest steps per field evaluation on
//    a smooth non-stiff field, and with a fixed-point corrector no linear solver is attached.
//    kBdf: BDF (CV_BDF, orders 1–5) with CVODE's default Newton corrector, a dense direct linear
//    solver (SUNDenseMatrix + SUNLinSol_Dense, CVodeSetLinearSolver) and the analytic Jacobian
//    of [p; v]' = [v; a] (constant: ∂ṗ/∂v = I, zero elsewhere; CVodeSetJacFn), so no field
//    evaluations go into difference quotients. It buys stability these flows do not need and
//    pays a dense LU per Jacobian update; it is here to be measured (the cost-of-accuracy
//    study), and for flows that one day are stiff.
//  - Restarts: CVodeReInit at every segment start (a mode change is a discontinuity of the
//    field; the multistep history must not cross it), CVodeSetStopTime(t_end), and one CVode
//    call per accepted step (CV_ONE_STEP) so that the observer sees every step.
//  - Guards: CVodeRootInit with one root function per guard slot of ModeFlow (slots past
//    n_guards read a constant −1) and CVodeSetRootDirection(+1), so CVODE stops a step at the
//    first rising crossing it brackets (Illinois method on its interpolant, to
//    ~100·u·(|t| + |h|)). After every return the backend applies the step-end test shared by
//    all numeric backends on CVODE's interpolant (CVodeGetDky: the state, and its derivative
//    for dg/dt): it shrinks the crossing's bracket with TOMS 748 to BackendOptions::event_tol
//    (default 4ε·max(1, |t|)), and it also catches what no sign test sees — a guard that rises
//    through zero and falls back within one step, or one that starts ≥ 0, dips below zero and
//    rises again within one step — from the sign of dg/dt at the step ends (dg/dt is assumed
//    to change sign at most once per step). The event state is the interpolant at the upper end
//    of the final bracket, where the guard is ≥ 0. Ties between guards go to the last one, as in
//    ExactBackend.
//  - The start of a segment mirrors first_rising_root at τ = 0: a guard that is ≥ 0 and rising
//    (dg/dt > 0, from one evaluation of the field) fires at t0 without a step; any other guard
//    ≥ 0 at t0 does not fire there. (CVODE ignores a root function that is exactly 0 at t0; a
//    root function it leaves disarmed across segments is covered by the step-end test.)
//
// Memory. One SUNContext per backend, created in the constructor. The CVODE memory, its vectors
// and its fixed-point solver (Adams) or dense matrix and linear solver (BDF) are created on the
// first advance() for a state of dimension 2N with G guard slots and reused by every later
// segment of that shape (CVodeReInit allocates nothing); a call with another N or G rebuilds
// them once. Nothing is allocated per step or per
// segment. SUNDIALS types stay out of this header: the C callbacks reach the templated field
// and guards through the function pointers below.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "events/guard_search.hpp"
#include "events/hybrid_system.hpp"

namespace slipwalk::events {

/// CVODE's linear multistep family and its corrector (see the top of this file).
enum class CvodeMethod {
  kAdams,  ///< Adams–Moulton, orders 1–12, fixed-point corrector (no linear solver)
  kBdf,    ///< BDF, orders 1–5, Newton corrector with a dense direct linear solver
};

class CvodeBackend {
 public:
  static constexpr const char* kName = "cvode";

  explicit CvodeBackend(const BackendOptions& options = {},
                        CvodeMethod method = CvodeMethod::kAdams);
  ~CvodeBackend();
  CvodeBackend(const CvodeBackend&) = delete;
  CvodeBackend& operator=(const CvodeBackend&) = delete;
  CvodeBackend(CvodeBackend&&) = delete;
  CvodeBackend& operator=(CvodeBackend&&) = delete;

  /// Advances x from t0 in the mode `flow` until its first guard rises through zero or t_end.
  /// Throws core::ComputationError when CVODE fails.
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
    guards_ = &flow_guards<N, G>;
    start_segment(2 * N, G, t0, x.data(), t_end);
    double t_lo = t0;
    long long taken = 0;  // this segment's steps (stats_.steps is updated at its end)
    while (true) {
      double t_hi = t_lo;
      const bool at_end = step(t_end, t_hi);
      ++taken;
      if (options_.max_steps > 0 && stats_.steps + taken > options_.max_steps) {
        finish_segment();
        throw core::BudgetExhausted(step_budget_message(kName, options_.max_steps));
      }
      const State<N> y_hi = Eigen::Map<const State<N>>(returned_state());
      const State<N> dy_hi = Eigen::Map<const State<N>>(interpolate(t_hi, 1));
      // The step-end test on [t_lo, t_hi], CVODE's interpolant giving g and dg/dt inside.
      double t_event = std::numeric_limits<double>::infinity();
      int event = -1;
      const double tol = guard_search::event_tolerance(options_, t_hi);
      for (int k = 0; k < flow.n_guards; ++k) {
        const AffineGuard<N>& guard = flow.guard[k];
        const GuardSample hi = sample(guard, y_hi, dy_hi);
        const double t_k = guard_search::first_rise(
            [&](double t) { return value(guard, interpolate(t, 0)); },
            [&](double t) { return rate(guard, interpolate(t, 1)); }, t_lo, t_hi, lo[k], hi, tol);
        if (std::isfinite(t_k) && t_k <= t_event) {
          t_event = t_k;
          event = k;
        }
        lo[k] = hi;
      }
      if (event >= 0) {
        x = t_event < t_hi ? State<N>(Eigen::Map<const State<N>>(interpolate(t_event, 0))) : y_hi;
        finish_segment();
        observe(t_event, x);
        return {t_event, event};
      }
      x = y_hi;
      observe(t_hi, x);
      if (at_end) {
        finish_segment();
        return {t_end, -1};
      }
      t_lo = t_hi;
    }
  }

  [[nodiscard]] const BackendStats& stats() const { return stats_; }

 private:
  using GuardSample = guard_search::GuardSample;
  using RhsFn = void (*)(const void* flow, const double* y, double* dydt);
  using GuardFn = void (*)(const void* flow, const double* y, double* g);

  /// The mode's vector field [p; v]' = [v; a]: all a backend knows of the flow.
  template <int N, int G>
  static void flow_rhs(const void* flow, const double* y, double* dydt) {
    const auto& f = *static_cast<const ModeFlow<N, G>*>(flow);
    for (int i = 0; i < N; ++i) {
      dydt[i] = y[N + i];
      dydt[N + i] = f.accel(i);
    }
  }

  /// CVODE's root functions: all G guard slots; unused slots read −1 (never a rising crossing).
  template <int N, int G>
  static void flow_guards(const void* flow, const double* y, double* g) {
    const auto& f = *static_cast<const ModeFlow<N, G>*>(flow);
    const State<N> x = Eigen::Map<const State<N>>(y);
    for (int k = 0; k < G; ++k) {
      g[k] = k < f.n_guards ? guard_value(f.guard[k], x) : -1.0;
    }
  }

  template <int N>
  GuardSample sample(const AffineGuard<N>& g, const State<N>& y, const State<N>& dy) {
    ++stats_.guard_evals;
    return guard_search::sample<N>(g, y.data(), dy.data());
  }
  template <int N>
  double value(const AffineGuard<N>& g, const double* y) {
    ++stats_.guard_evals;
    return guard_value(g, State<N>(Eigen::Map<const State<N>>(y)));
  }
  template <int N>
  static double rate(const AffineGuard<N>& g, const double* dy) {
    const State<N> d = Eigen::Map<const State<N>>(dy);
    return g.wp.dot(d.template head<N>()) + g.wv.dot(d.template tail<N>());
  }

  // Implemented in cvode_backend.cpp.
  void ensure_memory(int n_state, int n_roots);
  void free_memory();
  void start_segment(int n_state, int n_roots, double t0, const double* x0, double t_end);
  /// One CVode call (CV_ONE_STEP): t = the step end or CVODE's root; true at t_end.
  bool step(double t_end, double& t);
  [[nodiscard]] const double* returned_state() const;
  /// The k-th derivative (0 or 1) of CVODE's interpolant at t, inside the last step.
  const double* interpolate(double t, int k);
  void finish_segment();
  [[noreturn]] void fail(const char* what, int flag);
  struct Callbacks;  // the C callbacks handed to CVODE
  friend struct Callbacks;

  BackendOptions options_;
  CvodeMethod method_;
  BackendStats stats_;

  // The mode being integrated (valid during advance()).
  const void* flow_ = nullptr;
  RhsFn rhs_ = nullptr;
  GuardFn guards_ = nullptr;

  // SUNDIALS objects (opaque here; see cvode_backend.cpp).
  void* context_ = nullptr;  ///< SUNContext, created once
  void* cvode_ = nullptr;    ///< CVODE memory for n_state_ unknowns and n_roots_ root functions
  void* y_ = nullptr;        ///< N_Vector (n_state_): the solution CVODE returns
  void* dky_ = nullptr;      ///< N_Vectors (n_state_): interpolated state and derivative
  void* dky1_ = nullptr;
  void* nls_ = nullptr;     ///< SUNNonlinearSolver: fixed-point iteration (Adams only)
  void* matrix_ = nullptr;  ///< SUNMatrix (n_state_ × n_state_), dense (BDF only)
  void* linsol_ = nullptr;  ///< SUNLinearSolver, dense direct (BDF only)
  int n_state_ = 0;
  int n_roots_ = 0;
  std::string error_;  ///< last CVODE error message (written only on failure)
};

}  // namespace slipwalk::events
