// The one JSON reader (core/json_input.hpp) against generated hostile input: nesting of every
// shape up to 100,000 levels, duplicate keys at every depth, long tokens and long texts. The
// oracle is the generator itself: it knows where the first too-deep bracket and the second
// occurrence of a key stand.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"

namespace slipwalk::core {
namespace {

using nlohmann::json;

/// "j.json:<line>:<col>" of a 0-based byte offset, counted independently of the reader.
std::string place(const std::string& text, std::size_t offset) {
  const std::string before = text.substr(0, offset);
  const std::size_t newline = before.rfind('\n');
  const auto line = 1 + std::count(before.begin(), before.end(), '\n');
  const std::size_t col = newline == std::string::npos ? offset + 1 : offset - newline;
  return "j.json:" + std::to_string(line) + ":" + std::to_string(col);
}

/// The error parse_json throws for `text`, or "(accepted)".
struct Outcome {
  std::string where;
  std::string what;
};
Outcome outcome(const std::string& text) {
  try {
    (void)parse_json(text, "j.json");
  } catch (const InputError& e) {
    return {e.where(), e.what()};
  }
  return {"(accepted)", ""};
}

/// Depth of a parsed value, walked without recursion.
int depth_of(const json& root) {
  int deepest = 0;
  std::vector<std::pair<const json*, int>> todo = {{&root, 1}};
  while (!todo.empty()) {
    const auto [v, d] = todo.back();
    todo.pop_back();
    if (v->is_structured()) {
      deepest = std::max(deepest, d);
      for (const json& child : *v) {
        todo.emplace_back(&child, d + 1);
      }
    }
  }
  return deepest;
}

enum class Shape { kArrays, kObjects, kMixed, kRandom };

/// A value nested `depth` levels, every level on its own line when `lines`; `too_deep` receives
/// the offset of the bracket that opens level kJsonMaxDepth + 1 (if any). Each level but the
/// innermost also holds a container after the deeper value (a deep branch need not be the last)
/// and a string of brackets before it (brackets in strings do not count).
std::string nested(int depth, Shape shape, bool lines, std::mt19937& rng, std::size_t& too_deep) {
  std::string text;
  std::vector<std::string> closing;
  too_deep = std::string::npos;
  for (int level = 1; level <= depth; ++level) {
    bool object = shape == Shape::kObjects || (shape == Shape::kMixed && level % 2 == 0);
    if (shape == Shape::kRandom) {
      object = (rng() & 1U) != 0;
    }
    if (lines && level > 1) {
      text += "\n ";
    }
    if (level == kJsonMaxDepth + 1) {
      too_deep = text.size();
    }
    const bool innermost = level == depth;
    text += object ? R"({"x": "]}[{", "k": )" : R"(["[[{", )";
    closing.emplace_back(object ? (innermost ? "}" : R"(, "y": [1]})")
                                : (innermost ? "]" : R"(, {"a": 1}])"));
  }
  text += "0";
  for (auto it = closing.rbegin(); it != closing.rend(); ++it) {
    text += *it;
  }
  return text;
}

TEST(JsonInput, NestingUpToTheLimitIsReadAndDeeperIsRefusedAtTheFirstBracketTooDeep) {
  std::vector<int> depths;
  for (int d = 1; d <= kJsonMaxDepth + 8; ++d) {
    depths.push_back(d);
  }
  for (int d : {100, 1000, 10000, 70000, 100000}) {
    depths.push_back(d);
  }
  std::mt19937 rng(15);
  int accepted = 0;
  int refused = 0;
  for (const Shape shape : {Shape::kArrays, Shape::kObjects, Shape::kMixed, Shape::kRandom}) {
    for (const bool lines : {false, true}) {
      for (const int depth : depths) {
        std::size_t too_deep = 0;
        const std::string text = nested(depth, shape, lines, rng, too_deep);
        const Outcome o = outcome(text);
        if (depth <= kJsonMaxDepth) {
          ASSERT_EQ(o.where, "(accepted)") << depth << ": " << o.what;
          EXPECT_EQ(depth_of(parse_json(text, "j.json")), depth);
          ++accepted;
        } else {
          ASSERT_EQ(o.where, place(text, too_deep)) << depth << " " << o.what;
          EXPECT_NE(o.what.find("nested deeper than 64 levels"), std::string::npos) << o.what;
          EXPECT_LT(o.what.size(), 200U);  // the input is never repeated
          ++refused;
        }
      }
    }
  }
  EXPECT_EQ(accepted, 4 * 2 * kJsonMaxDepth);
  EXPECT_EQ(refused, 4 * 2 * (8 + 5));
}

TEST(JsonInput, TheFirstProblemInTheTextIsTheOneReported) {
  // A syntax error before the deep part is reported as such; one after it is never reached.
  const std::string deep(100000, '[');
  EXPECT_EQ(outcome("[1 2, " + deep).where, "j.json:1:4");
  EXPECT_EQ(outcome(deep + "1 2").where, "j.json:1:65");
  // A duplicate key before the deep part, and after it.
  EXPECT_EQ(outcome(R"({"a": 1, "a": )" + deep).where, "j.json:1:10");
  const std::string within = std::string(30, '[') + std::string(30, ']');
  EXPECT_EQ(outcome(R"({"a": )" + within + R"(, "a": 1})").where, "j.json:1:69");
}

/// A document whose innermost object (at `depth`, inside arrays and objects, each level on its
/// own line when `lines`) holds `key` twice as written (`first`, `second`: spellings that decode
/// alike); `second_at` and `first_at` receive the offsets of the two key strings.
std::string with_duplicate(int depth, const std::string& first, const std::string& second,
                           bool lines, std::size_t& first_at, std::size_t& second_at) {
  std::string text;
  std::string closing;
  for (int level = 1; level < depth; ++level) {
    text += level % 2 == 0 ? R"([0, )" : R"({"other": 1, "same": )";
    closing += level % 2 == 0 ? ']' : '}';
    text += lines ? "\n" : "";
  }
  text += "{\"a\": 1, ";
  first_at = text.size();
  text += "\"" + first + "\": {\"" + first + "\": 2},";  // the same key one level down is fine
  text += lines ? "\n   " : " ";
  text += "\"b\": [1, 2], ";
  second_at = text.size();
  text += "\"" + second + "\": 3}";
  text.append(closing.rbegin(), closing.rend());
  return text;
}

TEST(JsonInput, ADuplicateKeyIsRefusedAtItsSecondOccurrenceAtEveryDepth) {
  struct Spelling {
    std::string first, second;
  };
  const std::vector<Spelling> spellings = {
      {"q", "q"}, {"K", "\\u004B"}, {"mu", "m\\u0075"}, {"a\\\"b", "a\\u0022b"}, {"é", "\\u00e9"}};
  int refused = 0;
  // The key's object holds one object more: the deepest duplicate stands at the limit less one.
  for (int depth = 1; depth < kJsonMaxDepth; ++depth) {
    for (const Spelling& s : spellings) {
      for (const bool lines : {false, true}) {
        std::size_t first_at = 0;
        std::size_t second_at = 0;
        const std::string text =
            with_duplicate(depth, s.first, s.second, lines, first_at, second_at);
        const Outcome o = outcome(text);
        ASSERT_EQ(o.where, place(text, second_at)) << text << "\n" << o.what;
        const std::string first = place(text, first_at).substr(std::string("j.json:").size());
        EXPECT_NE(o.what.find("duplicate key"), std::string::npos) << o.what;
        EXPECT_NE(o.what.find("(first at " + first + ")"), std::string::npos) << o.what;
        ++refused;
      }
    }
  }
  EXPECT_EQ(refused, (kJsonMaxDepth - 1) * 5 * 2);
}

TEST(JsonInput, KeysThatDifferOrStandInDifferentObjectsAreNotDuplicates) {
  for (const char* text :
       {R"({"a": 1, "A": 2, "a ": 3, "\u0061b": 4})", R"({"a": {"a": {"a": 1}}})",
        R"([{"a": 1}, {"a": 2}])", R"({"a": [{"a": 1}, {"a": 2}], "b": {"a": 3}})"}) {
    EXPECT_EQ(outcome(text).where, "(accepted)") << text;
  }
}

TEST(JsonInput, MessagesQuoteOnlyAShortExcerptOfLongTokens) {
  const std::string big(1 << 20, 'x');
  const std::vector<std::string> texts = {
      "[\"" + big,                                 // a string never closed
      "[\"" + big + "\", tru]",                    // a bad literal after a long string
      "{\"" + big + "\": 1, \"" + big + "\": 2}",  // a long duplicate key
      "[1" + std::string(1 << 20, '0') + "e999]",  // a long number out of range
      "[" + std::string(1 << 20, ' ') + "?]",      // the error far into the text
  };
  for (const std::string& text : texts) {
    const Outcome o = outcome(text);
    ASSERT_NE(o.where, "(accepted)");
    EXPECT_EQ(o.where.rfind("j.json:1:", 0), 0U) << o.where;
    EXPECT_LT(o.what.size(), 300U) << o.what.substr(0, 300);
  }
}

TEST(JsonInput, ExcerptsCutAtACharacterBoundary) {
  const std::string text = "aé€𝄞bé€𝄞cé€𝄞dé€𝄞";  // 1-, 2-, 3- and 4-byte characters
  for (std::size_t max = 0; max <= text.size(); ++max) {
    const std::string cut = text_excerpt(text, max);
    if (max >= text.size()) {
      EXPECT_EQ(cut, text);
      continue;
    }
    const std::string kept = cut.substr(0, cut.size() - std::string("…").size());
    EXPECT_LE(kept.size(), max);
    EXPECT_EQ(text.rfind(kept, 0), 0U);
    // What is kept ends where a character ends: it reads back as valid UTF-8.
    EXPECT_NO_THROW((void)json(cut).dump()) << max;
  }
  EXPECT_EQ(json_excerpt(json::parse("[1, [2], {}]")), "an array of 3 entries");
  EXPECT_EQ(json_excerpt(json::parse(R"({"a": 1})")), "an object of 1 keys");
  EXPECT_EQ(json_excerpt(json(std::string(100, 'y'))), "\"" + std::string(40, 'y') + "…\"");
  EXPECT_EQ(json_excerpt(json(2.5)), "2.5");
}

TEST(JsonInput, TextsLongerThanTheLimitAreRefusedBeforeParsing) {
  std::string text(kJsonMaxBytes, ' ');
  text.front() = '1';
  EXPECT_EQ(outcome(text).where, "(accepted)");
  text.push_back(' ');
  EXPECT_EQ(outcome(text).where, "j.json");
  std::istringstream in(text);
  EXPECT_THROW((void)read_json_text(in, "<stdin>"), InputError);
  std::istringstream small(" [1, 2] ");
  EXPECT_EQ(read_json_text(small, "<stdin>"), " [1, 2] ");
}

TEST(JsonInput, FilesThatAreMissingOrFoldersAreRefusedNamingThem) {
  const testing::ScratchDir dir;
  for (const auto& path : {dir.path(), dir / "missing.json"}) {
    try {
      (void)read_json_text(path);
      ADD_FAILURE() << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), path.string());
    }
  }
  testing::write_text(dir / "ok.json", R"({"a": 1})");
  EXPECT_EQ(read_json_text(dir / "ok.json"), R"({"a": 1})");
}

}  // namespace
}  // namespace slipwalk::core
