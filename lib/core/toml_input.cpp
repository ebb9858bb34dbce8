#include "core/toml_input.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace slipwalk::core {

namespace {

/// A position in the text, 1-based, columns in bytes (toml++'s convention).
struct Cursor {
  std::string_view text;
  std::size_t i = 0;
  int line = 1;
  std::size_t line_start = 0;

  [[nodiscard]] bool done() const { return i >= text.size(); }
  [[nodiscard]] char at(std::size_t k) const { return i + k < text.size() ? text[i + k] : '\0'; }
  [[nodiscard]] std::string where(const std::string& source) const {
    return source + ":" + std::to_string(line) + ":" + std::to_string(i - line_start + 1);
  }
  void step() {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
    ++i;
  }
};

/// Skips a string starting at the cursor (basic or literal, one- or multi-line), escapes
/// included. An unterminated string runs to the end; toml++ then reports it.
void skip_string(Cursor& c) {
  const char quote = c.at(0);
  const bool multi = c.at(1) == quote && c.at(2) == quote;
  const std::size_t open = multi ? 3 : 1;
  for (std::size_t k = 0; k < open; ++k) {
    c.step();
  }
  while (!c.done()) {
    if (quote == '"' && c.at(0) == '\\') {
      c.step();
      if (!c.done()) {
        c.step();
      }
      continue;
    }
    if (c.at(0) == quote && (!multi || (c.at(1) == quote && c.at(2) == quote))) {
      for (std::size_t k = 0; k < open; ++k) {
        c.step();
      }
      return;
    }
    if (!multi && c.at(0) == '\n') {
      return;
    }
    c.step();
  }
}

}  // namespace

toml::table parse_toml(std::string_view text, const std::string& source) {
  // One pass outside strings and comments. A dotted key is parts separated by dots with only
  // blanks between, so the dots of one key all lie between two of "\n , = [ ] { }"; counting
  // the dots between those bounds the parts of every key (a float or a time has one dot there).
  Cursor c{text};
  int depth = 0;
  int dots = 0;
  while (!c.done()) {
    const char ch = c.at(0);
    if (ch == '"' || ch == '\'') {
      skip_string(c);
      continue;
    }
    if (ch == '#') {
      while (!c.done() && c.at(0) != '\n') {
        c.step();
      }
      continue;
    }
    if (ch == '[' || ch == '{') {
      if (++depth > kTomlMaxDepth) {
        throw InputError(c.where(source), "brackets nested deeper than " +
                                              std::to_string(kTomlMaxDepth) + " levels");
      }
    } else if (ch == ']' || ch == '}') {
      depth = depth > 0 ? depth - 1 : 0;
    }
    if (ch == '\n' || ch == ',' || ch == '=' || ch == '[' || ch == ']' || ch == '{' || ch == '}') {
      dots = 0;
    } else if (ch == '.' && ++dots >= kTomlMaxDepth) {
      throw InputError(c.where(source),
                       "a key of more than " + std::to_string(kTomlMaxDepth) + " dotted parts");
    }
    c.step();
  }
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const toml::source_position& at = e.source().begin;
    const auto line = std::max<toml::source_index>(at.line, 1);
    const auto column = std::max<toml::source_index>(at.column, 1);
    throw InputError(source + ":" + std::to_string(line) + ":" + std::to_string(column),
                     std::string(e.description()));
  }
}

}  // namespace slipwalk::core
