#pragma once
// Clocks and order statistics for the timed point kinds: one place, so that every timing in the
// report is taken and summarised the same way.
#include <chrono>
#include <string>
#include <vector>

namespace slipwalk::sweeps {

/// The calling thread's CPU time, s: unlike wall time it does not count the time the thread waits
/// for a core, which on a shared machine is most of the noise.
[[nodiscard]] double thread_cpu_seconds();
/// CPU time of the whole process (all threads), s: the work parallel sections did.
[[nodiscard]] double process_cpu_seconds();

/// Wall seconds on the steady clock since `start`.
[[nodiscard]] double seconds_since(std::chrono::steady_clock::time_point start);
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
