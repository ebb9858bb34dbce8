// Point kinds of the speed comparisons of thesis §3.5.3 (Fig. 3.13):
//
//   peer_scaling       Fig. 3.13 a: the cost of one model evaluation (ours: connection::evaluate
//                      with viscous-Coulomb friction) and of one mj_step of MuJoCo on the same
//                      random configurations of a disk robot with N legs (one row per config)
//   parallel_overhead  Fig. 3.13 b: a hexapod's random trajectories, the steps' body velocities
//                      computed on M = 1 … max_threads threads and composed into poses
//                      sequentially or by the parallel prefix product (one row per trajectory
//                      and M)
//
// Timing. A single evaluation lasts from a few hundred ns to a few hundred µs, far above the
// steady clock's resolution only at the top; so each configuration is run k times in a row
// (k chosen per configuration so that a batch lasts ≥ min_batch_us) and the batch's mean is one
// sample; `batches` such samples give the configuration's median. MuJoCo is rewound to the same
// state before every step (rewinding, a copy of qpos, qvel, ctrl and the warm start, is inside
// the timed loop; its own cost is reported as time_rewind_ns). Ours and MuJoCo's are timed
// alternately per configuration, so background load hits both alike. All inputs are built before
// the clock starts. Both kinds are timed (Timed::kYes): the runner runs their points one at a time,
// process-wide, whatever --jobs says, and holds that for the whole point, not only its timed loops
// (building another point's configurations on the second core would slow the timed loops down
// through the shared cache and memory bus). Every measured time, and every number computed from
// one, is a timing column: written as 0 under --no-timing.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "connection/local_connection.hpp"
#include "connection/parallel_steps.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/se2_scan.hpp"
#include "core/worker_pool.hpp"
#include "peers/mujoco/legged_spec.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/peer.hpp"
#endif

