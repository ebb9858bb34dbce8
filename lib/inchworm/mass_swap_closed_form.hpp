#pragma once
// The realistic-swap ("dm") inchworm of thesis §2.5 solved by hand: its stroke, its two swaps and
// the cycle map c -> c' between the common velocities at the starts of two successive extension
// strokes, whose fixed point is the steady state. This is an independent route to the hybrid
// system MassSwapSystem (mass_swap.hpp): nothing here calls it, the event loop or a backend; the
// physics is the one fixed in that header. There is no algebraic form of the fixed point (the
// cycle has up to ten phases, each case a different branch); it is found by GSL's Brent solver.
//
// Notation. m the end masses, Δm = M − m the moving mass, M = m + Δm; f_m = μmg, f_M = μMg;
// P = αF the push on Δm; F_b = μg(2m + Δm) and F_s = μ_s g(2m + Δm) the body's dynamic and static
// friction limits; ΔL = L_max − L_min.
//
// Stroke. Both strokes are the same in absolute coordinates: x, the end without Δm (mass m), is
// pushed forward by +F; y, the end carrying Δm (mass M), is pushed back by −F; x − y grows by ΔL
// (from L_min to L_max in an extension, from −L_max to −L_min in a contraction). From the common
// velocity c0 after the last collision, of either sign:
//   x  backward (c0 < 0): ẍ = (F + f_m)/m > 0, it stops at t_x = −c0 m/(F + f_m) and, since
//      F > μ_s m g, breaks away forward; forward (c0 ≥ 0, or after t_x): ẍ = (F − f_m)/m > 0.
//   y  forward (c0 > 0): ÿ = −(F + f_M)/M, it stops at t_y = c0 M/(F + f_M);
//      backward (c0 < 0): ÿ = (f_M − F)/M: if F < f_M it decelerates and stops at
//      t_y = −c0 M/(f_M − F); if F ≥ f_M it slides back for the whole stroke;
//      at rest (c0 = 0 or after t_y): stuck if F ≤ μ_s M g, else it slides back (ÿ = (f_M − F)/M
//      < 0). After a backward stop F < f_M ≤ μ_s M g, so it always sticks.
//   Hence at most three phases of constant accelerations, separated by t_x and t_y (§2.4 is the
//   case c0 ≥ 0: two phases). In a phase the relative displacement grows as q τ + ½ r τ², q the
//   relative velocity ẋ − ẏ, r = ẍ − ÿ; the length limit is the smallest positive root of
//   q τ + ½ r τ² = R (R what is left of ΔL), τ = 2R / (q + sqrt(q² + 2 r R)), free of
//   cancellation. (r < 0 only while x slides forward and y decelerates backward, with q > 0.)
//   The stroke ends in the plastic collision c = (m ẋ + M ẏ)/(m + M) (eq. 2.4).
//
// Swap. s = +1 after an extension (Δm travels D = L_max forward relative to the body, the body is
// pushed backward), s = −1 after a contraction (Δm travels D = L_min backward, the body is pushed
// forward). Along s, with U the m–m body's velocity and W Δm's, from U = W = s v:
//   body sliding along +s (U > 0): 2m U̇ = −P − F_b; it stops at t = 2m U / (P + F_b);
//   body sliding along −s (U < 0): 2m U̇ = F_b − P: for P > F_b it slides on (faster), for
//      P < F_b it stops at t = 2m (−U) / (F_b − P) and sticks (P < F_b ≤ F_s);
//   body at rest: stuck while P ≤ F_s (the "stop during swap" of §2.5.2 when it got there by
//      stopping), else it breaks away along −s with 2m U̇ = F_b − P;
//   Δm free: Δm Ẇ = P; the relative acceleration is ρ = P/Δm − U̇.
//   Held mode: when ρ < 0 (only with U < 0: P/Δm < (F_b − P)/(2m) ⇔ P < μ g Δm) free Δm would run
//      into the end it left; it is held there and all three slide together, U̇ = Ẇ = +μg, until
//      the body stops at t = −U/(μg); it then sticks (P < μgΔm < F_s) and Δm is pushed off from
//      rest.
//   Arrival: the relative displacement reaches D (the root formula above, relative velocity ≥ 0
//   and ρ ≥ 0); plastic collision of all three, c = (2m u + Δm w)/(2m + Δm).
//   Hence at most three phases too (slide along +s, stop, stick or break away; or held/slide
//   along −s, stop, stick).
//
// Cycle and steady state. G(c) = (extension stroke, swap s = +1, contraction stroke, swap
// s = −1) from c. Its fixed point c* is the steady state of the simulation, which starts from rest
// with an extension stroke: G is iterated a few times from c = 0 (the simulation's first cycles,
// and c* may well be negative), then bracketed outward from there (G' < 1 at c*, so
// G(c) − c > 0 below c* and < 0 above it) and solved by Brent. v_ss = displacement / duration of
// the steady cycle (eq. 2.5; every displacement is physical, there is no swap jump).
//
// Static friction above dynamic friction (μ_s > μ) makes G jump where a velocity that reaches a
// sliding/sticking decision is exactly zero: y with F ∈ (f_M, μ_s M g] keeps sliding back from
// c0 < 0 but is held at c0 = 0; the body with P ∈ (F_b, F_s] keeps sliding along −s but is held
// at rest. The fixed point is checked to be one (|G(c*) − c*| tiny), not such a jump.
#include "inchworm/params.hpp"

