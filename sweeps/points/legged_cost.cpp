// legged_cost: what one frame of the multi-legged model costs, and how accurate each friction
// solver is, on random frames of a hexapod or a disk robot (the cost of accuracy, and the
// per-frame cost and its growth with the number of legs; thesis §3.6.1 for the thesis' timings).
//
// A point builds `frames` frames and runs each through contact::spring_support, so the contact
// sets and loads are the model's own. The methods support_batch and model_batch take all frames at
// once, four per call (contact::spring_support_batch, connection::evaluate_batch: frame i of a
// group in lane i of a vector), independent frames only. sequence = "independent" (the default):
// random frames (jittered feet, some lifted, random foot velocities; a hexapod frame has 3–6 feet
// down), each solved on its own. sequence = "trajectory" (hexapod only): successive 100 Hz frames
// of BigANT's alternating tripod walking and turning (robots::bigant_tripod, its legs, mass and
// stiffness; §3.5.1.1's frame rate; 3–6 feet down, the hand-overs included), solved in order as a
// simulation would, each starting from the previous frame's answer: Coulomb warm-starts from it
// (CoulombOptions::warm_start), the spring support from its balance (SupportOptions::warm_start,
// in the support and the whole model), and every method gets the previous v_body, static marks
// and balance copied in (the same copy for all, so the times compare). It then
//  * solves every frame with classical Coulomb friction to a relative duality gap of 1e-14 (the
//    reference; frames whose reference is not unique or not certified are left out of the error
//    statistics and counted),
//  * solves every frame with the point's method and measures the error against the reference,
//  * times the method: `repeats` times a loop over all frames (each repeat lasting ≥ 0.5 ms, the
//    frames cycled as often as needed), reporting the median and quartiles over the repeats of
//    the mean time per frame; Coulomb, the ε-family and the thesis' solvers also time the
//    viscous-Coulomb balance in the same repeats, alternately (viscous_time_ns, and ratio_viscous:
//    the median of the per-repeat ratios, what the report states their cost in). All frames are
//    built before the clock starts, so nothing in the timed loop allocates (but the thesis'
//    solvers, whose MINPACK work arrays are part of what they cost); the kind is timed, so the
//    runner runs its points one at a time and two timings never share the cores of one sweep.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "contact/support_batch.hpp"
#include "core/csv.hpp"
#include "friction/solvers.hpp"
#include "friction/thesis_coulomb.hpp"
#include "robots/robots.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

const double kNaN = std::nan("");
constexpr double kReferenceTol = 1e-14;  // relative duality gap of the reference Coulomb solve
constexpr double kMinRepeatSeconds = 5e-4;
constexpr double kBodyWeight = 8.18 * 9.81;  // N: BigANT's 8.18 kg (thesis ch. 4)
constexpr double kSinkage = 0.01;            // m: static sinkage with every foot down
constexpr double kHeight = 0.1;              // m: feet this far below the body frame

enum class Method {
  kViscous,
  kEpsilon,
  kCoulomb,
  kSupport,
  kConnection,
  kModel,
  kSupportBatch,
  kModelBatch,
  kEpsilonThesis,  ///< one ε solve by the thesis' Levenberg–Marquardt (friction/thesis_coulomb.hpp)
  kCoulombThesis,  ///< the thesis' sequence of ε solves (§3.5.1.3)
};

const std::vector<std::string_view> kMethodNames = {
    "viscous", "epsilon",       "coulomb",     "support",        "connection",
    "model",   "support_batch", "model_batch", "epsilon_thesis", "coulomb_thesis"};

/// The thesis' own solvers (§3.5.1.3), timed beside ours: a peer, not a method of ours.
[[nodiscard]] bool is_thesis(Method m) {
  return m == Method::kEpsilonThesis || m == Method::kCoulombThesis;
}

[[nodiscard]] bool is_friction(Method m) {
  return m == Method::kViscous || m == Method::kEpsilon || m == Method::kCoulomb || is_thesis(m);
}

/// The methods that take all frames at once, four side by side (contact::spring_support_batch,
/// connection::evaluate_batch): independent frames only.
[[nodiscard]] bool is_batched(Method m) {
  return m == Method::kSupportBatch || m == Method::kModelBatch;
}

/// The methods that run the spring support, and so count its Newton steps.
[[nodiscard]] bool runs_support(Method m) {
  return m == Method::kSupport || m == Method::kModel || is_batched(m);
}

