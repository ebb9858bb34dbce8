// Per-frame cost of the spring-support search (thesis §3.3, Alg. 1) for a hexapod and for a
// 50-legged "centipede", on walking-like frames (feet stepping back and forth, swing feet
// lifted), and the cost of the convex-potential oracle the tests use (GSL BFGS + Newton) for the
// same hexapod frames. The 50/6 ratio is read off the two per-frame times of one run; the
// *PathOnly rows run Alg. 1 alone (no Newton route) on the same frames.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "../support/spring_support_oracle.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"

namespace {

using slipwalk::contact::Frame;
using slipwalk::contact::Robot;

constexpr int kFrames = 256;
constexpr double kPi = 3.14159265358979323846;

// Legs in pairs along the body (x from −half_length to +half_length, y = ±half_width), stepping
// in a wave: each foot's phase decides its stride position and whether it is lifted (swing).
struct Walker {
  Robot robot;
  std::vector<Frame> frames;
};

Walker walker(int pairs, double half_length, double half_width, double wave, unsigned seed) {
  const int n = 2 * pairs;
  Walker w{slipwalk::contact::uniform_robot(n, 2000.0, 0.5, 30.0), {}};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  for (int k = 0; k < kFrames; ++k) {
    Frame f(w.robot);
    const double time = static_cast<double>(k) / kFrames;
    for (int p = 0; p < pairs; ++p) {
      const double x0 = pairs == 1 ? 0.0 : -half_length + 2.0 * half_length * p / (pairs - 1);
      for (int side = 0; side < 2; ++side) {
        const int j = 2 * p + side;
        // wave = 0.5: alternating tripods; smaller: a travelling wave along the body.
        const double phase = std::fmod(time + 0.5 * side + wave * p, 1.0);
        const bool stance = phase < 0.55;
        const double stride = stance ? 0.04 * (1.0 - 2.0 * phase / 0.55) : 0.0;
        f.q(0, j) = x0 + stride + 0.002 * noise(rng);
        f.q(1, j) = (side == 0 ? 1.0 : -1.0) * half_width + 0.002 * noise(rng);
        // Swing feet rise to 2 cm and come down again: near lift-off and touch-down they are
        // within a compression of the ground and the contact set changes along the search.
        const double lift = stance ? 0.0 : 0.02 * std::sin(kPi * (phase - 0.55) / 0.45);
        f.q(2, j) = -0.12 + 0.001 * noise(rng) + lift;
      }
    }
    w.frames.push_back(f);
  }
  return w;
}

void run_support(benchmark::State& state, Walker w, bool newton = true) {
  slipwalk::contact::SupportOptions options;
  options.newton = newton;
  std::size_t i = 0;
  long long changes = 0;
  long long tipping = 0;
  long long certified = 0;
  long long calls = 0;
  for (auto _ : state) {
    Frame& f = w.frames[i];
    slipwalk::contact::spring_support(w.robot, f, options);
    benchmark::DoNotOptimize(f.z);
    changes += f.support.iterations;
    tipping += f.support.status == slipwalk::contact::SupportSummary::Status::kUnsupported ? 1 : 0;
    certified += f.support.route == slipwalk::contact::SupportSummary::Route::kNewton ? 1 : 0;
    ++calls;
    i = (i + 1) % w.frames.size();
  }
  state.counters["legs"] = w.robot.legs();
  state.counters["changes"] = static_cast<double>(changes) / static_cast<double>(calls);
  state.counters["tipping"] = static_cast<double>(tipping) / static_cast<double>(calls);
  state.counters["newton"] = static_cast<double>(certified) / static_cast<double>(calls);
}

void BM_SpringSupportHexapod(benchmark::State& state) {
  run_support(state, walker(3, 0.25, 0.18, 0.5, 1));
}
BENCHMARK(BM_SpringSupportHexapod);

void BM_SpringSupport50Legs(benchmark::State& state) {
  run_support(state, walker(25, 1.2, 0.15, 0.1, 2));
}
BENCHMARK(BM_SpringSupport50Legs);

// The same frames with Alg. 1 only (SupportOptions::newton = false): the Newton route's gain.
void BM_SpringSupportHexapodPathOnly(benchmark::State& state) {
  run_support(state, walker(3, 0.25, 0.18, 0.5, 1), false);
}
BENCHMARK(BM_SpringSupportHexapodPathOnly);

void BM_SpringSupport50LegsPathOnly(benchmark::State& state) {
  run_support(state, walker(25, 1.2, 0.15, 0.1, 2), false);
}
BENCHMARK(BM_SpringSupport50LegsPathOnly);

void BM_ConvexOracleHexapod(benchmark::State& state) {
  const Walker w = walker(3, 0.25, 0.18, 0.5, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    const slipwalk::testing::SupportProblem p{w.frames[i].q, w.robot.K, w.robot.Mg};
    benchmark::DoNotOptimize(slipwalk::testing::minimize_support_potential(p).z);
    i = (i + 1) % w.frames.size();
  }
}
BENCHMARK(BM_ConvexOracleHexapod);

}  // namespace

BENCHMARK_MAIN();
