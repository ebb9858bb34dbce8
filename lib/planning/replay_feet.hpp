#pragma once
// A plan's shaft angles as foot kinematics (thesis §5.5): what a robot that executes the plan
// open-loop does with its legs, so that another simulator (the MuJoCo peer, peers/mujoco/
// plan_replay.hpp) can walk the same feet and show where its body goes against the plan's.
//
// A plan executes, at step n, the speeds φ̇_n for τ = T_f Δt / T_s from t_n (planner.hpp), so each
// shaft angle is piecewise linear in time:
//   φ_i(t) = φ_i,n + φ̇_i,n (t − t_n)  (mod 1),   t_n ≤ t < t_{n+1},
// and the feet are q_i(t) = toe_i(φ_i(t)), q̇_i = dq_i/dφ · φ̇_i,n (the chain rule; φ in turns, φ̇
// in turns/s, dq/dφ in m per turn). The wrap of φ at 1 → 0 is the same toe position (the leg is a
// crank), so q is continuous across it. Before t_0 the feet are those at t_0 at rest; after the
// last step's end the shaft angles stay where that step left them, at rest.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"
#include "planning/plan_robot.hpp"
#include "planning/planner.hpp"
#include "robots/walker.hpp"

namespace slipwalk::planning {

/// The executed part of a plan: per step its start time, pose and shaft angles and the speeds
/// executed over it (the columns t, x, y, theta, phi_L, speed_L of a plan CSV, plan_csv.hpp).
struct PlanTrack {
  double step_duration = 0.0;     ///< τ = T_f Δt / T_s, s
  std::vector<double> t;          ///< (S) t_n, s, increasing
  std::vector<core::Pose2> pose;  ///< (S) the plan's pose at t_n (θ unwrapped)
  Eigen::MatrixXd phi;            ///< (N x S) φ_i,n, turns in [0, 1)
  Eigen::MatrixXd speed;          ///< (N x S) φ̇_i,n, turns/s
  core::Pose2 end_pose;           ///< the pose after the last step, at t_S = t_{S−1} + τ
  Eigen::VectorXd end_phi;        ///< (N) the shaft angles there

  [[nodiscard]] long long steps() const { return static_cast<long long>(t.size()); }
  [[nodiscard]] int legs() const { return static_cast<int>(phi.rows()); }
  [[nodiscard]] double end_time() const { return t.empty() ? 0.0 : t.back() + step_duration; }
};

/// Runs planning::plan and keeps what was executed. Throws what plan throws.
[[nodiscard]] PlanTrack plan_track(const PlanRobot& robot, const PlanOptions& options,
                                   const Goal& goal, const PlanState& start);

/// Throws core::InputError("plan track", ...) for an empty track, sizes that disagree with the
/// robot, times that do not increase, τ ≤ 0 or non-finite values.
void validate(const PlanRobot& robot, const PlanTrack& track);

/// φ_i(t) of every leg (the piecewise-linear law above, wrapped into [0, 1)). No allocation.
void replay_phase(const PlanTrack& track, double t, Eigen::VectorXd& phi);

/// The same track executed `factor` times slower: t_n → t_0 + factor (t_n − t_0), τ → factor τ,
/// φ̇ → φ̇ / factor; shaft angles and poses unchanged. The model of ch. 3 is rate-independent (the
/// body velocity is linear in q̇, v_b = A(q) q̇, for either friction law), so the plan predicts the
/// same path at the slower pace: replaying a slowed plan tests the quasi-static assumption.
/// Throws core::InputError("plan track", ...) unless factor ≥ 1 and finite.
[[nodiscard]] PlanTrack slowed(PlanTrack track, double factor);

/// The plan's feet as a robots::Walker: robot, leg names and kinematics of `robot`, feet q(t),
/// q̇(t) as above, phase φ(t), period the plan's duration. The walker holds copies of both, so it
/// outlives them; its feet allocate nothing per call. Throws as validate().
[[nodiscard]] robots::Walker replay_walker(const PlanRobot& robot, const PlanTrack& track);

}  // namespace slipwalk::planning