const std::vector<std::string_view> kCostKeys = {"robot", "N",      "method",  "eps",
                                                 "tol",   "frames", "seed",    "repeats",
                                                 "speed", "spread", "sequence"};

const std::vector<std::string_view> kSequenceNames = {"independent", "trajectory"};

// The trajectory: BigANT's tripod at 0.38 Hz (a cycle of 263.2 frames, no whole number: the
// frames of successive cycles differ) steering left (0.3: the inner side's shorter strokes make
// stance feet slip and turn the body; the inner pair often stands still), sampled at 100 Hz.
constexpr double kTrajectoryFrequency = 0.38;  // Hz
constexpr double kTrajectorySteer = 0.3;
constexpr double kFrameStep = 0.01;  // s

struct CostInputs {
  std::string robot = "hexapod";
  int n = 6;
  Method method = Method::kViscous;
  double eps = kNaN;
  double tol = kNaN;
  long long frames = 200;
  long long seed = 0;
  long long repeats = 11;
  double speed = 0.1;       ///< m/s: the feet's common backward speed relative to the body
  double spread = 0.5;      ///< relative spread of the feet's velocities around it
  bool trajectory = false;  ///< sequence = "trajectory": successive frames of a walk
};

CostInputs read_cost(const Point& point) {
  const Reader r(point, "legged_cost", kCostKeys);
  CostInputs in;
  in.robot = r.choice("robot", {"hexapod", "disk"});
  in.trajectory = r.choice("sequence", kSequenceNames) == "trajectory";
  if (in.trajectory && in.robot != "hexapod") {
    r.fail("sequence", "\"trajectory\" needs robot = \"hexapod\" (BigANT's tripod walk)");
  }
  for (const std::string_view key : {"speed", "spread"}) {
    if (in.trajectory && r.has(key)) {
      r.fail(key, "only used with sequence = \"independent\" (the walk sets the feet's speeds)");
    }
  }
  if (in.robot == "hexapod") {
    in.n = static_cast<int>(r.integer("N", 6, 6, 6));
  } else {
    if (!r.has("N")) {
      r.fail("N", "required with robot = \"disk\" (the number of legs on the rim)");
    }
    in.n = static_cast<int>(r.integer("N", 6, 3, 1000));
  }
  const std::string method = r.choice("method", kMethodNames);
  in.method = static_cast<Method>(std::find(kMethodNames.begin(), kMethodNames.end(), method) -
                                  kMethodNames.begin());
  if (in.trajectory && is_batched(in.method)) {
    r.fail("method", "\"" + method +
                         "\" takes independent frames four at a time: not with sequence = "
                         "\"trajectory\", whose frames start from each other's answers");
  }
  if (in.method == Method::kEpsilon || in.method == Method::kEpsilonThesis) {
    if (!r.has("eps")) {
      r.fail("eps", "required with method = \"" + method + "\" (eq. 3.14's ε, m/s)");
    }
    in.eps = r.number("eps", 1.0, core::closed(1e-12, 1e12, "m/s"));
    if (in.method == Method::kEpsilon) {
      in.tol = r.number("tol", friction::EpsilonOptions{}.tol, core::closed(1e-15, 1.0));
    }
  } else if (r.has("eps")) {
    r.fail("eps", "only used with method = \"epsilon\" or \"epsilon_thesis\"");
  }
  if (in.method == Method::kCoulomb) {
    in.tol = r.number("tol", friction::CoulombOptions{}.tol, core::closed(1e-15, 1.0));
  } else if (in.method != Method::kEpsilon && r.has("tol")) {
    r.fail("tol", "only used with method = \"epsilon\" or \"coulomb\"");
  }
  in.frames = r.integer("frames", 200, 1, 1'000'000);
  in.seed = r.integer("seed", 0, 0, 1LL << 53);
  in.repeats = r.integer("repeats", 11, 1, 100'000);
  in.speed = r.number("speed", 0.1, core::closed(1e-12, 1e6, "m/s"));
  in.spread = r.number("spread", 0.5, 0.0, 1e6, true);
  // frames × repeats solves of N legs, each up to about N² per iteration: 1e9 is a minute.
  r.limit_work("repeats", "N² · frames · repeats",
               static_cast<double>(in.n) * static_cast<double>(in.n) *
                   static_cast<double>(in.frames) * static_cast<double>(in.repeats),
               1e9);
  return in;
}

// --- robots and frames ---------------------------------------------------------------------------

/// hexapod: BigANT-like, feet at x ∈ {−0.3, 0, 0.3} m, y = ±0.2 m; disk: n feet equally spaced
/// on a rim of radius 0.3 m (thesis §3.5.3). Both: Mg = 8.18 kg · g, K such that the body sinks
/// kSinkage with every foot down, μ = 1, isotropic. Returns the nominal foot positions.
contact::Robot make_robot(const CostInputs& in, Eigen::Matrix3Xd& nominal) {
  contact::Robot robot =
      contact::uniform_robot(in.n, kBodyWeight / (in.n * kSinkage), 1.0, kBodyWeight);
  nominal.resize(3, in.n);
  for (int k = 0; k < in.n; ++k) {
    if (in.robot == "hexapod") {
      const int pair = k / 2;  // hind, middle, fore: x = −0.3, 0, 0.3 m
      nominal.col(k) << 0.3 * static_cast<double>(pair - 1), k % 2 == 0 ? 0.2 : -0.2, -kHeight;
    } else {
      const double a = 2.0 * std::numbers::pi * k / in.n;
      nominal.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -kHeight;
    }
  }
  return robot;
}

/// Frame i of a point, from its own random stream: every foot jittered by ±2 cm in x and y and
/// ±2 mm in z, half of them (on average) lifted by 0.5–4 cm as if swinging; drawn again
/// until the spring support balances (the CoM inside the support polygon). Foot velocities
/// relative to the body: speed·(−1 + spread·n₁, spread·n₂) plus a common turn of rate
/// speed·spread·n₃/0.3 m (n_i standard normal), so the body both slides and turns.
contact::Frame make_frame(const contact::Robot& robot, const Eigen::Matrix3Xd& nominal,
                          const CostInputs& in, long long i) {
  Random rng(static_cast<std::uint64_t>(in.seed), static_cast<std::uint64_t>(i));
  contact::Frame f(robot);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    for (int k = 0; k < in.n; ++k) {
      const bool swing = rng.uniform() < 0.5;
      f.q.col(k) =
          nominal.col(k) + Eigen::Vector3d(rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02),
                                           rng.uniform(-0.002, 0.002));
      if (swing) {
        f.q(2, k) += rng.uniform(0.005, 0.04);
      }
    }
    contact::spring_support(robot, f);
    if (f.support.status == contact::SupportSummary::Status::kBalanced) {
      break;
    }
  }
  const double turn = in.speed * in.spread * rng.normal() / 0.3;
  for (int k = 0; k < in.n; ++k) {
    f.qdot.col(k) << in.speed * (-1.0 + in.spread * rng.normal()) - turn * f.q(1, k),
        in.speed * in.spread * rng.normal() + turn * f.q(0, k), 0.0;
  }
  return f;
}