namespace slipwalk::sweeps::points {

namespace {

namespace peer = peers::mujoco;
using Clock = std::chrono::steady_clock;
const double kNaN = std::nan("");
constexpr double kBodyWeight = 8.18 * 9.81;  // N: BigANT's 8.18 kg (thesis ch. 4)
constexpr double kSinkage = 0.01;            // m: static sinkage with every foot down
constexpr double kHeight = 0.1;              // m: feet this far below the body frame
constexpr double kRadius = 0.3;              // m: the disk's rim (§3.5.3)
constexpr double kReach = 0.05;              // m: a foot's nominal distance outside its hip

/// ns per call of f: k calls in a row, k so that the batch lasts ≥ min_batch_s (from one
/// untimed-for-the-result call, which also warms the caches); median over `batches` batches.
template <class F>
double time_per_call(F&& f, double min_batch_s, long long batches) {
  auto t0 = Clock::now();
  f();
  const double once = seconds_since(t0);
  const long long k = std::clamp(
      static_cast<long long>(std::ceil(min_batch_s / std::max(once, 1e-9))), 1LL, 1'000'000LL);
  std::vector<double> samples;  // ns per call, one per batch
  samples.reserve(static_cast<std::size_t>(batches));
  for (long long b = 0; b < batches; ++b) {
    t0 = Clock::now();
    for (long long i = 0; i < k; ++i) {
      f();
    }
    samples.push_back(1e9 * seconds_since(t0) / static_cast<double>(k));
  }
  return median(std::move(samples));
}

/// A robot whose body sinks kSinkage with every foot down (K = Mg / (N kSinkage)), μ = 1.
contact::Robot uniform(int n) {
  return contact::uniform_robot(n, kBodyWeight / (n * kSinkage), 1.0, kBodyWeight);
}

/// Foot velocities relative to the body: speed·(−1 + spread·n₁, spread·n₂) plus a common turn of
/// rate speed·spread·n₃/0.3 m (n_i standard normal), as in legged_cost.
void draw_velocities(Random& rng, double speed, double spread, const Eigen::Matrix3Xd& q,
                     Eigen::Matrix3Xd& qdot) {
  const double turn = speed * spread * rng.normal() / 0.3;
  for (Eigen::Index k = 0; k < q.cols(); ++k) {
    qdot.col(k) << speed * (-1.0 + spread * rng.normal()) - turn * q(1, k),
        speed * spread * rng.normal() + turn * q(0, k), 0.0;
  }
}

/// A foot's height in the body frame: kHeight below, jittered ±2 mm, and with probability 1/3
/// lifted by up to 3 cm as if swinging.
double draw_height(Random& rng) {
  double z = -kHeight + rng.uniform(-0.002, 0.002);
  if (rng.uniform() < 1.0 / 3.0) {
    z += rng.uniform(0.0, 0.03);
  }
  return z;
}

[[nodiscard]] bool balanced(const contact::Frame& f) {
  return f.support.status == contact::SupportSummary::Status::kBalanced;
}

// --- peer_scaling (Fig. 3.13 a) -----------------------------------------------------------------

const std::vector<std::string_view> kScalingKeys = {
    "N", "configs", "seed", "batches", "min_batch_us", "warmstart", "speed", "spread"};

struct ScalingInputs {
  int n = 3;
  long long configs = 1000;
  long long seed = 0;
  long long batches = 3;
  double min_batch_s = 20e-6;
  std::string warmstart = "solution";
  double speed = 0.1;
  double spread = 0.5;
};

ScalingInputs read_scaling(const Point& point) {
  const Reader r(point, "peer_scaling", kScalingKeys);
  ScalingInputs in;
  if (!r.has("N")) {
    r.fail("N", "required (the number of legs on the disk's rim)");
  }
  in.n = static_cast<int>(r.integer("N", 3, 3, 500));
  in.configs = r.integer("configs", 1000, 1, 1'000'000);
  in.seed = r.integer("seed", 0, 0, 1LL << 53);
  in.batches = r.integer("batches", 3, 1, 1000);
  in.min_batch_s = 1e-6 * r.number("min_batch_us", 20.0, 0.0, 1e6, true);
  in.warmstart = r.choice("warmstart", {"solution", "cold"});
  in.speed = r.number("speed", 0.1, core::closed(1e-12, 1e6, "m/s"));
  in.spread = r.number("spread", 0.5, 0.0, 1e6, true);
  // Each batch times every configuration at least min_batch_us, for both simulators.
  r.limit_work(
      "configs", "N · configs · batches",
      static_cast<double>(in.n) * static_cast<double>(in.configs) * static_cast<double>(in.batches),
      1e9);
  r.limit_work("batches", "batches · min_batch_us (s)",
               static_cast<double>(in.batches) * in.min_batch_s, 600.0);
  return in;
}

/// Configuration i of a point: every foot at a random point of its leg's workspace (a third of
/// them lifted), drawn again until the spring support balances; random foot velocities; then our
/// model evaluated (support: z, α, β and the contacts; the body velocity).
contact::Frame draw_config(const contact::Robot& robot, const peer::PeerSpec& spec,
                           const ScalingInputs& in, long long i) {
  Random rng(static_cast<std::uint64_t>(in.seed),
             (static_cast<std::uint64_t>(in.n) << 32) + static_cast<std::uint64_t>(i));
  contact::Frame f(robot);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    for (int k = 0; k < in.n; ++k) {
      const double u = rng.uniform(), v = rng.uniform();
      f.q.col(k) =
          peer::workspace_point(spec.legs[static_cast<std::size_t>(k)], u, v, draw_height(rng));
    }
    contact::spring_support(robot, f);
    if (balanced(f)) {
      break;
    }
  }
  draw_velocities(rng, in.speed, in.spread, f.q, f.qdot);
  connection::evaluate(robot, f, connection::FrictionLaw::kViscousCoulomb);
  return f;
}

/// One row per configuration. contacts: our feet down; mujoco_contacts, mujoco_iter: MuJoCo's
/// contacts and constraint-solver iterations in the step from the configuration; unreachable: feet
/// the legs' inverse kinematics could not place (0 by construction). Without MuJoCo in the build
/// the mujoco_* columns are −1, the MuJoCo times NaN, peer "none" and the message says why.
struct ScalingRow {
  long long id = 0;
  long long legs = 0;  ///< N
  long long config = 0;
  long long seed = 0;
  std::string warmstart;
  std::string peer_name;  ///< "mujoco <version>" or "none"
  long long contacts = 0;
  long long mujoco_contacts = -1;
  long long mujoco_iter = -1;
  long long unreachable = -1;
  double time_ours_ns = kNaN;       ///< one connection::evaluate, median of the batches, its spring
                                    ///< support started as MuJoCo's solver is (warmstart)
  double time_ours_cold_ns = kNaN;  ///< the same with the cold start of the support, whatever
                                    ///< warmstart says
  double time_mujoco_ns = kNaN;     ///< one rewind + mj_step, median of the batches
  double time_rewind_ns = kNaN;     ///< the rewind alone
  std::string message;

