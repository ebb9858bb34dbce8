// Cost of v_ss of the dm model (§2.5) per (F, μ, α): the GSL Brent fixed point of the
// hand-derived cycle map (mass_swap_closed_form.hpp), and the exact event-driven simulation of
// MassSwapSystem to 1e-10 at F = 20 N, μ = 1 with α = 1 (the body stops during the swaps) and
// α = 10 (it is thrown out of its friction cone).
#include <benchmark/benchmark.h>

#include "events/exact_backend.hpp"
#include "inchworm/mass_swap.hpp"
#include "inchworm/mass_swap_closed_form.hpp"
#include "inchworm/simulate.hpp"

namespace {

using slipwalk::inchworm::Params;

Params params(double F, double mu, double alpha) {
  Params p;
  p.model = slipwalk::inchworm::SwapModel::kMass;
  p.F = F;
  p.mu = mu;
  p.alpha = alpha;
  return p;
}

void BM_DmFixedPoint(benchmark::State& state, double F, double mu, double alpha) {
  const Params p = params(F, mu, alpha);
  int iterations = 0;
  for (auto _ : state) {
    const auto s = slipwalk::inchworm::dm_steady_state(p);
    iterations = s.iterations;
    benchmark::DoNotOptimize(s.v_ss);
  }
  state.counters["brent_iterations"] = iterations;
}
BENCHMARK_CAPTURE(BM_DmFixedPoint, F20_mu1_a1, 20.0, 1.0, 1.0);
BENCHMARK_CAPTURE(BM_DmFixedPoint, F20_mu1_a10, 20.0, 1.0, 10.0);
BENCHMARK_CAPTURE(BM_DmFixedPoint, F73_mu0_1_a10, 73.575, 0.1, 10.0);
BENCHMARK_CAPTURE(BM_DmFixedPoint, F10_mu1_a0_05, 10.4, 1.0, 0.05);

void BM_DmFixedPointSweep(benchmark::State& state) {
  // F, μ and α varied from call to call so that the branch predictor sees every case.
  double F = 10.0;
  int k = 0;
  const double mus[] = {0.1, 0.6, 1.0};
  const double alphas[] = {0.05, 1.0, 5.0, 10.0};
  for (auto _ : state) {
    F = F > 73.0 ? 10.0 : F + 0.37;
    k = (k + 1) % 12;
    benchmark::DoNotOptimize(
        slipwalk::inchworm::dm_steady_state(params(F, mus[k % 3], alphas[k / 3])).v_ss);
  }
}
BENCHMARK(BM_DmFixedPointSweep);

void BM_DmCycleMap(benchmark::State& state) {
  const Params p = params(20.0, 1.0, 1.0);
  double c = 0.5;
  for (auto _ : state) {
    c = 0.5 + 1e-3 * slipwalk::inchworm::dm_cycle_map(p, c).c_next;
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_DmCycleMap);

void BM_DmExactSimulation(benchmark::State& state, double F, double mu, double alpha) {
  slipwalk::inchworm::SimulationOptions opt;
  opt.target = 1e-10;
  const slipwalk::inchworm::MassSwapSystem sys(params(F, mu, alpha));
  long long strokes = 0;
  for (auto _ : state) {
    slipwalk::events::ExactBackend backend;
    const auto s = slipwalk::inchworm::steady_state_by_simulation(sys, backend, opt);
    strokes = s.strokes;
    benchmark::DoNotOptimize(s.v_ss);
  }
  state.counters["strokes"] = static_cast<double>(strokes);
}
BENCHMARK_CAPTURE(BM_DmExactSimulation, F20_mu1_a1, 20.0, 1.0, 1.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_DmExactSimulation, F20_mu1_a10, 20.0, 1.0, 10.0)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