/// The point's robot and frames: random frames of make_robot's robot, or (trajectory) successive
/// frames of the turning tripod walk from a start time drawn from the point's stream, frames the
/// spring support cannot balance left out.
struct Frames {
  contact::Robot robot;
  std::vector<contact::Frame> frames;
};

Frames make_frames(const CostInputs& in) {
  Frames out;
  out.frames.reserve(static_cast<std::size_t>(in.frames));
  if (!in.trajectory) {
    Eigen::Matrix3Xd nominal;
    out.robot = make_robot(in, nominal);
    for (long long i = 0; i < in.frames; ++i) {
      out.frames.push_back(make_frame(out.robot, nominal, in, i));
    }
    return out;
  }
  const robots::Walker walker = robots::bigant_tripod(
      robots::TripodGait{.frequency = kTrajectoryFrequency, .steer = kTrajectorySteer});
  out.robot = walker.robot;
  Random rng(static_cast<std::uint64_t>(in.seed), 0);
  const double t0 = rng.uniform(0.0, walker.period);
  contact::Frame f(out.robot);
  for (long long i = 0; static_cast<long long>(out.frames.size()) < in.frames; ++i) {
    walker.feet(t0 + kFrameStep * static_cast<double>(i), f.q, f.qdot);
    contact::spring_support(out.robot, f);
    if (f.support.status == contact::SupportSummary::Status::kBalanced) {
      out.frames.push_back(f);
    }
  }
  return out;
}

// --- solving, timing, errors ---------------------------------------------------------------------

