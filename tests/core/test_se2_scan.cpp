// The parallel prefix product on SE(2) (core/se2_scan.hpp) and the worker pool it runs on
// (core/worker_pool.hpp): the blocked scan equals the sequential composition to 1e-12 over long
// random trajectories, is the same to the bit for any thread count, and handles the edge cases
// (no steps, one block, more blocks than steps); the pool runs every task once and passes on a
// task's exception.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"
#include "core/se2_scan.hpp"
#include "core/worker_pool.hpp"
#include "sweeps/engine/random.hpp"

namespace slipwalk::core {
namespace {

/// n random increments exp(ξ dt): body twists of up to 0.5 m/s and 2 rad/s over dt = 0.01 s.
std::vector<Pose2> random_increments(long long n, std::uint64_t seed) {
  sweeps::Random rng(seed, 0);
  std::vector<Pose2> inc(static_cast<std::size_t>(n));
  for (Pose2& p : inc) {
    p = exp(0.01 * Eigen::Vector3d(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5),
                                   rng.uniform(-2.0, 2.0)));
  }
  return inc;
}

double max_difference(const std::vector<Pose2>& a, const std::vector<Pose2>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    d = std::max({d, std::abs(a[k].x - b[k].x), std::abs(a[k].y - b[k].y),
                  std::abs(a[k].theta - b[k].theta)});
  }
  return d;
}

TEST(Se2Scan, PrefixProductEqualsSequentialComposition) {
  const Pose2 start{1.0, -2.0, 0.3};
  for (long long n : {1LL, 2LL, 7LL, 1000LL, 100000LL}) {
    const auto inc = random_increments(n, static_cast<std::uint64_t>(n));
    std::vector<Pose2> seq(inc.size() + 1), scan(inc.size() + 1);
    sequential_product(start, inc, seq);
    for (int threads : {1, 2, 3}) {
      WorkerPool pool(threads);
      for (int blocks : {1, 5, 64, 1000000}) {
        prefix_product(start, inc, scan, pool, blocks);
        // Poses reach ~10 m and ~10³ rad over 10⁵ steps; rounding stays near 1e-13.
        EXPECT_LT(max_difference(seq, scan), 1e-12)
            << "n = " << n << ", threads = " << threads << ", blocks = " << blocks;
      }
    }
  }
}

TEST(Se2Scan, SameBitsOnAnyNumberOfThreads) {
  const auto inc = random_increments(20000, 7);
  std::vector<Pose2> one(inc.size() + 1), many(inc.size() + 1);
  WorkerPool pool1(1);
  prefix_product({}, inc, one, pool1, 64);
  for (int threads : {2, 3, 4}) {
    WorkerPool pool(threads);
    prefix_product({}, inc, many, pool, 64);
    for (std::size_t k = 0; k < one.size(); ++k) {
      ASSERT_EQ(one[k].x, many[k].x);
      ASSERT_EQ(one[k].y, many[k].y);
      ASSERT_EQ(one[k].theta, many[k].theta);
    }
  }
}

TEST(Se2Scan, NoIncrementsGiveTheStart) {
  WorkerPool pool(2);
  std::vector<Pose2> out(1);
  const Pose2 start{1.0, 2.0, 3.0};
  prefix_product(start, std::span<const Pose2>(), out, pool, 8);
  EXPECT_EQ(out[0].x, 1.0);
  EXPECT_EQ(out[0].theta, 3.0);
}

TEST(WorkerPool, RunsEveryTaskOnceOnValidWorkers) {
  for (int threads : {1, 2, 4}) {
    WorkerPool pool(threads);
    for (int round = 0; round < 50; ++round) {  // many runs: no lost wake-ups
      std::vector<std::atomic<int>> hits(97);
      std::atomic<bool> bad_worker{false};
      pool.run(97, [&](int i, int worker) {
        hits[static_cast<std::size_t>(i)]++;
        if (worker < 0 || worker >= threads) {
          bad_worker = true;
        }
      });
      for (const auto& h : hits) {
        ASSERT_EQ(h.load(), 1);
      }
      ASSERT_FALSE(bad_worker);
    }
  }
}

TEST(WorkerPool, PassesOnATasksExceptionAndStaysUsable) {
  WorkerPool pool(3);
  EXPECT_THROW(pool.run(10,
                        [](int i, int) {
                          if (i == 4) {
                            throw std::runtime_error("task 4");
                          }
                        }),
               std::runtime_error);
  std::atomic<int> count{0};
  pool.run(10, [&](int, int) { count++; });
  EXPECT_EQ(count.load(), 10);
  EXPECT_THROW(WorkerPool(0), InputError);
}

}  // namespace
}  // namespace slipwalk::core
