// The planner of planner.hpp: a beam of nodes per level (H = 1: the thesis' greedy step), each
// node's options split into chunks over the worker pool, each chunk keeping its K best in the
// total order (cost, parent rank, option index), merged in chunk order.
#include "planning/planner.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/worker_pool.hpp"
#include "planning/cost.hpp"
#include "planning/option_kernel.hpp"

namespace slipwalk::planning {

namespace {

/// A child of a node: its cost so far, where it came from and where its option ended.
struct Candidate {
  double cost = std::numeric_limits<double>::infinity();
  int parent = 0;         ///< rank of the parent node in its level
  long long option = -1;  ///< the option that leads from the parent to this child
  core::Pose2 end = {};   ///< pose at the parent's t + Δt
};

/// The total order of candidates: least cost, then least parent rank, then least option index.
bool before(const Candidate& a, const Candidate& b) {
  if (a.cost != b.cost) {
    return a.cost < b.cost;
  }
  if (a.parent != b.parent) {
    return a.parent < b.parent;
  }
  return a.option < b.option;
}

/// Inserts c into the sorted list best[0, count) of capacity k (dropping the last when full).
void keep_best(Candidate* best, int& count, int k, const Candidate& c) {
  if (count == k && !before(c, best[count - 1])) {
    return;
  }
  int at = count < k ? count++ : k - 1;
  while (at > 0 && before(c, best[at - 1])) {
    best[at] = best[at - 1];
    --at;
  }
  best[at] = c;
}

/// A node of the beam: its state, the cost of the path to it and the root option it began with.
struct Node {
  double t = 0.0;
  core::Pose2 pose = {};
  double cost = 0.0;
  long long root_option = -1;
};

constexpr int kMinChunk = 32;

}  // namespace

struct PlanData::Impl {
  Impl(const PlanRobot& robot, const PlanOptions& options)
      : pool(options.threads),
        legs(robot.legs()),
        choices(static_cast<int>(options.speeds.size())),
        beam(options.lookahead > 1 ? options.beam : 1),
        max_chunks(8 * options.threads) {
    frames.reserve(static_cast<std::size_t>(pool.threads()));
    for (int w = 0; w < pool.threads(); ++w) {
      frames.emplace_back(robot.robot);
    }
    size_node(robot, options, root);
    size_node(robot, options, inner);
    power.resize(static_cast<std::size_t>(legs) + 1);
    power[0] = 1;
    for (int i = 1; i <= legs; ++i) {
      power[static_cast<std::size_t>(i)] = power[static_cast<std::size_t>(i) - 1] * choices;
    }
    for (auto* level : {&nodes, &next}) {
      level->resize(static_cast<std::size_t>(beam));
    }
    phi = Eigen::MatrixXd::Zero(legs, beam);
    next_phi = Eigen::MatrixXd::Zero(legs, beam);
    chooses.assign(static_cast<std::size_t>(legs) * static_cast<std::size_t>(beam), 0);
    chunk_best.resize(static_cast<std::size_t>(max_chunks) * static_cast<std::size_t>(beam));
    chunk_count.resize(static_cast<std::size_t>(max_chunks));
    chunk_infeasible.resize(static_cast<std::size_t>(max_chunks));
    level_best.resize(static_cast<std::size_t>(beam));
    root_phi = Eigen::VectorXd::Constant(legs, std::numeric_limits<double>::quiet_NaN());
  }

