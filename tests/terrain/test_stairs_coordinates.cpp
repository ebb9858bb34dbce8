// The stairs' change of coordinates (terrain/terrain.cpp, §5.2.2) by routes independent of its
// derivation. Oracles: the full rotation R_z(θ) R_y(β₀ + δβ) R_x(α) (Eigen's, with the thesis'
// R_y: β > 0 turns the nose down, β₀ = −γ) puts every toe at the height the linearized support
// sees, up to second order in (α, δβ), and over the tread under the toe's own world position
// (any yaw, any stairs heading); stairs whose steps vanish are a slope of the same angle, so the
// support finds the body's pitch, roll and height that SlopeGround finds on the plane.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "connection/trajectory_kernel.hpp"
#include "contact/spring_support.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::connection {
namespace {

constexpr double kPi = std::numbers::pi;

/// Six feet of a hexapod-like body (body frame), a tripod lower than the other three.
contact::Frame feet(const contact::Robot& robot) {
  contact::Frame f(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * kPi * k / 6.0 + 0.2;
    f.q.col(k) << 0.35 * std::cos(a), 0.2 * std::sin(a), (k % 2 == 0) ? -0.15 : -0.12;
    f.qdot.col(k) << -0.05, 0.01 * k, 0.02;
  }
  return f;
}

/// The world position of body-frame point q at yaw θ, pitch β (thesis' sign: nose-down) and roll
/// α, body origin at (x, y, z): the full rotation, no expansion.
Eigen::Vector3d world(const Eigen::Vector3d& q, double theta, double beta, double alpha,
                      const Eigen::Vector3d& origin) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return R * q + origin;
}

TEST(StairsCoordinates, ToeHeightsAreTheFullRotationsToFirstOrder) {
  // For small (α, δβ) the toe's height above its tread seen by the support (eq. 3.6 in q') is the
  // exact one, the tread read at the exact toe's horizontal position, up to O(ε²): halving ε
  // quarters the error.
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.6, 9.81);
  for (const terrain::Stairs st :
       {terrain::Stairs{0.3, 0.12, 0.0}, terrain::Stairs{0.25, 0.17, 0.7}}) {
    for (double theta : {0.0, 0.5, -1.2}) {
      const core::Pose2 pose{0.93, -0.41, theta};
      const double gamma = terrain::stair_pitch(st, theta);
      double previous = 0.0;
      for (double eps : {4e-3, 2e-3, 1e-3}) {
        const double alpha = 0.7 * eps;
        const double dbeta = -eps;
        const double z0 = 0.31;
        contact::Frame f = feet(robot);
        const contact::Frame body = f;
        Eigen::VectorXd h(6);
        terrain::to_stairs_support(st, pose, f, h);
        double err = 0.0;
        for (int k = 0; k < 6; ++k) {
          const Eigen::Vector3d p = world(body.q.col(k), theta, -gamma + dbeta, alpha,
                                          Eigen::Vector3d(pose.x, pose.y, z0));
          const Eigen::Vector3d p0 =
              world(body.q.col(k), theta, -gamma, 0.0, Eigen::Vector3d(pose.x, pose.y, z0));
          // The tread is read under the toe's own horizontal position (at α = δβ = 0).
          EXPECT_EQ(h(k), terrain::step_height(st, p0.x(), p0.y())) << k;
          const double linear = contact::foot_height(f, k, alpha, dbeta, z0);
          err = std::max(err, std::abs(linear - (p.z() - h(k))));
        }
        EXPECT_LT(err, 0.5 * eps * eps) << "theta " << theta << " eps " << eps;
        if (previous > 0.0) {
          EXPECT_NEAR(previous / err, 4.0, 0.6) << "second order, theta " << theta;
        }
        previous = err;
      }
    }
  }
}

