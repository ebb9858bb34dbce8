#pragma once
// One hybrid description, many integrators (DESIGN.md: Principles).
//
// The systems of thesis ch. 2 are mechanical: N point bodies whose accelerations are constant
// within a mode (Coulomb friction with static friction as a mode, a constant actuator force), and
// whose guards are affine in the state (a velocity reaching zero, a length limit). A system is
// described once by
//   flow(mode)          -> the bodies' accelerations in that mode and its active guards;
//   reset(mode, id, x)  -> the mode after guard `id` fired, with x reset in place.
// The exact piecewise integrator solves each mode in closed form (positions are quadratics in t);
// the numeric backends integrate the same flow as an ODE [p; v]' = [v; a] and locate the same
// guards numerically, so results and costs compare like for like.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <concepts>
#include <string>

namespace slipwalk::events {

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;

/// The continuous state of N bodies: positions then velocities, (2N).
template <int N>
using State = Eigen::Matrix<double, 2 * N, 1>;

/// g(p, v) = wp·p + wv·v + w0. The guard fires when g rises through zero (from g < 0).
template <int N>
struct AffineGuard {
  Vec<N> wp = Vec<N>::Zero();  ///< (N) weights on the positions
  Vec<N> wv = Vec<N>::Zero();  ///< (N) weights on the velocities
  double w0 = 0.0;             ///< constant term
  int id = 0;                  ///< the system's name for this guard, passed back to reset()
};

/// What a mode does: constant accelerations and the guards that can end it.
template <int N, int G>
struct ModeFlow {
  Vec<N> accel = Vec<N>::Zero();        ///< (N) accelerations of the bodies in this mode
  std::array<AffineGuard<N>, G> guard;  ///< (G) active guards, the first `n_guards` of them
  int n_guards = 0;
};

template <int N>
[[nodiscard]] inline double guard_value(const AffineGuard<N>& g, const State<N>& x) {
  return g.wp.dot(x.template head<N>()) + g.wv.dot(x.template tail<N>()) + g.w0;
}

/// A hybrid system with constant accelerations per mode and affine guards.
template <class S>
concept PiecewiseConstantAccelerationSystem = requires(const S& sys, typename S::Mode mode,
                                                       State<S::kBodies>& x, int guard_id) {
  requires S::kBodies >
  0;
  requires S::kMaxGuards >
  0;
  { sys.flow(mode) } -> std::same_as<ModeFlow<S::kBodies, S::kMaxGuards>>;
  { sys.reset(mode, guard_id, x) } -> std::same_as<typename S::Mode>;
};

/// Tolerances shared by the numeric backends. The exact backend ignores them.
struct BackendOptions {
  double rtol = 1e-10;     ///< relative tolerance of the ODE steps
  double atol = 1e-12;     ///< absolute tolerance of the ODE steps
  double event_tol = 0.0;  ///< s, time tolerance of guard location; 0 = 4ε·max(1, |t|)
  double step = 0.0;       ///< s, the step of FixedStepBackend (> 0 there; others ignore it)
  /// Every backend: fail (core::BudgetExhausted, "step budget ... used up") once it has taken
  /// this many accepted steps in all (the exact backend counts segments); 0 = no limit. A
  /// counter compare per step: what keeps a run whose step count the input sets (a tiny fixed
  /// step, a guard a fixed step misses) from running without end.
  long long max_steps = 0;
};

/// The message of a used-up step budget (FixedStepBackend has its own, with its step size).
[[nodiscard]] inline std::string step_budget_message(const char* backend, long long max_steps) {
  return std::string(backend) + ": step budget of " + std::to_string(max_steps) + " steps used up";
}

/// True when all of x is finite. A sum is NaN or ±inf iff some term is (or the terms are near
/// overflow, which is a blow-up too): one reduction and one compare per accepted step.
template <class Vector>
[[nodiscard]] inline bool all_finite(const Vector& x) {
  return std::isfinite(x.sum());
}

/// Work counters of one backend; summed over all segments it integrated.
struct BackendStats {
  long long segments = 0;     ///< mode segments integrated (one per event)
  long long steps = 0;        ///< accepted ODE steps
  long long rhs_evals = 0;    ///< right-hand-side evaluations (including root location)
  long long guard_evals = 0;  ///< guard evaluations during root location
};

/// Where a segment ended: at guard `guard` (an index into ModeFlow::guard), or at t_end (-1).
struct SegmentEnd {
  double t = 0.0;
  int guard = -1;
};

/// An observer of accepted steps that does nothing; the default of every backend.
struct NoStepObserver {
  template <class StateVector>
  void operator()(double /*t*/, const StateVector& /*x*/) const {}
};

}  // namespace slipwalk::events
