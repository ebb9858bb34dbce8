#pragma once
// Typed, checked access to a sweep point's inputs, shared by every point kind: unknown keys,
// wrong types and values out of range become core::InputError at the spec's file:line:col.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/range.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {

/// Typed access to a point's inputs; rejects keys the point kind does not take.
class Reader {
 public:
  Reader(const Point& p, std::string_view kind, const std::vector<std::string_view>& accepted)
      : point_(p) {
    for (const auto& [key, value] : p.values) {
      if (std::find(accepted.begin(), accepted.end(), key) == accepted.end()) {
        std::string message = "unknown key '" + key + "' for kind ";
        message += kind;
        message += "; expected one of ";
        for (std::size_t i = 0; i < accepted.size(); ++i) {
          message += i ? ", " : "";
          message += accepted[i];
        }
        throw core::InputError(value.origin, message);
      }
    }
  }

  [[nodiscard]] bool has(std::string_view key) const { return point_.find(key) != nullptr; }

  [[noreturn]] void fail(std::string_view key, const std::string& what) const {
    const Value* v = point_.find(key);
    throw core::InputError(
        v != nullptr ? v->origin : point_.source,
        std::string(key) + ": " + what + " (point " + std::to_string(point_.id) + ")");
  }

  [[nodiscard]] std::optional<double> number(std::string_view key) const {
    const Value* v = point_.find(key);
    if (v == nullptr) {
      return std::nullopt;
    }
    if (!v->is_number()) {
      fail(key, "expected a number, got " + v->repr());
    }
    return v->number();
  }

  [[nodiscard]] double number(std::string_view key, double fallback) const {
    return number(key).value_or(fallback);
  }
  /// A number, `fallback` if absent; fails unless lo < x (lo ≤ x if closed) and x ≤ hi.
  [[nodiscard]] double number(std::string_view key, double fallback, double lo, double hi,
                              bool closed_lo = false) const {
    const double x = number(key).value_or(fallback);
    if (!(closed_lo ? x >= lo : x > lo) || !(x <= hi)) {
      fail(key, "must be in " + std::string(closed_lo ? "[" : "(") + core::format_double(lo) +
                    ", " + core::format_double(hi) + "], got " + core::format_double(x));
    }
    return x;
  }

  /// A number, `fallback` if absent; fails unless `range` holds it (the message states the range
  /// and its unit, core/range.hpp).
  [[nodiscard]] double number(std::string_view key, double fallback,
                              const core::Range& range) const {
    const double x = number(key).value_or(fallback);
    if (!range.contains(x)) {
      fail(key, "must be in " + range.describe() + ", got " + core::format_double(x));
    }
    return x;
  }

  /// Fails at `key` when a point's work `amount` (`product`, e.g. "N · trials") passes `limit`:
  /// every point finishes in bounded time whatever its inputs, and a point that would not is bad
  /// input found before the sweep starts.
  void limit_work(std::string_view key, std::string_view product, double amount,
                  double limit) const {
    if (!(amount <= limit)) {
      fail(key, std::string(product) + " = " + core::format_double(amount) + "; at most " +
                    core::format_double(limit) + " per point (split it into more points)");
    }
  }

  [[nodiscard]] long long integer(std::string_view key, long long fallback, long long lo,
                                  long long hi) const {
    const auto v = number(key);
    if (!v) {
      return fallback;
    }
    if (*v != std::floor(*v) || *v < static_cast<double>(lo) || *v > static_cast<double>(hi)) {
      fail(key, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                    ", got " + core::format_double(*v));
    }
    return static_cast<long long>(*v);
  }

  [[nodiscard]] std::optional<std::string> text(std::string_view key) const {
    const Value* v = point_.find(key);
    if (v == nullptr) {
      return std::nullopt;
    }
    if (v->is_number()) {
      fail(key, "expected a string, got " + v->repr());
    }
    return v->text();
  }

  /// One of `options` (the first is the default).
  [[nodiscard]] std::string choice(std::string_view key,
                                   const std::vector<std::string_view>& options) const {
    const auto t = text(key);
    if (!t) {
      return std::string(options.front());
    }
    if (std::find(options.begin(), options.end(), *t) == options.end()) {
      std::string list;
      for (std::size_t i = 0; i < options.size(); ++i) {
        list += (i ? ", \"" : "\"") + std::string(options[i]) + "\"";
      }
      fail(key, "expected one of " + list + ", got '" + *t + "'");
    }
    return *t;
  }

  [[nodiscard]] const Point& point() const { return point_; }

 private:
  const Point& point_;
};

}  // namespace slipwalk::sweeps
