#include "inchworm/params.hpp"

#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/range.hpp"

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
  core::require_in("--m", p.m, ranges::kMass);
  core::require_in("--M", p.M, ranges::kMass);
  require(p.M > p.m, "--M",
          "the large mass must exceed the small mass m = " + num(p.m) + " kg, got " + num(p.M));
  core::require_in("--L-min", p.L_min, ranges::kLength);
  core::require_in("--L-max", p.L_max, ranges::kLength);
  require(p.L_max > p.L_min, "--L-max",
          "must exceed L_min = " + num(p.L_min) + " m, got " + num(p.L_max));
  core::require_in("--g", p.g, ranges::kGravity);
  core::require_in("--mu", p.mu, ranges::kFriction);
  if (!std::isnan(p.mu_s)) {
    core::require_in("--mu-s", p.mu_s, ranges::kFriction);
    require(p.mu_s >= p.mu, "--mu-s",
            "the static coefficient must be at least mu = " + num(p.mu) + ", got " + num(p.mu_s));
  }
  if (p.model == SwapModel::kMass) {
    core::require_in("--alpha", p.alpha, ranges::kAlpha);
  }
  core::require_in("--force", p.F, ranges::kForce);
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