  static std::vector<Column<ScalingRow>> columns() {
    using R = ScalingRow;
    return {value("id", &R::id),
            value("N", &R::legs),
            value("config", &R::config),
            value("seed", &R::seed),
            value("warmstart", &R::warmstart),
            value("peer", &R::peer_name),
            value("contacts", &R::contacts),
            value("mujoco_contacts", &R::mujoco_contacts),
            value("mujoco_iter", &R::mujoco_iter),
            value("unreachable", &R::unreachable),
            timing("time_ours_ns", &R::time_ours_ns, "ns"),
            timing("time_ours_cold_ns", &R::time_ours_cold_ns, "ns"),
            timing("time_mujoco_ns", &R::time_mujoco_ns, "ns"),
            timing("time_rewind_ns", &R::time_rewind_ns, "ns"),
            value("message", &R::message)};
  }
};

Rows<ScalingRow> run_scaling(const Point& point) {
  const ScalingInputs in = read_scaling(point);
  const contact::Robot robot = uniform(in.n);
  const peer::PeerSpec spec = peer::disk_spec(robot, kRadius, kReach, kHeight);
  std::vector<contact::Frame> configs;
  configs.reserve(static_cast<std::size_t>(in.configs));
  for (long long i = 0; i < in.configs; ++i) {
    configs.push_back(draw_config(robot, spec, in, i));
  }
  Rows<ScalingRow> out;
  out.rows.reserve(static_cast<std::size_t>(in.configs));
#ifdef SLIPWALK_HAVE_MUJOCO
  const peer::PeerModel model(spec);
  peer::PeerData data(model);
  const std::string name = "mujoco " + peer::version();
  const std::string message;
#else
  const std::string name = "none";
  const std::string message =
      "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): MuJoCo not timed";
  static std::once_flag warned;
  std::call_once(warned,
                 [&] { std::cerr << "slipwalk: warning: peer_scaling: " << message << '\n'; });
#endif
  for (long long i = 0; i < in.configs; ++i) {
    contact::Frame& f = configs[static_cast<std::size_t>(i)];
    ScalingRow row;
    row.id = point.id;
    row.legs = in.n;
    row.config = i;
    row.seed = in.seed;
    row.warmstart = in.warmstart;
    row.peer_name = name;
    for (char c : f.contact) {
      row.contacts += c != 0 ? 1 : 0;
    }
    // Warm: the support starts from the balance the previous call left, this configuration's own
    // (it repeats back to back), as MuJoCo's solver starts from the accelerations at that state.
    contact::SupportOptions warm;
    warm.warm_start = in.warmstart == "solution";
    row.time_ours_ns = time_per_call(
        [&] { connection::evaluate(robot, f, connection::FrictionLaw::kViscousCoulomb, warm); },
        in.min_batch_s, in.batches);
    row.time_ours_cold_ns = time_per_call(
        [&] { connection::evaluate(robot, f, connection::FrictionLaw::kViscousCoulomb); },
        in.min_batch_s, in.batches);
#ifdef SLIPWALK_HAVE_MUJOCO
    peer::BodyState body;
    body.z = f.z;
    body.alpha = f.alpha;
    body.beta = f.beta;
    body.v_body = f.v_body;
    row.unreachable = peer::set_state(model, data, body, f.q, f.qdot);
    if (in.warmstart == "solution") {
      peer::warm_start(model, data);
    }
    peer::checkpoint(model, data);
    row.time_mujoco_ns = time_per_call(
        [&] {
          peer::rewind(model, data);
          peer::step(model, data);
        },
        in.min_batch_s, in.batches);
    row.mujoco_contacts = peer::read_feet(model, data);
    row.mujoco_iter = peer::solver_iterations(data);
    row.time_rewind_ns =
        time_per_call([&] { peer::rewind(model, data); }, in.min_batch_s, in.batches);
#endif
    row.message = message;
    out.rows.push_back(std::move(row));
  }
  return out;
}

// --- parallel_overhead (Fig. 3.13 b) ------------------------------------------------------------

const std::vector<std::string_view> kParallelKeys = {
    "trajectories", "steps", "max_threads", "blocks", "seed", "dt", "speed", "spread"};

struct ParallelInputs {
  long long trajectories = 100;
  long long steps = 10000;
  int max_threads = 4;
  int blocks = 64;
  long long seed = 0;
  double dt = 0.01;
  double speed = 0.1;
  double spread = 0.5;
};

ParallelInputs read_parallel(const Point& point) {
  const Reader r(point, "parallel_overhead", kParallelKeys);
  ParallelInputs in;
  in.trajectories = r.integer("trajectories", 100, 1, 100'000);
  in.steps = r.integer("steps", 10000, 1, 10'000'000);
  in.max_threads = static_cast<int>(r.integer("max_threads", 4, 1, 64));
  in.blocks = static_cast<int>(r.integer("blocks", 64, 1, 1'000'000));
  in.seed = r.integer("seed", 0, 0, 1LL << 53);
  in.dt = r.number("dt", 0.01, core::closed(1e-9, 1e3, "s"));
  in.speed = r.number("speed", 0.1, core::closed(1e-12, 1e6, "m/s"));
  in.spread = r.number("spread", 0.5, 0.0, 1e6, true);
  // Every thread count up to max_threads runs every trajectory's steps.
  r.limit_work("steps", "trajectories · steps · max_threads",
               static_cast<double>(in.trajectories) * static_cast<double>(in.steps) *
                   static_cast<double>(in.max_threads),
               1e9);
  return in;
}

/// Trajectory t of a point: every step an independent random frame of the BigANT-like hexapod
/// (feet at x ∈ {−0.3, 0, 0.3} m, y = ±0.2 m, jittered ±2 cm, a third lifted; drawn again, up
/// to 20 times, until the support balances) with random foot velocities.
void draw_trajectory(const contact::Robot& robot, const ParallelInputs& in, long long t,
                     contact::Frame& f, connection::StepBatch& batch) {
  Random rng(static_cast<std::uint64_t>(in.seed), static_cast<std::uint64_t>(t));
  for (long long s = 0; s < in.steps; ++s) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      for (int k = 0; k < 6; ++k) {
        const int pair = k / 2;  // hind, middle, fore: x = −0.3, 0, 0.3 m
        f.q.col(k) << 0.3 * static_cast<double>(pair - 1) + rng.uniform(-0.02, 0.02),
            (k % 2 == 0 ? 0.2 : -0.2) + rng.uniform(-0.02, 0.02), draw_height(rng);
      }
      contact::spring_support(robot, f);
      if (balanced(f)) {
        break;
      }
    }
    draw_velocities(rng, in.speed, in.spread, f.q, f.qdot);
    batch.q.middleCols(s * 6, 6) = f.q;
    batch.qdot.middleCols(s * 6, 6) = f.qdot;
  }
}

