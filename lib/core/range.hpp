#pragma once
// Physical ranges checked up front (DESIGN.md: Command line). A value outside its range is bad
// input (core::InputError, exit 2) and the message states the allowed range with its unit, so a
// user never meets the limit as a non-finite result later. Ranges are chosen so that every
// intermediate quantity of the model stays finite and normal in double precision.
#include <cmath>
#include <string>
#include <string_view>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::core {

/// An interval of admissible values; an open end excludes its bound.
struct Range {
  double lo = 0.0;        ///< lower bound
  double hi = 0.0;        ///< upper bound
  bool lo_open = false;   ///< true: lo itself is not admissible
  bool hi_open = false;   ///< true: hi itself is not admissible
  std::string_view unit;  ///< printed after the interval ("kg", "m/s^2", "" for none)

  [[nodiscard]] bool contains(double v) const {
    if (!std::isfinite(v)) {
      return false;
    }
    const bool above = lo_open ? v > lo : v >= lo;
    const bool below = hi_open ? v < hi : v <= hi;
    return above && below;
  }

  /// "(0, 1000000] kg"
  [[nodiscard]] std::string describe() const {
    std::string s(lo_open ? "(" : "[");
    s.append(format_double(lo)).append(", ").append(format_double(hi));
    s.append(hi_open ? ")" : "]");
    if (!unit.empty()) {
      s.append(" ").append(unit);
    }
    return s;
  }
};

/// (0, hi] in `unit`.
constexpr Range positive_up_to(double hi, std::string_view unit = "") {
  return Range{0.0, hi, true, false, unit};
}

/// [lo, hi] in `unit`.
constexpr Range closed(double lo, double hi, std::string_view unit = "") {
  return Range{lo, hi, false, false, unit};
}

/// Throws InputError(where, "must be in <range>, got <value>") unless `range` contains `value`.
inline void require_in(const std::string& where, double value, const Range& range) {
  if (!range.contains(value)) {
    throw InputError(where, "must be in " + range.describe() + ", got " + format_double(value));
  }
}

}  // namespace slipwalk::core