/// Along a trajectory, what frame `from` left for the next one (`to`): its body velocity, the
/// Coulomb solver's static marks and the spring support's balance (allocation-free: the frames
/// have the same legs).
void carry(const contact::Frame& from, contact::Frame& to) {
  to.v_body = from.v_body;
  std::copy(from.work_idx.begin(), from.work_idx.end(), to.work_idx.begin());
  to.alpha = from.alpha;
  to.beta = from.beta;
  to.z = from.z;
  to.support.status = from.support.status;
}

void solve(const contact::Robot& robot, contact::Frame& f, const CostInputs& in) {
  switch (in.method) {
    case Method::kViscous:
      friction::solve_viscous_coulomb(robot, f);
      break;
    case Method::kEpsilon:
      friction::solve_epsilon(robot, f, in.eps, friction::EpsilonOptions{in.tol});
      break;
    case Method::kCoulomb: {
      friction::CoulombOptions options;
      options.tol = in.tol;
      options.warm_start = in.trajectory;
      friction::solve_coulomb(robot, f, options);
      break;
    }
    case Method::kEpsilonThesis:
    case Method::kCoulombThesis: {
      // The thesis hot-starts from the previous time step; an independent frame starts, as our
      // solvers do, from its viscous-Coulomb balance (timed with the method).
      if (!in.trajectory) {
        friction::solve_viscous_coulomb(robot, f);
      }
      const Eigen::Vector3d start = f.v_body;
      if (in.method == Method::kEpsilonThesis) {
        friction::solve_epsilon_thesis(robot, f, in.eps, start);
      } else {
        friction::solve_coulomb_thesis(robot, f, start);
      }
      break;
    }
    case Method::kSupport:
      contact::spring_support(robot, f, contact::SupportOptions{.warm_start = in.trajectory});
      break;
    case Method::kConnection:
      connection::local_connection(robot, f);
      break;
    case Method::kModel:
      connection::evaluate(robot, f, connection::FrictionLaw::kViscousCoulomb,
                           contact::SupportOptions{.warm_start = in.trajectory});
      break;
    case Method::kSupportBatch:
    case Method::kModelBatch:
      break;  // solve_all: all frames at once
  }
}

/// Every frame with the method: one after the other (along a trajectory each from what the
/// previous one left, carry; the first from the last, a jump back along the walk), or all at once
/// for the batched methods.
void solve_all(const contact::Robot& robot, std::vector<contact::Frame>& fs, const CostInputs& in,
               contact::BatchScratch& scratch) {
  if (in.method == Method::kSupportBatch) {
    contact::spring_support_batch(robot, fs, scratch);
  } else if (in.method == Method::kModelBatch) {
    connection::evaluate_batch(robot, fs, connection::FrictionLaw::kViscousCoulomb, scratch);
  } else if (in.trajectory) {
    const contact::Frame* prev = &fs.back();
    for (contact::Frame& f : fs) {
      carry(*prev, f);
      solve(robot, f, in);
      prev = &f;
    }
  } else {
    for (contact::Frame& f : fs) {
      solve(robot, f, in);
    }
  }
}

struct Timing {
  double median = kNaN;  ///< ns per frame
  double p25 = kNaN;
  double p75 = kNaN;
  double baseline = kNaN;  ///< the viscous-Coulomb balance, timed in the same repeats: median
  double ratio = kNaN;     ///< median over the repeats of (method ÷ viscous-Coulomb)
};

/// Whether a row also times the viscous-Coulomb balance alternately with its method: the friction
/// laws whose cost the report states as a multiple of it (Coulomb, the ε-family).
[[nodiscard]] bool paired_with_viscous(Method m) {
  return m == Method::kCoulomb || m == Method::kEpsilon || is_thesis(m);
}

