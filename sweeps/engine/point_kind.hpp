#pragma once
// Point kinds: what a sweep computes at one point. A spec's `kind` names one of them.
//
// A kind's rows are a plain struct (one member per output column) whose column table — name,
// unit, whether the column is a timing, and the member it reads — is a static `columns()`
// function next to the members:
//
//   struct VssRow {
//     long long id = 0;
//     double v_ss = 0.0;
//     double wall_s = 0.0;
//     static std::vector<Column<VssRow>> columns() {
//       return {value("id", &VssRow::id), value("v_ss", &VssRow::v_ss, "m/s"),
//               timing("wall_s", &VssRow::wall_s, "s")};
//     }
//   };
//
// The CSV header, every row's cells and the runner's timing flags are all read off that one
// table, so they cannot drift apart: reordering the members changes nothing, reordering the
// table reorders header and cells together. The first column is always `id`. Repeated groups
// (a column per leg) are built in a loop over an array member with value_at().
//
// A kind also has a check that validates a point's inputs (throws core::InputError naming the
// spec file:line:col and the key; the runner checks every point before it runs any, so a bad
// spec writes nothing) and a run that returns the point's rows. A run never throws for numerical
// trouble: the rows say what happened and `failed` marks the point, which is counted in the
// sidecar and does not stop the sweep. A point that stops at a budget (a step, stroke or
// iteration cap) is marked `at_budget`, its rows saying where it stopped (a status column); the
// spec says whether that is a failure (the default) or a designed outcome of its study
// (`budget_stops = "expected"`, Spec::budget_stops_expected), counted apart from the failures. A
// kind that measures time is `timed`: the runner runs its points one at a time, process-wide, so no
// two timed points share the machine's cores.
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {

using Cell = std::variant<double, long long, std::string>;
using Cells = std::vector<Cell>;

/// A member's value as a CSV cell: a floating-point number, an integer (a bool as 0 or 1) or a
/// text.
template <class T>
[[nodiscard]] Cell to_cell(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return static_cast<long long>(v ? 1 : 0);
  } else if constexpr (std::is_floating_point_v<T>) {
    return static_cast<double>(v);
  } else if constexpr (std::is_integral_v<T>) {
    return static_cast<long long>(v);
  } else {
    static_assert(std::is_convertible_v<T, std::string>, "a column holds a number or a text");
    return std::string(v);
  }
}

/// One output column of a row type: its name (the CSV header), unit ("" when dimensionless or a
/// label), whether it holds a measured time (written as 0 under --no-timing), and how to read it.
template <class Row>
struct Column {
  std::string name;
  std::string unit;
  bool timing = false;
  std::function<Cell(const Row&)> cell;
};

/// A value column reading a member.
template <class Row, class T>
[[nodiscard]] Column<Row> value(std::string name, T Row::*member, std::string unit = "") {
  return {std::move(name), std::move(unit), false,
          [member](const Row& r) { return to_cell(r.*member); }};
}
/// A value column reading element `index` of an array member (one of a repeated group).
template <class Row, class T, std::size_t N>
[[nodiscard]] Column<Row> value_at(std::string name, std::array<T, N> Row::*member,
                                   std::size_t index, std::string unit = "") {
  if (index >= N) {
    throw std::logic_error("column " + name + ": index past its array");
  }
  return {std::move(name), std::move(unit), false,
          [member, index](const Row& r) { return to_cell((r.*member)[index]); }};
}
/// A column that holds a measured time, or a number computed from measured times.
template <class Row, class T>
[[nodiscard]] Column<Row> timing(std::string name, T Row::*member, std::string unit = "s") {
  return {std::move(name), std::move(unit), true,
          [member](const Row& r) { return to_cell(r.*member); }};
}

/// A column as the runner and the sidecar see it.
struct ColumnInfo {
  std::string name;
  std::string unit;
  bool timing = false;
};

/// A point's rows as typed by its kind, with the point's outcome.
template <class Row>
struct Rows {
  std::vector<Row> rows;
  bool failed = false;     ///< something went wrong that should not have (a failure)
  bool at_budget = false;  ///< not failed: it stopped at a budget (a step or iteration cap)
  std::string message;     ///< why it failed or which budget it reached (empty otherwise)
};

/// A point's rows as cells, in the order of the kind's columns.
struct PointResult {
  std::vector<Cells> rows;
  bool failed = false;     ///< something went wrong that should not have (a failure)
  bool at_budget = false;  ///< not failed: it stopped at a budget (a step or iteration cap)
  std::string message;     ///< why it failed or which budget it reached (empty otherwise)
};

/// Whether a kind's points measure time (and so run one at a time, process-wide).
enum class Timed { kNo, kYes };

struct PointKind {
  std::string name;
  std::string summary;
  std::vector<ColumnInfo> columns;
  Timed timed = Timed::kNo;
  std::function<void(const Point&)> check;       ///< throws core::InputError
  std::function<PointResult(const Point&)> run;  ///< for a checked point

  [[nodiscard]] std::vector<std::string> column_names() const {
    std::vector<std::string> out;
    out.reserve(columns.size());
    for (const ColumnInfo& c : columns) {
      out.push_back(c.name);
    }
    return out;
  }
};

/// A row's cells in the order of its column table.
template <class Row>
[[nodiscard]] Cells cells_of(const Row& row, const std::vector<Column<Row>>& table) {
  Cells out;
  out.reserve(table.size());
  for (const Column<Row>& c : table) {
    out.push_back(c.cell(row));
  }
  return out;
}

/// A point kind whose rows are `Row`: header, cells and timing flags from Row::columns().
template <class Row>
[[nodiscard]] PointKind make_point_kind(std::string name, std::string summary, Timed timed,
                                        std::function<void(const Point&)> check,
                                        std::function<Rows<Row>(const Point&)> run) {
  auto table = std::make_shared<const std::vector<Column<Row>>>(Row::columns());
  if (table->empty() || table->front().name != "id") {
    throw std::logic_error("point kind " + name + ": the first column must be `id`");
  }
  PointKind kind;
  kind.name = std::move(name);
  kind.summary = std::move(summary);
  for (const Column<Row>& c : *table) {
    kind.columns.push_back({c.name, c.unit, c.timing});
  }
  kind.timed = timed;
  kind.check = std::move(check);
  kind.run = [table, typed = std::move(run)](const Point& point) {
    Rows<Row> r = typed(point);
    PointResult out;
    out.rows.reserve(r.rows.size());
    for (const Row& row : r.rows) {
      out.rows.push_back(cells_of(row, *table));
    }
    out.failed = r.failed;
    out.at_budget = r.at_budget && !r.failed;
    out.message = std::move(r.message);
    return out;
  };
  return kind;
}

/// The kind of this name among `kinds`; nullptr if none.
[[nodiscard]] const PointKind* find_point_kind(std::span<const PointKind> kinds,
                                               std::string_view name);
/// "inchworm_vss|inchworm_convergence|...", for messages.
[[nodiscard]] std::string point_kind_names(std::span<const PointKind> kinds);

/// The kinds as a user reads them (`slipwalk kinds --json`): an array of {"name", "summary",
/// "timed", "columns": [{"name", "unit", "timing"}, ...]} in the order given.
[[nodiscard]] nlohmann::json kinds_to_json(std::span<const PointKind> kinds);
/// The same as text: per kind its name, summary and columns ("v_ss [m/s]", "wall_s [s, timing]").
[[nodiscard]] std::string kinds_to_text(std::span<const PointKind> kinds);

}  // namespace slipwalk::sweeps
