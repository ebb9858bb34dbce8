#pragma once
// Reading TOML tables against a schema, with errors that name file:line:col (DESIGN.md): an
// unknown key (the nearest valid name suggested, or the table it belongs in), a wrong type, a
// value out of range, a missing required field, a parameter of an effect that is not chosen.
// Every error is a core::InputError; the scene reader (scene.cpp) is its first user, and a new
// table or effect extends the schema, not this reader.
#include <toml++/toml.h>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "core/range.hpp"

namespace slipwalk::scene {

/// A table of a file and the keys it may hold.
struct TableSchema {
  std::string_view name;               ///< e.g. "gait"
  std::vector<std::string_view> keys;  ///< every key valid in it
};

/// The table `name` of `schema`; throws std::logic_error when the schema has none (a bug).
[[nodiscard]] const TableSchema& schema_table(const std::vector<TableSchema>& schema,
                                              std::string_view name);

/// Checks that the top level of `doc` (read from `path`) holds only the tables of `schema`:
/// throws core::InputError at the offending key's file:line:col for a table named in the schema
/// that is not a table, an unknown table (the nearest name suggested) or a key at the top level
/// (the table it belongs in named), listing the schema's tables.
void check_top_level(const toml::table& doc, const std::string& path,
                     const std::vector<TableSchema>& schema);

/// The Levenshtein distance of two words (for "did you mean ...").
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate nearest to `word` if it is plausibly a misspelling (distance ≤ max(2, |word|/3)),
/// else empty.
[[nodiscard]] std::string_view nearest(std::string_view word,
                                       const std::vector<std::string_view>& candidates);

/// Whether `word` is one of `list` (the tables' key and owner lists are short).
[[nodiscard]] inline bool contains(const std::vector<std::string_view>& list,
                                   std::string_view word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

/// Who owns a key, for messages: "the tripod gait", "the tripod and trot gaits",
/// "the a, b and c gaits" (`names` in order, `noun` singular).
[[nodiscard]] std::string owner_phrase(const std::vector<std::string_view>& names,
                                       std::string_view noun);

/// `path:line:col` of a source region (toml++ counts from 1; an unknown region reads 1:1).
[[nodiscard]] std::string origin_of(const toml::source_region& region, const std::string& path);

/// "a string", "an integer", ... for messages.
[[nodiscard]] const char* type_name(const toml::node& node);

/// One table being read. The constructor rejects keys outside the table's schema (suggesting the
/// nearest valid key, or the other table of `all` that holds it).
class TableReader {
 public:
  TableReader(const toml::table& table, const TableSchema& schema, const std::string& path,
              const std::vector<TableSchema>& all);

  /// The node of `key`, nullptr if absent.
  [[nodiscard]] const toml::node* find(std::string_view key) const;
  /// The node of `key`; throws "missing required key" at the table's header if absent.
  [[nodiscard]] const toml::node& required(std::string_view key) const;

  /// The value of `node` (of `key`) as a finite number (integers accepted).
  [[nodiscard]] double number(const toml::node& node, std::string_view key) const;
  /// The value of `node` as a number in `range` (integers accepted); outside it (NaN and ±inf
  /// included) the message states the range with its unit (scene/ranges.hpp).
  [[nodiscard]] double number_in(const toml::node& node, std::string_view key,
                                 const core::Range& range) const;
  /// number_in() of `key` into `value` when the table has it (else `value` stays).
  void read_in(std::string_view key, const core::Range& range, double& value) const;
  /// The value as an integer (a float is a wrong type, even 6.0).
  [[nodiscard]] long long integer(const toml::node& node, std::string_view key) const;
  /// The value as a string that is one of `choices` (the nearest suggested otherwise).
  [[nodiscard]] std::string choice(const toml::node& node, std::string_view key,
                                   const std::vector<std::string_view>& choices) const;

  /// Throws "<table>.<key>: <what>" at the node unless ok.
  void check(bool ok, const toml::node& node, std::string_view key, const std::string& what) const;
  /// Throws "<table>.<key>: <what>" at the node (check(false, ...) that says so to the compiler).
  [[noreturn]] void fail(const toml::node& node, std::string_view key,
                         const std::string& what) const;
  /// Throws if `key` is present: it is a parameter of an effect (or a variant) not chosen here;
  /// `owner` says whose ("the coulomb law", "the multipod and disk robots").
  void forbid(std::string_view key, std::string_view owner, std::string_view chosen) const;

  [[nodiscard]] std::string origin(const toml::node& node) const;
  [[nodiscard]] std::string origin() const;  ///< the table's header
  [[nodiscard]] std::string_view name() const { return schema_.name; }

 private:
  [[nodiscard]] std::string where(std::string_view key) const;
  const toml::table& table_;
  const TableSchema& schema_;
  const std::string& path_;
};

}  // namespace slipwalk::scene
