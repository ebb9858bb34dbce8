// core::Lanes and the loads and stores of a pass over the feet: each against the scalar loop it
// replaces, at every count of feet up to three groups (full groups, a padded last group, fewer
// than four feet), and the sums bit for bit against Lanes::sum's left-to-right order.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/lanes.hpp"

namespace slipwalk::core {
namespace {

using L = Lanes<4>;
using V = L::V;

double left_to_right(V v) { return ((v[0] + v[1]) + v[2]) + v[3]; }

TEST(Lanes, LaneSumsAddEachVectorLeftToRightLikeSum) {
  // Values whose sum depends on the order (1e16 + 1 − 1e16 + 1 is 1 left to right, 2 paired).
  const V a{1e16, 1.0, -1e16, 1.0};
  const V b{1.0, 1e16, 1.0, -1e16};
  const V c{-0.0, -0.0, -0.0, -0.0};
  const V d{0.1, 0.2, 0.3, -0.6};
  const V s = lane_sums(a, b, c, d);
  const V args[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(s[i]), std::bit_cast<std::uint64_t>(L::sum(args[i])))
        << "vector " << i;
    EXPECT_EQ(s[i], left_to_right(args[i])) << "vector " << i;
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  for (int trial = 0; trial < 1000; ++trial) {
    V v[4];
    for (V& x : v) {
      x = V{value(rng), value(rng) * 1e-9, value(rng) * 1e9, value(rng)};
    }
    const V t = lane_sums(v[0], v[1], v[2], v[3]);
    for (int i = 0; i < 4; ++i) {
      ASSERT_EQ(t[i], left_to_right(v[i])) << "trial " << trial << ", vector " << i;
    }
  }
}

TEST(Lanes, SumKeepsANegativeZeroAndPropagatesNaN) {
  EXPECT_TRUE(std::signbit(L::sum(V{-0.0, -0.0, -0.0, -0.0})));
  EXPECT_TRUE(std::isnan(L::sum(V{1.0, std::numeric_limits<double>::quiet_NaN(), 2.0, 3.0})));
}

TEST(Lanes, LoadFlagsMarksExactlyTheNonZeroCharsOfEveryGroupAndNothingPastTheEnd) {
  std::mt19937 rng(3);
  for (std::ptrdiff_t n = 1; n <= 12; ++n) {
    for (int trial = 0; trial < 50; ++trial) {
      // Any non-zero char is a flag (1, but also 2, −1, 0x80); a sentinel after the end.
      std::vector<char> flags(static_cast<std::size_t>(n) + 4, char{1});
      for (std::ptrdiff_t i = 0; i < n; ++i) {
        const int r = static_cast<int>(rng() % 5);
        flags[static_cast<std::size_t>(i)] =
            r == 0 ? char{0}
                   : (r == 1 ? char{1} : (r == 2 ? char{2} : (r == 3 ? char{-1} : '\x80')));
      }
      for (std::ptrdiff_t j = 0; j < n; j += 4) {
        const L::M m = load_flags(flags.data(), n, j);
        for (int i = 0; i < 4; ++i) {
          const bool expect = j + i < n && flags[static_cast<std::size_t>(j + i)] != 0;
          ASSERT_EQ(m[i], expect ? -1 : 0) << "n " << n << ", group " << j << ", lane " << i;
        }
      }
    }
  }
}

TEST(Lanes, StoreFlagsWritesOneOrZeroPerFootAndLeavesThePaddingAlone) {
  for (std::ptrdiff_t n = 1; n <= 9; ++n) {
    std::vector<char> out(static_cast<std::size_t>(n) + 4, char{7});
    for (std::ptrdiff_t j = 0; j < n; j += 4) {
      store_flags(out.data(), n, j, L::M{-1, 0, -1, 0});
    }
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      EXPECT_EQ(out[static_cast<std::size_t>(i)], i % 2 == 0 ? 1 : 0) << "n " << n << ", " << i;
    }
    EXPECT_EQ(out[static_cast<std::size_t>(n)], 7) << "n " << n;
  }
}

TEST(Lanes, ColumnsAndPaddedLoadsReadEveryFootOnceAndZerosPastTheEnd) {
  for (std::ptrdiff_t n = 1; n <= 12; ++n) {
    std::vector<double> m(static_cast<std::size_t>(3 * n));
    std::vector<double> p(static_cast<std::size_t>(n));
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      for (std::ptrdiff_t r = 0; r < 3; ++r) {
        m[static_cast<std::size_t>(3 * k + r)] = static_cast<double>(100 * (r + 1) + k);
      }
      p[static_cast<std::size_t>(k)] = static_cast<double>(k) + 0.5;
    }
    for (std::ptrdiff_t j = 0; j < n; j += 4) {
      V x;
      V y;
      V z;
      load_columns3(m.data(), n, j, x, y, z);
      const V q = load_padded(p.data(), n, j);
      for (int i = 0; i < 4; ++i) {
        const std::ptrdiff_t k = j + i;
        const bool foot = k < n;
        EXPECT_EQ(x[i], foot ? static_cast<double>(100 + k) : 0.0) << "n " << n << ", k " << k;
        EXPECT_EQ(y[i], foot ? static_cast<double>(200 + k) : 0.0) << "n " << n << ", k " << k;
        EXPECT_EQ(z[i], foot ? static_cast<double>(300 + k) : 0.0) << "n " << n << ", k " << k;
        EXPECT_EQ(q[i], foot ? static_cast<double>(k) + 0.5 : 0.0) << "n " << n << ", k " << k;
      }
    }
  }
}

TEST(Lanes, AllWithinFailsOnAnyValueOutsideTheBoundOrNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (std::ptrdiff_t n = 1; n <= 11; ++n) {
    std::vector<double> v(static_cast<std::size_t>(n), -2.0);
    EXPECT_TRUE(all_within(v.data(), n, 2.0)) << "n " << n;
    for (std::ptrdiff_t bad = 0; bad < n; ++bad) {
      for (const double x : {nan, inf, -inf, std::nextafter(2.0, 3.0), -2.5}) {
        std::vector<double> w = v;
        w[static_cast<std::size_t>(bad)] = x;
        EXPECT_FALSE(all_within(w.data(), n, 2.0)) << "n " << n << ", value " << x << " at " << bad;
      }
    }
  }
}

TEST(Lanes, AnyIsSetExactlyWhenSomeLaneIsNonZero) {
  // Every pattern of four lanes, each 0, all ones (a comparison's mask) or another non-zero value
  // (a count), against the lane-by-lane test.
  const std::int64_t values[3] = {0, -1, 7};
  for (int pattern = 0; pattern < 81; ++pattern) {
    Lanes<4>::M m{};
    bool expected = false;
    int code = pattern;
    for (int i = 0; i < 4; ++i, code /= 3) {
      m[i] = values[code % 3];
      expected = expected || m[i] != 0;
    }
    EXPECT_EQ(any(m), expected) << "pattern " << pattern;
  }
}

}  // namespace
}  // namespace slipwalk::core
