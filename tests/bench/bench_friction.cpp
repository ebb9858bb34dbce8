// Cost per frame of the friction balance (§3.4) with contact and F_z given: viscous-Coulomb, the
// local connection A, the ε-law and classical Coulomb to a relative duality gap of 1e-9 (aim: ≤ 5×
// viscous on spring-supported hexapod frames, along a trajectory with warm starts, whose solves are
// also timed route by route), for 3…50 legs; Coulomb on a 17° slope beside the flat hexapod (aim:
// ≤ 1.5× flat); and the whole frame (connection::evaluate: spring support, A, friction law; aims:
// ≤ 0.15 µs for a hexapod and ≤ 8 ns per leg, the slope of a + b N over the disk robots) and the
// spring support alone, the rows Fig. 3.13a times; both also four independent frames at a time
// (evaluate_batch, spring_support_batch: the counter "frame" is their time per frame). (The
// report's performance page measures the same aims on the ch3_legged cost study, with the
// arithmetic each stage must do beside them.) Robots as in thesis §3.5.3 / Fig. 3.13: a disk of
// radius 0.3 m with N legs equally spaced on the rim; 4096 random poses and velocities per N, all
// feet on the ground with random loads (for the whole frame: random leg heights, so that the
// support search works). Each is copied into one working frame before the call (BM_CopyInputs times
// the copy alone): so many inputs that the branch predictor cannot learn the sequence (with 256, a
// current CPU memorizes it for small N and a 12-leg spring support looked twice as fast as it is),
// one frame so that they need not fit in the caches. Compare the rows as ratios; the counter "legs"
// lets a script fit time = a + b N per row.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "contact/support_batch.hpp"
#include "friction/solvers.hpp"
#include "robots/robots.hpp"
#include "terrain/terrain.hpp"

namespace {

using slipwalk::contact::Frame;
using slipwalk::contact::Robot;

/// One frame's inputs.
struct Inputs {
  Eigen::Matrix3Xd q;
  Eigen::Matrix3Xd qdot;
  std::vector<char> contact;
  Eigen::VectorXd Fz;
};

struct Pool {
  Robot robot;
  std::vector<Inputs> inputs;
  Frame frame;  ///< the working frame
  explicit Pool(Robot r) : robot(std::move(r)), frame(robot) {}
  void load(std::size_t i) {
    const Inputs& in = inputs[i];
    frame.q = in.q;
    frame.qdot = in.qdot;
    frame.contact = in.contact;
    frame.Fz = in.Fz;
  }
};

constexpr int kInputs = 4096;

Pool make_pool(int n, bool aniso = false) {
  Pool p(slipwalk::contact::uniform_robot(n));
  std::mt19937 rng(static_cast<unsigned>(1000 + n));
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  if (aniso) {
    for (int k = 0; k < n; ++k) {
      p.robot.w.col(k) << U(rng), U(rng);
    }
  }
  for (int i = 0; i < kInputs; ++i) {
    Inputs in{Eigen::Matrix3Xd(3, n), Eigen::Matrix3Xd(3, n),
              std::vector<char>(static_cast<std::size_t>(n), 1), Eigen::VectorXd(n)};
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * M_PI * k / n;
      in.q.col(k) << 0.3 * std::cos(a) + 0.05 * U(rng), 0.3 * std::sin(a) + 0.05 * U(rng), -0.1;
      in.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
      in.Fz(k) = (1.0 + 0.5 * U(rng)) / n;
    }
    p.inputs.push_back(std::move(in));
  }
  return p;
}

