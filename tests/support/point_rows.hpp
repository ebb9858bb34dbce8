#pragma once
// Shared by the tests of sweep point functions: a spec's points from the body of a study file,
// a point kind by name, and a column's index in its rows (throwing, so that a renamed
// column fails the test instead of reading past the row).
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::test_support {

/// The points of a spec "study = t, name = t, kind = KIND" followed by BODY ([params], [axes]).
inline std::vector<sweeps::Point> points_of(const std::string& kind, const std::string& body) {
  const std::string text = "study = \"t\"\nname = \"t\"\nkind = \"" + kind + "\"\n" + body;
  return sweeps::expand(sweeps::parse_spec(text, "peer.toml"));
}

inline const sweeps::PointKind& point_kind(const std::string& kind) {
  const sweeps::PointKind* f = sweeps::find_point_kind(sweeps::points::all_kinds(), kind);
  if (f == nullptr) {
    throw std::runtime_error("no point kind " + kind);
  }
  return *f;
}

inline std::size_t column(const sweeps::PointKind& f, const std::string& name) {
  const auto it = std::find_if(f.columns.begin(), f.columns.end(),
                               [&](const sweeps::ColumnInfo& c) { return c.name == name; });
  if (it == f.columns.end()) {
    throw std::runtime_error("no column " + name);
  }
  return static_cast<std::size_t>(it - f.columns.begin());
}

}  // namespace slipwalk::test_support
