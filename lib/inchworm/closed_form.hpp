#pragma once
// The exact solution of §2.4, derived afresh (the printed eqs. 2.9–2.11 carry typos; see
// docs in reports and the derivation below).
//
// A stroke starts right after a plastic collision with both masses at the CoM velocity c0 ≥ 0.
// Phase 1 (both slide forward): m accelerates at a_x = (F − μmg)/m, M decelerates at
//   b = (F + μMg)/M, the CoM at −μg; M stops after t1 = c0/b, the CoM velocity is then
//   c1 = κ c0 with κ = F/(F + μMg).
// Phase 2 (M stuck, regime I, or sliding back, regime II): constant relative acceleration r2 and
//   CoM acceleration a2 until x − y has grown by ΔL = L_max − L_min:
//   ΔL = ½ r1 t1² + r1 t1 t2 + ½ r2 t2²   (eq. 2.9 with its missing ½ restored), r1 = F/m + F/M.
// If ½ r1 t1² ≥ ΔL the stroke ends before M stops.
// At the fixed point c_next = c0, so t2 = (1 − κ) c0 / a2 and every term of the length equation
// is quadratic in c0: c0 = sqrt(ΔL / Q) in closed form. The CoM velocity is piecewise linear
// from c0 down to c1 and back, so the dynamic part of v_ss is (c0 + c1)/2; the swaps add
// ρ ΔL per two strokes (ρ = (M − m)/(M + m)), hence eq. 2.11 with T = t1 + t2:
//   v_ss = (c0 + c1)/2 + ρ ΔL / (2 T).
#include "inchworm/params.hpp"

namespace slipwalk::inchworm {

/// The constant accelerations of a stroke's two phases.
struct StrokeAccelerations {
  double a_x;    ///< m's acceleration, both phases
  double b;      ///< M's deceleration in phase 1 (M sliding forward)
  double r1;     ///< relative acceleration (x − y)'' in phase 1
  double r2;     ///< relative acceleration in phase 2
  double a2;     ///< CoM acceleration in phase 2 (phase 1: −μg)
  double kappa;  ///< c1 / c0 = F / (F + μ M g)
  Regime regime;
};

[[nodiscard]] StrokeAccelerations stroke_accelerations(const Params& p);

/// One stroke of the map c0 -> c_next (§2.4, eq. 2.10 corrected), for c0 ≥ 0.
struct Stroke {
  double c_next;        ///< CoM velocity after the closing collision
  double duration;      ///< T = t1 + t2
  double t1;            ///< time until M stops (= duration if the stroke ends first)
  double t2;            ///< remaining time after M stops (0 if the stroke ends first)
  double displacement;  ///< CoM displacement from the dynamics, swap jump excluded
  bool ends_before_M_stops;
};

[[nodiscard]] Stroke stroke_map(const Params& p, double c0);

/// The steady state: the fixed point of the stroke map and what follows from it.
struct SteadyState {
  double v_ss;         ///< eq. 2.5: average CoM speed over a steady cycle, swaps included
  double period;       ///< duration of one stroke T (a full cycle is two strokes)
  double c0;           ///< CoM velocity at the start of a steady stroke
  double t1;           ///< phase 1 duration
  double t2;           ///< phase 2 duration
  double contraction;  ///< d c_next / d c0 at the fixed point: per-stroke contraction factor
  Regime regime;
  int iterations = 0;  ///< root-solver iterations (0 for the algebraic closed form)
};

/// The algebraic closed form c0 = sqrt(ΔL / Q) (`--method exact`).
[[nodiscard]] SteadyState steady_state_closed_form(const Params& p);

/// The fixed point c_next(c0) = c0 found by GSL's Brent solver on the stroke map (`--method
/// rootfind`): an independent route to the same number.
[[nodiscard]] SteadyState steady_state_fixed_point(const Params& p);

/// eq. 2.6, the thesis' nondimensional governing law for regime II: ṽ = v_ss / sqrt(L g) as a
/// function of f̃ = F / (μ M g). L is L_max (the thesis: "the maximal length of the actuator").
[[nodiscard]] double governing_law_eq_2_6(double mu, double f_tilde);

}  // namespace slipwalk::inchworm
