#pragma once
// The one way the project parses TOML (scenes, sweep specs, study files): hostile text is
// refused with an InputError naming `file:line:col` before toml++ sees it, where toml++ would
// recurse once per level. A table header or key of tens of thousands of dotted parts
// (`[a.a.a.…]`) makes it build — and later destroy — that many nested tables recursively, and
// overflows the stack; so do brackets nested as deep.
#include <toml++/toml.h>

#include <string>
#include <string_view>

namespace slipwalk::core {

/// The most parts a dotted key may have, and the deepest nesting of arrays and inline tables.
/// Our files use at most 3 and 2; 64 leaves room without letting recursion run deep.
inline constexpr int kTomlMaxDepth = 64;

/// Parses `text` (named `source` in errors). Throws InputError at "<source>:<line>:<col>" for a
/// key of more than kTomlMaxDepth parts, brackets nested deeper than that, or a syntax error.
[[nodiscard]] toml::table parse_toml(std::string_view text, const std::string& source);

}  // namespace slipwalk::core
