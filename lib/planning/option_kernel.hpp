#pragma once
// The inside of a planning step (planning/planner.hpp): one node's table of toe positions and
// velocities, and the integration of one option over its substeps.
//
// What options share. Leg i's toe at substep s depends only on its own speed, so one node needs
// N × (M + 1) × (T_s + 1) toe evaluations (the M choices and the swing speed), however many of
// the M^N options it integrates; the per-option loop reads them from the table. The model of
// ch. 3 itself couples all legs (the spring support balances the whole body), so each option
// and substep is one evaluation of it.
#include <Eigen/Core>
#include <vector>

#include "contact/robot.hpp"
#include "core/se2.hpp"
#include "planning/planner.hpp"

namespace slipwalk::planning {

struct NodeTable {
  int legs = 0;
  int columns = 0;   ///< M + 1: the M choices, then the swing speed
  int substeps = 0;  ///< T_s
  double h = 0.0;    ///< Δt / T_s, s
  /// (3 × (T_s + 1)·columns·N) toe positions q and velocities q̇ = dq/dφ · φ̇, body frame; column
  /// (s · columns + c) · N + i is leg i at substep s moving at speed column c.
  Eigen::Matrix3Xd q;
  Eigen::Matrix3Xd qdot;
  std::vector<char> chooses;   ///< (N) 1 for a leg that chooses its speed (the contact rule)
  std::vector<int> free_legs;  ///< the legs that choose, ascending (capacity N)

  // ---- substep 0, the same for every option (q does not depend on the speeds): its spring
  // support, solved once per node by contact::spring_support (fast_kernel.hpp) ----------------
  bool start_ok = false;     ///< the support balanced the body (planner.hpp: else infeasible)
  double start_alpha = 0.0;  ///< α, β, z at substep 0
  double start_beta = 0.0;
  double start_z = 0.0;
  std::vector<char> start_contact;  ///< (N)
  Eigen::VectorXd start_Fz;         ///< (N)
  // ---- constants of the fast route over the whole table --------------------------------------
  double lever = 1.0;  ///< L = max ‖q_xy‖: scales the 3 × 3 solves
  double size_y = 0.0, size_x = 0.0, size_z = 0.0;  ///< max |q_y|, |q_x|, |q_z|: bound rounding
  bool isotropic = true;  ///< every foot has w = 0 (the fast viscous balance needs it)

  [[nodiscard]] Eigen::Index at(int s, int column, int leg) const {
    return (static_cast<Eigen::Index>(s) * columns + column) * legs + leg;
  }
};

/// Sizes `table` for the robot and options (once; build_node does not allocate).
void size_node(const PlanRobot& robot, const PlanOptions& options, NodeTable& table);

/// Fills the table for shaft angles `phi` (N, turns) and decides which legs choose (the contact
/// rule; kSupport runs the spring support on `scratch` at the node's configuration).
void build_node(const PlanRobot& robot, const PlanOptions& options, const Eigen::VectorXd& phi,
                NodeTable& table, contact::Frame& scratch);

/// The speed column of each leg for option digits c (N): c_i for a leg that chooses, M (the
/// swing speed) for the others.
void option_columns(const NodeTable& table, const int* digits, int* columns);

/// The reference loop (contact::spring_support then the friction law's solver per substep, as
/// connection::integrate): what the fast route must agree with. Same contract as integrate_option.
bool integrate_option_reference(const PlanRobot& robot, const PlanOptions& options,
                                const NodeTable& table, const int* columns, int substeps,
                                core::Pose2& pose, contact::Frame& frame);

/// Integrates the option whose legs move at speed columns `columns` (N) over substeps 0 …
/// `substeps` − 1 from `pose`, which it advances. False (and the pose as far as it got) when the
/// option is infeasible (planner.hpp). `frame` is scratch of the robot's size. The
/// viscous-Coulomb law takes the fast route (fast_kernel.hpp), equal to the reference to rounding;
/// the Coulomb law the reference.
bool integrate_option(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                      const int* columns, int substeps, core::Pose2& pose, contact::Frame& frame);

/// integrate_option for `count` options at once (at most kOptionBatch; columns[l] and poses[l]
/// are option l's, ok[l] its result): the planner's call. Each option's result is the one
/// integrate_option gives it alone, bit for bit.
inline constexpr int kOptionBatch = 4;
void integrate_options(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                       const int* const* columns, int count, int substeps, core::Pose2* poses,
                       bool* ok, contact::Frame& frame);

/// φ_i + φ̇_i · (substeps · h), wrapped to [0, 1): where the option leaves leg i's shaft.
[[nodiscard]] double advanced_phi(double phi, double speed, int substeps, double h);

}  // namespace slipwalk::planning
