#pragma once
// v_ss by event-driven simulation (§2.2.2, §2.3): start at rest with x − y = L_min, integrate
// stroke after stroke with any backend, and average the CoM speed over each cycle (two strokes,
// the swap jumps included, eq. 2.5).
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

struct SimulationOptions {
  double target = 1e-12;              ///< stop threshold (relative), see StopRule
  long long max_strokes = 4'000'000;  ///< give up (converged = false) after this many strokes
  int min_cycles = 4;                 ///< never stop before this many cycles
  StopRule stop = StopRule::kEstimatedError;
  Estimator estimator = Estimator::kCycleAverage;
};

struct SimulationSummary {
  bool converged = false;
  std::string message;           ///< why it stopped
  double v_ss = 0.0;             ///< the last cycle average (eq. 2.5)
  double period = 0.0;           ///< mean stroke duration of the last cycle
  double c0 = 0.0;               ///< CoM velocity at the start of the last cycle's first stroke
  Regime regime = Regime::kOne;  ///< what M did in the last stroke: stayed stuck (I) or slid (II)
  double est_error = 0.0;        ///< estimated |v_ss(last cycle) − v_ss(limit)| / v_ss
  double last_difference = 0.0;  ///< |V_j − V_{j−1}| / V_j, what the thesis' criterion looks at
  double contraction = 0.0;      ///< estimated per-cycle contraction λ
  long long strokes = 0;
  events::BackendStats stats;
  std::vector<double> cycle_averages;  ///< V_0, V_1, ... (kept only if record_cycles)
};

/// Per stroke, what the simulation saw.
struct StrokeRecord {
  double duration;
  double displacement;  ///< CoM displacement including the closing swap jump
  double c_start;       ///< CoM velocity at the start
  bool large_mass_slid_back;
};

/// Integrates one stroke from (mode, x) at t = 0 until the length limit and its reset.
template <class Backend>
StrokeRecord simulate_stroke(const InstantSwapSystem& sys, Backend& backend,
                             InstantSwapSystem::Mode& mode, InstantSwapSystem::StateType& x) {
  StrokeRecord rec{0.0, 0.0, sys.com_velocity(x), false};
  const double c_before = sys.com(x);
  double t = 0.0;
  events::RunLimits limits;
  limits.max_events = 64;  // a stroke has at most 3 events; more means a Zeno loop
  bool ended = false;
  const auto summary = events::run_hybrid(sys, backend, t, mode, x, limits, [&](const auto& ev) {
    if (ev.guard_id == InstantSwapSystem::kLargeStops && ev.mode_after.slide_M < 0) {
      rec.large_mass_slid_back = true;
    }
    if (ev.guard_id == InstantSwapSystem::kLengthLimit) {
      ended = true;
      return false;
    }
    return true;
  });
  if (!ended) {
    throw core::ComputationError("stroke did not reach the length limit: " + summary.message);
  }
  rec.duration = t;
  rec.displacement = sys.com(x) - c_before;
  // Move the CoM back to the origin: translation invariance keeps the dynamics unchanged.
  const double c = sys.com(x);
  x(0) -= c;
  x(1) -= c;
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

template <class Backend>
SimulationSummary steady_state_by_simulation(const Params& p, Backend& backend,
                                             const SimulationOptions& opt = {},
                                             bool record_cycles = false) {
  const InstantSwapSystem sys(p);
  auto x = sys.rest_state();
  auto mode = sys.mode_of(x, 1);
  SimulationSummary out;
  std::vector<double> averages;  // one per cycle; a run keeps at most max_strokes/2 of them
  double total_displacement = 0.0;
  double total_time = 0.0;
  double previous_reported = std::nan("");
  try {
    for (long long cycle = 0; 2 * cycle < opt.max_strokes; ++cycle) {
      const double c_start = sys.com_velocity(x);
      const StrokeRecord a = simulate_stroke(sys, backend, mode, x);
      const StrokeRecord b = simulate_stroke(sys, backend, mode, x);
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
      out.regime = b.large_mass_slid_back ? Regime::kTwo : Regime::kOne;
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
      out.message = "no convergence within " + std::to_string(opt.max_strokes) + " strokes";
    }
  } catch (const std::exception& e) {
    out.converged = false;
    out.message = e.what();
  }
  if (record_cycles) {
    out.cycle_averages = std::move(averages);
  }
  out.stats = backend.stats();
  return out;
}

}  // namespace slipwalk::inchworm
