#pragma once
// A walking robot (thesis §3.5, §5.3.2, §5.5): its legs as the multi-legged model sees them (a
// contact::Robot: K, μ, w, Mg) and a gait that moves the feet in the body frame. A Walker is a
// model: built once (robots/*.cpp), then asked for the feet at any time without allocating.
// Trajectories (connection/trajectory.hpp) take the foot kinematics as a callable, so connection/
// does not depend on robots/ (DESIGN.md: core ← contact ← friction ← connection ← robots).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "contact/robot.hpp"

namespace slipwalk::robots {

/// Writes the feet's positions q (3 × N, m) and velocities q̇ = dq/dt (3 × N, m/s) in the body
/// frame at time t (s). Sizes are the robot's; implementations must not allocate.
using FootKinematics = std::function<void(double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot)>;

/// Writes each leg's gait phase at time t: the shaft angle φ ∈ [0, 1) for BigANT's crank legs,
/// the oscillator phase (2πft + iΔφ)/2π mod 1 for the Multipod and the quadruped. Optional.
using GaitPhase = std::function<void(double t, Eigen::VectorXd& phase)>;

struct Walker {
  std::string name;                    ///< e.g. "bigant_tripod", "multipod6"
  contact::Robot robot;                ///< leg constants (K, μ, w) and Mg
  std::vector<std::string> leg_names;  ///< N names, e.g. HL, ML, FL, HR, MR, FR for BigANT
  double period = 1.0;                 ///< s, one gait cycle
  FootKinematics feet;                 ///< the gait (required)
  GaitPhase phase;                     ///< may be empty

  [[nodiscard]] int legs() const { return robot.legs(); }
};

}  // namespace slipwalk::robots
