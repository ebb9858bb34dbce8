#pragma once
// Parameters of the inchworm of thesis §2.2–2.3 (SI units). Defaults are the thesis' choices.
#include <cmath>
#include <limits>
#include <string_view>

#include "core/range.hpp"

namespace slipwalk::inchworm {

/// The admissible ranges of the model's parameters and of a run's settings, checked up front by
/// validate() (and by the sweep specs, which read the same table), so no input meets a limit
/// later as a non-finite number. Why these bounds (SI units, thesis §2.2–2.5):
///  - Every quantity of a stroke is built from F/m, F/M, μg, ΔL and the mass ratio: the
///    accelerations a_x = (F − μmg)/m, b = (F + μMg)/M, r1 = F/m + F/M (§2.4), the stroke time
///    T ~ sqrt(ΔL / r) up to ΔL / (μ g ρ) scales (phase 2 in regime II, a2 = μ g ρ), the speeds
///    c0 = sqrt(ΔL / Q) ~ sqrt(ΔL r) and the dm model's swap times ~ sqrt(ΔL Δm / (α F)).
///  - With m, M in [1e-6, 1e6] kg, lengths in [1e-6, 1e3] m, g in [1e-3, 1e3] m/s², μ in
///    [1e-4, 10], F ≤ 1e9 N and α in [1e-3, 1e3], the accelerations lie within about 1e-23
///    (F a hair above μ_s m g, or M a hair above m) .. 1e15 m/s² (F/m), the stroke times within
///    3e-19 s (ΔL one ulp of 1e-6 m at r = 1e15) .. 1e13 s (sqrt(ΔL / r2) at the smallest r2),
///    and the speeds c0 ~ sqrt(ΔL r) within 1e-13 .. 1e9 m/s: products of a few of them stay
///    far from overflow (1e308) and from subnormals (1e-308). The thesis' values (m = 1,
///    M = 1.5, L = 0.02–0.5 m, g = 9.81, μ = 0.05–1.3, F up to 50 Mg, α = 0.05–20) lie well
///    inside. (A stroke longer than a run's time limit, 1e9 s, ends the run with exit 1.)
///  - The ratio constraints M > m, L_max > L_min, μ_s ≥ μ and F > μ_s m g (else nothing moves)
///    are checked besides.
namespace ranges {
inline constexpr core::Range kMass = core::closed(1e-6, 1e6, "kg");
inline constexpr core::Range kLength = core::closed(1e-6, 1e3, "m");
inline constexpr core::Range kGravity = core::closed(1e-3, 1e3, "m/s^2");
inline constexpr core::Range kFriction = core::closed(1e-4, 10.0);
inline constexpr core::Range kForce = core::positive_up_to(1e9, "N");
inline constexpr core::Range kAlpha = core::closed(1e-3, 1e3);

/// Integrators' relative tolerance: below ~1e-15 (a few ulp) no integrator can honour it.
inline constexpr core::Range kRtol = core::Range{1e-15, 1.0, false, true, ""};
/// fixed_rk4's step (s): below 1e-12 s a stroke of the thesis' scale (0.1 s) takes 1e11 steps,
/// far beyond any step budget.
inline constexpr core::Range kFixedStep = core::Range{1e-12, 1.0, false, true, "s"};
/// A trace's sampling interval (s): sample times k dt with k a 64-bit integer cover any time a
/// run reaches (t_end = 1e9 s) only if dt ≥ 1e-9 s; the row bound does the rest.
inline constexpr core::Range kSampleDt = core::closed(1e-9, 1e3, "s");
/// Whole-number settings, as ranges of doubles.
inline constexpr core::Range kCycles = core::closed(1.0, 1e4);
inline constexpr core::Range kMaxStrokes = core::closed(8.0, 1e9);
inline constexpr core::Range kMaxSteps = core::closed(1.0, 1e15);
inline constexpr core::Range kMaxRows = core::closed(1.0, 1e9);
}  // namespace ranges

/// Steps an integrator may take in one solve or trace unless told otherwise (--max-steps; a
/// spec's max_steps): about 5 s of fixed_rk4 (55 ns a step), the one method whose step count the
/// input sets directly (period / h). The adaptive methods take a few hundred to a few thousand
/// steps per stroke at any rtol ≥ 1e-15, so for them the stroke bound (--max-strokes) is the
/// effective one. A count, not a wall time: a run's outcome must not depend on the machine.
inline constexpr long long kDefaultMaxSteps = 100'000'000;

/// Rows a trace may write unless told otherwise (--max-rows): 1e7 rows, ~1.7 GB at the ~170
/// bytes of a row (nine numbers at full precision).
inline constexpr long long kDefaultMaxRows = 10'000'000;

/// How the load moves from one end mass to the other after each stroke.
enum class SwapModel {
  kInstant,  ///< §2.2: the two masses swap positions instantaneously
  kMass,     ///< §2.5 ("dm"): Δm = M − m is pushed across by α F while the ends are held apart
};

struct Params {
  double m = 1.0;       ///< kg, the smaller point mass (x); in ranges::kMass
  double M = 1.5;       ///< kg, the larger point mass (y); kMass and > m (else no net motion)
  double L_min = 0.02;  ///< m, shortest actuator length; in ranges::kLength
  double L_max = 0.5;   ///< m, longest actuator length; kLength and > L_min
  double g = 9.81;      ///< m/s², gravitational acceleration; ranges::kGravity
  double mu = 1.0;      ///< dynamic friction coefficient; ranges::kFriction (thesis: 0.05–1)
  double mu_s = std::numeric_limits<double>::quiet_NaN();  ///< static coefficient; NaN = mu; ≥ mu
  double F = 45.0;  ///< N, actuator force; ranges::kForce and > mu_s·m·g (else m never moves)
  SwapModel model = SwapModel::kInstant;  ///< instant swap (§2.2) or moving Δm (§2.5, "dm")
  double alpha = 1.0;  ///< F_Δm = α F pushes Δm across (model kMass); ranges::kAlpha

  [[nodiscard]] double static_mu() const { return std::isnan(mu_s) ? mu : mu_s; }
  [[nodiscard]] double stroke() const { return L_max - L_min; }          ///< ΔL
  [[nodiscard]] double swap_ratio() const { return (M - m) / (M + m); }  ///< ρ: CoM jump / d
  [[nodiscard]] double moving_mass() const { return M - m; }             ///< Δm (§2.5)
};

/// Throws core::InputError naming the offending option (--force, --mu, ...) when a parameter is
/// out of its range (ranges:: above; the message states it) or breaks a ratio constraint.
void validate(const Params& p);

/// The Params field (as spec files name it: F, mu, mu_s, m, M, L_min, L_max, g, alpha) that a
/// validate() error's option names; empty if the option is not one of validate()'s.
[[nodiscard]] std::string_view param_key_of_option(std::string_view option);

/// The regimes of §2.3.1: I, M stops and stays (F ≤ μ_s M g); II, M stops then slides back.
enum class Regime { kOne = 1, kTwo = 2 };

/// Which regime the steady stroke is in; decided by static friction of M alone.
[[nodiscard]] inline Regime regime_of(const Params& p) {
  return p.F <= p.static_mu() * p.M * p.g ? Regime::kOne : Regime::kTwo;
}

[[nodiscard]] inline const char* regime_name(Regime r) { return r == Regime::kOne ? "I" : "II"; }

}  // namespace slipwalk::inchworm
