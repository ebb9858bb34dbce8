#include "sweeps/engine/spec.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/toml_input.hpp"
#include "sweeps/engine/toml_util.hpp"

namespace slipwalk::sweeps {

namespace {

using core::InputError;

bool before(const toml::source_region& a, const toml::source_region& b) {
  return a.begin.line != b.begin.line ? a.begin.line < b.begin.line
                                      : a.begin.column < b.begin.column;
}

/// The keys of a table in the order they are written in the file (toml++ iterates by name).
std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(const toml::table& t) {
  std::vector<std::pair<const toml::key*, const toml::node*>> out;
  for (auto&& [k, v] : t) {
    out.emplace_back(&k, &v);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return before(a.first->source(), b.first->source());
  });
  return out;
}

/// A number or a text (the only value types a point takes).
Value parse_value(const std::string& key, const toml::node& node, const std::string& path) {
  Value v;
  v.origin = origin_of(node.source(), path);
  if (const auto* i = node.as_integer()) {
    v.value = static_cast<double>(i->get());
    v.integer = true;
  } else if (const auto* f = node.as_floating_point()) {
    if (!std::isfinite(f->get())) {
      throw InputError(v.origin,
                       key + ": must be a finite number, got " + core::format_double(f->get()));
    }
    v.value = f->get();
  } else if (const auto* s = node.as_string()) {
    v.value = s->get();
  } else {
    throw InputError(v.origin, key + ": expected a number or a string");
  }
  return v;
}

NamedValues parse_named(const toml::node& node, const std::string& what, const std::string& path) {
  const auto* t = node.as_table();
  if (t == nullptr) {
    throw InputError(origin_of(node.source(), path), what + ": expected a table of values");
  }
  NamedValues out;
  for (const auto& [k, v] : in_file_order(*t)) {
    out.emplace_back(std::string(k->str()), parse_value(std::string(k->str()), *v, path));
  }
  return out;
}

double range_end(const toml::node& node, const std::string& what, const std::string& path) {
  const auto number = node.value<double>();
  if (!number || !std::isfinite(*number)) {
    throw InputError(origin_of(node.source(), path), what + ": expected a finite number");
  }
  return *number;
}

Axis parse_axis(const std::string& key, const toml::node& node, const std::string& path) {
  Axis axis;
  axis.key = key;
  axis.origin = origin_of(node.source(), path);
  const std::string what = "axis " + key;
  if (const auto* a = node.as_array()) {
    if (a->empty()) {
      throw InputError(axis.origin, what + ": the list is empty");
    }
    for (const auto& element : *a) {
      axis.values.push_back(parse_value(key, element, path));
      if (axis.values.back().is_number() != axis.values.front().is_number()) {
        throw InputError(axis.values.back().origin, what + ": a list mixes numbers and strings");
      }
    }
    return axis;
  }
  const auto* t = node.as_table();
  const char* expected =
      ": expected a list of numbers, a list of strings, { linspace = [a, b], n = N } or "
      "{ logspace = [a, b], n = N }";
  if (t == nullptr) {
    throw InputError(axis.origin, what + expected);
  }
  const toml::node* range = nullptr;
  const toml::node* count = nullptr;
  bool geometric = false;
  for (auto&& [k, v] : *t) {
    if (k == "linspace" || k == "logspace") {
      if (range != nullptr) {
        throw InputError(origin_of(k.source(), path), what + ": both linspace and logspace");
      }
      range = &v;
      geometric = k == "logspace";
    } else if (k == "n") {
      count = &v;
    } else {
      throw InputError(origin_of(k.source(), path),
                       what + ": unknown key '" + std::string(k.str()) + "'" + expected);
    }
  }
  if (range == nullptr || count == nullptr) {
    throw InputError(axis.origin, what + expected);
  }
  const auto* ends = range->as_array();
  if (ends == nullptr || ends->size() != 2) {
    throw InputError(origin_of(range->source(), path), what + ": expected [a, b]");
  }
  const double a = range_end(*ends->get(0), what, path);
  const double b = range_end(*ends->get(1), what, path);
  const auto* n = count->as_integer();
  if (n == nullptr || n->get() < 1 || n->get() > static_cast<long long>(kMaxPoints)) {
    throw InputError(origin_of(count->source(), path),
                     what + ": n must be an integer from 1 to " + std::to_string(kMaxPoints));
  }
  if (geometric && !(a > 0.0 && b > 0.0)) {
    throw InputError(origin_of(range->source(), path),
                     what + ": logspace needs positive ends, got [" + core::format_double(a) +
                         ", " + core::format_double(b) + "]");
  }
  const std::vector<double> values =
      geometric ? logspace(a, b, n->get()) : linspace(a, b, n->get());
  for (double x : values) {
    axis.values.push_back(Value{x, false, axis.origin});
  }
  return axis;
}

std::vector<Axis> parse_axes(const toml::node& node, const std::string& path) {
  const auto* t = node.as_table();
  if (t == nullptr) {
    throw InputError(origin_of(node.source(), path), "axes: expected a table");
  }
  std::vector<Axis> axes;
  for (const auto& [k, v] : in_file_order(*t)) {
    axes.push_back(parse_axis(std::string(k->str()), *v, path));
  }
  return axes;
}

std::vector<NamedValues> parse_points(const toml::node& node, const std::string& path) {
  const auto* a = node.as_array();
  if (a == nullptr || !a->is_array_of_tables()) {
    throw InputError(origin_of(node.source(), path),
                     "points: expected an array of tables ([[points]])");
  }
  std::vector<NamedValues> points;
  for (const auto& p : *a) {
    points.push_back(parse_named(p, "points", path));
  }
  if (points.empty()) {
    throw InputError(origin_of(node.source(), path), "points: the list is empty");
  }
  return points;
}

bool has_key(const NamedValues& values, std::string_view key) {
  return std::any_of(values.begin(), values.end(), [&](const auto& kv) { return kv.first == key; });
}

/// Sets key = value, replacing an earlier value (which moves to the end).
void put(NamedValues& values, const std::string& key, const Value& value) {
  std::erase_if(values, [&](const auto& kv) { return kv.first == key; });
  values.emplace_back(key, value);
}

const Axis* find_axis(const Block& b, std::string_view key) {
  for (const auto& a : b.axes) {
    if (a.key == key) {
      return &a;
    }
  }
  return nullptr;
}

void check_block(const Block& b) {
  for (const auto& point : b.points) {
    for (const auto& [key, value] : point) {
      if (const Axis* axis = find_axis(b, key)) {
        throw InputError(value.origin,
                         "'" + key + "' is both an axis (" + axis->origin + ") and a point key");
      }
    }
  }
}

/// One block from a table holding params/axes/points (the top level or a [[block]]).
Block parse_block(const toml::table& t, const std::string& path, bool top_level) {
  Block b;
  b.origin = origin_of(t.source(), path);
  for (auto&& [k, v] : t) {
    if (k == "axes") {
      b.axes = parse_axes(v, path);
    } else if (k == "points") {
      b.points = parse_points(v, path);
    } else if (k == "params" && !top_level) {
      b.params = parse_named(v, "block.params", path);
    } else if (!top_level) {
      throw InputError(origin_of(k.source(), path),
                       "unknown key '" + std::string(k.str()) +
                           "' in a [[block]]; expected params, axes, points");
    }
  }
  check_block(b);
  return b;
}

std::string text_key(const toml::table& t, std::string_view key, const std::string& path,
                     bool required, std::string* origin = nullptr) {
  const toml::node* node = t.get(key);
  if (node == nullptr) {
    if (required) {
      throw InputError(path, "missing required key '" + std::string(key) + "'");
    }
    return {};
  }
  const auto* s = node->as_string();
  if (s == nullptr) {
    throw InputError(origin_of(node->source(), path), std::string(key) + ": expected a string");
  }
  if (origin != nullptr) {
    *origin = origin_of(node->source(), path);
  }
  return s->get();
}

void check_file_name(const std::string& value, const char* key, const toml::node& node,
                     const std::string& path) {
  // A name becomes a file or folder name (with ".csv.tmp.<pid>" appended): at most 100 bytes
  // keeps it well inside NAME_MAX (255) on every file system we write to.
  constexpr std::size_t kMaxName = 100;
  if (value.size() > kMaxName) {
    throw InputError(origin_of(node.source(), path),
                     std::string(key) + ": a name of " + std::to_string(value.size()) +
                         " bytes; at most " + std::to_string(kMaxName));
  }
  const bool ok =
      !value.empty() && value.front() != '.' && std::all_of(value.begin(), value.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!ok) {
    throw InputError(
        origin_of(node.source(), path),
        std::string(key) + ": '" + value + "' is not a plain file name (letters, digits, _ - .)");
  }
}

/// Applies an override section ([quick] or [full], named `section`) to `spec`.
void apply_overrides(Spec& spec, const toml::node& node, const std::string& section,
                     const std::string& path, int top_block) {
  const auto* t = node.as_table();
  if (t == nullptr) {
    throw InputError(origin_of(node.source(), path), section + ": expected a table");
  }
  for (auto&& [k, v] : *t) {
    if (k == "params") {
      for (const auto& named : parse_named(v, section + ".params", path)) {
        const auto& key = named.first;  // a plain reference: lambdas may not capture bindings
        const auto& value = named.second;
        for (const Block& b : spec.blocks) {
          const bool in_points = std::any_of(b.points.begin(), b.points.end(),
                                             [&](const auto& p) { return has_key(p, key); });
          if (find_axis(b, key) != nullptr || in_points) {
            std::string what = section + ".params.";
            what.append(key).append(": an axis or point key; override it in ");
            throw InputError(value.origin, what.append(section).append(".axes"));
          }
        }
        put(spec.params, key, value);
        for (Block& b : spec.blocks) {
          if (has_key(b.params, key)) {
            put(b.params, key, value);
          }
        }
      }
    } else if (k == "axes") {
      for (const Axis& axis : parse_axes(v, path)) {
        bool replaced = false;
        for (Block& b : spec.blocks) {
          for (Axis& a : b.axes) {
            if (a.key == axis.key) {
              a = axis;
              replaced = true;
            }
          }
        }
        if (!replaced) {
          throw InputError(axis.origin, section + ".axes." + axis.key + ": the spec has no axis '" +
                                            axis.key + "'");
        }
      }
    } else if (k == "points") {
      if (top_block < 0) {
        throw InputError(origin_of(v.source(), path),
                         section + ".points: the spec has no top-level [axes] or [[points]]");
      }
      spec.blocks[static_cast<std::size_t>(top_block)].points = parse_points(v, path);
      check_block(spec.blocks[static_cast<std::size_t>(top_block)]);
    } else {
      std::string what = "unknown key '" + section;
      what.append(".").append(k.str()).append("'; expected ").append(section);
      what.append(".params, ").append(section).append(".axes, ").append(section);
      throw InputError(origin_of(k.source(), path), what.append(".points"));
    }
  }
}

std::size_t blocks_size(const std::vector<Block>& blocks) {
  std::size_t n = 0;
  for (const Block& b : blocks) {
    n += b.size();
    if (n > kMaxPoints) {
      return kMaxPoints + 1;
    }
  }
  return n;
}

/// Every point of `blocks` over `params`, in product order, ids 0, 1, 2, ...
std::vector<Point> expand_blocks(const NamedValues& params, const std::vector<Block>& blocks,
                                 const std::string& path) {
  std::vector<Point> out;
  out.reserve(blocks_size(blocks));
  long long id = 0;
  for (const Block& b : blocks) {
    NamedValues base = params;
    for (const auto& [k, v] : b.params) {
      put(base, k, v);
    }
    const std::vector<NamedValues> explicit_points =
        b.points.empty() ? std::vector<NamedValues>(1) : b.points;
    for (const NamedValues& p : explicit_points) {
      NamedValues with_point = base;
      for (const auto& [k, v] : p) {
        put(with_point, k, v);
      }
      // Mixed radix over the axes, the last axis fastest.
      std::size_t combinations = 1;
      for (const Axis& a : b.axes) {
        combinations *= a.values.size();
      }
      std::vector<std::size_t> index(b.axes.size(), 0);
      for (std::size_t c = 0; c < combinations; ++c) {
        std::size_t rest = c;
        for (std::size_t a = b.axes.size(); a-- > 0;) {
          index[a] = rest % b.axes[a].values.size();
          rest /= b.axes[a].values.size();
        }
        Point point;
        point.id = id++;
        point.source = path;
        point.values = with_point;
        for (std::size_t a = 0; a < b.axes.size(); ++a) {
          put(point.values, b.axes[a].key, b.axes[a].values[index[a]]);
        }
        out.push_back(std::move(point));
      }
    }
  }
  return out;
}

}  // namespace

