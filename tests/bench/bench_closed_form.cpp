// Cost of v_ss per (F, μ): the algebraic closed form (aim: ≤ 2 µs), the GSL fixed
// point of the stroke map, and the exact event-driven simulation to 1e-12.
#include <benchmark/benchmark.h>

#include "events/exact_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/simulate.hpp"

namespace {

using slipwalk::inchworm::Params;

Params params(double F, double mu) {
  Params p;
  p.F = F;
  p.mu = mu;
  return p;
}

void BM_ClosedForm(benchmark::State& state) {
  // Sweep F over the regime II and I range so the branch predictor sees both regimes.
  double F = 10.0;
  for (auto _ : state) {
    F = F > 73.0 ? 10.0 : F + 0.37;
    benchmark::DoNotOptimize(slipwalk::inchworm::steady_state_closed_form(params(F, 1.0)).v_ss);
  }
}
BENCHMARK(BM_ClosedForm);

void BM_FixedPointBrent(benchmark::State& state) {
  double F = 10.0;
  for (auto _ : state) {
    F = F > 73.0 ? 10.0 : F + 0.37;
    benchmark::DoNotOptimize(slipwalk::inchworm::steady_state_fixed_point(params(F, 1.0)).v_ss);
  }
}
BENCHMARK(BM_FixedPointBrent);

void BM_ExactSimulation(benchmark::State& state, double F, double mu) {
  slipwalk::inchworm::SimulationOptions opt;
  opt.target = 1e-12;
  long long strokes = 0;
  for (auto _ : state) {
    slipwalk::events::ExactBackend backend;
    const auto s = slipwalk::inchworm::steady_state_by_simulation(params(F, mu), backend, opt);
    strokes = s.strokes;
    benchmark::DoNotOptimize(s.v_ss);
  }
  state.counters["strokes"] = static_cast<double>(strokes);
}
BENCHMARK_CAPTURE(BM_ExactSimulation, F45_mu1, 45.0, 1.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ExactSimulation, F5Mg_mu0_05, 73.575, 0.05)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
