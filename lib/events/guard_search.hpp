#pragma once
// Guard location shared by the numeric backends (CVODE, odeint, GSL): after every accepted step,
// find the first time inside the step at which a guard rises through zero, from the guard's
// value and rate at the step ends and evaluators inside the step (each backend's own
// interpolant or re-integration). Written by hand because no library offers a "first rising
// crossing within a step" test; the root polishing itself is Boost's TOMS 748.
#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>

#include "events/hybrid_system.hpp"

namespace slipwalk::events::guard_search {

/// A guard's value and rate of change at one time.
struct GuardSample {
  double g = -1.0;
  double dg = 0.0;
};

/// g and dg/dt of an affine guard from a state y = [p; v] and its time derivative dy, (2N) each.
template <int N>
[[nodiscard]] GuardSample sample(const AffineGuard<N>& g, const double* y, const double* dy) {
  GuardSample s{g.w0, 0.0};
  for (int i = 0; i < N; ++i) {
    s.g += g.wp(i) * y[i] + g.wv(i) * y[N + i];
    s.dg += g.wp(i) * dy[i] + g.wv(i) * dy[N + i];
  }
  return s;
}

/// The segment start, as first_rising_root at τ = 0: samples every active guard into lo[k] and
/// returns the last one that is on or above zero and rising (it fires at once), or −1. A guard
/// that is ≥ 0 and not rising does not fire at the start.
template <int N, int G>
[[nodiscard]] int fires_at_start(const ModeFlow<N, G>& flow, const double* y, const double* dy,
                                 GuardSample* lo) {
  int fired = -1;
  for (int k = 0; k < flow.n_guards; ++k) {
    lo[k] = sample<N>(flow.guard[k], y, dy);
    if (lo[k].g >= 0.0 && lo[k].dg > 0.0) {
      fired = k;
    }
  }
  return fired;
}

/// The time tolerance of guard location: BackendOptions::event_tol, or 4ε·max(1, |t|).
[[nodiscard]] inline double event_tolerance(const BackendOptions& options, double t) {
  return options.event_tol > 0.0 ? options.event_tol
                                 : 4.0 * DBL_EPSILON * std::max(1.0, std::abs(t));
}

/// Shrinks [a, b] with f(a) < 0 ≤ f(b) to width ≤ tol (TOMS 748, then bisection if it runs
/// out of iterations); returns the upper end, where f ≥ 0.
template <class F>
double shrink(F&& f, double a, double b, double fa, double fb, double tol) {
  std::uintmax_t iterations = 100;
  auto [lo, hi] = boost::math::tools::toms748_solve(
      f, a, b, fa, fb, [tol](double u, double v) { return std::abs(v - u) <= tol; }, iterations);
  while (hi - lo > tol) {
    const double mid = lo + 0.5 * (hi - lo);
    if (mid <= lo || mid >= hi) {
      break;
    }
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return hi;
}

/// The step-end test: the first time in (t_lo, t_hi] at which a guard rises through zero, or
/// +inf, from g and dg/dt at the step ends (lo, hi) and evaluators g_at, dg_at inside the
/// step. Besides a plain sign change it finds a rise hidden inside the step: a maximum
/// (dg/dt from + to −) that reaches zero, or a minimum (dg/dt from − to +) below zero
/// followed by a rise; dg/dt is assumed to change sign at most once per step.
template <class GAt, class DgAt>
double first_rise(GAt&& g_at, DgAt&& dg_at, double t_lo, double t_hi, GuardSample lo,
                  GuardSample hi, double tol) {
  if (lo.g < 0.0 && hi.g >= 0.0) {
    return shrink(g_at, t_lo, t_hi, lo.g, hi.g, tol);
  }
  if (lo.g < 0.0 && hi.g < 0.0 && lo.dg > 0.0 && hi.dg < 0.0) {
    const double t_max =
        shrink([&](double t) { return -dg_at(t); }, t_lo, t_hi, -lo.dg, -hi.dg, tol);
    const double g_max = g_at(t_max);
    if (g_max >= 0.0) {
      return shrink(g_at, t_lo, t_max, lo.g, g_max, tol);
    }
  } else if (lo.g >= 0.0 && hi.g >= 0.0 && lo.dg < 0.0 && hi.dg > 0.0) {
    const double t_min = shrink(dg_at, t_lo, t_hi, lo.dg, hi.dg, tol);
    const double g_min = g_at(t_min);
    if (g_min < 0.0) {
      return shrink(g_at, t_min, t_hi, g_min, hi.g, tol);
    }
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace slipwalk::events::guard_search