  core::WorkerPool pool;
  int legs;
  int choices;
  int beam;                            ///< K (1 for the greedy planner)
  int max_chunks;                      ///< chunks a node's options are split into, at most
  std::vector<contact::Frame> frames;  ///< one per worker
  std::vector<long long> power;        ///< M^i, i = 0 … N
  NodeTable root;                      ///< the table of the step's start state
  Eigen::VectorXd root_phi;            ///< the φ `root` was built for
  NodeTable inner;                     ///< the table of a deeper node
  std::vector<Node> nodes;             ///< (K) this level's nodes
  std::vector<Node> next;              ///< (K) the next level's
  Eigen::MatrixXd phi;                 ///< (N × K) this level's shaft angles
  Eigen::MatrixXd next_phi;            ///< (N × K)
  std::vector<char> chooses;           ///< (N × K) which legs of this level's nodes chose
  std::vector<Candidate> chunk_best;   ///< (max_chunks × K)
  std::vector<int> chunk_count;
  std::vector<long long> chunk_infeasible;
  std::vector<Candidate> level_best;  ///< (K) the next level, sorted
};

PlanData::PlanData(const PlanRobot& robot, const PlanOptions& options)
    : impl_(std::make_unique<Impl>(robot, options)) {}
PlanData::~PlanData() = default;
PlanData::PlanData(PlanData&&) noexcept = default;
PlanData& PlanData::operator=(PlanData&&) noexcept = default;

long long option_index(const int* digits, int legs, int choices) {
  long long o = 0;
  for (int i = legs - 1; i >= 0; --i) {
    o = o * choices + digits[i];
  }
  return o;
}

void option_digits(long long option, int legs, int choices, int* digits) {
  for (int i = 0; i < legs; ++i) {
    digits[i] = static_cast<int>(option % choices);
    option /= choices;
  }
}

void validate(const PlanRobot& robot, const PlanOptions& options) {
  validate(robot);
  using core::require_in;
  require_in("plan.horizon", options.horizon, ranges::kHorizon);
  require_in("plan.substeps", options.substeps, ranges::kSubsteps);
  require_in("plan.execute", options.execute, core::closed(1.0, options.substeps));
  require_in("plan.speeds (count)", static_cast<double>(options.speeds.size()), ranges::kChoices);
  for (std::size_t c = 0; c < options.speeds.size(); ++c) {
    require_in("plan.speeds[" + std::to_string(c) + "]", options.speeds[c], ranges::kSpeed);
  }
  require_in("plan.swing_speed", options.swing_speed, ranges::kSpeed);
  require_in("plan.rotation_length", options.rotation_length, ranges::kRotationLength);
  require_in("plan.steps", static_cast<double>(options.steps), ranges::kSteps);
  require_in("plan.lookahead", options.lookahead, ranges::kLookahead);
  require_in("plan.beam", options.beam, ranges::kBeam);
  require_in("plan.threads", options.threads, ranges::kThreads);
  if (robot.legs() > kMaxPlanLegs) {
    throw core::InputError("plan.robot", "a planner handles at most " +
                                             std::to_string(kMaxPlanLegs) + " legs, got " +
                                             std::to_string(robot.legs()));
  }
  const double options_count =
      std::pow(static_cast<double>(options.speeds.size()), static_cast<double>(robot.legs()));
  if (options_count > static_cast<double>(kMaxOptions)) {
    throw core::InputError("plan.speeds", std::to_string(options.speeds.size()) + " speeds on " +
                                              std::to_string(robot.legs()) +
                                              " legs make more than 2^24 options per step");
  }
}

PlanState tripod_start(const PlanRobot& robot) {
  const int n = robot.legs();
  const int side = n / 2;
  PlanState s;
  s.phi.resize(n);
  for (int j = 0; j < n; ++j) {
    const int along = side > 0 ? j % side : j;
    const int parity = (along + (j < side ? 0 : 1)) % 2;
    s.phi(j) = parity == 0 ? 0.5 : 0.0;
  }
  return s;
}

namespace {

void validate_state(const PlanRobot& robot, const PlanState& state) {
  core::require_in("start.t", state.t, core::closed(-1e9, 1e9, "s"));
  core::require_in("start.x", state.pose.x, contact::limits::kPosition);
  core::require_in("start.y", state.pose.y, contact::limits::kPosition);
  core::require_in("start.theta", state.pose.theta, contact::limits::kYaw);
  if (state.phi.size() != robot.legs()) {
    throw core::InputError("start.phi", std::to_string(state.phi.size()) + " shaft angles for " +
                                            std::to_string(robot.legs()) + " legs");
  }
  for (int i = 0; i < robot.legs(); ++i) {
    core::require_in("start.phi[" + std::to_string(i) + "]", state.phi(i),
                     core::Range{0.0, 1.0, false, true, "turns"});
  }
}

/// What the chunks of one node share.
struct Expansion {
  const PlanRobot& robot;
  const PlanOptions& options;
  PlanData::Impl& d;
  const NodeTable& table;
  const Node& node;
  int rank;
  core::Pose2 target;
  long long total;
  long long per_chunk;
};

/// Integrates the options [chunk · per_chunk, …) of the node and keeps the chunk's K best.
void expand_chunk(const Expansion& e, int chunk, int worker) {
  PlanData::Impl& d = e.d;
  const int n = d.legs;
  const int m = d.choices;
  const int free = static_cast<int>(e.table.free_legs.size());
  Candidate* best =
      &d.chunk_best[static_cast<std::size_t>(chunk) * static_cast<std::size_t>(d.beam)];
  int count = 0;
  long long bad = 0;
  std::array<int, kMaxPlanLegs> digits{};
  // kOptionBatch options integrated side by side (option_kernel.hpp): each one's result is the
  // one it has alone, so the batches' boundaries do not matter.
  std::array<std::array<int, kMaxPlanLegs>, kOptionBatch> columns{};
  std::array<const int*, kOptionBatch> pointers{};
  std::array<long long, kOptionBatch> indices{};
  std::array<core::Pose2, kOptionBatch> poses{};
  std::array<bool, kOptionBatch> ok{};
  for (int l = 0; l < kOptionBatch; ++l) {
    pointers[static_cast<std::size_t>(l)] = columns[static_cast<std::size_t>(l)].data();
  }
  contact::Frame& frame = d.frames[static_cast<std::size_t>(worker)];
  const long long begin = chunk * e.per_chunk;
  const long long end = std::min(e.total, begin + e.per_chunk);
  for (long long first = begin; first < end; first += kOptionBatch) {
    const int lanes = static_cast<int>(std::min<long long>(kOptionBatch, end - first));
    for (int l = 0; l < lanes; ++l) {
      const long long r = first + l;
      long long option = r;
      if (e.options.deduplicate) {
        // Digits of r on the free legs (ascending), 0 on the swinging legs: the least option
        // index of its class, and increasing with r.
        digits.fill(0);
        option = 0;
        long long rest = r;
        for (int k = 0; k < free; ++k) {
          const auto leg = static_cast<std::size_t>(e.table.free_legs[static_cast<std::size_t>(k)]);
          digits[leg] = static_cast<int>(rest % m);
          option += digits[leg] * d.power[leg];
          rest /= m;
        }
      } else {
        option_digits(r, n, m, digits.data());
      }
      const auto u = static_cast<std::size_t>(l);
      option_columns(e.table, digits.data(), columns[u].data());
      indices[u] = option;
      poses[u] = e.node.pose;
    }
    integrate_options(e.robot, e.options, e.table, pointers.data(), lanes, e.table.substeps,
                      poses.data(), ok.data(), frame);
    for (int l = 0; l < lanes; ++l) {
      const auto u = static_cast<std::size_t>(l);
      if (!ok[u]) {
        ++bad;
        continue;
      }
      const double cost = e.node.cost + se2_distance(poses[u], e.target, e.options.rotation_length);
      if (!std::isfinite(cost)) {
        ++bad;
        continue;
      }
      keep_best(best, count, d.beam, Candidate{cost, e.rank, indices[u], poses[u]});
    }
  }
  d.chunk_count[static_cast<std::size_t>(chunk)] = count;
  d.chunk_infeasible[static_cast<std::size_t>(chunk)] = bad;
}

/// Evaluates every option of node `rank` (table `table`) and merges its K best into
/// d.level_best (level_count of them so far). Returns the options evaluated; adds the infeasible
/// ones to `infeasible`.
long long expand(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
                 PlanData::Impl& d, const NodeTable& table, const Node& node, int rank,
                 int& level_count, long long& infeasible) {
  const int free = static_cast<int>(table.free_legs.size());
  const long long total = options.deduplicate ? d.power[static_cast<std::size_t>(free)]
                                              : d.power[static_cast<std::size_t>(d.legs)];
  const int chunks =
      static_cast<int>(std::clamp<long long>((total + kMinChunk - 1) / kMinChunk, 1, d.max_chunks));
  const Expansion e{robot,
                    options,
                    d,
                    table,
                    node,
                    rank,
                    target_at(goal, node.t + options.horizon),
                    total,
                    (total + chunks - 1) / chunks};
  // One reference captured: the task fits std::function's local storage (no allocation).
  d.pool.run(chunks, [&e](int chunk, int worker) { expand_chunk(e, chunk, worker); });
  for (int c = 0; c < chunks; ++c) {
    const Candidate* best =
        &d.chunk_best[static_cast<std::size_t>(c) * static_cast<std::size_t>(d.beam)];
    for (int k = 0; k < d.chunk_count[static_cast<std::size_t>(c)]; ++k) {
      keep_best(d.level_best.data(), level_count, d.beam, best[k]);
    }
    infeasible += d.chunk_infeasible[static_cast<std::size_t>(c)];
  }
  return total;
}

/// φ̇ of leg i under `option` for a node whose choosing legs are `chooses`.
double leg_speed(const PlanOptions& options, const char* chooses, long long option, int leg,
                 const std::vector<long long>& power, int m) {
  if (chooses[leg] == 0) {
    return options.swing_speed;
  }
  const long long digit = (option / power[static_cast<std::size_t>(leg)]) % m;
  return options.speeds[static_cast<std::size_t>(digit)];
}

}  // namespace

void plan_step(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
               const PlanState& state, PlanData& data, StepChoice& choice) {
  PlanData::Impl& d = data.impl();
  const int n = d.legs;
  const int m = d.choices;
  choice.speed.resize(n);  // no allocation once sized
  choice.chooses.resize(static_cast<std::size_t>(n));
  choice.evaluated = 0;
  choice.infeasible = 0;

  // Level 0: the root.
  build_node(robot, options, state.phi, d.root, d.frames[0]);
  d.root_phi = state.phi;
  d.nodes[0] = Node{state.t, state.pose, 0.0, -1};
  d.phi.col(0) = state.phi;
  std::copy(d.root.chooses.begin(), d.root.chooses.end(), d.chooses.begin());
  int live = 1;
  const int levels = options.lookahead;
  for (int level = 1; level <= levels; ++level) {
    int count = 0;
    for (int b = 0; b < live; ++b) {
      NodeTable* table = &d.root;
      if (level > 1) {
        build_node(robot, options, d.phi.col(b), d.inner, d.frames[0]);
        std::copy(d.inner.chooses.begin(), d.inner.chooses.end(),
                  d.chooses.begin() + static_cast<std::ptrdiff_t>(b) * n);
        table = &d.inner;
      }
      choice.evaluated += expand(robot, options, goal, d, *table,
                                 d.nodes[static_cast<std::size_t>(b)], b, count, choice.infeasible);
    }
    if (count == 0) {
      // Every option of every node of this level is infeasible.
      throw core::ComputationError("t = " + core::format_double(state.t) +
                                   " s: no option is feasible (every option tips the robot or "
                                   "loses the friction balance)");
    }
    if (level == levels) {
      const Candidate& best = d.level_best[0];
      const Node& parent = d.nodes[static_cast<std::size_t>(best.parent)];
      choice.option = level == 1 ? best.option : parent.root_option;
      choice.cost = best.cost;
      break;
    }
    // The kept children become the next level's nodes.
    const double h = options.horizon / static_cast<double>(options.substeps);
    for (int k = 0; k < count; ++k) {
      const Candidate& c = d.level_best[static_cast<std::size_t>(k)];
      const Node& parent = d.nodes[static_cast<std::size_t>(c.parent)];
      const char* parent_chooses =
          &d.chooses[static_cast<std::size_t>(c.parent) * static_cast<std::size_t>(n)];
      for (int i = 0; i < n; ++i) {
        d.next_phi(i, k) = advanced_phi(d.phi(i, c.parent),
                                        leg_speed(options, parent_chooses, c.option, i, d.power, m),
                                        options.substeps, h);
      }
      d.next[static_cast<std::size_t>(k)] = Node{parent.t + options.horizon, c.end, c.cost,
                                                 level == 1 ? c.option : parent.root_option};
    }
    std::swap(d.nodes, d.next);
    d.phi.swap(d.next_phi);
    live = count;
  }
  for (int i = 0; i < n; ++i) {
    choice.chooses[static_cast<std::size_t>(i)] = d.root.chooses[static_cast<std::size_t>(i)];
    choice.speed(i) = leg_speed(options, d.root.chooses.data(), choice.option, i, d.power, m);
  }
}

void execute(const PlanRobot& robot, const PlanOptions& options, const StepChoice& choice,
             PlanState& state, PlanData& data) {
  PlanData::Impl& d = data.impl();
  const int n = d.legs;
  if (!(d.root_phi.array() == state.phi.array()).all()) {
    build_node(robot, options, state.phi, d.root, d.frames[0]);
    d.root_phi = state.phi;
  }
  std::array<int, kMaxPlanLegs> digits{};
  std::array<int, kMaxPlanLegs> columns{};
  option_digits(choice.option, n, d.choices, digits.data());
  option_columns(d.root, digits.data(), columns.data());
  core::Pose2 pose = state.pose;
  if (!integrate_option(robot, options, d.root, columns.data(), options.execute, pose,
                        d.frames[0])) {
    throw core::ComputationError("t = " + core::format_double(state.t) +
                                 " s: the chosen option is not feasible when executed");
  }
  for (int i = 0; i < n; ++i) {
    state.phi(i) = advanced_phi(state.phi(i), choice.speed(i), options.execute, d.root.h);
  }
  state.pose = pose;
  state.t += static_cast<double>(options.execute) * d.root.h;
}

PlanSummary plan(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
                 const PlanState& start, const StepSink& sink, const Progress& progress) {
  validate(robot, options);
  validate(goal);
  validate_state(robot, start);
  PlanData data(robot, options);
  PlanSummary summary;
  PlanState state = start;
  const double tau = static_cast<double>(options.execute) * options.horizon /
                     static_cast<double>(options.substeps);
  double distance_sum = 0.0;
  StepChoice choice;
  for (long long step = 0; step < options.steps; ++step) {
    const core::Pose2 target = target_at(goal, state.t);
    try {
      plan_step(robot, options, goal, state, data, choice);
    } catch (const core::ComputationError& e) {
      throw core::ComputationError("step " + std::to_string(step) + ", " + e.what());
    }
    distance_sum += se2_distance(state.pose, target, options.rotation_length);
    if (sink) {
      sink(StepRecord{step, state, target, choice});
    }
    execute(robot, options, choice, state, data);
    state.t = start.t + static_cast<double>(step + 1) * tau;  // not accumulated
    summary.evaluated += choice.evaluated;
    summary.infeasible += choice.infeasible;
    summary.steps = step + 1;
    if (progress) {
      progress(step + 1, options.steps);
    }
  }
  summary.end = state;
  summary.mean_distance =
      options.steps > 0 ? distance_sum / static_cast<double>(options.steps) : 0.0;
  summary.final_distance =
      se2_distance(state.pose, target_at(goal, state.t), options.rotation_length);
  return summary;
}

}  // namespace slipwalk::planning
