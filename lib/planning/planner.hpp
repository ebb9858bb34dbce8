#pragma once
// Brute-force motion planning on the multi-legged model (thesis §5.4–5.5).
//
// The problem (§5.4.3). A robot with N legs, each with one periodic degree of freedom φ_i (a
// shaft angle in turns, planning/plan_robot.hpp). At each planning step every leg in contact
// chooses one of M shaft speeds φ̇ (default {−1, 0, 1, 2} turns/s: back, stay, forward, fast
// forward); a leg not in contact swings at a fixed speed (2). An *option* is one choice for every
// leg, M^N of them, numbered o = Σ_i c_i M^i with c_i ∈ [0, M) the choice of leg i (leg 0 the
// least significant digit); a swinging leg's digit does not change its motion.
//
// One option (§5.5). Held over the look-ahead Δt (0.05 s) and integrated in T_s (20) substeps of
// h = Δt/T_s: at substep s = 0 … T_s − 1 the legs are at φ_i + φ̇_i s h, the model of ch. 3 gives
// the body velocity (spring support §3.3, then the friction law's balance §3.4 — viscous-Coulomb
// by default, Coulomb as an option), and the pose moves exactly on SE(2) with that twist held over
// h (core::advance), as connection::integrate does. The cost is the geodesic distance
// (planning/cost.hpp) between the pose at t + Δt and the target Ω^target(t + Δt)
// (planning/goal.hpp). The best option — least cost, ties to the least option index — is
// executed for its first T_f (2) substeps only, "without risk of the contact switches causing
// wrongly predicted motion", and the next planning step starts there.
//
// Where the thesis is silent we chose, and each choice is a parameter (PlanOptions):
//  - "in contact" for the swing rule: the spring support's contact set at the step's start
//    (ContactRule::kSupport, the model's own answer); or φ inside the stance window
//    (kStanceWindow, a geometric rule); or every leg chooses (kAll).
//  - the metric: ρ = 0.3 m per radian of heading error (cost.hpp).
//  - the time a planning step executes: T_f h = 5 ms; the thesis' figures count steps "Δt =
//    0.05" apart, which would be T_f = T_s. We keep the text's T_s = 20, T_f = 2 and report time
//    in seconds and steps (a plan of 300 steps covers 1.5 s).
//
// Evaluating each distinct motion once. Options that differ only in the digits of swinging legs
// are the same motion, bit for bit: the planner (deduplicate = true) enumerates only the M^n_c
// combinations of the n_c legs in contact, each represented by its least option index (swinging
// digits 0). The least-index representatives keep the order of option indices, so the chosen
// option equals full enumeration's (tests/planning/test_planner.cpp runs whole plans both ways).
//
// Beyond the thesis (§5.7.3: a one-step greedy choice finds local minima): a receding horizon.
// With lookahead H > 1 the planner keeps a beam of the K best nodes per level: level 1 expands
// the current state by every option over Δt; level ℓ + 1 expands each kept node from where its
// option ended (t + ℓΔt); a node's cost is the sum of its levels' distances to the target. The
// first option of the best leaf is executed for T_f substeps, and the search starts again. H = 1
// is the thesis' greedy planner exactly (same code path).
//
// Threads split the options of a node into chunks; each chunk keeps its K best by (cost, index),
// and the chunks merge in that total order, so the plan is the same for any thread count.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "connection/local_connection.hpp"
#include "core/range.hpp"
#include "core/se2.hpp"
#include "friction/solvers.hpp"
#include "planning/goal.hpp"
#include "planning/plan_robot.hpp"

