#pragma once
// Shared by the tests of sweep point kinds: a spec's points from the body of a study file,
// a point kind by name, a column's index in its rows (throwing, so that a renamed column fails
// the test instead of reading past the row), the first difference between two runs of a point
// outside its timing columns, and the check that a kind refuses a parameter at its value.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/error.hpp"
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
  const std::vector<std::string> names = f.column_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    throw std::runtime_error("no column " + name);
  }
  return static_cast<std::size_t>(it - names.begin());
}

/// Whether two cells are the same to the bit (a NaN equals the same NaN).
inline bool same_cell(const sweeps::Cell& a, const sweeps::Cell& b) {
  if (a.index() != b.index()) {
    return false;
  }
  if (const auto* x = std::get_if<double>(&a)) {
    return std::bit_cast<std::uint64_t>(*x) == std::bit_cast<std::uint64_t>(std::get<double>(b));
  }
  return a == b;
}

/// "" if two results of a kind's point have the same rows in every column the kind does not flag
/// as a timing (so that the CSV under --no-timing is the same byte for byte); else where they
/// first differ.
inline std::string first_value_difference(const sweeps::PointKind& f, const sweeps::PointResult& a,
                                          const sweeps::PointResult& b) {
  if (a.rows.size() != b.rows.size()) {
    return "row counts " + std::to_string(a.rows.size()) + " and " + std::to_string(b.rows.size());
  }
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    for (std::size_t c = 0; c < f.columns.size(); ++c) {
      if (!f.columns[c].timing && !same_cell(a.rows[i].at(c), b.rows[i].at(c))) {
        return "row " + std::to_string(i) + ", column " + f.columns[c].name;
      }
    }
  }
  return "";
}

/// The kind's check refuses the last line of `params` (key = value) at that value's
/// file:line:col of the spec points_of makes, naming the key.
inline void expect_refused_at_last_line(const std::string& kind, const std::string& params) {
  const std::vector<sweeps::Point> pts = points_of(kind, "[params]\n" + params);
  const std::size_t lines =
      static_cast<std::size_t>(std::count(params.begin(), params.end(), '\n'));
  const std::size_t last = params.rfind('\n', params.size() - 2);
  const std::string line = params.substr(last == std::string::npos ? 0 : last + 1);
  const std::string key = line.substr(0, line.find(' '));
  // The spec: three header lines and [params], then params: its last line is 4 + lines.
  const std::string place =
      "peer.toml:" + std::to_string(4 + lines) + ":" + std::to_string(key.size() + 4);
  try {
    point_kind(kind).check(pts.at(0));
    ADD_FAILURE() << kind << " accepted: " << params;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), place) << e.what();
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

}  // namespace slipwalk::test_support
