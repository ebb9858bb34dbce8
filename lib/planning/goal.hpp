#pragma once
// What a plan tracks (thesis §5.4.4): a target *trajectory* Ω^target(t) ∈ SE(2), not a target
// velocity, so that a robot that fell behind is pulled back onto the path ("catch up") instead of
// merely matching a speed. Two kinds: a constant body twist held from the start pose — the
// thesis' three goals (walk straight at 0.2 m/s, turn in place at 0.2 rad/s, move diagonally at
// (0.05, 0.02) m/s with the heading held) — or waypoints (t, x, y, θ) interpolated linearly.
#include <Eigen/Core>
#include <array>
#include <string_view>
#include <vector>

#include "core/se2.hpp"

namespace slipwalk::planning {

struct Goal {
  core::Pose2 start = {};  ///< the target at t = 0 (the plan's start pose for the thesis' goals)
  /// (v_x, v_y, ω) in m/s and rad/s, a body twist held from `start`: Ω(t) = start · exp(twist t),
  /// a straight line for ω = 0 and a circle otherwise. Used when `times` is empty.
  Eigen::Vector3d twist = Eigen::Vector3d::Zero();
  /// Waypoints instead of a twist: times (s, strictly increasing, ≥ 2 of them) and poses (θ
  /// unwrapped, interpolated as a number). Before the first time the target is the first pose,
  /// after the last the last pose.
  std::vector<double> times;
  std::vector<core::Pose2> waypoints;
};

/// The thesis' three goals (§5.5.1.2 and the captions of Figs. 5.9–5.11) as body twists
/// (v_x, v_y, ω) held from the start pose.
struct NamedTwist {
  std::string_view name;
  double vx, vy, omega;  ///< m/s, m/s, rad/s
};
inline constexpr std::array<NamedTwist, 3> kThesisGoals = {{
    {"straight", 0.2, 0.0, 0.0},    ///< Fig. 5.9: walk along x at 0.2 m/s
    {"turn", 0.0, 0.0, 0.2},        ///< Fig. 5.10: turn in place at 0.2 rad/s
    {"diagonal", 0.05, 0.02, 0.0},  ///< Fig. 5.11: (0.05, 0.02) m/s with the heading held
}};

/// The goal of kThesisGoals named `name` from the origin; throws core::InputError("goal", ...)
/// naming the three for another name.
[[nodiscard]] Goal thesis_goal(std::string_view name);

/// Throws core::InputError ("goal.twist", "goal.times[3]", ...) for non-finite values, sizes that
/// disagree, fewer than two waypoints or times that do not increase.
void validate(const Goal& goal);

/// Ω^target(t). No allocation.
[[nodiscard]] core::Pose2 target_at(const Goal& goal, double t);

}  // namespace slipwalk::planning
