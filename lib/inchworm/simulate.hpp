#pragma once
// v_ss by event-driven simulation (§2.2.2, §2.3, §2.5.1): start at rest with x − y = L_min,
// integrate half cycle after half cycle (a stroke and its swap, instant or with moving Δm) with
// any backend, and average the CoM speed over each cycle (two half cycles, eq. 2.5).
//
// When to stop. The thesis stopped when two consecutive cycle averages differed by 1e-4. The
// cycle averages approach v_ss geometrically, V_j − v_ss ≈ C λ^j with λ the per-cycle
// contraction (the square of the stroke map's slope at its fixed point), which approaches 1 at
// low friction and high force; the last difference δ_j then underestimates the remaining error
// by the factor λ/(1 − λ). We estimate λ from successive differences and stop when the
// estimated remaining error |δ_j| λ/(1 − λ) is below the target.
//
// Precision. Positions and time grow without bound over a long run; each stroke is therefore
// integrated from t = 0 with the CoM moved to the origin, and per-stroke durations and
// displacements are summed separately, so no digits are lost to large coordinates.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "events/hybrid_run.hpp"
#include "inchworm/instant_swap.hpp"
#include "inchworm/mass_swap.hpp"

namespace slipwalk::inchworm {

/// When a simulation stops.
enum class StopRule {
  kEstimatedError,         ///< ours: estimated remaining error (from the contraction) ≤ target
  kConsecutiveDifference,  ///< the thesis (§2.2.2): |A_j − A_{j−1}| / |A_j| ≤ target
};

/// What is reported as v_ss.
enum class Estimator {
  kCycleAverage,  ///< the average over the last cycle (eq. 2.5)
  kRunningMean,   ///< the average over the whole run from rest ("over a long simulation", §2.2.2)
};

/// The budget that ended a solve that did not converge (none for every other end).
enum class Budget {
  kNone,     ///< converged, or stopped for another reason (a failure)
  kSteps,    ///< the backend's step budget (events::BackendOptions::max_steps) ran out
  kStrokes,  ///< no convergence within SimulationOptions::max_strokes strokes
};

struct SimulationOptions {
  double target = 1e-12;              ///< stop threshold (relative), see StopRule
  long long max_strokes = 4'000'000;  ///< give up (converged = false) after this many strokes
  int min_cycles = 4;                 ///< never stop before this many cycles
  StopRule stop = StopRule::kEstimatedError;
  Estimator estimator = Estimator::kCycleAverage;
};

struct SimulationSummary {
  bool converged = false;
  /// Which budget ended a run that did not converge: the backend's steps (BackendOptions::
  /// max_steps, core::BudgetExhausted) or SimulationOptions::max_strokes; kNone otherwise.
  Budget budget = Budget::kNone;
  std::string message;           ///< why it stopped
  double v_ss = 0.0;             ///< the last cycle average (eq. 2.5)
  double period = 0.0;           ///< mean stroke duration of the last cycle
  double c0 = 0.0;               ///< CoM velocity at the start of the last cycle's first stroke
  Regime regime = Regime::kOne;  ///< what M did in the last stroke: stayed stuck (I) or slid (II)
  bool swap_stopped = false;     ///< dm model: the m–m body stopped and stuck in a swap of the
                                 ///< last cycle (§2.5.2, "stop during swap")
  double est_error = 0.0;        ///< estimated |v_ss(last cycle) − v_ss(limit)| / v_ss
  double last_difference = 0.0;  ///< |V_j − V_{j−1}| / V_j, what the thesis' criterion looks at
  double contraction = 0.0;      ///< estimated per-cycle contraction λ
  long long strokes = 0;
  events::BackendStats stats;
  std::vector<double> cycle_averages;  ///< V_0, V_1, ... (kept only if record_cycles)
};

/// Per half cycle (a stroke and its swap), what the simulation saw.
struct HalfCycleRecord {
  double duration;
  double displacement;  ///< CoM displacement, the swap included
  double c_start;       ///< CoM velocity at the start
  unsigned flags;       ///< System::mode_flags of the modes it went through, or-ed
};

/// The inchworm systems: hybrid systems with a half-cycle event, a rest state, a CoM.
template <class S>
concept InchwormSystem = events::PiecewiseConstantAccelerationSystem<S> &&
    requires(const S& sys, const typename S::StateType& x, typename S::Mode mode) {
  { S::kHalfCycleEnd } -> std::convertible_to<int>;
  { sys.rest_state() } -> std::same_as<typename S::StateType>;
  { sys.initial_mode(x) } -> std::same_as<typename S::Mode>;
  { sys.com(x) } -> std::convertible_to<double>;
  { sys.com_velocity(x) } -> std::convertible_to<double>;
  { sys.mode_flags(mode) } -> std::convertible_to<unsigned>;
};

/// Integrates one half cycle from (mode, x) at t = 0 until its closing event and reset, then
/// moves the CoM back to the origin (translation invariance keeps the dynamics unchanged).
template <InchwormSystem System, class Backend>
HalfCycleRecord simulate_half_cycle(const System& sys, Backend& backend,
                                    typename System::Mode& mode, typename System::StateType& x) {
  HalfCycleRecord rec{0.0, 0.0, sys.com_velocity(x), sys.mode_flags(mode)};
  const double c_before = sys.com(x);
  double t = 0.0;
  events::RunLimits limits;
  limits.max_events = 64;  // a half cycle has at most 5 events; more means a Zeno loop
  bool ended = false;
  const auto summary = events::run_hybrid(sys, backend, t, mode, x, limits, [&](const auto& ev) {
    if (ev.guard_id == System::kHalfCycleEnd) {
      ended = true;  // the mode after it starts the next half cycle
      return false;
    }
    rec.flags |= sys.mode_flags(ev.mode_after);
    return true;
  });
  if (!ended && summary.status == events::RunStatus::kStepBudget) {
    throw core::BudgetExhausted("half cycle did not end: " + summary.message);
  }
  if (!ended) {
    throw core::ComputationError("half cycle did not end: " + summary.message);
  }
  rec.duration = t;
  const double c = sys.com(x);
  rec.displacement = c - c_before;
  for (int i = 0; i < System::kBodies; ++i) {
    x(i) -= c;
  }
  return rec;
}

/// Estimated |V_last − V_∞| from a sequence converging geometrically, V_j − V_∞ ≈ C λ^j.
/// Three points spaced s = j/4 cycles apart (Aitken over a window): D1 = V_{j−s} − V_{j−2s},
/// D2 = V_j − V_{j−s}, ρ = D2/D1 = λ^s, remaining error |D2| ρ/(1 − ρ). A window that grows with
/// j keeps the differences far above round-off until the sequence has truly converged; once
/// they reach the noise floor ρ leaves (0, 1) and the estimate falls back to |D1| + |D2|.
struct RemainingError {
  double error;        ///< absolute
  double contraction;  ///< per-cycle λ, NaN when the differences are noise
};

inline RemainingError remaining_error(const std::vector<double>& v) {
  const auto j = static_cast<long long>(v.size()) - 1;
  const long long s = std::max<long long>(1, j / 4);
  const double d1 = v[j - s] - v[j - 2 * s];
  const double d2 = v[j] - v[j - s];
  const double rho = d2 / d1;
  if (rho > 0.0 && rho < 1.0) {
    return {std::abs(d2) * rho / (1.0 - rho), std::pow(rho, 1.0 / static_cast<double>(s))};
  }
  return {std::abs(d1) + std::abs(d2), std::nan("")};
}

template <InchwormSystem System, class Backend>
SimulationSummary steady_state_by_simulation(const System& sys, Backend& backend,
                                             const SimulationOptions& opt = {},
                                             bool record_cycles = false) {
  auto x = sys.rest_state();
  auto mode = sys.initial_mode(x);
  SimulationSummary out;
  std::vector<double> averages;  // one per cycle; a run keeps at most max_strokes/2 of them
  double total_displacement = 0.0;
  double total_time = 0.0;
  double previous_reported = std::nan("");
  try {
    for (long long cycle = 0; 2 * cycle < opt.max_strokes; ++cycle) {
      const double c_start = sys.com_velocity(x);
      const HalfCycleRecord a = simulate_half_cycle(sys, backend, mode, x);
      const HalfCycleRecord b = simulate_half_cycle(sys, backend, mode, x);
      out.strokes += 2;
      const double avg = (a.displacement + b.displacement) / (a.duration + b.duration);
      averages.push_back(avg);
      total_displacement += a.displacement + b.displacement;
      total_time += a.duration + b.duration;
      const double reported =
          opt.estimator == Estimator::kRunningMean ? total_displacement / total_time : avg;
      out.v_ss = reported;
      out.period = 0.5 * (a.duration + b.duration);
      out.c0 = c_start;
      out.regime = (b.flags & System::kLargeMassSlidBack) != 0U ? Regime::kTwo : Regime::kOne;
      if constexpr (requires { System::kSwapStopped; }) {
        out.swap_stopped = ((a.flags | b.flags) & System::kSwapStopped) != 0U;
      }
      const auto j = static_cast<long long>(averages.size()) - 1;
      if (j >= 1) {
        out.last_difference = std::abs(reported - previous_reported) / std::abs(reported);
      }
      previous_reported = reported;
      if (j >= 2) {
        // The remaining-error estimate is always that of the cycle averages; for the running
        // mean it is a lower bound (the running mean converges only like 1/j).
        const RemainingError r = remaining_error(averages);
        out.est_error = r.error / std::abs(avg);
        out.contraction = r.contraction;
        const double criterion =
            opt.stop == StopRule::kEstimatedError ? out.est_error : out.last_difference;
        if (cycle + 1 >= opt.min_cycles && criterion <= opt.target) {
          out.converged = true;
          out.message = "converged";
          break;
        }
      }
    }
    if (!out.converged) {
      out.budget = Budget::kStrokes;
      out.message = "no convergence within " + std::to_string(opt.max_strokes) + " strokes";
    }
  } catch (const core::BudgetExhausted& e) {
    out.converged = false;
    out.budget = Budget::kSteps;
    out.message = e.what();
  } catch (const std::exception& e) {
    out.converged = false;
    out.budget = Budget::kNone;
    out.message = e.what();
  }
  if (record_cycles) {
    out.cycle_averages = std::move(averages);
  }
  out.stats = backend.stats();
  return out;
}

/// The model chosen once per run (Params::model); the per-step code never branches on it.
template <class Backend>
SimulationSummary steady_state_by_simulation(const Params& p, Backend& backend,
                                             const SimulationOptions& opt = {},
                                             bool record_cycles = false) {
  if (p.model == SwapModel::kMass) {
    return steady_state_by_simulation(MassSwapSystem(p), backend, opt, record_cycles);
  }
  return steady_state_by_simulation(InstantSwapSystem(p), backend, opt, record_cycles);
}

}  // namespace slipwalk::inchworm