template <class Solve>
void run(benchmark::State& state, Pool& pool, Solve solve) {
  std::size_t i = 0;
  double iterations = 0.0;
  double unique = 0.0;
  double certified = 0.0;
  double changes = 0.0;
  double contacts = 0.0;
  double newton = 0.0;
  double steps = 0.0;
  double sliding = 0.0;
  double fallback = 0.0;
  long long calls = 0;
  Frame& f = pool.frame;
  for (auto _ : state) {
    pool.load(i);
    i = (i + 1) % pool.inputs.size();
    solve(pool.robot, f);
    benchmark::DoNotOptimize(f.v_body.data());
    iterations += f.friction.iterations;
    unique += f.friction.unique ? 1.0 : 0.0;
    certified += f.friction.converged ? 1.0 : 0.0;
    changes += f.support.iterations;
    contacts += static_cast<double>(std::count(f.contact.begin(), f.contact.end(), 1));
    newton += f.support.route == slipwalk::contact::SupportSummary::Route::kNewton ? 1.0 : 0.0;
    steps += f.support.newton_steps;
    sliding += f.friction.message.rfind("sliding", 0) == 0 ? 1.0 : 0.0;
    fallback +=
        f.friction.route == slipwalk::contact::FrictionSummary::Route::kFallback ? 1.0 : 0.0;
    ++calls;
  }
  const double c = calls > 0 ? static_cast<double>(calls) : 1.0;
  state.counters["legs"] = static_cast<double>(pool.robot.legs());
  state.counters["iters"] = iterations / c;
  state.counters["unique"] = unique / c;
  state.counters["ok"] = certified / c;
  state.counters["changes"] = changes / c;    // contact changes of the support search
  state.counters["contacts"] = contacts / c;  // feet on the ground
  state.counters["newton"] = newton / c;      // support certified by the Newton route
  state.counters["steps"] = steps / c;        // its Newton steps (also when it handed over)
  state.counters["sliding"] = sliding / c;    // Coulomb under a load it cannot hold
  state.counters["fallback"] = fallback / c;  // Coulomb through the fallback route
}

void BM_CopyInputs(benchmark::State& state) {
  Pool pool = make_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot&, Frame&) {});
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

/// Frames as the ch3_legged cost study draws them (sweeps/legged_cost_points.cpp): a BigANT-like
/// hexapod (feet jittered about x ∈ {−0.3, 0, 0.3} m, y = ±0.2 m, about half lifted), the spring
/// support deciding which feet are down and their loads (3–6, often one foot that Coulomb
/// friction holds still), feet sliding backward at ~0.1 m/s plus a turn. The rows the study's
/// hexapod ratio comes from; the all-feet-down disks above have fewer static feet. On a slope of
/// σ rad the support carries Mg cos σ, as connection::SlopeGround's does (σ = 0: the same frames).
Pool make_supported_hexapod_pool(double slope = 0.0) {
  const double Mg = 8.18 * 9.81;
  Pool p(slipwalk::contact::uniform_robot(6, Mg / (6 * 0.01), 1.0, Mg));
  Robot support = p.robot;
  support.Mg = Mg * std::cos(slope);
  std::mt19937 rng(3000);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::normal_distribution<double> N(0.0, 1.0);
  Frame& f = p.frame;
  while (p.inputs.size() < kInputs) {
    for (int k = 0; k < 6; ++k) {
      const int row = k / 2 - 1;  // the pair of legs: back, middle, front
      f.q.col(k) << 0.3 * row + 0.02 * U(rng), (k % 2 == 0 ? 0.2 : -0.2) + 0.02 * U(rng),
          -0.1 + 0.002 * U(rng) + (U(rng) < 0.0 ? 0.0225 + 0.0175 * U(rng) : 0.0);
    }
    slipwalk::contact::spring_support(support, f);
    if (f.support.status != slipwalk::contact::SupportSummary::Status::kBalanced) {
      continue;
    }
    const double turn = 0.05 * N(rng) / 0.3;
    for (int k = 0; k < 6; ++k) {
      f.qdot.col(k) << 0.1 * (-1.0 + 0.5 * N(rng)) - turn * f.q(1, k),
          0.05 * N(rng) + turn * f.q(0, k), 0.0;
    }
    p.inputs.push_back(Inputs{f.q, f.qdot, f.contact, f.Fz});
  }
  return p;
}

void BM_ViscousSupportedHexapod(benchmark::State& state) {
  Pool pool = make_supported_hexapod_pool();
  run(state, pool,
      [](const Robot& r, Frame& f) { slipwalk::friction::solve_viscous_coulomb(r, f); });
}