std::string Value::repr() const {
  return is_number() ? core::format_double(number()) : "'" + text() + "'";
}

nlohmann::json Value::to_json() const {
  if (!is_number()) {
    return text();
  }
  if (integer) {
    return static_cast<long long>(number());
  }
  return number();
}

const Value* Point::find(std::string_view key) const {
  for (const auto& [k, v] : values) {
    if (k == key) {
      return &v;
    }
  }
  return nullptr;
}

nlohmann::json Point::to_json() const {
  nlohmann::json out = nlohmann::json::object();
  out["id"] = id;
  for (const auto& [k, v] : values) {
    out[k] = v.to_json();
  }
  return out;
}

std::size_t Block::size() const {
  std::size_t n = points.empty() ? 1 : points.size();
  for (const Axis& a : axes) {
    if (a.values.size() > kMaxPoints / std::max<std::size_t>(n, 1)) {
      return kMaxPoints + 1;
    }
    n *= a.values.size();
  }
  return n;
}

std::vector<double> linspace(double a, double b, long long n) {
  std::vector<double> out;
  if (n == 1) {
    out.push_back(a);
    return out;
  }
  // numpy.linspace: a + i·step, the last value set to b exactly.
  const double step = (b - a) / static_cast<double>(n - 1);
  for (long long i = 0; i < n; ++i) {
    out.push_back(i == n - 1 ? b : a + static_cast<double>(i) * step);
  }
  return out;
}

