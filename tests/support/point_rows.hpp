#pragma once
// Shared by the tests of sweep point functions: a spec's points from the body of a study file,
// a point function by kind, and a column's index in its rows (throwing, so that a renamed
// column fails the test instead of reading past the row).
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "sweeps/point_functions.hpp"
#include "sweeps/spec.hpp"

namespace slipwalk::test_support {

/// The points of a spec "study = t, name = t, kind = KIND" followed by BODY ([params], [axes]).
inline std::vector<sweeps::Point> points_of(const std::string& kind, const std::string& body) {
  const std::string text = "study = \"t\"\nname = \"t\"\nkind = \"" + kind + "\"\n" + body;
  return sweeps::expand(sweeps::parse_spec(text, "peer.toml"));
}

inline const sweeps::PointFunction& point_function(const std::string& kind) {
  const sweeps::PointFunction* f = sweeps::find_point_function(kind);
  if (f == nullptr) {
    throw std::runtime_error("no point function " + kind);
  }
  return *f;
}

inline std::size_t column(const sweeps::PointFunction& f, const std::string& name) {
  const auto it = std::find(f.columns.begin(), f.columns.end(), name);
  if (it == f.columns.end()) {
    throw std::runtime_error("no column " + name);
  }
  return static_cast<std::size_t>(it - f.columns.begin());
}

}  // namespace slipwalk::test_support
