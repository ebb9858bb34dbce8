#pragma once
// Terrain policies of a trajectory kernel (thesis §5.2; terrain/terrain.hpp has the geometry and
// the derivations): each one is steps 2–3 of the per-frame pipeline, the spring support and the
// friction law's balance, on its ground. FlatGround is exactly those two calls, so a flat kernel
// has no terrain code at all; the others transform the frame's inputs around the same calls
// (contact::spring_support is used unchanged). Buffers are sized once per run in reset().
#include <Eigen/Core>

#include "connection/local_connection.hpp"
#include "contact/spring_support.hpp"
#include "core/se2.hpp"
#include "friction/solvers.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::connection {

/// The spring support along a trajectory: each frame starts from the balance of the frame before
/// (SupportOptions::warm_start), which the feet have moved little from in one step.
inline constexpr contact::SupportOptions kTrajectorySupport{.warm_start = true};

/// Flat ground: the ch. 3 model.
struct FlatGround {
  void validate() const {}
  void reset(const contact::Robot& /*robot*/) {}
  template <class Law>
  void operator()(const contact::Robot& robot, contact::Frame& f, const core::Pose2& /*pose*/,
                  const Law& law) {
    contact::spring_support(robot, f, kTrajectorySupport);
    law(robot, f);
  }
};

/// A constant slope (§5.2.1): the support carries Mg cos σ about the point where the weight's line
/// crosses the plane; the friction balance carries gravity's planar part as a load, so the body
/// velocity is affine in q̇ (viscous-Coulomb) or the minimizer of dissipation minus the load's
/// power (Coulomb), and a load beyond what friction holds is reported as sliding.
struct SlopeGround {
  terrain::Slope slope;
  contact::Robot support;  ///< the robot with Mg cos σ (set by reset)
  Eigen::Matrix2Xd saved;  ///< (2 x N) the feet's q_xy while the support sees them shifted

  void validate() const { terrain::validate(slope); }
  void reset(const contact::Robot& robot) {
    support = robot;
    support.Mg = robot.Mg * std::cos(slope.angle);
    saved.resize(2, robot.legs());
  }
  template <class Law>
  void operator()(const contact::Robot& robot, contact::Frame& f, const core::Pose2& pose,
                  const Law& law) {
    // Normal loads balanced about the weight's crossing point c (0 when com_height = 0).
    const Eigen::Vector2d c = terrain::support_offset(slope, pose.theta);
    saved = f.q.topRows<2>();
    f.q.topRows<2>().colwise() -= c;
    contact::spring_support(support, f, kTrajectorySupport);
    f.q.topRows<2>() = saved;
    // Gravity's planar component (body frame); it passes through the body's normal axis.
    const Eigen::Vector3d load = terrain::slope_load(slope, robot.Mg, pose.theta);
    if constexpr (Law::kLaw == FrictionLaw::kCoulomb) {
      friction::solve_coulomb_loaded(robot, f, load, law.options);
    } else {
      friction::solve_viscous_coulomb_loaded(robot, f, load);
    }
  }
};

/// Stairs (§5.2.2): the support searches in the stair coordinates of terrain::to_stairs_support
/// (each toe measured from its tread, the body pitched by the stair slope), the friction balance
/// is planar in the horizontal plane with the toes' horizontal levers; no planar load.
struct StairsGround {
  terrain::Stairs stairs;
  Eigen::VectorXd height;  ///< (N) the tread height under each toe, m
  Eigen::VectorXd qy;      ///< (N) the gait's q_y (the horizontal lateral levers)

  void validate() const { terrain::validate(stairs); }
  void reset(const contact::Robot& robot) {
    height.resize(robot.legs());
    qy.resize(robot.legs());
  }
  template <class Law>
  void operator()(const contact::Robot& robot, contact::Frame& f, const core::Pose2& pose,
                  const Law& law) {
    qy = f.q.row(1).transpose();
    terrain::to_stairs_support(stairs, pose, f, height);
    contact::spring_support(robot, f, kTrajectorySupport);
    terrain::stairs_levers(f, qy);
    law(robot, f);
  }
};

}  // namespace slipwalk::connection
