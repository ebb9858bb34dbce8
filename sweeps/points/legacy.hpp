#pragma once
// TEMPORARY during the restructure: positional rows beside a list of column names. Every family
// moves to row structs (engine/point_kind.hpp) and this header goes.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "sweeps/engine/point_kind.hpp"

namespace slipwalk::sweeps {

using Row = Cells;

struct LegacyKind {
  std::string name;
  std::string summary;
  std::vector<std::string> columns;
  std::function<void(const Point&)> check;
  std::function<PointResult(const Point&)> run;
  Timed timed = Timed::kNo;

  operator PointKind() const {  // NOLINT(google-explicit-constructor)
    PointKind k;
    k.name = name;
    k.summary = summary;
    for (const auto& c : columns) {
      k.columns.push_back({c, "", c == "wall_s" || c == "cpu_s" || c.starts_with("time_")});
    }
    k.timed = timed;
    k.check = check;
    k.run = run;
    return k;
  }
};

inline std::vector<PointKind> legacy_kinds(const std::vector<LegacyKind>& legacy) {
  return {legacy.begin(), legacy.end()};
}

}  // namespace slipwalk::sweeps
