// Cost per frame of the friction balance (§3.4) with contact and F_z given: viscous-Coulomb (issue
// 5 target ≤ 1 µs for a hexapod), the local connection A, the ε-law and classical Coulomb to a
// relative duality gap of 1e-9 (target ≤ 10 µs and ≤ 10× viscous), for 3…50 legs (target: ≤ ×2
// from 3 to 50 legs). Robots as in thesis §3.5.3 / Fig. 3.13: a disk of radius 0.3 m with N legs
// equally spaced on the rim; 256 random poses and velocities per N, all feet on the ground with
// random loads, cycled through so that no branch is learnt. Compare the rows as ratios.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "friction/solvers.hpp"

namespace {

using slipwalk::contact::Frame;
using slipwalk::contact::Robot;

struct Pool {
  Robot robot;
  std::vector<Frame> frames;
};

Pool make_pool(int n, bool aniso = false) {
  Pool p{slipwalk::contact::uniform_robot(n), {}};
  std::mt19937 rng(static_cast<unsigned>(1000 + n));
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  if (aniso) {
    for (int k = 0; k < n; ++k) {
      p.robot.w.col(k) << U(rng), U(rng);
    }
  }
  for (int i = 0; i < 256; ++i) {
    Frame f(p.robot);
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * M_PI * k / n;
      f.q.col(k) << 0.3 * std::cos(a) + 0.05 * U(rng), 0.3 * std::sin(a) + 0.05 * U(rng), -0.1;
      f.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
      f.contact[static_cast<std::size_t>(k)] = 1;
      f.Fz(k) = (1.0 + 0.5 * U(rng)) / n;
    }
    p.frames.push_back(std::move(f));
  }
  return p;
}

template <class Solve>
void run(benchmark::State& state, Pool& pool, Solve solve) {
  std::size_t i = 0;
  double iterations = 0.0;
  double unique = 0.0;
  double certified = 0.0;
  long long calls = 0;
  for (auto _ : state) {
    Frame& f = pool.frames[i];
    i = (i + 1) % pool.frames.size();
    solve(pool.robot, f);
    benchmark::DoNotOptimize(f.v_body.data());
    iterations += f.friction.iterations;
    unique += f.friction.unique ? 1.0 : 0.0;
    certified += f.friction.converged ? 1.0 : 0.0;
    ++calls;
  }
  const double c = calls > 0 ? static_cast<double>(calls) : 1.0;
  state.counters["iters"] = iterations / c;
  state.counters["unique"] = unique / c;
  state.counters["ok"] = certified / c;
}

void BM_Viscous(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)));
  run(state, pool,
      [](const Robot& r, Frame& f) { slipwalk::friction::solve_viscous_coulomb(r, f); });
}

void BM_ViscousAnisotropic(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)), true);
  run(state, pool,
      [](const Robot& r, Frame& f) { slipwalk::friction::solve_viscous_coulomb(r, f); });
}

void BM_LocalConnection(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot& r, Frame& f) { slipwalk::connection::local_connection(r, f); });
}

void BM_Epsilon0_01(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot& r, Frame& f) { slipwalk::friction::solve_epsilon(r, f, 0.01); });
}

void BM_Coulomb1e9(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)));
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  run(state, pool,
      [&opt](const Robot& r, Frame& f) { slipwalk::friction::solve_coulomb(r, f, opt); });
}

void BM_CoulombAnisotropic1e9(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)), true);
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  run(state, pool,
      [&opt](const Robot& r, Frame& f) { slipwalk::friction::solve_coulomb(r, f, opt); });
}

#define LEGS Arg(3)->Arg(6)->Arg(12)->Arg(24)->Arg(50)
BENCHMARK(BM_Viscous)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ViscousAnisotropic)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_LocalConnection)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_Epsilon0_01)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_Coulomb1e9)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombAnisotropic1e9)->LEGS->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
