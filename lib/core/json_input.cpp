#include "core/json_input.hpp"

#include <istream>
#include <map>
#include <optional>
#include <vector>

#include "core/error.hpp"
#include "core/input_file.hpp"

namespace slipwalk::core {

namespace {

using nlohmann::json;

/// "<source>:<line>:<col>" of a 0-based byte offset in `text`.
std::string position(std::string_view text, std::size_t offset, const std::string& source) {
  std::size_t line = 1;
  std::size_t col = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  std::string where = source;
  where.append(":").append(std::to_string(line)).append(":").append(std::to_string(col));
  return where;
}

/// What the checking pass stopped at, counted in the parser's own events so that locate() can
/// find it in the text: the n-th bracket opened or the n-th key read (0-based).
struct Finding {
  enum class Kind { kNone, kTooDeep, kDuplicateKey, kSyntax } kind = Kind::kNone;
  std::size_t ordinal = 0;        // the bracket or key
  std::size_t first_ordinal = 0;  // a duplicate key's first occurrence
  std::string key;
  std::size_t byte = 0;  // a syntax error's 1-based byte, as the parser reports it
  std::string message;
};

/// The parser's message without its "[json.exception...] parse error at line, column" prefix
/// (the place is given in our own form), and with the token it quotes (the token last read, or
/// the number too large) cut to an excerpt: a long string would otherwise be repeated whole.
std::string parser_message(const std::string& what) {
  const auto bracket = what.find("] ");
  std::string message = bracket == std::string::npos ? what : what.substr(bracket + 2);
  const auto syntax = message.find("syntax error");
  message = syntax == std::string::npos ? message : message.substr(syntax);
  for (const std::string_view marker : {"; last read: '", "overflow parsing '"}) {
    const auto token = message.find(marker);
    const auto close = message.rfind('\'');
    if (token != std::string::npos && close != std::string::npos &&
        close >= token + marker.size()) {
      const std::size_t from = token + marker.size();
      return message.substr(0, from) + text_excerpt(message.substr(from, close - from)) +
             message.substr(close);
    }
  }
  return text_excerpt(message, 160);
}

/// The checking pass: nlohmann's SAX parser is iterative, and this handler keeps no values, only
/// the open brackets and each open object's keys, so it stops at the first bracket too deep, the
/// first duplicate key or the first syntax error, whichever comes first in the text.
class Checker final : public nlohmann::json_sax<json> {
 public:
  Finding finding;

  bool null() override { return true; }
  bool boolean(bool /*value*/) override { return true; }
  bool number_integer(number_integer_t /*value*/) override { return true; }
  bool number_unsigned(number_unsigned_t /*value*/) override { return true; }
  bool number_float(number_float_t /*value*/, const string_t& /*text*/) override { return true; }
  bool string(string_t& /*value*/) override { return true; }
  bool binary(binary_t& /*value*/) override { return true; }
  bool start_object(std::size_t /*elements*/) override { return open(); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t /*elements*/) override { return open(); }
  bool end_array() override { return close(); }

  bool key(string_t& value) override {
    const std::size_t ordinal = keys_++;
    auto& seen = open_.back().keys;
    const auto [it, inserted] = seen.emplace(value, ordinal);
    if (!inserted) {
      finding.kind = Finding::Kind::kDuplicateKey;
      finding.ordinal = ordinal;
      finding.first_ordinal = it->second;
      finding.key = value;
      return false;
    }
    return true;
  }

  bool parse_error(std::size_t byte, const std::string& /*last_token*/,
                   const nlohmann::detail::exception& ex) override {
    finding.kind = Finding::Kind::kSyntax;
    finding.byte = byte;
    finding.message = parser_message(ex.what());
    return false;
  }

 private:
  struct Open {
    std::map<std::string, std::size_t> keys;  // key -> its ordinal (objects only)
  };

  bool open() {
    const std::size_t ordinal = brackets_++;
    if (open_.size() >= static_cast<std::size_t>(kJsonMaxDepth)) {
      finding.kind = Finding::Kind::kTooDeep;
      finding.ordinal = ordinal;
      return false;
    }
    open_.emplace_back();
    return true;
  }

  bool close() {
    open_.pop_back();
    return true;
  }