namespace slipwalk::inchworm {

/// One stroke of the dm model from the common velocity c0 (any sign).
struct DmStroke {
  double v_x = 0.0;              ///< m/s, x's velocity at the length limit (before the collision)
  double v_y = 0.0;              ///< m/s, y's (and Δm's) velocity there
  double c_next = 0.0;           ///< m/s, common velocity after the closing collision (eq. 2.4)
  double duration = 0.0;         ///< s
  double displacement = 0.0;     ///< m, CoM displacement (x, and y carrying Δm)
  int phases = 0;                ///< constant-acceleration phases (1–3)
  bool small_slid_back = false;  ///< x moved backward (c0 < 0)
  bool large_slid_back = false;  ///< y moved backward at some time of the stroke
  /// y was driven backward: it slid back with F > μMg (accelerating backward), regime II in the
  /// sense of §2.3.1. (Sliding back from c0 < 0 with F < μMg only decelerates it to rest.)
  bool large_driven_back = false;
  /// y came to rest and then slid back (the §2.4 picture of regime II; a y driven back from the
  /// start, c0 < 0 with F > μMg or c0 = 0 with F > μ_s M g, has no stop first).
  bool large_stopped_then_slid_back = false;
};

[[nodiscard]] DmStroke dm_stroke_map(const Params& p, double c0);

/// One swap: Δm pushed across from the common velocity v.
struct DmSwap {
  double c_next = 0.0;          ///< m/s, common velocity after the arrival, momentum/(2m + Δm)
  double v_body = 0.0;          ///< m/s, the m–m body's velocity just before the arrival
  double v_dm = 0.0;            ///< m/s, Δm's velocity just before the arrival
  double duration = 0.0;        ///< s
  double displacement = 0.0;    ///< m, CoM displacement
  int phases = 0;               ///< constant-acceleration phases (1–3)
  bool stopped = false;         ///< the body came to rest and stuck ("stop during swap", §2.5.2;
                                ///< MassSwapSystem's kSwapStopped)
  bool stuck_at_start = false;  ///< the swap started with the body exactly at rest and stuck
  bool broke_away = false;      ///< the body left rest (static friction exceeded) along −s
  bool held = false;            ///< Δm was held against the end it left (held mode)
};

/// side = +1: the swap after an extension stroke; −1: after a contraction stroke.
[[nodiscard]] DmSwap dm_swap_map(const Params& p, int side, double v);

/// A stroke and its swap, from the common velocity c0 at the start of the stroke.
struct DmHalfCycle {
  DmStroke stroke;
  DmSwap swap;
  double c_next = 0.0;        ///< m/s, common velocity at the start of the next stroke
  double duration = 0.0;      ///< s
  double displacement = 0.0;  ///< m, CoM displacement
};

[[nodiscard]] DmHalfCycle dm_half_cycle(const Params& p, int side, double c0);

/// The cycle map: extension stroke, its swap, contraction stroke, its swap.
struct DmCycle {
  DmHalfCycle extension;
  DmHalfCycle contraction;
  double c_next = 0.0;        ///< m/s, G(c0)
  double duration = 0.0;      ///< s
  double displacement = 0.0;  ///< m
};

[[nodiscard]] DmCycle dm_cycle_map(const Params& p, double c0);

/// Regime of one stroke by its motion: II iff y was driven backward (two masses moving); what
/// MassSwapSystem::mode_flags reports as kLargeMassSlidBack.
[[nodiscard]] inline Regime stroke_regime(const DmStroke& s) {
  return s.large_driven_back ? Regime::kTwo : Regime::kOne;
}

/// The steady state of the dm model: the fixed point of the cycle map.
struct DmSteadyState {
  double v_ss = 0.0;           ///< m/s, eq. 2.5 over one steady cycle
  double period = 0.0;         ///< s, half the cycle duration (as SimulationSummary::period)
  double c0 = 0.0;             ///< m/s, common velocity at the start of an extension stroke
  double c_contraction = 0.0;  ///< m/s, common velocity at the start of a contraction stroke
  /// Regime of the contraction stroke, as steady_state_by_simulation reports it (its second half
  /// cycle).
  Regime regime = Regime::kOne;
  Regime regime_extension = Regime::kOne;    ///< stroke_regime of the extension stroke
  Regime regime_contraction = Regime::kOne;  ///< stroke_regime of the contraction stroke
  bool swap_stopped = false;                 ///< the body stopped and stuck in either swap
  bool held = false;                         ///< Δm was held in either swap
  double contraction = 0.0;                  ///< G'(c*), per cycle (central difference)
  double residual = 0.0;                     ///< |G(c*) − c*|, m/s
  int iterations = 0;                        ///< Brent iterations
  DmCycle cycle;                             ///< the steady cycle
};

/// Throws core::ComputationError if no fixed point is found.
[[nodiscard]] DmSteadyState dm_steady_state(const Params& p);

}  // namespace slipwalk::inchworm