std::vector<double> logspace(double a, double b, long long n) {
  std::vector<double> out;
  if (n == 1) {
    out.push_back(a);
    return out;
  }
  // numpy.geomspace: 10^(log10 a + i·step), both ends set exactly.
  const double la = std::log10(a);
  const double step = (std::log10(b) - la) / static_cast<double>(n - 1);
  for (long long i = 0; i < n; ++i) {
    out.push_back(i == 0 ? a : i == n - 1 ? b : std::pow(10.0, la + static_cast<double>(i) * step));
  }
  return out;
}

const char* variant_name(Variant v) {
  switch (v) {
    case Variant::kQuick:
      return "quick";
    case Variant::kFull:
      return "full";
    case Variant::kDefault:
      break;
  }
  return "default";
}

Spec parse_spec(std::string_view text, const std::string& path, Variant variant) {
  const toml::table doc = core::parse_toml(text, path);
  Spec spec;
  spec.path = path;
  spec.source = toml_to_json(doc);
  spec.study = text_key(doc, "study", path, true);
  check_file_name(spec.study, "study", *doc.get("study"), path);
  spec.name = text_key(doc, "name", path, true);
  check_file_name(spec.name, "name", *doc.get("name"), path);
  spec.kind = text_key(doc, "kind", path, true, &spec.kind_origin);
  spec.description = text_key(doc, "description", path, false);
  if (doc.contains("budget_stops")) {
    const std::string stops = text_key(doc, "budget_stops", path, true);
    if (stops != "expected" && stops != "failures") {
      throw InputError(
          origin_of(doc.get("budget_stops")->source(), path),
          "budget_stops: expected \"expected\" or \"failures\", got \"" + stops + "\"");
    }
    spec.budget_stops_expected = stops == "expected";
  }

  int top_block = -1;
  const toml::node* quick_node = nullptr;
  const toml::node* full_node = nullptr;
  for (auto&& [k, v] : doc) {
    if (k == "study" || k == "name" || k == "kind" || k == "description" || k == "axes" ||
        k == "points" || k == "budget_stops") {
      continue;
    }
    if (k == "params") {
      spec.params = parse_named(v, "params", path);
    } else if (k == "quick") {
      quick_node = &v;
    } else if (k == "full") {
      full_node = &v;
    } else if (k == "block") {
      const auto* blocks = v.as_array();
      if (blocks == nullptr || !blocks->is_array_of_tables()) {
        throw InputError(origin_of(v.source(), path), "block: expected [[block]] tables");
      }
      for (const auto& b : *blocks) {
        spec.blocks.push_back(parse_block(*b.as_table(), path, false));
      }
    } else {
      throw InputError(origin_of(k.source(), path),
                       "unknown key '" + std::string(k.str()) +
                           "'; expected study, name, kind, description, budget_stops, params, "
                           "axes, points, block, quick, full");
    }
  }
  // The top-level axes/points form the first block; a spec with neither and no [[block]] has
  // one point made of its params.
  if (doc.contains("axes") || doc.contains("points") || spec.blocks.empty()) {
    spec.blocks.insert(spec.blocks.begin(), parse_block(doc, path, true));
    top_block = 0;
  }
  // Every size is kept: the one run, and the others for prepare() to check (a bad [quick] or
  // [full] section is an error in every run, and so is a bad value an override replaces).
  std::vector<Spec> sizes;
  sizes.push_back(spec);
  sizes.back().variant = Variant::kDefault;
  for (const auto& [section, node, v] : {std::tuple{"quick", quick_node, Variant::kQuick},
                                         std::tuple{"full", full_node, Variant::kFull}}) {
    if (node != nullptr) {
      sizes.push_back(spec);
      sizes.back().variant = v;
      apply_overrides(sizes.back(), *node, section, path, top_block);
    }
  }
  std::size_t run = 0;  // a spec without the variant's section runs its default
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    run = sizes[i].variant == variant ? i : run;
  }
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (point_count(sizes[i]) > kMaxPoints) {
      throw InputError(
          path, "the spec expands to more than " + std::to_string(kMaxPoints) + " points" +
                    (i == 0 ? "" : std::string(" under [") + variant_name(sizes[i].variant) + "]"));
    }
  }
  Spec out = std::move(sizes[run]);
  out.variant = variant;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (i != run) {
      out.others.push_back(
          {sizes[i].variant, std::move(sizes[i].params), std::move(sizes[i].blocks)});
    }
  }
  return out;
}

Spec load_spec(const std::filesystem::path& path, Variant variant) {
  return parse_spec(core::read_input_file(path, "a sweep spec"), path.string(), variant);
}

std::size_t point_count(const Spec& spec) { return blocks_size(spec.blocks); }

std::vector<Point> expand(const Spec& spec) {
  return expand_blocks(spec.params, spec.blocks, spec.path);
}

std::vector<Point> expand_other(const Spec& spec, const OtherVariant& other) {
  return expand_blocks(other.params, other.blocks, spec.path);
}

}  // namespace slipwalk::sweeps
