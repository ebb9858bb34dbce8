// Fuzz targets run as deterministic tests (a fixed seed, a bounded number of cases): a sweep spec
// built from random bytes, or a valid spec with random edits, must either load or be rejected
// with an InputError — never crash, hang or throw anything else. A failure prints the case.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/error.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

const std::string kValid = R"(study = "ch2"
name = "fuzz"
kind = "inchworm_vss"
[params]
rtol = 1e-10
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.005, 1.0], n = 4 }
method = ["exact", "analytic"]
[[points]]
mu_s = 1.3
[quick]
axes.F_frac = { linspace = [0.05, 1.0], n = 2 }
)";

/// Loads, expands and validates; true if accepted, false if rejected as bad input.
bool accepted(const std::string& text) {
  try {
    const PreparedSweep p = points::prepare(parse_spec(text, "fuzz.toml", false));
    return p.points.size() < 100'000;
  } catch (const core::InputError&) {
    return false;
  }
}

TEST(FuzzSpecs, RandomBytesAreRejectedCleanly) {
  std::mt19937_64 rng(20261121);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 300);
  for (int i = 0; i < 10000; ++i) {
    std::string text(static_cast<std::size_t>(length(rng)), '\0');
    for (char& ch : text) {
      ch = static_cast<char>(byte(rng));
    }
    EXPECT_NO_THROW((void)accepted(text)) << "case " << i;
  }
}

TEST(FuzzSpecs, MutatedValidSpecsLoadOrAreRejectedCleanly) {
  ASSERT_TRUE(accepted(kValid));
  std::mt19937_64 rng(7);
  const std::string alphabet = "0123456789.-+eE[]{}=,\"'# \nabcnxyzFmu_";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  int still_valid = 0;
  for (int i = 0; i < 10000; ++i) {
    std::string text = kValid;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text[at] = alphabet[pick(rng)];
          break;
        case 1:
          text.insert(at, 1, alphabet[pick(rng)]);
          break;
        default:
          text.erase(at, 1);
          break;
      }
    }
    bool ok = false;
    EXPECT_NO_THROW(ok = accepted(text)) << "case " << i << ":\n" << text;
    still_valid += ok ? 1 : 0;
  }
  // The mutations must reach both outcomes, or the test explores nothing.
  EXPECT_GT(still_valid, 0);
  EXPECT_LT(still_valid, 10000);
}

}  // namespace
}  // namespace slipwalk::sweeps
