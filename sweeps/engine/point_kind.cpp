#include "sweeps/engine/point_kind.hpp"

namespace slipwalk::sweeps {

const PointKind* find_point_kind(std::span<const PointKind> kinds, std::string_view name) {
  for (const PointKind& k : kinds) {
    if (k.name == name) {
      return &k;
    }
  }
  return nullptr;
}

std::string point_kind_names(std::span<const PointKind> kinds) {
  std::string out;
  for (const PointKind& k : kinds) {
    out.append(out.empty() ? "" : "|").append(k.name);
  }
  return out;
}

nlohmann::json kinds_to_json(std::span<const PointKind> kinds) {
  nlohmann::json out = nlohmann::json::array();
  for (const PointKind& k : kinds) {
    nlohmann::json columns = nlohmann::json::array();
    for (const ColumnInfo& c : k.columns) {
      columns.push_back({{"name", c.name}, {"unit", c.unit}, {"timing", c.timing}});
    }
    out.push_back({{"name", k.name},
                   {"summary", k.summary},
                   {"timed", k.timed == Timed::kYes},
                   {"columns", columns}});
  }
  return out;
}

std::string kinds_to_text(std::span<const PointKind> kinds) {
  std::string out;
  for (const PointKind& k : kinds) {
    out.append(k.name).append(k.timed == Timed::kYes ? " (timed)" : "").append("\n  ");
    out.append(k.summary).append("\n  columns:");
    for (const ColumnInfo& c : k.columns) {
      out.append(" ").append(c.name);
      if (!c.unit.empty() || c.timing) {
        out.append(" [").append(c.unit);
        out.append(c.timing ? (c.unit.empty() ? "timing" : ", timing") : "").append("]");
      }
    }
    out.append("\n");
  }
  return out;
}

}  // namespace slipwalk::sweeps