  std::vector<Open> open_;
  std::size_t brackets_ = 0;
  std::size_t keys_ = 0;
};

/// Byte offsets of the bracket and keys a finding counts. The text up to them is valid JSON (the
/// parser read it without error), so a scan that skips strings and tracks where a key may stand
/// sees the same brackets and keys in the same order.
struct Located {
  std::size_t bracket = 0;
  std::size_t key = 0;
  std::size_t first_key = 0;
};

Located locate(std::string_view text, const Finding& f) {
  Located at;
  std::vector<bool> in_object;  // one per open bracket, never deeper than the finding
  bool expect_key = false;
  std::size_t brackets = 0;
  std::size_t keys = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '{' || c == '[') {
      if (brackets++ == f.ordinal && f.kind == Finding::Kind::kTooDeep) {
        at.bracket = i;
        return at;
      }
      in_object.push_back(c == '{');
      expect_key = c == '{';
    } else if (c == '}' || c == ']') {
      if (!in_object.empty()) {
        in_object.pop_back();
      }
      expect_key = false;
    } else if (c == ',') {
      expect_key = !in_object.empty() && in_object.back();
    } else if (c == '"') {
      const std::size_t start = i;
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        i += text[i] == '\\' ? 1 : 0;
      }
      if (expect_key) {
        const std::size_t ordinal = keys++;
        if (ordinal == f.first_ordinal) {
          at.first_key = start;
        }
        if (ordinal == f.ordinal && f.kind == Finding::Kind::kDuplicateKey) {
          at.key = start;
          return at;
        }
      }
      expect_key = false;
    }
  }
  return at;
}

}  // namespace

std::string text_excerpt(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) {
    return std::string(text);
  }
  std::size_t cut = max_bytes;
  // Back off to the start of a UTF-8 character (continuation bytes are 10xxxxxx).
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
    --cut;
  }
  return std::string(text.substr(0, cut)) + "…";
}

std::string json_excerpt(const json& value) {
  switch (value.type()) {
    case json::value_t::object:
      return "an object of " + std::to_string(value.size()) + " keys";
    case json::value_t::array:
      return "an array of " + std::to_string(value.size()) + " entries";
    case json::value_t::string: {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on operator+ chains.
      std::string quoted = "\"";
      quoted.append(text_excerpt(value.get_ref<const std::string&>())).append("\"");
      return quoted;
    }
    case json::value_t::binary:
      return "binary data";
    default:  // a number, a boolean or null: short by nature
      return value.dump();
  }
}

json parse_json(std::string_view text, const std::string& source) {
  if (text.size() > kJsonMaxBytes) {
    throw InputError(source, "JSON text of " + std::to_string(text.size()) +
                                 " bytes; the limit is " + std::to_string(kJsonMaxBytes));
  }
  Checker checker;
  (void)json::sax_parse(text.begin(), text.end(), &checker);
  const Finding& f = checker.finding;
  switch (f.kind) {
    case Finding::Kind::kNone:
      break;
    case Finding::Kind::kSyntax:
      // The parser's byte is 1-based: the last character it read.
      throw InputError(position(text, f.byte == 0 ? 0 : f.byte - 1, source),
                       "malformed JSON: " + f.message);
    case Finding::Kind::kTooDeep:
      throw InputError(position(text, locate(text, f).bracket, source),
                       "JSON nested deeper than " + std::to_string(kJsonMaxDepth) + " levels");
    case Finding::Kind::kDuplicateKey: {
      const Located at = locate(text, f);
      std::string first = position(text, at.first_key, "");
      first = first.substr(1);  // "line:col" without the leading ":"
      throw InputError(position(text, at.key, source),
                       "duplicate key \"" + text_excerpt(f.key) + "\" (first at " + first + ")");
    }
  }
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {  // not expected once the checking pass accepted the text
    throw InputError(source, "malformed JSON: " + parser_message(e.what()));
  }
}

std::string read_json_text(std::istream& in, const std::string& source) {
  return read_input_stream(in, source, "the JSON text", kJsonMaxBytes);
}

std::string read_json_text(const std::filesystem::path& path) {
  return read_input_file(path, "a JSON file", kJsonMaxBytes);
}

}  // namespace slipwalk::core