namespace slipwalk::planning {

/// Which legs choose a speed (the others swing at PlanOptions::swing_speed).
enum class ContactRule {
  kSupport,       ///< the feet the spring support puts on the ground at the step's start
  kStanceWindow,  ///< the legs with φ within PlanRobot::stance_half_width of 0 (mod 1)
  kAll,           ///< every leg (M^N distinct motions)
};

/// The most options one node may have (M^N ≤ 2^24, e.g. 4^12).
inline constexpr long long kMaxOptions = 1LL << 24;
/// The most legs a planner handles (the option digits live in a fixed array).
inline constexpr int kMaxPlanLegs = 24;

/// The admissible plan options (validate(), the plan file reader). Generous, and chosen so that a
/// plan cannot run without end: substeps × options × levels per step are bounded.
namespace ranges {
inline constexpr core::Range kHorizon = core::positive_up_to(10.0, "s");    ///< Δt
inline constexpr core::Range kSubsteps = core::closed(1.0, 1e4);            ///< T_s
inline constexpr core::Range kSpeed = core::closed(-100.0, 100.0, "turns/s");  ///< φ̇ choices
inline constexpr core::Range kChoices = core::closed(1.0, 64.0);            ///< M
inline constexpr core::Range kRotationLength = core::closed(0.0, 1e3, "m/rad");  ///< ρ
inline constexpr core::Range kSteps = core::closed(0.0, 1e8);               ///< planning steps
inline constexpr core::Range kLookahead = core::closed(1.0, 16.0);          ///< H
inline constexpr core::Range kBeam = core::closed(1.0, 64.0);               ///< K
inline constexpr core::Range kThreads = core::closed(1.0, 256.0);
}  // namespace ranges

struct PlanOptions {
  double horizon = 0.05;                           ///< Δt, s: how far one option looks ahead
  int substeps = 20;                               ///< T_s ≥ 1: substeps of Δt
  int execute = 2;                                 ///< T_f ∈ [1, T_s]: substeps executed per step
  std::vector<double> speeds = {-1.0, 0.0, 1.0, 2.0};  ///< the M choices of φ̇, turns/s
  double swing_speed = 2.0;                        ///< φ̇ of a leg not in contact, turns/s
  ContactRule contact = ContactRule::kSupport;
  double rotation_length = 0.3;  ///< ρ, m/rad (cost.hpp)
  connection::FrictionLaw law = connection::FrictionLaw::kViscousCoulomb;
  friction::CoulombOptions coulomb = {};  ///< with law = kCoulomb
  long long steps = 300;                  ///< planning steps of a plan
  int lookahead = 1;                      ///< H ≥ 1 levels (1: the thesis' greedy planner)
  int beam = 1;                           ///< K ≥ 1 nodes kept per level (used when H > 1)
  bool deduplicate = true;                ///< evaluate each distinct motion once
  int threads = 1;                        ///< ≥ 1 (the caller's thread counts as one)
};

/// Throws core::InputError naming the option ("plan.substeps", "plan.speeds[2]", ...) for values
/// out of range, and ("plan.speeds") when M^N of this robot passes kMaxOptions.
void validate(const PlanRobot& robot, const PlanOptions& options);

/// Where the robot is: time, pose, shaft angles.
struct PlanState {
  double t = 0.0;          ///< s
  core::Pose2 pose = {};   ///< world frame
  Eigen::VectorXd phi;     ///< (N) shaft angles, turns, in [0, 1)
};

/// The thesis' start (§5.5): the two tripods out of phase, φ = [0.5, 0, 0.5, 0, 0.5, 0] for
/// BigANT; for other leg counts the same alternation along each side, the right side starting
/// with the other phase (legs/2 odd) so that the two tripod-like sets alternate.
[[nodiscard]] PlanState tripod_start(const PlanRobot& robot);

/// One planning step's decision.
struct StepChoice {
  long long option = -1;  ///< the chosen option index (least index among equal costs)
  double cost = 0.0;      ///< its cost: distance at t + Δt (H = 1), or the best leaf's sum
  Eigen::VectorXd speed;  ///< (N) φ̇ each leg executes, turns/s (swinging legs: swing_speed)
  std::vector<char> chooses;  ///< (N) 1 for a leg that chose (in contact by the rule), 0 swinging
  long long evaluated = 0;    ///< options integrated for this step, over all levels and nodes
  long long infeasible = 0;   ///< of these, options the model could not follow (below)
};

/// One planning step as it is executed: the state at its start, the target there, the choice.
struct StepRecord {
  long long step = 0;
  const PlanState& state;
  const core::Pose2& goal;  ///< Ω^target(t)
  const StepChoice& choice;
};

using StepSink = std::function<void(const StepRecord&)>;
/// Called after each step with (steps done, steps in all).
using Progress = std::function<void(long long done, long long total)>;

struct PlanSummary {
  long long steps = 0;           ///< planning steps taken
  PlanState end;                 ///< the state after the last step
  long long evaluated = 0;       ///< options integrated, all steps
  long long infeasible = 0;      ///< of these, infeasible
  double mean_distance = 0.0;    ///< mean over the steps of d(pose(t), Ω^target(t)), m
  double final_distance = 0.0;   ///< d(end pose, Ω^target(end t)), m
};

/// Buffers and threads of a planner, sized once for a robot and options: nothing is allocated
/// per planning step (tests/planning/test_planner.cpp counts). Not shared between threads.
class PlanData {
 public:
  PlanData(const PlanRobot& robot, const PlanOptions& options);
  ~PlanData();
  PlanData(const PlanData&) = delete;
  PlanData& operator=(const PlanData&) = delete;
  PlanData(PlanData&&) noexcept;
  PlanData& operator=(PlanData&&) noexcept;

  struct Impl;
  [[nodiscard]] Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// An option is infeasible when the model cannot follow it at some substep: the spring support
/// finds no balance (the robot tips: kUnsupported; or kIterationLimit, kNonFinite), the friction
/// solve does not converge, or the pose is not finite. Its cost is +∞; it is never chosen. A
/// step whose options are all infeasible throws core::ComputationError ("step 12 at t = 0.06 s:
/// no option is feasible").

/// Chooses the option to execute from `state`, towards `goal`, into `choice` (its vectors are
/// sized on the first call and reused: no allocation afterwards).
void plan_step(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
               const PlanState& state, PlanData& data, StepChoice& choice);

/// Executes `choice` from `state` for T_f substeps: the same substeps, bit for bit, as the
/// option's first T_f in plan_step. t advances to t + T_f h.
void execute(const PlanRobot& robot, const PlanOptions& options, const StepChoice& choice,
             PlanState& state, PlanData& data);

/// options.steps planning steps from `start` (plan_step, then execute); `sink` sees each step
/// before it is executed, `progress` (may be empty) after it. Throws core::InputError for bad
/// robots, options, goals or start states, core::ComputationError for a step with no feasible
/// option.
PlanSummary plan(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
                 const PlanState& start, const StepSink& sink, const Progress& progress = {});

/// The option index of choices c (N digits in [0, M)), and back. No allocation.
[[nodiscard]] long long option_index(const int* digits, int legs, int choices);
void option_digits(long long option, int legs, int choices, int* digits);

}  // namespace slipwalk::planning
