// Cost of the brute-force planner (thesis §5.5: "a single planning step takes 6.9 ms on the GPU",
// 4096 options × 20 substeps; 31 s on a CPU). Rows:
//  - BM_Kernel / BM_KernelReference (legs, M): the inner loop alone, fast and reference, over 4096
//    random options of one node (every leg chooses, so 12 legs are measured on a subset of their
//    4^12 options); counter s_per_evaluation = time per option-substep.
//  - BM_FullStep (legs, M, threads): one planning step enumerating all M^N options
//    (deduplicate = false) at the tripod start; 6 and 8 legs (4^10 and 4^12 options take seconds
//    per step: use BM_Kernel's per-evaluation time for them).
//  - BM_DedupStep (legs, M, threads): planning steps as the planner runs them (deduplicate = true)
//    over the states of a straight plan (300 steps; 40 beyond 6 legs), cycled; counter options =
//    distinct options per step.
// Counters: options_per_second (options integrated per second of wall time). Compare rows as
// ratios taken in one run; the timed sweep studies/ch5_planning/cost.toml gives the report's
// numbers.
#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <vector>

#include "planning/option_kernel.hpp"
#include "planning/planner.hpp"

namespace {

using namespace slipwalk::planning;

/// The M speed choices of a row (M = 4: the thesis' {−1, 0, 1, 2} turns/s).
std::vector<double> speeds(int m) {
  switch (m) {
    case 2:
      return {0.0, 1.0};
    case 3:
      return {-1.0, 0.0, 1.0};
    case 5:
      return {-1.0, 0.0, 1.0, 2.0, 3.0};
    default:
      return {-1.0, 0.0, 1.0, 2.0};
  }
}

template <bool kFast>
void kernel(benchmark::State& state) {
  const auto legs = static_cast<int>(state.range(0));
  const PlanRobot robot = bigant_plan_robot(legs);
  PlanOptions options;
  options.speeds = speeds(static_cast<int>(state.range(1)));
  options.contact = ContactRule::kAll;
  NodeTable table;
  size_node(robot, options, table);
  slipwalk::contact::Frame frame(robot.robot);
  build_node(robot, options, tripod_start(robot).phi, table, frame);
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> digit(0, static_cast<int>(options.speeds.size()) - 1);
  constexpr int kOptions = 4096;
  std::vector<std::array<int, kMaxPlanLegs>> columns(kOptions);
  for (auto& c : columns) {
    std::array<int, kMaxPlanLegs> digits{};
    for (int i = 0; i < legs; ++i) {
      digits[static_cast<std::size_t>(i)] = digit(rng);
    }
    option_columns(table, digits.data(), c.data());
  }
  long long evaluations = 0;
  for (auto _ : state) {
    if constexpr (kFast) {
      // As the planner calls it: kOptionBatch options at a time.
      for (std::size_t o = 0; o < columns.size(); o += kOptionBatch) {
        std::array<const int*, kOptionBatch> pointers{};
        std::array<slipwalk::core::Pose2, kOptionBatch> poses{};
        std::array<bool, kOptionBatch> ok{};
        for (std::size_t l = 0; l < kOptionBatch; ++l) {
          pointers[l] = columns[o + l].data();
        }
        integrate_options(robot, options, table, pointers.data(), kOptionBatch, table.substeps,
                          poses.data(), ok.data(), frame);
        benchmark::DoNotOptimize(ok);
        benchmark::DoNotOptimize(poses);
      }
    } else {
      for (const auto& c : columns) {
        slipwalk::core::Pose2 pose;
        const bool ok = integrate_option_reference(robot, options, table, c.data(), table.substeps,
                                                   pose, frame);
        benchmark::DoNotOptimize(ok);
        benchmark::DoNotOptimize(pose);
      }
    }
    evaluations += static_cast<long long>(kOptions) * table.substeps;
  }
  // Seconds per option-substep (printed with an SI prefix: "85n" is 85 ns).
  state.counters["s_per_evaluation"] = benchmark::Counter(
      static_cast<double>(evaluations), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["options_per_second"] = benchmark::Counter(
      static_cast<double>(evaluations) / table.substeps, benchmark::Counter::kIsRate);
  state.counters["legs"] = legs;
}

void BM_Kernel(benchmark::State& state) { kernel<true>(state); }
void BM_KernelReference(benchmark::State& state) { kernel<false>(state); }

void step(benchmark::State& state, bool dedup) {
  const auto legs = static_cast<int>(state.range(0));
  const PlanRobot robot = bigant_plan_robot(legs);
  PlanOptions options;
  options.speeds = speeds(static_cast<int>(state.range(1)));
  options.threads = static_cast<int>(state.range(2));
  options.deduplicate = dedup;
  Goal goal;
  goal.twist = {0.2, 0.0, 0.0};
  // The states a plan passes through (dedup: 300 steps for BigANT, 40 for more legs, whose
  // later steps have up to 4^N options; full enumeration: its start).
  std::vector<PlanState> states;
  if (dedup) {
    PlanOptions run = options;
    run.steps = legs == 6 ? 300 : 40;
    plan(robot, run, goal, tripod_start(robot),
         [&states](const StepRecord& r) { states.push_back(r.state); });
  } else {
    states.push_back(tripod_start(robot));
  }
  PlanData data(robot, options);
  StepChoice choice;
  long long evaluated = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    plan_step(robot, options, goal, states[k], data, choice);
    evaluated += choice.evaluated;
    k = (k + 1) % states.size();
  }
  state.counters["options"] =
      static_cast<double>(evaluated) / static_cast<double>(state.iterations());
  state.counters["options_per_second"] =
      benchmark::Counter(static_cast<double>(evaluated), benchmark::Counter::kIsRate);
  state.counters["legs"] = legs;
}

void BM_FullStep(benchmark::State& state) { step(state, false); }
void BM_DedupStep(benchmark::State& state) { step(state, true); }

void kernel_args(benchmark::internal::Benchmark* b) {
  for (const int legs : {6, 8, 10, 12}) {
    b->Args({legs, 4});
  }
  for (const int m : {2, 3, 5}) {
    b->Args({6, m});
  }
}

void step_args(benchmark::internal::Benchmark* b, bool full) {
  for (const int threads : {1, 2}) {
    // Full enumeration beyond 8 legs (4^10, 4^12 options) and the deduplicated planner at 12
    // legs (up to 4^12 options a step late in a plan) take seconds per step: BM_Kernel's time per
    // option-substep costs them.
    for (const int legs : full ? std::vector<int>{6, 8} : std::vector<int>{6, 8, 10}) {
      b->Args({legs, 4, threads});
    }
    for (const int m : {2, 3, 5}) {
      b->Args({6, m, threads});
    }
  }
}

BENCHMARK(BM_Kernel)->Apply(kernel_args)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KernelReference)->Apply(kernel_args)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullStep)
    ->Apply([](benchmark::internal::Benchmark* b) { step_args(b, true); })
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_DedupStep)
    ->Apply([](benchmark::internal::Benchmark* b) { step_args(b, false); })
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
