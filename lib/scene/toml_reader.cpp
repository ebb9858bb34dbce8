#include "scene/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::scene {

namespace {

std::string quoted_list(const std::vector<std::string_view>& words) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) {
    out.append(i == 0 ? "" : ", ").append(words[i]);
  }
  return out;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // One row of the dynamic program: row[j] = distance(a[0, i), b[0, j)).
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string_view nearest(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (std::string_view c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

std::string owner_phrase(const std::vector<std::string_view>& names, std::string_view noun) {
  std::string out = "the ";
  for (std::size_t i = 0; i < names.size(); ++i) {
    out.append(i == 0 ? "" : i + 1 == names.size() ? " and " : ", ").append(names[i]);
  }
  out.append(" ").append(noun);
  return out.append(names.size() > 1 ? "s" : "");
}

std::string origin_of(const toml::source_region& region, const std::string& path) {
  const auto line = std::max<toml::source_index>(region.begin.line, 1);
  const auto column = std::max<toml::source_index>(region.begin.column, 1);
  std::string out = path;
  out.append(":").append(std::to_string(line)).append(":").append(std::to_string(column));
  return out;
}

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date or time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

TableReader::TableReader(const toml::table& table, const TableSchema& schema,
                         const std::string& path, const std::vector<TableSchema>& all)
    : table_(table), schema_(schema), path_(path) {
  for (auto&& [k, v] : table_) {
    const std::string_view key = k.str();
    if (std::find(schema_.keys.begin(), schema_.keys.end(), key) != schema_.keys.end()) {
      continue;
    }
    std::string what = "unknown key '";
    what.append(key).append("' in [").append(schema_.name).append("]");
    if (const std::string_view guess = nearest(key, schema_.keys); !guess.empty()) {
      what.append("; did you mean '").append(guess).append("'?");
    } else {
      for (const TableSchema& other : all) {
        if (std::find(other.keys.begin(), other.keys.end(), key) != other.keys.end()) {
          what.append("; it belongs in [").append(other.name).append("]");
          break;
        }
      }
    }
    what.append(" (valid: ").append(quoted_list(schema_.keys)).append(")");
    throw core::InputError(origin_of(k.source(), path_), what);
  }
}

const toml::node* TableReader::find(std::string_view key) const { return table_.get(key); }

const toml::node& TableReader::required(std::string_view key) const {
  const toml::node* node = find(key);
  if (node == nullptr) {
    std::string what = "missing required key '";
    what.append(key).append("' in [").append(schema_.name).append("]");
    throw core::InputError(origin(), what);
  }
  return *node;
}

std::string TableReader::where(std::string_view key) const {
  std::string out(schema_.name);
  out.append(".").append(key);
  return out;
}

double TableReader::number(const toml::node& node, std::string_view key) const {
  double value = 0.0;
  if (const auto* i = node.as_integer()) {
    value = static_cast<double>(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    value = f->get();
  } else {
    check(false, node, key, std::string("expected a number, got ") + type_name(node));
  }
  check(std::isfinite(value), node, key, "must be finite, got " + core::format_double(value));
  return value;
}

double TableReader::number_in(const toml::node& node, std::string_view key,
                              const core::Range& range) const {
  double value = 0.0;
  if (const auto* i = node.as_integer()) {
    value = static_cast<double>(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    value = f->get();
  } else {
    fail(node, key, std::string("expected a number, got ") + type_name(node));
  }
  check(range.contains(value), node, key,
        "must be in " + range.describe() + ", got " + core::format_double(value));
  return value;
}

void TableReader::read_in(std::string_view key, const core::Range& range, double& value) const {
  if (const toml::node* n = find(key)) {
    value = number_in(*n, key, range);
  }
}

long long TableReader::integer(const toml::node& node, std::string_view key) const {
  const auto* i = node.as_integer();
  check(i != nullptr, node, key, std::string("expected an integer, got ") + type_name(node));
  return i->get();
}

std::string TableReader::choice(const toml::node& node, std::string_view key,
                                const std::vector<std::string_view>& choices) const {
  const auto* s = node.as_string();
  check(s != nullptr, node, key, std::string("expected a string, got ") + type_name(node));
  const std::string& value = s->get();
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    std::string what = "unknown value '";
    what.append(value).append("'");
    if (const std::string_view guess = nearest(value, choices); !guess.empty()) {
      what.append("; did you mean '").append(guess).append("'?");
    }
    what.append(" (valid: ").append(quoted_list(choices)).append(")");
    check(false, node, key, what);
  }
  return value;
}

void TableReader::check(bool ok, const toml::node& node, std::string_view key,
                        const std::string& what) const {
  if (!ok) {
    std::string message = where(key);
    message.append(": ").append(what);
    throw core::InputError(origin(node), message);
  }
}

void TableReader::fail(const toml::node& node, std::string_view key,
                       const std::string& what) const {
  std::string message = where(key);
  message.append(": ").append(what);
  throw core::InputError(origin(node), message);
}

void TableReader::forbid(std::string_view key, std::string_view owner,
                         std::string_view chosen) const {
  if (const toml::node* node = find(key)) {
    std::string what = "a parameter of ";
    what.append(owner).append(", given with ").append(chosen);
    check(false, *node, key, what);
  }
}

std::string TableReader::origin(const toml::node& node) const {
  return origin_of(node.source(), path_);
}

std::string TableReader::origin() const { return origin_of(table_.source(), path_); }

const TableSchema& schema_table(const std::vector<TableSchema>& schema, std::string_view name) {
  for (const TableSchema& t : schema) {
    if (t.name == name) {
      return t;
    }
  }
  throw std::logic_error("no schema for the table [" + std::string(name) + "]");
}

void check_top_level(const toml::table& doc, const std::string& path,
                     const std::vector<TableSchema>& schema) {
  std::vector<std::string_view> names;
  names.reserve(schema.size());
  for (const TableSchema& t : schema) {
    names.push_back(t.name);
  }
  for (auto&& [k, v] : doc) {
    const std::string_view key = k.str();
    const bool known = std::find(names.begin(), names.end(), key) != names.end();
    if (known && v.is_table()) {
      continue;
    }
    std::string what;
    if (known) {
      what.append("expected a table [").append(key).append("], got ").append(type_name(v));
    } else if (v.is_table()) {
      what.append("unknown table [").append(key).append("]");
      if (const std::string_view guess = nearest(key, names); !guess.empty()) {
        what.append("; did you mean [").append(guess).append("]?");
      }
    } else {
      what.append("unknown key '").append(key).append("' at the top level");
      for (const TableSchema& t : schema) {
        if (std::find(t.keys.begin(), t.keys.end(), key) != t.keys.end()) {
          what.append("; it belongs in [").append(t.name).append("]");
          break;
        }
      }
    }
    what.append(" (tables: ");
    for (std::size_t i = 0; i < names.size(); ++i) {
      what.append(i == 0 ? "" : ", ").append(names[i]);
    }
    what.append(")");
    throw core::InputError(origin_of(k.source(), path), what);
  }
}

}  // namespace slipwalk::scene
