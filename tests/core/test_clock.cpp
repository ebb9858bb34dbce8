// The clocks every timing reads: thread CPU time counts work and not waiting, process CPU time
// covers the thread's, and the steady clock measures at least a sleep's length.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "core/clock.hpp"

namespace slipwalk::core {
namespace {

/// Busy work the optimiser cannot drop: about `n` dependent floating-point operations.
double spin(long long n) {
  volatile double x = 1.0;
  for (long long i = 0; i < n; ++i) {
    x = std::sqrt(x + 1.0);
  }
  return x;
}

TEST(Clock, ThreadCpuTimeCountsWorkButNotSleep) {
  const double t0 = thread_cpu_seconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  const double slept = thread_cpu_seconds() - t0;
  const double t1 = thread_cpu_seconds();
  EXPECT_GT(spin(20'000'000), 1.0);
  const double worked = thread_cpu_seconds() - t1;
  EXPECT_LT(slept, 0.03);  // a sleeping thread uses next to no CPU
  EXPECT_GT(worked, 0.005);
  EXPECT_GT(worked, slept);
}

TEST(Clock, ProcessCpuTimeIncludesThisThreadsWork) {
  const double p0 = process_cpu_seconds();
  const double t0 = thread_cpu_seconds();
  EXPECT_GT(spin(10'000'000), 1.0);
  const double thread = thread_cpu_seconds() - t0;
  const double process = process_cpu_seconds() - p0;
  EXPECT_GE(process, 0.9 * thread);
}

TEST(Clock, SteadySecondsSinceCoverASleep) {
  const auto start = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double s = seconds_since(start);
  EXPECT_GE(s, 0.020);
  EXPECT_LT(s, 10.0);
}

}  // namespace
}  // namespace slipwalk::core
