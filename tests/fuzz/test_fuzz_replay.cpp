// The fuzz targets of tests/fuzz (fuzz_target.hpp) as deterministic tests: every seed of a
// target's corpus is accepted, every crash the fuzzers found (tests/fuzz/regressions/<target>/)
// keeps the contract, and so do seeded mutations of the seeds (numbers swapped for extremes,
// brackets and quotes inserted, ranges erased, duplicated or spliced) and random bytes. Keeping
// the contract: the target returns (accepted, or refused with core::InputError); anything it
// throws is a failure that prints the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {
namespace {

struct Target {
  const char* name;
  Outcome (*run)(std::string_view);
  int mutations;  ///< seeded mutations replayed (a spec expands and checks every point: fewer)
};

const std::array<Target, 11> kTargets = {{{"scene", &scene, 2000},
                                          {"spec", &spec, 400},
                                          {"frame_json", &frame_json, 2000},
                                          {"frame_batch", &frame_batch, 2000},
                                          {"residual", &residual, 2000},
                                          {"spring_support", &spring_support, 2000},
                                          {"coulomb", &coulomb, 2000},
                                          {"plan_file", &plan_file, 1000},
                                          {"trial", &trial, 1000},
                                          {"calibration_hanging", &calibration_hanging, 1000},
                                          {"calibration_poses", &calibration_poses, 1000}}};

/// GoogleTest prints a parameter by its name.
[[maybe_unused]] void PrintTo(const Target& t, std::ostream* os) { *os << t.name; }

struct Input {
  std::string name;
  std::string bytes;
};

/// The files of tests/fuzz/<folder>/<target>/, in name order (none if the folder is absent).
std::vector<Input> inputs(const std::string& folder, const std::string& target) {
  const std::filesystem::path dir =
      std::filesystem::path(SLIPWALK_SOURCE_DIR) / "tests" / "fuzz" / folder / target;
  std::vector<Input> out;
  if (!std::filesystem::is_directory(dir)) {
    return out;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    out.push_back({entry.path().filename().string(),
                   {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()}});
  }
  std::sort(out.begin(), out.end(), [](const Input& a, const Input& b) { return a.name < b.name; });
  return out;
}

/// The input as C-escaped text (octal escapes), for a failure message that can be pasted back.
std::string escaped(std::string_view bytes) {
  std::string out = "\"";
  for (const char c : bytes) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n\"\n\"";
    } else if (u < 0x20 || u >= 0x7f) {
      out += '\\';
      out += static_cast<char>('0' + (u >> 6U));
      out += static_cast<char>('0' + ((u >> 3U) & 7U));
      out += static_cast<char>('0' + (u & 7U));
    } else {
      out += c;
    }
  }
  return out + '"';
}

/// Runs the target; a failure (anything thrown) names the case and prints the input.
std::optional<Outcome> keeps_contract(const Target& t, const std::string& label,
                                      std::string_view bytes) {
  try {
    return t.run(bytes);
  } catch (const std::exception& e) {
    ADD_FAILURE() << t.name << ", " << label << ": threw " << e.what() << "\ninput:\n"
                  << escaped(bytes);
  } catch (...) {
    ADD_FAILURE() << t.name << ", " << label << ": threw a non-exception\ninput:\n"
                  << escaped(bytes);
  }
  return std::nullopt;
}

/// Replacements a hostile user tries: extreme and non-numbers, structure, odd bytes.
const std::vector<std::string> kTokens = {"nan",
                                          "inf",
                                          "-inf",
                                          "1e308",
                                          "-1e308",
                                          "1e-320",
                                          "4.9e-324",
                                          "0",
                                          "-0",
                                          "1e999",
                                          "-1",
                                          "1",
                                          "2",
                                          "65",
                                          "1000",
                                          "1e9",
                                          "99999999999999999999",
                                          "0x10",
                                          "[",
                                          "]",
                                          "{",
                                          "}",
                                          "[[",
                                          "]]",
                                          "\"",
                                          "'",
                                          ",",
                                          "=",
                                          "\n",
                                          "#",
                                          ".",
                                          "-",
                                          "e",
                                          "\\",
                                          "true",
                                          "null",
                                          "\"\"",
                                          "[]",
                                          "{}",
                                          " ",
                                          "\t",
                                          "\r\n",
                                          std::string(1, '\0'),
                                          "\xff",
                                          "[[points]]\n",
                                          "[quick]\n",
                                          "legs",
                                          "K",
                                          "mu",
                                          "q"};