void BM_CoulombSupportedHexapod1e9(benchmark::State& state) {
  Pool pool = make_supported_hexapod_pool();
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  run(state, pool,
      [&opt](const Robot& r, Frame& f) { slipwalk::friction::solve_coulomb(r, f, opt); });
}

/// The same hexapod uphill on §5.2.1's 17° slope (heading 0, yaw 0): gravity's planar part
/// Mg sin σ pulls backward (terrain::slope_load), about 30 % of what the feet can hold
/// (μ Mg cos σ); certified like the flat row, which runs beside it for the ratio slope/flat.
void BM_CoulombSlopeHexapod1e9(benchmark::State& state) {
  const slipwalk::terrain::Slope slope{17.0 * M_PI / 180.0, 0.0, 0.0};
  Pool pool = make_supported_hexapod_pool(slope.angle);
  const Eigen::Vector3d load = slipwalk::terrain::slope_load(slope, pool.robot.Mg, 0.0);
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  run(state, pool, [&opt, &load](const Robot& r, Frame& f) {
    slipwalk::friction::solve_coulomb_loaded(r, f, load, opt);
  });
}

/// The whole frame: leg heights vary by ±1 cm around −0.1 m (stiffness 1000 N/m, weight 10 N:
/// compressions of about 10/(1000 N) m), so feet lift off and the support search has work.
Pool make_model_pool(int n) {
  Pool p = make_pool(n);
  p.robot = slipwalk::contact::uniform_robot(n, 1000.0, 0.8, 10.0);
  std::mt19937 rng(static_cast<unsigned>(2000 + n));
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Inputs& in : p.inputs) {
    for (int k = 0; k < n; ++k) {
      in.q(2, k) = -0.1 + 0.01 * U(rng);
    }
  }
  return p;
}

void BM_SpringSupport(benchmark::State& state) {
  Pool pool = make_model_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot& r, Frame& f) { slipwalk::contact::spring_support(r, f); });
}

void BM_ModelViscous(benchmark::State& state) {
  Pool pool = make_model_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot& r, Frame& f) {
    slipwalk::connection::evaluate(r, f, slipwalk::connection::FrictionLaw::kViscousCoulomb);
  });
}

void BM_ModelCoulomb(benchmark::State& state) {
  Pool pool = make_model_pool(static_cast<int>(state.range(0)));
  run(state, pool, [](const Robot& r, Frame& f) {
    slipwalk::connection::evaluate(r, f, slipwalk::connection::FrictionLaw::kCoulomb);
  });
}