/// One row per (trajectory, M threads). time_increments_ns: the steps' increments exp(v dt) on M
/// threads (support, connection and viscous-Coulomb balance per step); time_sequential_ns: their
/// sequential product (one thread, as in the thesis); time_scan_ns: the blocked parallel prefix
/// product on M threads; time_cpu_*: the process's CPU time (all threads) in those two sections.
/// end_*: the last pose of the sequential product; scan_max_diff: the largest
/// |Δx| + |Δy| + |Δθ| between the two products over all poses; same_as_one_thread: 1 if both
/// products' last poses equal the one-thread run's to the bit.
struct ParallelRow {
  long long id = 0;
  long long trajectory = 0;
  long long steps = 0;
  long long threads = 0;  ///< M
  long long blocks = 0;
  long long unsupported = 0;
  double end_x = 0.0;
  double end_y = 0.0;
  double end_theta = 0.0;
  double scan_max_diff = 0.0;  ///< m and rad summed, as a bound on both
  bool same_as_one_thread = false;
  double time_increments_ns = 0.0;
  double time_sequential_ns = 0.0;
  double time_scan_ns = 0.0;
  double time_cpu_increments_ns = 0.0;
  double time_cpu_scan_ns = 0.0;

  static std::vector<Column<ParallelRow>> columns() {
    using R = ParallelRow;
    return {value("id", &R::id),
            value("trajectory", &R::trajectory),
            value("steps", &R::steps),
            value("threads", &R::threads),
            value("blocks", &R::blocks),
            value("unsupported", &R::unsupported),
            value("end_x", &R::end_x, "m"),
            value("end_y", &R::end_y, "m"),
            value("end_theta", &R::end_theta, "rad"),
            value("scan_max_diff", &R::scan_max_diff),
            value("same_as_one_thread", &R::same_as_one_thread),
            timing("time_increments_ns", &R::time_increments_ns, "ns"),
            timing("time_sequential_ns", &R::time_sequential_ns, "ns"),
            timing("time_scan_ns", &R::time_scan_ns, "ns"),
            timing("time_cpu_increments_ns", &R::time_cpu_increments_ns, "ns"),
            timing("time_cpu_scan_ns", &R::time_cpu_scan_ns, "ns")};
  }
};

