#pragma once
// Option checks shared by the robot factories: each throws core::InputError naming the option
// ("multipod.legs") and the bad value.
#include <cmath>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::robots::detail {

inline void require_positive(const std::string& where, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw core::InputError(where, "must be positive, got " + core::format_double(value));
  }
}

/// lo ≤ value ≤ hi (closed interval), finite.
inline void require_range(const std::string& where, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    std::string what = "must be in [";
    what.append(core::format_double(lo)).append(", ").append(core::format_double(hi));
    what.append("], got ").append(core::format_double(value));
    throw core::InputError(where, what);
  }
}

}  // namespace slipwalk::robots::detail