/// The batched model (connection::evaluate_batch, contact::spring_support_batch): four of the
/// pool's inputs per iteration, copied into four working frames and evaluated as one group (frame i
/// in lane i of a vector). Its time per iteration is that of four frames: the counter "frame" is
/// the time per frame, to set beside BM_ModelViscous and BM_SpringSupport (which copy one input
/// per frame the same way).
template <class Solve>
void run_batch(benchmark::State& state, Pool& pool, Solve solve) {
  constexpr int kGroup = 4;
  std::vector<Frame> frames(kGroup, pool.frame);
  slipwalk::contact::BatchScratch scratch(pool.robot.legs());
  std::size_t next = 0;
  double steps = 0.0;
  long long calls = 0;
  for (auto _ : state) {
    for (Frame& f : frames) {
      const Inputs& in = pool.inputs[next];
      next = (next + 1) % pool.inputs.size();
      f.q = in.q;
      f.qdot = in.qdot;
      f.contact = in.contact;
      f.Fz = in.Fz;
    }
    solve(pool.robot, frames, scratch);
    benchmark::DoNotOptimize(frames.front().v_body.data());
    for (const Frame& f : frames) {
      steps += f.support.newton_steps;
    }
    calls += kGroup;
  }
  state.counters["legs"] = static_cast<double>(pool.robot.legs());
  state.counters["steps"] = steps / static_cast<double>(calls > 0 ? calls : 1);
  state.counters["frame"] = benchmark::Counter(
      kGroup, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SpringSupportBatch(benchmark::State& state) {
  Pool pool = make_model_pool(static_cast<int>(state.range(0)));
  run_batch(state, pool, [](const Robot& r, std::vector<Frame>& fs, auto& scratch) {
    slipwalk::contact::spring_support_batch(r, fs, scratch);
  });
}

void BM_ModelViscousBatch(benchmark::State& state) {
  Pool pool = make_model_pool(static_cast<int>(state.range(0)));
  run_batch(state, pool, [](const Robot& r, std::vector<Frame>& fs, auto& scratch) {
    slipwalk::connection::evaluate_batch(r, fs, slipwalk::connection::FrictionLaw::kViscousCoulomb,
                                         scratch);
  });
}

/// Successive frames of a walk (the cost a trajectory pays per frame): BigANT's alternating tripod
/// (robots::bigant_tripod, its four-bar legs, mass and stiffness) sampled at 100 Hz as the
/// thesis' F/T and motion data were (§3.5.1.1), steering left (steer 0.3: the inner side's
/// shorter strokes make the stance feet slip and turn the body) at 0.38 Hz, a frequency whose
/// cycle is no whole number of frames, so that the 4096 frames (15.6 cycles) do not repeat. The
/// spring support decides the feet down and their loads frame by frame, so the hand-overs
/// between the tripods (4–6 feet down) are in the sequence; the rare frame it cannot balance is
/// left out. The warm row starts each Coulomb solve from the previous frame's answer
/// (CoulombOptions::warm_start; the working frame keeps v_body from call to call), the cold row
/// from the viscous-Coulomb start as the independent frames above do: read warm/viscous and
/// warm/cold off one run.
Pool make_trajectory_hexapod_pool() {
  const slipwalk::robots::Walker walker =
      slipwalk::robots::bigant_tripod({.frequency = 0.38, .steer = 0.3});
  Pool p(walker.robot);
  Frame& f = p.frame;
  for (int i = 0; p.inputs.size() < kInputs; ++i) {
    walker.feet(0.01 * i, f.q, f.qdot);
    slipwalk::contact::spring_support(p.robot, f);
    if (f.support.status == slipwalk::contact::SupportSummary::Status::kBalanced) {
      p.inputs.push_back(Inputs{f.q, f.qdot, f.contact, f.Fz});
    }
  }
  return p;
}

void BM_ViscousTrajectoryHexapod(benchmark::State& state) {
  Pool pool = make_trajectory_hexapod_pool();
  run(state, pool,
      [](const Robot& r, Frame& f) { slipwalk::friction::solve_viscous_coulomb(r, f); });
}

void BM_CoulombTrajectoryHexapod1e9(benchmark::State& state) {
  Pool pool = make_trajectory_hexapod_pool();
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  opt.warm_start = true;
  run(state, pool,
      [&opt](const Robot& r, Frame& f) { slipwalk::friction::solve_coulomb(r, f, opt); });
}

// The whole model along the walk, its spring support started from the previous frame's balance
// (warm:1, SupportOptions::warm_start, as connection::integrate runs it) or cold (warm:0).
void BM_ModelTrajectoryHexapod(benchmark::State& state) {
  Pool pool = make_trajectory_hexapod_pool();
  const slipwalk::contact::SupportOptions support{.warm_start = state.range(0) != 0};
  run(state, pool, [&support](const Robot& r, Frame& f) {
    slipwalk::connection::evaluate(r, f, slipwalk::connection::FrictionLaw::kViscousCoulomb,
                                   support);
  });
}

void BM_CoulombTrajectoryHexapodCold1e9(benchmark::State& state) {
  Pool pool = make_trajectory_hexapod_pool();
  slipwalk::friction::CoulombOptions opt;
  opt.tol = 1e-9;
  run(state, pool,
      [&opt](const Robot& r, Frame& f) { slipwalk::friction::solve_coulomb(r, f, opt); });
}

/// The walk's warm Coulomb solves by what they do, so that the cost of each route can be read off
/// (the walk's own row times their mix). Along the walk of make_trajectory_hexapod_pool, each
/// frame's solve is recorded with the state the previous solve left in the frame, its velocity
/// and its feet's static marks (all that a warm solve reads of it), and classed by the route it
/// took: 0, the previous frame's static foot kept and one polish step; 1, the same in two steps;
/// 2, a static pair kept with no step; 3, three steps or more (the tripod's hand-overs, where two
/// feet slow down together). The benchmark replays its class's frames from those states in turn.
/// Counters: share, the class's fraction of the walk's frames; same, the fraction of the replays
/// that took the walk's own number of steps (1: the replay is the walk's solve).
class WalkRoutes {
 public:
  static constexpr int kClasses = 4;
  WalkRoutes() : pool_(make_trajectory_hexapod_pool()) {
    slipwalk::friction::CoulombOptions opt = options();
    Frame& f = pool_.frame;
    for (std::size_t i = 0; i < pool_.inputs.size(); ++i) {
      pool_.load(i);
      const Eigen::Vector3d v = f.v_body;
      const std::vector<int> marks = f.work_idx;
      slipwalk::friction::solve_coulomb(pool_.robot, f, opt);
      const int c = route(f.friction.static_feet, f.friction.iterations);
      if (c >= 0) {
        frames_[static_cast<std::size_t>(c)].push_back(Replay{i, v, marks, f.friction.iterations});
      }
    }
  }
  static slipwalk::friction::CoulombOptions options() {
    slipwalk::friction::CoulombOptions opt;
    opt.tol = 1e-9;
    opt.warm_start = true;
    return opt;
  }
  void run(benchmark::State& state, int c) {
    const std::vector<Replay>& replays = frames_[static_cast<std::size_t>(c)];
    if (replays.empty()) {
      state.SkipWithError("no frame of this class on the walk");
      return;
    }
    const slipwalk::friction::CoulombOptions opt = options();
    Frame& f = pool_.frame;
    std::size_t next = 0;
    double same = 0.0;
    long long calls = 0;
    while (state.KeepRunningBatch(1)) {
      const Replay& r = replays[next];
      next = (next + 1) % replays.size();
      pool_.load(r.input);
      f.v_body = r.v_body;
      f.work_idx = r.marks;  // same size: a copy, no allocation
      slipwalk::friction::solve_coulomb(pool_.robot, f, opt);
      benchmark::DoNotOptimize(f.v_body.data());
      same += f.friction.iterations == r.iterations ? 1.0 : 0.0;
      ++calls;
    }
    std::size_t all = 0;
    for (const auto& v : frames_) {
      all += v.size();
    }
    state.counters["share"] = static_cast<double>(replays.size()) / static_cast<double>(all);
    state.counters["same"] = same / static_cast<double>(calls > 0 ? calls : 1);
  }

 private:
  struct Replay {
    std::size_t input;
    Eigen::Vector3d v_body;
    std::vector<int> marks;
    int iterations;
  };
  static int route(int static_feet, int steps) {
    if (steps >= 3) {
      return 3;
    }
    if (static_feet == 1 && (steps == 1 || steps == 2)) {
      return steps - 1;
    }
    return static_feet == 2 && steps == 0 ? 2 : -1;
  }
  Pool pool_;
  std::array<std::vector<Replay>, kClasses> frames_;
};

void BM_CoulombTrajectoryHexapodRoute(benchmark::State& state) {
  static WalkRoutes routes;  // the walk is solved once for all four classes
  routes.run(state, static_cast<int>(state.range(0)));
}

#define LEGS Arg(3)->Arg(6)->Arg(12)->Arg(24)->Arg(50)
BENCHMARK(BM_CopyInputs)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_Viscous)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ViscousAnisotropic)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_LocalConnection)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_Epsilon0_01)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_Coulomb1e9)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombAnisotropic1e9)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ViscousSupportedHexapod)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombSupportedHexapod1e9)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombSlopeHexapod1e9)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_SpringSupport)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ModelViscous)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ModelCoulomb)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_SpringSupportBatch)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ModelViscousBatch)->LEGS->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ViscousTrajectoryHexapod)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombTrajectoryHexapod1e9)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombTrajectoryHexapodCold1e9)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_CoulombTrajectoryHexapodRoute)
    ->ArgName("route")
    ->DenseRange(0, WalkRoutes::kClasses - 1)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ModelTrajectoryHexapod)->ArgName("warm")->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
