// The engine's order statistics against their definitions: numpy's default (linear) percentile,
// the median as the middle value or the mean of the two middle ones, NaN for no data.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {
namespace {

TEST(Timing, QuantilesInterpolateLinearlyBetweenOrderStatistics) {
  // numpy.percentile([1, 2, 4, 8, 16], [0, 25, 50, 75, 90, 100]) = 1, 2, 4, 8, 12.8, 16
  const std::vector<double> sorted = {1.0, 2.0, 4.0, 8.0, 16.0};
  EXPECT_EQ(quantile_of_sorted(sorted, 0.0), 1.0);
  EXPECT_EQ(quantile_of_sorted(sorted, 0.25), 2.0);
  EXPECT_EQ(quantile_of_sorted(sorted, 0.5), 4.0);
  EXPECT_EQ(quantile_of_sorted(sorted, 0.75), 8.0);
  EXPECT_NEAR(quantile_of_sorted(sorted, 0.9), 12.8, 1e-12);
  EXPECT_EQ(quantile_of_sorted(sorted, 1.0), 16.0);
  // numpy.percentile([3, 1, 2, 10], 50) = 2.5: the unsorted form sorts first
  EXPECT_EQ(quantile({3.0, 1.0, 2.0, 10.0}, 0.5), 2.5);
}

TEST(Timing, MedianIsTheMiddleOrTheMeanOfTheTwoMiddleValues) {
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_EQ(median({7.0}), 7.0);
}

TEST(Timing, NoValuesGiveNaN) {
  EXPECT_TRUE(std::isnan(median({})));
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
  EXPECT_TRUE(std::isnan(quantile_of_sorted({}, 0.5)));
}

TEST(Timing, DurationsPrintWithOneDecimal) {
  EXPECT_EQ(seconds_text(61.25), "61.2 s");
  EXPECT_EQ(seconds_text(0.04), "0.0 s");
}

}  // namespace
}  // namespace slipwalk::sweeps
