#pragma once
// Clocks and order statistics for the timed point kinds: one place, so that every timing in the
// report is taken and summarised the same way.
#include <string>
#include <vector>

#include "core/clock.hpp"

namespace slipwalk::sweeps {

// The clocks are the library's (core/clock.hpp), so the engine and the library time alike.
using core::process_cpu_seconds;
using core::seconds_since;
using core::thread_cpu_seconds;

/// A duration as the logs print it: "12.3 s".
[[nodiscard]] std::string seconds_text(double seconds);

/// The p-quantile of sorted values by linear interpolation between order statistics (numpy's
/// default percentile); NaN for no values.
[[nodiscard]] double quantile_of_sorted(const std::vector<double>& sorted, double p);
/// The same for values in any order.
[[nodiscard]] double quantile(std::vector<double> values, double p);
/// The median: the middle value, or the mean of the two middle values; NaN for no values.
[[nodiscard]] double median(std::vector<double> values);

}  // namespace slipwalk::sweeps