/// Mean CPU time per frame of the method over all frames, `repeats` times; the frames were solved
/// once already (warm caches, and the outputs the errors are computed from). Along a trajectory
/// each frame is solved after the previous one, from what it left (carry; the first from the
/// last, once per pass a jump back along the walk). With `baseline` frames (a copy, so that
/// neither solve changes the other's warm starts), every repeat also times the viscous-Coulomb
/// balance on them, before or after the method in turn: a ratio of two times taken seconds apart
/// moves with the load of a shared machine, one taken within a repeat does not.
Timing time_method(const contact::Robot& robot, std::vector<contact::Frame>& frames,
                   const CostInputs& in, std::vector<contact::Frame>* baseline) {
  contact::BatchScratch scratch(robot.legs());  // before the clock starts
  const auto pass = [&robot, &scratch](std::vector<contact::Frame>& fs, const CostInputs& how) {
    solve_all(robot, fs, how, scratch);
  };
  CostInputs viscous = in;
  viscous.method = Method::kViscous;
  // How many passes make one repeat last kMinRepeatSeconds (the clock's resolution and the
  // loop's overhead then do not matter).
  const auto passes_for = [&](std::vector<contact::Frame>& fs, const CostInputs& how) {
    const double t0 = thread_cpu_seconds();
    pass(fs, how);
    const double once = thread_cpu_seconds() - t0;
    return std::clamp(static_cast<long long>(std::ceil(kMinRepeatSeconds / std::max(once, 1e-9))),
                      1LL, 1'000'000LL);
  };
  // The mean time per frame, ns, of `count` passes.
  const auto timed = [&](std::vector<contact::Frame>& fs, const CostInputs& how, long long count) {
    const double t0 = thread_cpu_seconds();
    for (long long p = 0; p < count; ++p) {
      pass(fs, how);
    }
    return 1e9 * (thread_cpu_seconds() - t0) / static_cast<double>(count * in.frames);
  };
  const long long passes = passes_for(frames, in);
  const long long base_passes = baseline != nullptr ? passes_for(*baseline, viscous) : 0;
  std::vector<double> per_frame;
  std::vector<double> base_per_frame;
  std::vector<double> ratios;
  per_frame.reserve(static_cast<std::size_t>(in.repeats));
  base_per_frame.reserve(static_cast<std::size_t>(in.repeats));
  ratios.reserve(static_cast<std::size_t>(in.repeats));
  for (long long r = 0; r < in.repeats; ++r) {
    if (baseline == nullptr) {
      per_frame.push_back(timed(frames, in, passes));
      continue;
    }
    double method_ns = 0.0;
    double base_ns = 0.0;
    if (r % 2 == 0) {
      base_ns = timed(*baseline, viscous, base_passes);
      method_ns = timed(frames, in, passes);
    } else {
      method_ns = timed(frames, in, passes);
      base_ns = timed(*baseline, viscous, base_passes);
    }
    per_frame.push_back(method_ns);
    base_per_frame.push_back(base_ns);
    ratios.push_back(method_ns / base_ns);
  }
  std::sort(per_frame.begin(), per_frame.end());
  Timing t{quantile_of_sorted(per_frame, 0.5), quantile_of_sorted(per_frame, 0.25),
           quantile_of_sorted(per_frame, 0.75)};
  if (baseline != nullptr) {
    std::sort(base_per_frame.begin(), base_per_frame.end());
    std::sort(ratios.begin(), ratios.end());
    t.baseline = quantile_of_sorted(base_per_frame, 0.5);
    t.ratio = quantile_of_sorted(ratios, 0.5);
  }
  return t;
}

struct Errors {
  std::vector<double> v;  ///< per frame: ‖(Δv_x, Δv_y, L Δω)‖ / V
  std::vector<double> F;  ///< per frame: max_k ‖ΔF_k‖ / (μ_k F_z,k)
  long long nonunique = 0;
  long long ref_unconverged = 0;
};

