#pragma once
// Parameters of the inchworm of thesis §2.2–2.3 (SI units). Defaults are the thesis' choices.
#include <cmath>
#include <limits>
#include <string_view>

namespace slipwalk::inchworm {

/// How the load moves from one end mass to the other after each stroke.
enum class SwapModel {
  kInstant,  ///< §2.2: the two masses swap positions instantaneously
  kMass,     ///< §2.5 ("dm"): Δm = M − m is pushed across by α F while the ends are held apart
};

struct Params {
  double m = 1.0;       ///< kg, the smaller point mass (x); valid: > 0
  double M = 1.5;       ///< kg, the larger point mass (y); valid: > m (else no net motion)
  double L_min = 0.02;  ///< m, shortest actuator length; valid: > 0
  double L_max = 0.5;   ///< m, longest actuator length; valid: > L_min
  double g = 9.81;      ///< m/s², gravitational acceleration; valid: > 0
  double mu = 1.0;      ///< dynamic friction coefficient; valid: > 0 (thesis range 0.05–1)
  double mu_s = std::numeric_limits<double>::quiet_NaN();  ///< static coefficient; NaN = mu; ≥ mu
  double F = 45.0;  ///< N, actuator force magnitude; valid: > mu_s·m·g (else m never moves)
  SwapModel model = SwapModel::kInstant;  ///< instant swap (§2.2) or moving Δm (§2.5, "dm")
  double alpha = 1.0;  ///< F_Δm = α F pushes Δm across (model kMass); valid: > 0

  [[nodiscard]] double static_mu() const { return std::isnan(mu_s) ? mu : mu_s; }
  [[nodiscard]] double stroke() const { return L_max - L_min; }          ///< ΔL
  [[nodiscard]] double swap_ratio() const { return (M - m) / (M + m); }  ///< ρ: CoM jump / d
  [[nodiscard]] double moving_mass() const { return M - m; }             ///< Δm (§2.5)
};

/// Throws core::InputError naming the offending option (--force, --mu, ...) when a parameter is
/// out of its valid range or not a finite number.
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
