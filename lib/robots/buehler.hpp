#pragma once
// Gait clocks: time → shaft angle φ (in turns) of a crank leg (thesis §3.5.1.4, §3.5.1.5).
//
// The Buehler clock of RHex (Saranli, Buehler & Koditschek 2001, the thesis' [6]) turns the leg
// slowly through a short "stance sweep" of the shaft, centred on the angle where the toe is lowest,
// and quickly through the rest of the turn (the return). In cycle phase s (cycles; s = 0 at
// mid-stance, period 1), with duty D and sweep Σ (turns):
//   stance, |s| ≤ D/2 (mod 1):      φ = φ_c + Σ s / D                          (slow)
//   return, D/2 ≤ s ≤ 1 − D/2:      φ = φ_c + Σ/2 + (1 − Σ)(s − D/2)/(1 − D)   (fast)
// φ is continuous and increases by exactly one turn per cycle; dφ/ds is piecewise constant and
// jumps at touchdown and lift-off (as the commanded clock of the robot does).
//
// The metachronal gait's clock (§3.5.1.5) is the same with a cubic stance: with τ = s/D + 1/2,
//   φ = φ_c − Σ/2 + Σ (3τ² − 2τ³),   dφ/ds = 6 Σ τ(1 − τ) / D,
// so feet at different points of their stance turn their shafts at different rates ("contacting
// feet have vastly incompatible velocities"); the thesis says only "cubic in time"; this cubic is
// the one that starts and ends the stance at rest and keeps φ monotone.
namespace slipwalk::robots {

/// Shape of one clock cycle; phases in cycles, shaft angles in turns.
struct ClockShape {
  double duty = 0.55;   ///< D: fraction of the cycle in stance; valid: (0, 1)
  double sweep = 0.35;  ///< Σ: shaft turns swept during stance; valid: [0, 1)
  double center = 0.0;  ///< φ_c: shaft angle at mid-stance, turns
  bool cubic = false;   ///< false: linear stance (Buehler); true: cubic stance (metachronal)
};

/// Throws core::InputError("<where>.duty", ...) etc. for values out of range.
void validate(const ClockShape& shape, const char* where);

struct ClockState {
  double phi;   ///< shaft angle, turns, in [0, 1)
  double rate;  ///< dφ/ds, turns per cycle (> 0 except at the ends of a cubic stance)
  bool stance;  ///< s in the stance part of the cycle
};

/// The clock at cycle phase s (any real; s = 0 is mid-stance). No allocation.
[[nodiscard]] ClockState clock_at(const ClockShape& shape, double s);

/// The shaft angle before reduction to [0, 1): continuous and non-decreasing in s, with
/// φ(s + 1) = φ(s) + 1 and φ(0) = φ_c. clock_at(...).phi is this reduced to [0, 1).
[[nodiscard]] double clock_unwrapped(const ClockShape& shape, double s);

}  // namespace slipwalk::robots
