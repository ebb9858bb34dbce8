// core::parse_toml: keys of any spelling with more dotted parts than the limit, and brackets
// nested deeper than it, are refused at their line and column before toml++ recurses on them;
// everything else parses exactly as toml++ parses it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/toml_input.hpp"

namespace slipwalk::core {
namespace {

/// The InputError's place for `text`, or "" when it parses.
std::string refused_at(const std::string& text) {
  try {
    (void)parse_toml(text, "t.toml");
  } catch (const InputError& e) {
    return e.where();
  }
  return "";
}

/// A dotted key of `parts` parts, each spelt by `rng` as bare, digits, quoted or literal, with
/// random blanks around the dots.
std::string dotted_key(int parts, std::mt19937& rng) {
  static const char* const kSpellings[] = {"a", "a1", "1", "-", "\"q\"", "'l'", "\"x.y\""};
  std::string key;
  for (int i = 0; i < parts; ++i) {
    if (i > 0) {
      key += (rng() % 3 == 0 ? " . " : ".");
    }
    key += kSpellings[rng() % std::size(kSpellings)];
  }
  return key;
}

TEST(TomlInput, KeysWithMorePartsThanTheLimitAreRefusedAtTheirLineInEverySpelling) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int parts = kTomlMaxDepth + 1 + static_cast<int>(rng() % 100'000);
    const std::string key = dotted_key(parts, rng);
    const std::string header = "x = 1\n[" + key + "]\ny = 2\n";
    const std::string assignment = "x = 1\n" + key + " = 2\n";
    const std::string inline_table = "x = 1\nt = { " + key + " = 2 }\n";
    for (const std::string& text : {header, assignment, inline_table}) {
      EXPECT_EQ(refused_at(text).rfind("t.toml:2:", 0), 0U) << "parts " << parts;
    }
  }
}

TEST(TomlInput, KeysWithinTheLimitParseAsTomlxxParsesThem) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 200; ++trial) {
    const std::string key = dotted_key(1 + static_cast<int>(rng() % (kTomlMaxDepth - 1)), rng);
    const std::string text = "[" + key + "]\ny = 2\n";
    std::ostringstream ours;
    std::ostringstream theirs;
    try {
      ours << parse_toml(text, "t.toml");
    } catch (const InputError& e) {
      ours << "refused " << e.what();
    }
    try {
      theirs << toml::parse(std::string_view(text), std::string("t.toml"));
    } catch (const toml::parse_error& e) {
      theirs << "refused";
    }
    // A key that repeats a table is refused by both; otherwise both give the same document.
    if (ours.str().rfind("refused", 0) == 0) {
      EXPECT_EQ(theirs.str(), "refused") << text;
    } else {
      EXPECT_EQ(ours.str(), theirs.str()) << text;
    }
  }
}

TEST(TomlInput, BracketsNestedDeeperThanTheLimitAreRefused) {
  for (int depth : {kTomlMaxDepth + 1, 1000, 1'000'000}) {
    for (const char* open : {"[", "{a="}) {
      std::string text = "x = ";
      for (int i = 0; i < depth; ++i) {
        text += open;
      }
      EXPECT_EQ(refused_at(text).rfind("t.toml:1:", 0), 0U) << depth;
    }
  }
  std::string ok = "x = ";
  ok += std::string(kTomlMaxDepth, '[') + std::string(kTomlMaxDepth, ']') + "\n";
  EXPECT_EQ(refused_at(ok), "");
}

TEST(TomlInput, LongLinesOfFloatsTimesAndDottedStringsAreNotKeys) {
  std::string floats = "x = [";
  for (int i = 0; i < 10'000; ++i) {
    floats += (i > 0 ? ", " : "") + std::string("-1.5e-3");
  }
  floats += "]\ns = \"" + std::string(10'000, '.') + "\"\nl = '''" + std::string(10'000, '.') +
            "'''\nt = 07:32:00.999\n# " + std::string(10'000, '.') + "\n";
  EXPECT_EQ(refused_at(floats), "");
}

TEST(TomlInput, EveryShippedTomlFileParsesAsTomlxxParsesIt) {
  int files = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(SLIPWALK_SOURCE_DIR "/studies")) {
    if (entry.path().extension() != ".toml") {
      continue;
    }
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    std::ostringstream ours;
    std::ostringstream theirs;
    ours << parse_toml(text.str(), entry.path().string());
    theirs << toml::parse(std::string_view(text.str()), entry.path().string());
    EXPECT_EQ(ours.str(), theirs.str()) << entry.path();
    ++files;
  }
  EXPECT_GT(files, 20);
}

TEST(TomlInput, ASyntaxErrorNamesItsLineAndColumn) {
  EXPECT_EQ(refused_at("a = 1\nb = = 2\n"), "t.toml:2:5");
}

}  // namespace
}  // namespace slipwalk::core