TEST(StairsCoordinates, HorizontalLeversAreTheRotatedToesForAnyYawAndHeading) {
  // After the search the friction balance sees (q'_x, q_y): q'_x is the toe's forward distance
  // from the body origin in the horizontal plane, q_y the lateral one, as the rotation gives them.
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.6, 9.81);
  const terrain::Stairs st{0.27, 0.1, -2.1};
  for (double theta : {-2.1, 0.3, 2.9}) {
    const core::Pose2 pose{-0.2, 1.7, theta};
    const double gamma = terrain::stair_pitch(st, theta);
    contact::Frame f = feet(robot);
    const contact::Frame body = f;
    StairsGround ground{st, {}, {}};
    ground.reset(robot);
    ground(robot, f, pose, ViscousCoulombKernel{});
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector3d p =
          world(body.q.col(k), theta, -gamma, 0.0, Eigen::Vector3d(pose.x, pose.y, 0.0));
      const Eigen::Vector2d d = p.head<2>() - Eigen::Vector2d(pose.x, pose.y);
      EXPECT_NEAR(f.q(0, k), std::cos(theta) * d.x() + std::sin(theta) * d.y(), 1e-14) << k;
      EXPECT_NEAR(f.q(1, k), -std::sin(theta) * d.x() + std::cos(theta) * d.y(), 1e-14) << k;
      EXPECT_EQ(ground.height(k), terrain::step_height(st, p.x(), p.y())) << k;
    }
  }
}

TEST(StairsCoordinates, VanishingStepsAreTheSlopeOfTheSameAngle) {
  // Stairs of tread 0.1 mm rising at σ: the ground is the plane of slope σ to 0.1 mm. The body
  // that SlopeGround puts at normal height n above plane point (x, 0) has its origin at world
  // (x cos σ − n sin σ, x sin σ + n cos σ); stairs put it at that height, with the same pitch and
  // roll about the ground (first order in both: to the compressions' cos σ, a few 1e-4). On the
  // stairs the weight is vertical through the body origin, so on the slope it crosses the plane
  // n tan σ downhill of the origin: the slope's com_height is n.
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.6, 9.81);
  for (double sigma_deg : {10.0, 21.8}) {
    const double sigma = sigma_deg * kPi / 180.0;
    const double tread = 1e-4;
    const terrain::Stairs st{tread, tread * std::tan(sigma), 0.0};
    for (double x : {0.0, 0.37}) {
      // The weight acts along the vertical through the body origin, which stands n above the
      // plane: SlopeGround with com_height = n (found by iterating from the stance feet's depth).
      contact::Frame on_slope = feet(robot);
      const contact::Frame body = on_slope;
      double n = 0.15;
      for (int iteration = 0; iteration < 3; ++iteration) {
        on_slope = body;
        SlopeGround slope{terrain::Slope{sigma, 0.0, n}, {}, {}};
        slope.reset(robot);
        slope(robot, on_slope, core::Pose2{x, 0.0, 0.0}, ViscousCoulombKernel{});
        n = on_slope.z;
      }
      contact::Frame on_stairs = body;
      const core::Pose2 above{x * std::cos(sigma) - n * std::sin(sigma), 0.0, 0.0};
      StairsGround stairs{st, {}, {}};
      stairs.reset(robot);
      stairs(robot, on_stairs, above, ViscousCoulombKernel{});
      EXPECT_NEAR(on_stairs.z, x * std::sin(sigma) + n * std::cos(sigma), 5e-4) << sigma_deg;
      EXPECT_NEAR(on_stairs.beta, on_slope.beta, 2e-3) << sigma_deg;
      EXPECT_NEAR(on_stairs.alpha, on_slope.alpha, 2e-3) << sigma_deg;
      for (int k = 0; k < 6; ++k) {
        EXPECT_EQ(on_stairs.contact[static_cast<std::size_t>(k)],
                  on_slope.contact[static_cast<std::size_t>(k)])
            << k;
      }
    }
  }
}

}  // namespace
}  // namespace slipwalk::connection
