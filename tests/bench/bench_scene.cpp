// "Unused effects cost nothing" (DESIGN.md, Principles): the time per step of BigANT's tripod (0.5
// Hz, dt = 0.01 s, 1000 steps per run) through the kernel hand-written for the flat isotropic
// viscous case (scene/reference_kernel.hpp) and through composed scenes (scene::compose) with
// none or exactly one effect: anisotropic friction, Coulomb friction, the inertia filter, the
// residual B, measurement noise, a slope, stairs. Counter "ns_per_step" per row.
// BM_FlatRatio times the hand-written and the composed flat scene alternately in one run and
// reports the median of the per-pair ratios composed / hand-written (target ≤ 1.05). The
// report's table comes from the scene_cost point kind (studies/scene_effects), which times the
// same cases the same way; this is the developer's quick view of it.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "scene/reference_kernel.hpp"
#include "scene/scene.hpp"

namespace {

using slipwalk::connection::TrajectoryData;
using slipwalk::connection::TrajectorySink;
using slipwalk::connection::TrajectoryStep;
namespace scene = slipwalk::scene;

constexpr long long kSteps = 1000;

const std::vector<std::pair<std::string, std::string>>& cases() {
  static const std::vector<std::pair<std::string, std::string>> all = {
      {"flat_viscous", "[friction]\nlaw = \"viscous\"\n"},
      {"anisotropic", "[friction]\nlaw = \"anisotropic\"\nw = [0.8, 0.3]\n"},
      {"coulomb", "[friction]\nlaw = \"coulomb\"\n"},
      {"filter", "[friction]\nlaw = \"viscous\"\n[filter]\n"},
      {"residual", "[friction]\nlaw = \"viscous\"\n"},  // B set below
      {"noise", "[friction]\nlaw = \"viscous\"\n[noise]\nsigma = 0.001\nsigma_theta = 0.01\n"},
      {"slope", "[friction]\nlaw = \"viscous\"\n[terrain]\nkind = \"slope\"\nangle_deg = 10\n"},
      {"stairs",
       "[friction]\nlaw = \"viscous\"\n[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = 0.12\n"},
  };
  return all;
}

scene::Simulator simulator(std::size_t i) {
  const auto& [name, tables] = cases()[i];
  scene::Scene s = scene::parse_scene(
      "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = 0.5\n[run]\nduration "
      "= 10.0\nsteps = " +
          std::to_string(kSteps) + "\n" + tables,
      name);
  if (name == "residual") {
    scene::ResidualEffect r;
    r.B = Eigen::Matrix<double, 3, Eigen::Dynamic>::Constant(3, 12, 0.01);
    s.residual = r;
  }
  return scene::compose(s);
}

/// What a CSV writer reads, kept observable.
struct Sink {
  double sum = 0.0;
  TrajectorySink fn() {
    return [this](const TrajectoryStep& s) {
      sum += s.measured.x + s.v_body(0) + s.slip(0, 0) + s.frame.Fz(0);
    };
  }
};

/// Wall time per step: a rate of (steps · 1e-9) per second, inverted.
benchmark::Counter ns_per_step(const benchmark::State& state) {
  return benchmark::Counter(static_cast<double>(state.iterations() * (kSteps + 1)) * 1e-9,
                            benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_HandWritten(benchmark::State& state) {
  const scene::Simulator sim = simulator(0);
  Sink sink;
  const TrajectorySink fn = sink.fn();
  for (auto _ : state) {
    TrajectoryData data(sim.walker.robot);
    benchmark::DoNotOptimize(scene::run_flat_viscous(sim.walker, sim.options, data, fn));
  }
  benchmark::DoNotOptimize(sink.sum);
  state.counters["ns_per_step"] = ns_per_step(state);
}
BENCHMARK(BM_HandWritten)->Unit(benchmark::kMicrosecond);

void BM_Composed(benchmark::State& state) {
  const auto i = static_cast<std::size_t>(state.range(0));
  const scene::Simulator sim = simulator(i);
  state.SetLabel(cases()[i].first + " (" + sim.kernel_name + ")");
  Sink sink;
  const TrajectorySink fn = sink.fn();
  for (auto _ : state) {
    benchmark::DoNotOptimize(sim.run(fn));
  }
  benchmark::DoNotOptimize(sink.sum);
  state.counters["ns_per_step"] = ns_per_step(state);
}
BENCHMARK(BM_Composed)->DenseRange(0, 7)->Unit(benchmark::kMicrosecond);

/// Hand-written and composed flat runs alternately; counter ratio = median(composed / hand).
void BM_FlatRatio(benchmark::State& state) {
  const scene::Simulator sim = simulator(0);
  Sink sink;
  const TrajectorySink fn = sink.fn();
  std::vector<double> ratio;
  using Clock = std::chrono::steady_clock;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    {
      TrajectoryData data(sim.walker.robot);
      benchmark::DoNotOptimize(scene::run_flat_viscous(sim.walker, sim.options, data, fn));
    }
    const auto t1 = Clock::now();
    benchmark::DoNotOptimize(sim.run(fn));
    const auto t2 = Clock::now();
    ratio.push_back(std::chrono::duration<double>(t2 - t1).count() /
                    std::chrono::duration<double>(t1 - t0).count());
  }
  benchmark::DoNotOptimize(sink.sum);
  std::sort(ratio.begin(), ratio.end());
  state.counters["ratio"] = ratio.empty() ? 0.0 : ratio[ratio.size() / 2];
}
BENCHMARK(BM_FlatRatio)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
