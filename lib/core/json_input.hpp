#pragma once
// The one way the project reads JSON (frame and robot files, sidecars): hostile input is refused
// with an InputError naming `file:line:col` before anything can recurse on it or repeat it.
//  - Nesting deeper than kJsonMaxDepth is refused where the first too-deep bracket opens. The
//    parser is iterative, but everything after it (dump, copy, compare, our own readers) recurses
//    once a level, so ~70,000 levels would overflow the stack.
//  - Text longer than kJsonMaxBytes is refused before it is parsed (and, from a stream or file,
//    before it is read whole).
//  - A key repeated in one object is refused at its second occurrence: "last wins" would lose a
//    value silently.
//  - Messages quote at most a short excerpt of the input, never the input re-serialised.
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace slipwalk::core {

/// The deepest nesting accepted: a top-level object is level 1. Our files reach 7 (a sidecar with
/// its spec and parameters); 64 leaves room without letting recursion run deep.
inline constexpr int kJsonMaxDepth = 64;
/// The longest JSON text accepted: a frame of 100,000 legs (the robot reader's limit) is about
/// 25 MB.
inline constexpr std::size_t kJsonMaxBytes = std::size_t{64} << 20;
/// The longest piece of input an error message quotes.
inline constexpr std::size_t kJsonExcerptBytes = 40;

/// Parses `text` as one JSON value; `source` names it in errors (a file name or "<stdin>").
/// Throws InputError: where = "<source>:<line>:<col>" (1-based, columns in bytes) for a syntax
/// error, a number out of range of a double, nesting too deep or a duplicate key (at its second
/// occurrence); "<source>" for text too long.
[[nodiscard]] nlohmann::json parse_json(std::string_view text, const std::string& source);

/// All of `in` as text; InputError naming `source` once it passes kJsonMaxBytes or cannot be
/// read.
[[nodiscard]] std::string read_json_text(std::istream& in, const std::string& source);

/// The text of the file at `path` (named by `path` in errors): refused when it is missing, a
/// folder, unreadable or longer than kJsonMaxBytes.
[[nodiscard]] std::string read_json_text(const std::filesystem::path& path);

/// A value as an error message may show it: numbers, booleans and null as written, a string
/// quoted and cut to kJsonExcerptBytes, an array or object by its size only.
[[nodiscard]] std::string json_excerpt(const nlohmann::json& value);

/// `text` cut to at most `max_bytes` (at a UTF-8 character boundary) with "…" when cut.
[[nodiscard]] std::string text_excerpt(std::string_view text,
                                       std::size_t max_bytes = kJsonExcerptBytes);

}  // namespace slipwalk::core