Rows<ParallelRow> run_parallel(const Point& point) {
  const ParallelInputs in = read_parallel(point);
  const contact::Robot robot = uniform(6);
  connection::StepBatch batch;
  batch.q.resize(3, 6 * in.steps);
  batch.qdot.resize(3, 6 * in.steps);
  batch.dt = in.dt;
  connection::StepBatchData data(robot, in.max_threads, in.steps);
  std::vector<core::Pose2> seq(static_cast<std::size_t>(in.steps + 1));
  std::vector<core::Pose2> scan(seq.size());
  std::vector<std::unique_ptr<core::WorkerPool>> pools;
  for (int m = 1; m <= in.max_threads; ++m) {
    pools.push_back(std::make_unique<core::WorkerPool>(m));
  }
  contact::Frame f(robot);
  Rows<ParallelRow> out;
  const auto threads = static_cast<std::size_t>(in.max_threads);
  std::vector<ParallelRow> rows(threads);
  std::vector<core::Pose2> end_seq(threads), end_scan(threads);
  for (long long t = 0; t < in.trajectories; ++t) {
    draw_trajectory(robot, in, t, f, batch);
    // Thread counts in rotated order per trajectory, so no M always runs first (cold caches).
    for (int j = 0; j < in.max_threads; ++j) {
      const int m = 1 + static_cast<int>((t + j) % in.max_threads);
      const auto um = static_cast<std::size_t>(m - 1);
      core::WorkerPool& pool = *pools[um];
      double c0 = process_cpu_seconds();
      auto t0 = Clock::now();
      connection::step_increments(robot, batch, connection::FrictionLaw::kViscousCoulomb, pool,
                                  in.blocks, data);
      const double t_inc = seconds_since(t0);
      const double c_inc = process_cpu_seconds() - c0;
      t0 = Clock::now();
      core::sequential_product({}, data.increments, seq);
      const double t_seq = seconds_since(t0);
      c0 = process_cpu_seconds();
      t0 = Clock::now();
      core::prefix_product({}, data.increments, scan, pool, in.blocks);
      const double t_scan = seconds_since(t0);
      const double c_scan = process_cpu_seconds() - c0;
      double diff = 0.0;
      for (std::size_t k = 0; k < seq.size(); ++k) {
        diff = std::max(diff, std::abs(seq[k].x - scan[k].x) + std::abs(seq[k].y - scan[k].y) +
                                  std::abs(seq[k].theta - scan[k].theta));
      }
      end_seq[um] = seq.back();
      end_scan[um] = scan.back();
      ParallelRow& row = rows[um];
      row.id = point.id;
      row.trajectory = t;
      row.steps = in.steps;
      row.threads = m;
      row.blocks = in.blocks;
      row.unsupported = data.unsupported();
      row.end_x = seq.back().x;
      row.end_y = seq.back().y;
      row.end_theta = seq.back().theta;
      row.scan_max_diff = diff;
      row.time_increments_ns = 1e9 * t_inc;
      row.time_sequential_ns = 1e9 * t_seq;
      row.time_scan_ns = 1e9 * t_scan;
      row.time_cpu_increments_ns = 1e9 * c_inc;
      row.time_cpu_scan_ns = 1e9 * c_scan;
    }
    const auto same = [](const core::Pose2& a, const core::Pose2& b) {
      return a.x == b.x && a.y == b.y && a.theta == b.theta;
    };
    for (std::size_t m = 0; m < threads; ++m) {
      rows[m].same_as_one_thread = same(end_seq[m], end_seq[0]) && same(end_scan[m], end_scan[0]);
      out.rows.push_back(rows[m]);
    }
  }
  return out;
}

}  // namespace

std::vector<PointKind> peer_kinds() {
  return {make_point_kind<ScalingRow>(
              "peer_scaling",
              "§3.5.3, Fig. 3.13 a: time of one model evaluation (ours, viscous-Coulomb) and of "
              "one MuJoCo mj_step on the same random configurations of a disk robot with N legs "
              "(one row per configuration)",
              Timed::kYes, [](const Point& p) { (void)read_scaling(p); }, run_scaling),
          make_point_kind<ParallelRow>(
              "parallel_overhead",
              "§3.5.3, Fig. 3.13 b: a hexapod's random trajectories, step increments on M "
              "threads, sequential vs parallel prefix product of the poses (one row per "
              "trajectory and M)",
              Timed::kYes, [](const Point& p) { (void)read_parallel(p); }, run_parallel)};
}

}  // namespace slipwalk::sweeps::points
