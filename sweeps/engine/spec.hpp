#pragma once
// A sweep spec (TOML, sweeps/README.md) and its expansion into points.
//
// A spec names a study (output folder), a name (output file stem) and a kind (the point kind,
// point_functions.hpp). Its points are the union of blocks; each block is the cartesian product of
// its explicit [[points]] (slowest) and its axes in the order they are written in the file (the
// first axis slowest). Every value remembers where in the file it came from, so a point kind
// can report a bad value as `file:line:col`.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace slipwalk::sweeps {

/// One named input of a point: a number or a text, and where in the spec it came from.
struct Value {
  std::variant<double, std::string> value;
  bool integer = false;  ///< written as a TOML integer (point kinds may require one)
  std::string origin;    ///< "file:line:col" of the TOML node it came from

  [[nodiscard]] bool is_number() const { return std::holds_alternative<double>(value); }
  [[nodiscard]] double number() const { return std::get<double>(value); }
  [[nodiscard]] const std::string& text() const { return std::get<std::string>(value); }
  /// The value as written in a message: 17 significant digits or the text in quotes.
  [[nodiscard]] std::string repr() const;
  [[nodiscard]] nlohmann::json to_json() const;
};

using NamedValues = std::vector<std::pair<std::string, Value>>;

/// One point of a sweep: its id (product order) and every named input.
struct Point {
  long long id = 0;
  std::string source;  ///< the spec file, for errors about keys that are absent
  NamedValues values;  ///< params, then the explicit point's keys, then the axes

  [[nodiscard]] const Value* find(std::string_view key) const;
  [[nodiscard]] nlohmann::json to_json() const;  ///< {"id": .., key: value, ...}
};

struct Axis {
  std::string key;
  std::vector<Value> values;
  std::string origin;
};

/// One product: explicit points (none = one empty point) × axes.
struct Block {
  NamedValues params;               ///< this block's fixed values over the spec's [params]
  std::vector<NamedValues> points;  ///< [[points]] / [[block.points]]
  std::vector<Axis> axes;           ///< in file order, first = slowest
  std::string origin;
  [[nodiscard]] std::size_t size() const;
};

/// Which size of a spec runs: its own values (the default: what the study's claims need), its
/// [quick] overrides (a smoke run, `--quick`) or its [full] overrides (the study's long version,
/// `--full`). Both override sections have one grammar (sweeps/README.md).
enum class Variant { kDefault, kQuick, kFull };
/// "default", "quick", "full": the sidecar's `variant`.
[[nodiscard]] const char* variant_name(Variant v);
/// The variant two command-line flags select (--quick wins; the front ends refuse both).
[[nodiscard]] inline Variant variant_of(bool quick, bool full) {
  return quick ? Variant::kQuick : (full ? Variant::kFull : Variant::kDefault);
}

/// A size of the spec that is not run, kept for prepare() to check (a bad value is bad input
/// whichever size runs).
struct OtherVariant {
  Variant variant = Variant::kDefault;
  NamedValues params;
  std::vector<Block> blocks;
};

struct Spec {
  std::string path;  ///< the file as named by the user (error messages use it)
  std::string study;
  std::string name;
  std::string kind;
  std::string kind_origin;
  std::string description;
  Variant variant = Variant::kDefault;  ///< the size run (its overrides applied)
  /// `budget_stops = "expected"`: a point that stops at a budget (PointResult::at_budget) is a
  /// designed outcome of this study, counted apart; "failures" (the default): it is a failure.
  bool budget_stops_expected = false;
  nlohmann::json source;  ///< the whole file as JSON (before any overrides)
  NamedValues params;     ///< [params] (the variant's params applied)
  std::vector<Block> blocks;
  /// The sizes of the spec that are not run: the default's and each override section's but the
  /// one run. prepare() checks their points too, so that a bad value is refused before anything
  /// runs whichever size is run, including a value that --quick or --full overrides.
  std::vector<OtherVariant> others;

  [[nodiscard]] bool quick() const { return variant == Variant::kQuick; }
};

/// Largest number of points a spec may expand to.
inline constexpr std::size_t kMaxPoints = 10'000'000;

/// Reads and parses a spec file, its `variant` applied. Throws core::InputError (`file:line:col`)
/// for a malformed file, an unknown key, a bad axis or an override that names no axis. A spec
/// without the variant's section runs its default values.
[[nodiscard]] Spec load_spec(const std::filesystem::path& path, Variant variant);
[[nodiscard]] inline Spec load_spec(const std::filesystem::path& path, bool quick = false) {
  return load_spec(path, quick ? Variant::kQuick : Variant::kDefault);
}
/// The same from text; `path` labels the errors.
[[nodiscard]] Spec parse_spec(std::string_view text, const std::string& path, Variant variant);
[[nodiscard]] inline Spec parse_spec(std::string_view text, const std::string& path,
                                     bool quick = false) {
  return parse_spec(text, path, quick ? Variant::kQuick : Variant::kDefault);
}

[[nodiscard]] std::size_t point_count(const Spec& spec);
/// Every point in product order, ids 0, 1, 2, ...
[[nodiscard]] std::vector<Point> expand(const Spec& spec);
/// The points of a size not run (one of Spec::others), in product order.
[[nodiscard]] std::vector<Point> expand_other(const Spec& spec, const OtherVariant& other);

/// Axis helpers (exact endpoints): n values from a to b, evenly / geometrically spaced.
[[nodiscard]] std::vector<double> linspace(double a, double b, long long n);
[[nodiscard]] std::vector<double> logspace(double a, double b, long long n);

}  // namespace slipwalk::sweeps