/// The error of a solved frame against the reference. V = the fastest foot in contact (‖q̇_k‖),
/// L = the largest lever arm of a foot in contact, so Δω is weighed by the speed it gives a foot.
/// The viscous-type laws (viscous-Coulomb, the ε-family) give forces in their own units
/// (−μ F_z u, in N·s/m): like the thesis (§3.5.1.4, one positive scale σ per frame fitted to the
/// measured forces) their forces are compared after the least-squares σ = Σ F·F_ref / Σ ‖F‖².
void add_error(const contact::Robot& robot, const contact::Frame& f, const contact::Frame& ref,
               bool scaled, Errors& e) {
  if (!ref.friction.converged) {
    ++e.ref_unconverged;
    return;
  }
  if (!ref.friction.unique) {
    ++e.nonunique;
    return;
  }
  double sigma = 1.0;
  if (scaled) {
    const double den = f.Fxy.squaredNorm();
    sigma = den > 0.0 ? (f.Fxy.array() * ref.Fxy.array()).sum() / den : 1.0;
  }
  double V = 0.0;
  double L = 0.0;
  double dF = 0.0;
  for (int k = 0; k < f.legs(); ++k) {
    if (f.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    V = std::max(V, f.qdot.col(k).head<2>().norm());
    L = std::max(L, f.q.col(k).head<2>().norm());
    const double c = robot.mu(k) * f.Fz(k);
    if (c > 0.0) {
      dF = std::max(dF, (sigma * f.Fxy.col(k) - ref.Fxy.col(k)).norm() / c);
    }
  }
  const Eigen::Vector3d d = f.v_body - ref.v_body;
  e.v.push_back(V > 0.0 ? std::hypot(d(0), d(1), L * d(2)) / V : 0.0);
  e.F.push_back(dF);
}

struct Stats {
  double median = kNaN;
  double p95 = kNaN;
  double max = kNaN;
};

Stats stats(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  if (x.empty()) {
    return {};
  }
  return {quantile_of_sorted(x, 0.5), quantile_of_sorted(x, 0.95), x.back()};
}

/// One row per point. Errors are NaN for the methods that compute no friction balance (support,
/// connection, model); contacts_* count the feet down per frame; iterations_mean and unconverged
/// are the method's own (friction.iterations and !friction.converged; spring support: its
/// iterations). The time_ns* columns are the only ones that vary between runs.
struct CostRow {
  long long id = 0;
  std::string robot;
  std::string sequence;  ///< "independent" (random frames) or "trajectory" (a walk, warm starts)
  long long N = 0;
  std::string method;
  double eps = kNaN;
  double tol = kNaN;
  long long frames = 0;
  long long seed = 0;
  long long repeats = 0;
  double contacts_mean = 0.0;
  long long contacts_min = 0;
  long long contacts_max = 0;
  double time_ns = kNaN;      ///< median over the repeats of the mean time per frame
  double time_ns_p25 = kNaN;  ///< its quartiles
  double time_ns_p75 = kNaN;
  double viscous_time_ns = kNaN;  ///< coulomb, epsilon: viscous-Coulomb in the same repeats
  double ratio_viscous = kNaN;    ///< coulomb, epsilon: median per-repeat time ÷ viscous-Coulomb's
  double err_v_median = kNaN;     ///< ‖(Δv_x, Δv_y, L Δω)‖ / V over the frames
  double err_v_p95 = kNaN;
  double err_v_max = kNaN;
  double err_F_median = kNaN;  ///< max_k ‖ΔF_k‖ / (μ_k F_z,k) over the frames
  double err_F_p95 = kNaN;
  double err_F_max = kNaN;
  long long error_frames = 0;  ///< frames in the error statistics
  long long nonunique = 0;
  long long ref_unconverged = 0;
  double ref_static_mean = kNaN;  ///< static feet per frame in the reference
  double iterations_mean = 0.0;
  double newton_steps_mean = kNaN;  ///< support, model: the support's Newton steps per frame
  long long unconverged = 0;
  std::string message;

  static std::vector<Column<CostRow>> columns() {
    using R = CostRow;
    return {value("id", &R::id),
            value("robot", &R::robot),
            value("sequence", &R::sequence),
            value("N", &R::N),
            value("method", &R::method),
            value("eps", &R::eps, "m/s"),
            value("tol", &R::tol),
            value("frames", &R::frames),
            value("seed", &R::seed),
            value("repeats", &R::repeats),
            value("contacts_mean", &R::contacts_mean),
            value("contacts_min", &R::contacts_min),
            value("contacts_max", &R::contacts_max),
            timing("time_ns", &R::time_ns, "ns"),
            timing("time_ns_p25", &R::time_ns_p25, "ns"),
            timing("time_ns_p75", &R::time_ns_p75, "ns"),
            timing("viscous_time_ns", &R::viscous_time_ns, "ns"),
            timing("ratio_viscous", &R::ratio_viscous, ""),
            value("err_v_median", &R::err_v_median),
            value("err_v_p95", &R::err_v_p95),
            value("err_v_max", &R::err_v_max),
            value("err_F_median", &R::err_F_median),
            value("err_F_p95", &R::err_F_p95),
            value("err_F_max", &R::err_F_max),
            value("error_frames", &R::error_frames),
            value("nonunique", &R::nonunique),
            value("ref_unconverged", &R::ref_unconverged),
            value("ref_static_mean", &R::ref_static_mean),
            value("iterations_mean", &R::iterations_mean),
            value("newton_steps_mean", &R::newton_steps_mean),
            value("unconverged", &R::unconverged),
            value("message", &R::message)};
  }
};

Rows<CostRow> run_cost(const Point& point) {
  const CostInputs in = read_cost(point);
  Frames made = make_frames(in);
  const contact::Robot& robot = made.robot;
  std::vector<contact::Frame>& frames = made.frames;

  // The reference and the method's own answer, frame by frame.
  Errors errors;
  long long contacts_sum = 0;
  long long contacts_min = in.n;
  long long contacts_max = 0;
  long long iterations = 0;
  long long newton_steps = 0;
  long long unconverged = 0;
  long long ref_static = 0;
  contact::Frame ref(robot);
  if (is_batched(in.method)) {
    contact::BatchScratch scratch(robot.legs());
    solve_all(robot, frames, in, scratch);  // the contacts counted below are those of make_frames
  }
  const contact::Frame* prev = nullptr;
  for (contact::Frame& f : frames) {
    if (in.trajectory && prev != nullptr) {
      carry(*prev, f);
    }
    prev = &f;
    long long down = 0;
    for (char c : f.contact) {
      down += c != 0 ? 1 : 0;
    }
    contacts_sum += down;
    contacts_min = std::min(contacts_min, down);
    contacts_max = std::max(contacts_max, down);
    if (!is_batched(in.method)) {
      solve(robot, f, in);
    }
    newton_steps += f.support.newton_steps;
    if (in.method == Method::kSupport || in.method == Method::kSupportBatch) {
      iterations += f.support.iterations;
      unconverged += f.support.status == contact::SupportSummary::Status::kIterationLimit ? 1 : 0;
    } else if (is_friction(in.method)) {
      iterations += f.friction.iterations;
      unconverged += f.friction.converged ? 0 : 1;
      ref = f;
      friction::solve_coulomb(robot, ref, friction::CoulombOptions{kReferenceTol});
      ref_static += ref.friction.static_feet;
      add_error(robot, f, ref, in.method != Method::kCoulomb && in.method != Method::kCoulombThesis,
                errors);
    }
  }
  const bool paired = paired_with_viscous(in.method);
  std::vector<contact::Frame> baseline;
  if (paired) {
    baseline = frames;  // before the clock starts: the timed loops allocate nothing
  }
  const Timing t = time_method(robot, frames, in, paired ? &baseline : nullptr);
  const Stats ev = stats(errors.v);
  const Stats eF = stats(errors.F);
  const double nf = static_cast<double>(in.frames);
  const bool friction = is_friction(in.method);
  std::string message;
  if (unconverged > 0) {
    message = std::to_string(unconverged) + " of " + std::to_string(in.frames) +
              " frames did not converge";
  }
  if (errors.ref_unconverged > 0) {
    message += message.empty() ? "" : "; ";
    message += std::to_string(errors.ref_unconverged);
    message += " reference solves not certified to 1e-14";
  }
  Rows<CostRow> out;
  out.rows.push_back({point.id,
                      in.robot,
                      std::string(in.trajectory ? "trajectory" : "independent"),
                      static_cast<long long>(in.n),
                      std::string(kMethodNames[static_cast<std::size_t>(in.method)]),
                      in.eps,
                      in.tol,
                      in.frames,
                      in.seed,
                      in.repeats,
                      static_cast<double>(contacts_sum) / nf,
                      contacts_min,
                      contacts_max,
                      t.median,
                      t.p25,
                      t.p75,
                      t.baseline,
                      t.ratio,
                      ev.median,
                      ev.p95,
                      ev.max,
                      eF.median,
                      eF.p95,
                      eF.max,
                      static_cast<long long>(errors.v.size()),
                      errors.nonunique,
                      errors.ref_unconverged,
                      friction ? static_cast<double>(ref_static) / nf : kNaN,
                      static_cast<double>(iterations) / nf,
                      runs_support(in.method) ? static_cast<double>(newton_steps) / nf : kNaN,
                      unconverged,
                      message});
  return out;
}

}  // namespace

std::vector<PointKind> legged_cost_kinds() {
  return {make_point_kind<CostRow>(
      "legged_cost",
      "§3.6.1: time per frame and error against a 1e-14 Coulomb reference of a friction solver "
      "(or the support search, the connection, the whole model) on random frames of a hexapod or "
      "a disk robot, or on successive frames of BigANT's tripod walk with warm starts (one row "
      "per point)",
      Timed::kYes, [](const Point& p) { (void)read_cost(p); }, run_cost)};
}

}  // namespace slipwalk::sweeps::points
