#pragma once
// The point families: one file per family under sweeps/points/, each contributing its kinds to
// one explicit list (families.cpp). A new kind is one entry in its family's list; a new family is
// one file and one line in families.cpp.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps::points {

/// The inchworm of ch. 2: v_ss by any method, convergence from rest (inchworm.cpp).
[[nodiscard]] std::vector<PointKind> inchworm_kinds();
/// The friction laws of ch. 3 on synthetic feet: 1-D legs, law comparisons, ε errors
/// (legged_laws.cpp).
[[nodiscard]] std::vector<PointKind> legged_law_kinds();
/// The multi-legged model of ch. 3 on robot frame files: force maps, support paths
/// (legged_frames.cpp).
[[nodiscard]] std::vector<PointKind> legged_frame_kinds();
/// The cost and accuracy of the multi-legged model's solvers (legged_cost.cpp).
[[nodiscard]] std::vector<PointKind> legged_cost_kinds();
/// The speed comparisons of §3.5.3, Fig. 3.13: MuJoCo peer and parallel steps (peer.cpp).
[[nodiscard]] std::vector<PointKind> peer_kinds();
/// The sim-to-sim comparison of §3.5.4, Fig. 3.14: BigANT in MuJoCo (peer_bigant.cpp).
[[nodiscard]] std::vector<PointKind> peer_bigant_kinds();
/// The referee on §5.2's slope and stairs, Figs. 5.2-5.3: MuJoCo's BigANT (peer_terrain.cpp).
[[nodiscard]] std::vector<PointKind> peer_terrain_kinds();
/// A motion plan of §5.5 replayed on MuJoCo's BigANT (plan_replay.cpp).
[[nodiscard]] std::vector<PointKind> plan_replay_kinds();
/// What each scene effect costs per step (scene_cost.cpp).
[[nodiscard]] std::vector<PointKind> scene_cost_kinds();
/// BigANT up a slope: progress per cycle and the stall slope, §5.2.1 (slope.cpp).
[[nodiscard]] std::vector<PointKind> slope_kinds();
/// The brute-force planner of §5.4–5.5 on BigANT: plans, their summaries, the toe path of Fig.
/// 5.8 (planning.cpp).
[[nodiscard]] std::vector<PointKind> planning_kinds();
/// The long run of the Coulomb solver on random stress frames, §3.4 (coulomb_long_run.cpp).
[[nodiscard]] std::vector<PointKind> coulomb_long_run_kinds();
/// What one step of the brute-force planner costs, §5.5 (planning_cost.cpp).
[[nodiscard]] std::vector<PointKind> planning_cost_kinds();

/// The residual transfer of §5.3 on MuJoCo's Multipod: trials, the fit of B and its errors, the
/// training-set size curve (residual.cpp).
[[nodiscard]] std::vector<PointKind> residual_kinds();

/// The in-situ F/T calibration of ch. 4 on the synthetic BigANT: estimates against the truth,
/// the CoM, the residuals, Table 4.2, the multistart, the accuracy grid (calibration.cpp).
[[nodiscard]] std::vector<PointKind> calibration_kinds();

/// The hostile-input campaign against the binary itself (hostile_inputs_kind.cpp).
[[nodiscard]] std::vector<PointKind> hostile_input_kinds();
/// Scaling out: noop, scale_out and coordinator_throughput (scale_out.cpp).
[[nodiscard]] std::vector<PointKind> scale_out_kinds();

/// This machine's clock, peak flops per cycle and operation latencies, for the performance
/// page's physical limits (machine_limits.cpp).
[[nodiscard]] std::vector<PointKind> machine_limit_kinds();

/// Every point kind of every family, in the order of families.cpp.
[[nodiscard]] std::span<const PointKind> all_kinds();

/// sweeps::prepare against every kind of every family.
[[nodiscard]] PreparedSweep prepare(Spec spec);

}  // namespace slipwalk::sweeps::points
