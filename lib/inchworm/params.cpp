#include "inchworm/params.hpp"

#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::inchworm {

namespace {
void require(bool ok, const char* where, const std::string& what) {
  if (!ok) {
    throw core::InputError(where, what);
  }
}
std::string num(double v) { return core::format_double(v); }
}  // namespace

void validate(const Params& p) {
  const std::pair<const char*, double> finite[] = {
      {"--m", p.m}, {"--M", p.M},   {"--L-min", p.L_min}, {"--L-max", p.L_max},
      {"--g", p.g}, {"--mu", p.mu}, {"--force", p.F}};
  for (const auto& [name, value] : finite) {
    require(std::isfinite(value), name, "must be a finite number, got " + num(value));
  }
  require(p.m > 0.0, "--m", "the small mass must be positive, got " + num(p.m));
  require(p.M > p.m, "--M",
          "the large mass must exceed the small mass m = " + num(p.m) + " kg, got " + num(p.M));
  require(p.L_min > 0.0, "--L-min", "must be positive, got " + num(p.L_min));
  require(p.L_max > p.L_min, "--L-max",
          "must exceed L_min = " + num(p.L_min) + " m, got " + num(p.L_max));
  require(p.g > 0.0, "--g", "must be positive, got " + num(p.g));
  require(p.mu > 0.0, "--mu", "the friction coefficient must be positive, got " + num(p.mu));
  if (!std::isnan(p.mu_s)) {
    require(std::isfinite(p.mu_s), "--mu-s", "must be a finite number, got " + num(p.mu_s));
    require(p.mu_s >= p.mu, "--mu-s",
            "the static coefficient must be at least mu = " + num(p.mu) + ", got " + num(p.mu_s));
  }
  if (p.model == SwapModel::kMass) {
    require(std::isfinite(p.alpha) && p.alpha > 0.0, "--alpha",
            "the swap force factor must be a positive number, got " + num(p.alpha));
  }
  const double threshold = p.static_mu() * p.m * p.g;
  require(p.F > threshold, "--force",
          "F = " + num(p.F) + " N does not exceed mu_s*m*g = " + num(threshold) +
              " N: the small mass never leaves static friction");
}

std::string_view param_key_of_option(std::string_view option) {
  static constexpr std::pair<std::string_view, std::string_view> kOptionKey[] = {
      {"--force", "F"},     {"--mu", "mu"}, {"--mu-s", "mu_s"},
      {"--m", "m"},         {"--M", "M"},   {"--L-min", "L_min"},
      {"--L-max", "L_max"}, {"--g", "g"},   {"--alpha", "alpha"},
  };
  for (const auto& [opt, key] : kOptionKey) {
    if (opt == option) {
      return key;
    }
  }
  return {};
}

}  // namespace slipwalk::inchworm
