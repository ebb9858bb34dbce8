#include "planning/plan_robot.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "robots/bigant.hpp"

namespace slipwalk::planning {

PlanRobot bigant_plan_robot(int legs) {
  PlanRobot r;
  robots::BigAntLegs bigant = robots::bigant_legs(legs);
  r.name = legs == robots::kBigAntLegs ? "bigant" : "bigant" + std::to_string(legs);
  r.robot = legs == robots::kBigAntLegs ? robots::bigant_robot() : robots::bigant_robot(legs);
  r.leg_names = bigant.names;
  r.stance_half_width = 0.5 * robots::kBigAntStanceSweep;
  r.toe = [bigant = std::move(bigant)](int leg, double phi, const Eigen::Ref<Eigen::Vector3d>& q,
                                       const Eigen::Ref<Eigen::Vector3d>& dq_dphi) {
    robots::bigant_toe(bigant, leg, phi, q, dq_dphi);
  };
  return r;
}

void validate(const PlanRobot& robot) {
  contact::validate(robot.robot);
  if (!robot.toe) {
    throw core::InputError("robot.toe", "a planning robot needs its legs' kinematics");
  }
  if (static_cast<int>(robot.leg_names.size()) != robot.legs()) {
    throw core::InputError("robot.leg_names", std::to_string(robot.leg_names.size()) +
                                                  " names for " + std::to_string(robot.legs()) +
                                                  " legs");
  }
  if (!(robot.stance_half_width > 0.0 && robot.stance_half_width < 0.5)) {
    throw core::InputError("robot.stance_half_width", "must be in (0, 0.5) turns");
  }
}

}  // namespace slipwalk::planning