/// One seeded edit of `text`; `other` is another seed to splice from.
void mutate(std::string& text, const std::string& other, std::mt19937_64& rng) {
  const auto below = [&](std::size_t n) { return n == 0 ? std::size_t{0} : rng() % n; };
  const std::string& token = kTokens[below(kTokens.size())];
  const std::size_t at = below(text.size() + 1);
  switch (rng() % 7) {
    case 0:  // a number becomes a token
    {
      const std::size_t digit = text.find_first_of("0123456789", at);
      if (digit != std::string::npos) {
        const std::size_t end = text.find_first_not_of("0123456789.eE+-", digit);
        text.replace(digit, (end == std::string::npos ? text.size() : end) - digit, token);
        break;
      }
      text.insert(at, token);
      break;
    }
    case 1:
      text.insert(at, token);
      break;
    case 2:
      if (at < text.size()) {
        text[at] = static_cast<char>(rng());
      }
      break;
    case 3:
      text.erase(at, 1 + below(16));
      break;
    case 4:  // a range repeated
    {
      const std::string piece = text.substr(at, 1 + below(64));
      text.insert(at, piece);
      break;
    }
    case 5:  // the tail of another seed
    {
      const std::size_t from = below(other.size() + 1);
      text = text.substr(0, at) + other.substr(from);
      break;
    }
    default:
      text.erase(at);
      text += token;
      break;
  }
}

class FuzzReplay : public ::testing::TestWithParam<Target> {};

TEST_P(FuzzReplay, EverySeedIsAcceptedAndEveryRegressionKeepsTheContract) {
  const Target& t = GetParam();
  const std::vector<Input> seeds = inputs("corpus", t.name);
  ASSERT_GE(seeds.size(), 1U) << "no seeds for " << t.name;
  for (const Input& seed : seeds) {
    EXPECT_EQ(keeps_contract(t, "seed " + seed.name, seed.bytes), Outcome::kAccepted)
        << t.name << ": the seed " << seed.name << " should be accepted";
  }
  for (const Input& crash : inputs("regressions", t.name)) {
    EXPECT_TRUE(keeps_contract(t, "regression " + crash.name, crash.bytes).has_value());
  }
}

TEST_P(FuzzReplay, SeededMutationsOfTheSeedsKeepTheContract) {
  const Target& t = GetParam();
  const std::vector<Input> seeds = inputs("corpus", t.name);
  ASSERT_GE(seeds.size(), 1U);
  std::mt19937_64 rng(20261124U + std::hash<std::string>{}(t.name) % 1000U);
  int accepted = 0;
  int rejected = 0;
  for (int i = 0; i < t.mutations; ++i) {
    std::string text = seeds[rng() % seeds.size()].bytes;
    const std::string& other = seeds[rng() % seeds.size()].bytes;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      mutate(text, other, rng);
    }
    const auto outcome = keeps_contract(t, "mutation " + std::to_string(i), text);
    accepted += outcome == Outcome::kAccepted ? 1 : 0;
    rejected += outcome == Outcome::kRejected ? 1 : 0;
  }
  // The mutations must reach both outcomes, or they explore nothing.
  EXPECT_GT(accepted, 0) << t.name;
  EXPECT_GT(rejected, 0) << t.name;
}

TEST_P(FuzzReplay, RandomBytesKeepTheContract) {
  const Target& t = GetParam();
  std::mt19937_64 rng(7U + std::hash<std::string>{}(t.name) % 1000U);
  int kept = 0;
  constexpr int kCases = 500;
  for (int i = 0; i < kCases; ++i) {
    std::string bytes(rng() % 400, '\0');
    for (char& c : bytes) {
      c = static_cast<char>(rng());
    }
    kept += keeps_contract(t, "random bytes " + std::to_string(i), bytes).has_value() ? 1 : 0;
  }
  EXPECT_EQ(kept, kCases);
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<Target>& param_info) {
                           return std::string(param_info.param.name);
                         });

}  // namespace
}  // namespace slipwalk::fuzz
