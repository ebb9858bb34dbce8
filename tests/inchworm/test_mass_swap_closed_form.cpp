// The hand-derived dm model (mass_swap_closed_form.hpp: stroke, swap and cycle maps, the fixed
// point of the cycle map) against the exact event-driven simulation of MassSwapSystem (the
// oracle): the steady state over the thesis range, single strokes, swaps and half cycles from
// constructed states, hard cases (strong swaps, low friction, static friction), and the numeric
// backends.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "events/cvode_backend.hpp"
#include "events/exact_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/hybrid_run.hpp"
#include "events/odeint_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/mass_swap.hpp"
#include "inchworm/mass_swap_closed_form.hpp"
#include "inchworm/simulate.hpp"
#include "inchworm/vss.hpp"
#include "support/inchworm_grid.hpp"

namespace slipwalk::inchworm {
namespace {

using testing::rel_diff;
using Sys = MassSwapSystem;

Params dm(double mu, double alpha, double force, double mu_s = std::nan("")) {
  Params p;
  p.model = SwapModel::kMass;
  p.mu = mu;
  p.mu_s = mu_s;
  p.alpha = alpha;
  p.F = force;
  return p;
}

std::string describe(const Params& p) {
  return "F=" + std::to_string(p.F) + " mu=" + std::to_string(p.mu) +
         " mu_s=" + std::to_string(p.static_mu()) + " alpha=" + std::to_string(p.alpha);
}

double total_mass(const Params& p) { return 2.0 * p.m + p.moving_mass(); }

/// The α at which the push αF equals `factor` × the body's static friction μ_s g (2m + Δm).
double alpha_at_body_friction(const Params& p, double factor) {
  return factor * p.static_mu() * p.g * total_mass(p) / p.F;
}

SimulationSummary simulate_exact(const Params& p, double target = 1e-12) {
  events::ExactBackend backend;
  SimulationOptions opt;
  opt.target = target;
  return steady_state_by_simulation(Sys(p), backend, opt);
}

/// c0 changes sign with F and may be near zero: compare it on the scale of the cycle's
/// common velocities.
double c0_error(const SimulationSummary& sim, const DmSteadyState& cf) {
  return std::abs(sim.c0 - cf.c0) / std::max(std::abs(cf.c0), std::abs(cf.c_contraction));
}

/// Closed form vs a converged simulation: v_ss, period, c0 and the classification.
void expect_agrees(const Params& p, const SimulationSummary& sim, const DmSteadyState& cf,
                   double tolerance) {
  SCOPED_TRACE(describe(p));
  ASSERT_TRUE(sim.converged) << sim.message;
  EXPECT_LT(rel_diff(sim.v_ss, cf.v_ss), tolerance);
  EXPECT_LT(rel_diff(sim.period, cf.period), tolerance);
  EXPECT_LT(c0_error(sim, cf), tolerance) << "c0=" << cf.c0;
  EXPECT_EQ(sim.regime, cf.regime);
  EXPECT_EQ(sim.swap_stopped, cf.swap_stopped);
}

void expect_agrees_with_simulation(const Params& p, double tolerance = 1e-9) {
  expect_agrees(p, simulate_exact(p), dm_steady_state(p), tolerance);
}

/// μ ∈ {0.1, 0.6, 1} × α ∈ {0.05, 1, 5, 10} × 8 forces in (μmg, 5Mg]: next to μmg, inside regime
/// I, both sides of μMg, and four up to 5Mg.
std::vector<Params> thesis_grid() {
  std::vector<Params> out;
  for (double mu : {0.1, 0.6, 1.0}) {
    for (double alpha : {0.05, 1.0, 5.0, 10.0}) {
      const Params base;
      const double lo = mu * base.m * base.g;
      const double boundary = mu * base.M * base.g;
      const double hi = 5.0 * base.M * base.g;
      for (double force : {lo * (1.0 + 1e-3), std::sqrt(lo * boundary), boundary * (1.0 - 1e-3),
                           boundary * (1.0 + 1e-3)}) {
        out.push_back(dm(mu, alpha, force));
      }
      for (int k = 1; k <= 4; ++k) {
        out.push_back(dm(mu, alpha, boundary * std::pow(hi / boundary, k / 4.0)));
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Steady state vs the exact simulation.

TEST(DmSteadyState, AgreesWithTheExactSimulationOverTheThesisRange) {
  int regimes[3] = {0, 0, 0};
  int stopped = 0;
  int held = 0;
  int negative_c0 = 0;
  for (const Params& p : thesis_grid()) {
    const SimulationSummary sim = simulate_exact(p);
    const DmSteadyState cf = dm_steady_state(p);
    expect_agrees(p, sim, cf, 1e-9);
    // The simulation's estimate of the per-cycle contraction (where it is not noise).
    if (std::isfinite(sim.contraction) && cf.contraction > 1e-3) {
      EXPECT_NEAR(sim.contraction, cf.contraction, 1e-4 + 1e-3 * cf.contraction) << describe(p);
    }
    EXPECT_GE(cf.contraction, 0.0);
    EXPECT_LT(cf.contraction, 1.0);
    ++regimes[static_cast<int>(cf.regime)];
    stopped += cf.swap_stopped ? 1 : 0;
    held += cf.held ? 1 : 0;
    negative_c0 += cf.c0 < 0.0 ? 1 : 0;
  }
  // The grid covers both stroke regimes, both swap regimes, the held mode and c0 < 0.
  EXPECT_GT(regimes[1], 10);
  EXPECT_GT(regimes[2], 10);
  EXPECT_GT(stopped, 10);
  EXPECT_GT(held, 5);
  EXPECT_GT(negative_c0, 5);
}

TEST(DmSteadyState, IsAFixedPointOfTheCycleMap) {
  for (const Params& p : thesis_grid()) {
    const DmSteadyState s = dm_steady_state(p);
    const DmCycle c = dm_cycle_map(p, s.c0);
    EXPECT_LT(std::abs(c.c_next - s.c0), 1e-14) << describe(p);
    EXPECT_DOUBLE_EQ(s.v_ss, c.displacement / c.duration);
    EXPECT_DOUBLE_EQ(s.period, 0.5 * c.duration);
    EXPECT_DOUBLE_EQ(s.c_contraction, c.extension.c_next);
    EXPECT_EQ(s.regime, stroke_regime(c.contraction.stroke));
    // Contraction: the central difference against a wider one (the map is smooth there).
    const double h = 1e-4;
    const double fd =
        (dm_cycle_map(p, s.c0 + h).c_next - dm_cycle_map(p, s.c0 - h).c_next) / (2 * h);
    EXPECT_NEAR(s.contraction, fd, 1e-6) << describe(p);
  }
}

// The negative start of the extension stroke (μ = 1, α = 1, F = 10.4 N): the contraction swap
// pushes Δm backward over L_min = 2 cm, which it covers before the body (pushed forward, braked
// by F_b > αF) has stopped; Δm arrives moving backward fast enough that the common velocity
// after the arrival is negative. The extension stroke then starts with x and y sliding back.
TEST(DmSteadyState, NegativeCommonVelocityAtTheStartOfAHalfCycle) {
  const Params p = dm(1.0, 1.0, 10.4);
  const DmSteadyState s = dm_steady_state(p);
  const DmSwap& swap = s.cycle.contraction.swap;
  EXPECT_LT(s.c0, -0.04);
  EXPECT_FALSE(swap.stopped);
  EXPECT_GT(swap.v_body, 0.0);
  EXPECT_LT(swap.v_dm, 0.0);
  EXPECT_DOUBLE_EQ(swap.c_next, s.c0);
  EXPECT_TRUE(s.cycle.extension.stroke.small_slid_back);
  EXPECT_TRUE(s.cycle.extension.stroke.large_slid_back);
  EXPECT_EQ(s.cycle.extension.stroke.phases, 3);  // x stops, y stops (and sticks), the limit
  expect_agrees_with_simulation(p);
  // The most negative start in the thesis range: F just above μmg.
  EXPECT_LT(dm_steady_state(dm(1.0, 1.0, 9.82)).c0, -0.1);
}

// Regimes. The simulation classifies the contraction stroke (second half cycle) by its motion:
// y driven back (F > μMg, accelerating backward) is two masses moving. The extension stroke can
// start with c0 < 0 and y driven back from its start, without a stop first; the hybrid system's
// mode flags count that too.
TEST(DmSteadyState, RegimeOfTheSimulationIsTheMotionOfTheContractionStroke) {
  for (const Params& p : thesis_grid()) {
    const DmSteadyState s = dm_steady_state(p);
    EXPECT_EQ(s.regime, s.regime_contraction) << describe(p);
  }
}

TEST(DmSteadyState, ExtensionStrokeFromNegativeVelocityDrivesTheLargeMassBackFromItsStart) {
  const Params p = dm(0.6, 0.05, 15.0);  // F > μMg = 8.83 N
  const DmSteadyState s = dm_steady_state(p);
  const DmStroke& ext = s.cycle.extension.stroke;
  ASSERT_LT(s.c0, 0.0);
  EXPECT_TRUE(ext.large_driven_back);
  EXPECT_FALSE(ext.large_stopped_then_slid_back);
  EXPECT_EQ(s.regime_extension, Regime::kTwo);
  // The hybrid system's own flags over that half cycle.
  const Sys sys(p);
  Sys::StateType x = sys.rest_state();
  x.tail<3>().setConstant(s.c0);
  Sys::Mode mode = sys.initial_mode(x);
  events::ExactBackend backend;
  const HalfCycleRecord rec = simulate_half_cycle(sys, backend, mode, x);
  EXPECT_NE(rec.flags & Sys::kLargeMassSlidBack, 0U);
}

TEST(DmSteadyState, SolveVssReturnsTheFixedPointForBothClosedFormMethods) {
  const Params p = dm(1.0, 1.0, 20.0);
  const DmSteadyState s = dm_steady_state(p);
  for (Method m : {Method::kExact, Method::kRootfind}) {
    const VssResult r = solve_vss(p, m);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.method, m);
    EXPECT_DOUBLE_EQ(r.v_ss, s.v_ss);
    EXPECT_DOUBLE_EQ(r.period, s.period);
    EXPECT_DOUBLE_EQ(r.c0, s.c0);
    EXPECT_EQ(r.regime, s.regime);
    EXPECT_EQ(r.swap_stopped, s.swap_stopped);
    EXPECT_DOUBLE_EQ(r.contraction, s.contraction);
  }
  const VssResult analytic = solve_vss(p, Method::kAnalytic);
  ASSERT_TRUE(analytic.converged);
  EXPECT_LT(rel_diff(analytic.v_ss, s.v_ss), 1e-9);
  EXPECT_EQ(analytic.swap_stopped, s.swap_stopped);
}

// ---------------------------------------------------------------------------------------------
// Single strokes, swaps and half cycles from constructed states.

/// Parameters with every stroke and swap case: both stroke regimes (F vs μMg), static friction
/// above dynamic, the held mode (αF < μgΔm), a stuck body, a body that breaks away (αF > F_s) and
/// one that slides on but sticks at rest (F_b < αF ≤ F_s).
std::vector<Params> case_grid() {
  std::vector<Params> out;
  for (double mu : {0.1, 1.0}) {
    const Params base;
    for (double f : {1.2, 1.6, 4.0}) {  // F / μmg: regime I, II (μMg = 1.5 μmg), II
      for (double alpha : {0.01, 0.3, 1.0, 3.0, 10.0}) {
        out.push_back(dm(mu, alpha, f * mu * base.m * base.g));
      }
    }
    // μ_s = 1.3 μ: y held between μMg and μ_s Mg; the body held at rest between F_b and F_s.
    const double mu_s = 1.3 * mu;
    Params q = dm(mu, 1.0, 1.4 * mu_s * base.m * base.g, mu_s);  // F ∈ (μMg, μ_s Mg]
    out.push_back(q);
    q.alpha = alpha_at_body_friction(q, 0.9);  // F_b < αF < F_s
    out.push_back(q);
    q.alpha = alpha_at_body_friction(q, 1.5);  // αF > F_s
    out.push_back(q);
  }
  return out;
}

const double kVelocities[] = {-2.0, -0.5, -0.05, -1e-6, 0.0, 1e-6, 0.05, 0.5, 2.0};

/// A stroke-start state of MassSwapSystem at common velocity c: made by the system's own resets
/// (the rest state for an extension; the arrival of an extension swap for a contraction).
void stroke_start(const Sys& sys, const Params& p, int side, double c, Sys::Mode& mode,
                  Sys::StateType& x) {
  x = sys.rest_state();
  if (side > 0) {
    x.tail<3>().setConstant(c);
    mode = sys.initial_mode(x);
    return;
  }
  // End of an extension swap: x front, y at x − L_max, Δm arrived at x.
  x << 0.5 * p.L_max, -0.5 * p.L_max, 0.5 * p.L_max, c, c, c;
  Sys::Mode swap;
  swap.phase = Sys::kSwap;
  swap.side = 1;
  mode = sys.reset(swap, Sys::kArrival, x);
  ASSERT_EQ(mode.side, -1);
}

/// A swap-start state at common velocity v: the length-limit collision of a stroke.
void swap_start(const Sys& sys, const Params& p, int side, double v, Sys::Mode& mode,
                Sys::StateType& x) {
  const double d = side > 0 ? p.L_max : -p.L_min;  // x − y at the limit
  x << 0.5 * d, -0.5 * d, -0.5 * d, v, v, v;
  Sys::Mode stroke;
  stroke.phase = Sys::kStroke;
  stroke.side = static_cast<std::int8_t>(side);
  mode = sys.reset(stroke, Sys::kLengthLimit, x);
  ASSERT_EQ(mode.phase, Sys::kSwap);
}

/// |a − b| ≤ 1e-12 max(|b|, scale): relative, with a floor for quantities that may vanish.
void expect_close(double a, double b, double scale, const char* what) {
  EXPECT_LE(std::abs(a - b), 1e-12 * std::max(std::abs(b), scale))
      << what << ": " << a << " vs " << b;
}

TEST(DmStrokeMap, ReducesToTheInstantSwapStrokeMapForNonNegativeVelocity) {
  for (const Params& p : testing::thesis_grid()) {
    for (double c0 : {0.0, 1e-6, 0.3, 1.0, 3.0, 10.0}) {
      SCOPED_TRACE(describe(p) + " c0=" + std::to_string(c0));
      const Stroke a = stroke_map(p, c0);
      const DmStroke b = dm_stroke_map(p, c0);
      EXPECT_LE(std::abs(b.c_next - a.c_next), 1e-14 * std::max(1.0, std::abs(a.c_next)));
      EXPECT_LE(rel_diff(b.duration, a.duration), 1e-14);
      EXPECT_LE(std::abs(b.displacement - a.displacement), 1e-14 * std::max(1.0, c0));
      // From rest (c0 = 0) y does not stop first: §2.4's phase 1 has zero length.
      EXPECT_EQ(b.phases, a.ends_before_M_stops || c0 == 0.0 ? 1 : 2);
      EXPECT_EQ(b.large_stopped_then_slid_back,
                !a.ends_before_M_stops && c0 > 0.0 && regime_of(p) == Regime::kTwo);
    }
  }
}

TEST(DmStrokeMap, MatchesTheIntegratedStrokeForEitherSignOfVelocity) {
  int slid_back_from_start = 0;
  for (const Params& p : case_grid()) {
    const Sys sys(p);
    for (int side : {1, -1}) {
      for (double c0 : kVelocities) {
        SCOPED_TRACE(describe(p) + " side=" + std::to_string(side) + " c0=" + std::to_string(c0));
        Sys::Mode mode;
        Sys::StateType x;
        stroke_start(sys, p, side, c0, mode, x);
        const double com0 = sys.com(x);
        double t = 0.0;
        Sys::StateType before = x;
        unsigned flags = sys.mode_flags(mode);
        events::ExactBackend backend;
        events::RunLimits limits;
        limits.max_events = 16;
        (void)events::run_hybrid(sys, backend, t, mode, x, limits, [&](const auto& ev) {
          before = ev.x_before;
          if (ev.guard_id == Sys::kLengthLimit) {
            return false;  // the swap mode after it belongs to the swap
          }
          flags |= sys.mode_flags(ev.mode_after);
          return true;
        });
        const DmStroke s = dm_stroke_map(p, c0);
        const double vscale = std::max(1.0, std::abs(c0));
        expect_close(s.v_x, before(3), vscale, "v_x");
        expect_close(s.v_y, before(4), vscale, "v_y");
        expect_close(s.c_next, sys.com_velocity(x), vscale, "c_next");
        expect_close(s.duration, t, 0.0, "duration");
        expect_close(s.displacement, sys.com(x) - com0, p.stroke(), "displacement");
        EXPECT_EQ(s.large_driven_back, (flags & Sys::kLargeMassSlidBack) != 0U);
        slid_back_from_start += s.large_slid_back && !s.large_stopped_then_slid_back ? 1 : 0;
      }
    }
  }
  EXPECT_GT(slid_back_from_start, 0);
}

struct SwapRun {
  HalfCycleRecord rec;
  double c_next;
  bool held;
};

SwapRun integrate_swap(const Sys& sys, const Params& p, int side, double v) {
  Sys::Mode mode;
  Sys::StateType x;
  swap_start(sys, p, side, v, mode, x);
  // Held mode: look at the modes the hybrid system goes through.
  bool held = mode.held != 0;
  {
    Sys::Mode m = mode;
    Sys::StateType y = x;
    double t = 0.0;
    events::ExactBackend backend;
    (void)events::run_hybrid(sys, backend, t, m, y, {}, [&](const auto& ev) {
      held = held || ev.mode_before.held != 0;
      return ev.guard_id != Sys::kArrival;
    });
  }
  events::ExactBackend backend;
  const HalfCycleRecord rec = simulate_half_cycle(sys, backend, mode, x);
  return {rec, sys.com_velocity(x), held};
}

TEST(DmSwapMap, MatchesTheIntegratedSwapFromEitherSignOfVelocity) {
  int held = 0;
  int stopped = 0;
  int broke_away = 0;
  int stuck_at_start = 0;
  for (const Params& p : case_grid()) {
    const Sys sys(p);
    for (int side : {1, -1}) {
      for (double v : kVelocities) {
        SCOPED_TRACE(describe(p) + " side=" + std::to_string(side) + " v=" + std::to_string(v));
        const SwapRun run = integrate_swap(sys, p, side, v);
        const DmSwap s = dm_swap_map(p, side, v);
        const double vscale = std::max(1.0, std::abs(v));
        expect_close(s.c_next, run.c_next, vscale, "c_next");
        expect_close(s.duration, run.rec.duration, 0.0, "duration");
        expect_close(s.displacement, run.rec.displacement, p.L_min, "displacement");
        EXPECT_EQ(s.stopped || s.stuck_at_start, (run.rec.flags & Sys::kSwapStopped) != 0U);
        EXPECT_EQ(s.held, run.held);
        held += s.held ? 1 : 0;
        stopped += s.stopped ? 1 : 0;
        broke_away += s.broke_away ? 1 : 0;
        stuck_at_start += s.stuck_at_start ? 1 : 0;
        // Momentum: the arrival's common velocity is the momentum of body and Δm.
        EXPECT_NEAR(s.c_next, (2.0 * p.m * s.v_body + p.moving_mass() * s.v_dm) / total_mass(p),
                    1e-15);
      }
    }
  }
  EXPECT_GT(held, 0);
  EXPECT_GT(stopped, 0);
  EXPECT_GT(broke_away, 0);
  EXPECT_GT(stuck_at_start, 0);
}

TEST(DmHalfCycle, MatchesSimulateHalfCycle) {
  for (const Params& p : case_grid()) {
    const Sys sys(p);
    for (int side : {1, -1}) {
      for (double c0 : kVelocities) {
        SCOPED_TRACE(describe(p) + " side=" + std::to_string(side) + " c0=" + std::to_string(c0));
        Sys::Mode mode;
        Sys::StateType x;
        stroke_start(sys, p, side, c0, mode, x);
        events::ExactBackend backend;
        const HalfCycleRecord rec = simulate_half_cycle(sys, backend, mode, x);
        const DmHalfCycle h = dm_half_cycle(p, side, c0);
        const double vscale = std::max(1.0, std::abs(c0));
        expect_close(h.c_next, sys.com_velocity(x), vscale, "c_next");
        expect_close(h.duration, rec.duration, 0.0, "duration");
        expect_close(h.displacement, rec.displacement, p.stroke(), "displacement");
        EXPECT_EQ(h.stroke.large_driven_back, (rec.flags & Sys::kLargeMassSlidBack) != 0U);
        EXPECT_EQ(h.swap.stopped || h.swap.stuck_at_start, (rec.flags & Sys::kSwapStopped) != 0U);
        EXPECT_EQ(mode.side, -side);  // the next stroke runs the other way
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Hard cases: strong swaps at low friction, static friction at the body, very small swap forces,
// and the speed across the boundaries between the models' modes.

TEST(DmHardCases, StrongSwapAtLowFriction) {
  // α = 10, μ = 0.1: the body is thrown backward at (αF − F_b)/2m in the extension swap and
  // forward in the contraction swap; slow convergence at high force (λ ≈ 0.95 per cycle).
  const Params base;
  for (double force : {1.05 * 0.13 * base.m * base.g, 2.0, 10.0, 40.0, 5.0 * base.M * base.g}) {
    expect_agrees_with_simulation(dm(0.1, 10.0, force));
    expect_agrees_with_simulation(dm(0.1, 10.0, force, 0.13));
  }
}

TEST(DmHardCases, PushAtTheBodyStaticFriction) {
  // αF = μ_s g (2m + Δm) (1 ± 1e-9), α chosen for each F: the body at rest just holds, or just
  // breaks away.
  const Params base;
  for (double mu : {0.1, 0.6, 1.0}) {
    for (double mu_s : {mu, 1.3 * mu}) {
      for (double f : {1.6, 4.0}) {
        for (double side : {-1.0, 1.0}) {
          Params p = dm(mu, 1.0, f * mu_s * base.m * base.g, mu_s);
          p.alpha = alpha_at_body_friction(p, 1.0 + side * 1e-9);
          SCOPED_TRACE(side < 0 ? "just holds" : "just breaks away");
          expect_agrees_with_simulation(p);
        }
      }
    }
  }
}

TEST(DmHardCases, VerySmallSwapForce) {
  // α = 0.01: P = αF ≪ μgΔm, the held mode in one swap and a slow swap from rest.
  const Params base;
  for (double mu : {0.1, 1.0}) {
    for (double f : {1.01, 1.5, 3.0, 7.5}) {
      const Params p = dm(mu, 0.01, f * mu * base.m * base.g);
      const DmSteadyState s = dm_steady_state(p);
      EXPECT_TRUE(s.held) << describe(p);
      EXPECT_TRUE(s.swap_stopped);
      // Slow swaps: both take longer than at α = 1.
      const DmSteadyState unit = dm_steady_state(dm(p.mu, 1.0, p.F));
      EXPECT_GT(s.cycle.extension.swap.duration, unit.cycle.extension.swap.duration);
      EXPECT_GT(s.cycle.contraction.swap.duration, unit.cycle.contraction.swap.duration);
      expect_agrees_with_simulation(p);
    }
  }
}

TEST(DmHardCases, SpeedIsContinuousWhereThePushReachesTheBodyFriction) {
  // μ_s = μ: at αF = F_b the body after stopping either sticks or slides back at
  // (αF − F_b)/2m → 0, so v_ss is continuous (its slope is not): the difference across ±ε is
  // O(ε).
  const Params base;
  for (double mu : {0.1, 0.6, 1.0}) {
    for (double f : {1.6, 4.0}) {
      Params p = dm(mu, 1.0, f * mu * base.m * base.g);
      for (double eps : {1e-9, 1e-6}) {
        p.alpha = alpha_at_body_friction(p, 1.0 - eps);
        const DmSteadyState below = dm_steady_state(p);
        p.alpha = alpha_at_body_friction(p, 1.0 + eps);
        const DmSteadyState above = dm_steady_state(p);
        EXPECT_LT(rel_diff(above.v_ss, below.v_ss), 10.0 * eps) << describe(p) << " eps=" << eps;
        EXPECT_LT(rel_diff(above.period, below.period), 10.0 * eps);
      }
    }
  }
}

TEST(DmHardCases, SpeedJumpsAtTheBodyStaticFrictionWhenItExceedsDynamicFriction) {
  // μ_s = 1.3 μ: just below αF = F_s a stopped body sticks; just above it breaks away at the
  // finite acceleration (F_s − F_b)/2m = 0.3 μ g (2m + Δm)/2m. v_ss jumps (a real discontinuity
  // of Coulomb friction with μ_s > μ, not a numerical one); both sides match the simulation.
  const Params base;
  for (double mu : {0.6, 1.0}) {
    Params p = dm(mu, 1.0, 4.0 * 1.3 * mu * base.m * base.g, 1.3 * mu);
    p.alpha = alpha_at_body_friction(p, 1.0 - 1e-9);
    const DmSteadyState below = dm_steady_state(p);
    expect_agrees_with_simulation(p);
    p.alpha = alpha_at_body_friction(p, 1.0 + 1e-9);
    const DmSteadyState above = dm_steady_state(p);
    expect_agrees_with_simulation(p);
    EXPECT_TRUE(below.cycle.extension.swap.stopped);
    EXPECT_FALSE(above.cycle.extension.swap.stopped);
    EXPECT_TRUE(above.cycle.extension.swap.broke_away);
    EXPECT_GT(rel_diff(above.v_ss, below.v_ss), 1e-3) << describe(p);
  }
}

TEST(DmHardCases, SpeedIsContinuousAtTheHeldModeBoundary) {
  // αF = μgΔm: below it Δm is held and all slide together; above, Δm's relative acceleration
  // is ≥ 0 but → 0. Continuous.
  const Params base;
  for (double mu : {0.1, 1.0}) {
    Params p = dm(mu, 1.0, 3.0 * mu * base.m * base.g);
    const double alpha = mu * p.g * p.moving_mass() / p.F;
    p.alpha = alpha * (1.0 - 1e-9);
    const DmSteadyState below = dm_steady_state(p);
    p.alpha = alpha * (1.0 + 1e-9);
    const DmSteadyState above = dm_steady_state(p);
    EXPECT_TRUE(below.held);
    EXPECT_FALSE(above.held);
    EXPECT_LT(rel_diff(above.v_ss, below.v_ss), 1e-7) << describe(p);
  }
}

// ---------------------------------------------------------------------------------------------
// Numeric backends vs the closed form.

template <class Backend>
class DmBackendVsClosedForm : public ::testing::Test {};

using Backends = ::testing::Types<events::CvodeBackend, events::OdeintBackend, events::GslBackend>;
TYPED_TEST_SUITE(DmBackendVsClosedForm, Backends);

TYPED_TEST(DmBackendVsClosedForm, AgreesOnASmallGrid) {
  events::BackendOptions bo;
  bo.rtol = 1e-11;
  bo.atol = 1e-13;
  SimulationOptions so;
  so.target = 1e-11;
  const Params base;
  for (double mu : {0.1, 0.6, 1.0}) {
    for (double alpha : {0.05, 1.0, 10.0}) {
      for (double force :
           {std::sqrt(mu * base.m * base.g * mu * base.M * base.g), 22.0, 5.0 * base.M * base.g}) {
        const Params p = dm(mu, alpha, force);
        TypeParam backend(bo);
        const SimulationSummary sim = steady_state_by_simulation(Sys(p), backend, so);
        expect_agrees(p, sim, dm_steady_state(p), 1e-9);
        EXPECT_GT(sim.stats.steps, sim.strokes);  // integrated, not solved in closed form
      }
    }
  }
}

}  // namespace
}  // namespace slipwalk::inchworm
