#pragma once
// The robot a planner drives (thesis §5.4.3, §5.5): N legs, each with one periodic degree of
// freedom φ_i ∈ [0, 1) (turns of a motor shaft), and the multi-legged model of ch. 3 that turns
// the feet into a body velocity. For BigANT φ is the shaft angle of its four-bar leg
// (robots/bigant.hpp): φ = 0 mid-stance, φ = 0.5 mid-return.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "contact/robot.hpp"

namespace slipwalk::planning {

/// A leg's toe at shaft angle φ (turns): its position q (m) and dq/dφ (m per turn), body frame.
/// Called only when a planning step starts (its values are tabulated), never per option.
using LegKinematics = std::function<void(int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                                         Eigen::Ref<Eigen::Vector3d> dq_dphi)>;

struct PlanRobot {
  std::string name;                    ///< "bigant", "bigant8", …
  contact::Robot robot;                ///< K, μ, w, Mg of the legs (ch. 3)
  std::vector<std::string> leg_names;  ///< N names, e.g. HL, ML, FL, HR, MR, FR
  LegKinematics toe;                   ///< φ → toe (required)
  /// Half-width (turns) of the stance window about φ = 0 that ContactRule::kStanceWindow counts
  /// as "in contact" (planner.hpp). BigANT: half its 0.35-turn flat stance sweep.
  double stance_half_width = 0.175;

  [[nodiscard]] int legs() const { return robot.legs(); }
};

/// BigANT (legs = 6, robots::bigant_legs) or a BigANT-like robot with an even number of legs
/// (robots::bigant_robot(legs)): the same four-bar legs, legs/2 per side. Throws
/// core::InputError("legs", ...) for other counts.
[[nodiscard]] PlanRobot bigant_plan_robot(int legs = 6);

/// Throws core::InputError naming what is wrong: the robot (contact::validate), a missing toe
/// function, leg names of the wrong count, a stance half-width outside (0, 0.5).
void validate(const PlanRobot& robot);

}  // namespace slipwalk::planning
