// The local connection of eq. 3.20: A(q)·q̇ reproduces the viscous-Coulomb solve, feet in the
// air have zero columns, A is linear (superposition), yaw- and rotation-covariant, and finite
// for degenerate contact sets.
#include <gtest/gtest.h>

#include <random>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::connection {
namespace {

using contact::Frame;
using contact::Robot;
using Eigen::Matrix2d;
using Eigen::Vector3d;

struct Scene {
  Robot robot;
  Frame frame;
  explicit Scene(int n) : robot(contact::uniform_robot(n)), frame(robot) {
    std::fill(frame.contact.begin(), frame.contact.end(), 1);
    frame.Fz.setConstant(1.0 / n);
  }
};

Scene random_scene(std::mt19937& rng, int n, bool aniso) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::uniform_real_distribution<double> P(0.2, 1.0);
  Scene s(n);
  for (int k = 0; k < n; ++k) {
    s.frame.q.col(k) << 0.3 * U(rng), 0.3 * U(rng), -0.1;
    s.frame.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
    s.frame.Fz(k) = P(rng);
    s.robot.mu(k) = P(rng);
    if (aniso) {
      s.robot.w.col(k) << U(rng), U(rng);
    }
  }
  return s;
}

/// vec(q̇_xy): (q̇_x,0, q̇_y,0, q̇_x,1, ...).
Eigen::VectorXd stacked(const Frame& f) {
  Eigen::VectorXd v(2 * f.legs());
  for (int k = 0; k < f.legs(); ++k) {
    v.segment<2>(2 * k) = f.qdot.col(k).head<2>();
  }
  return v;
}

TEST(LocalConnection, ReproducesTheViscousSolveOnRandomFrames) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 300; ++trial) {
    Scene s = random_scene(rng, 2 + trial % 12, trial % 3 == 0);
    for (int k = 0; k < s.robot.legs(); ++k) {
      s.frame.contact[static_cast<std::size_t>(k)] = (k + trial) % 4 == 0 ? 0 : 1;
    }
    local_connection(s.robot, s.frame);
    friction::solve_viscous_coulomb(s.robot, s.frame);
    const Vector3d v = s.frame.A * stacked(s.frame);
    EXPECT_LE((v - s.frame.v_body).norm(), 1e-13 * (1.0 + s.frame.v_body.norm()))
        << "trial " << trial;
  }
}

TEST(LocalConnection, ColumnsOfFeetInTheAirAreZero) {
  std::mt19937 rng(2);
  Scene s = random_scene(rng, 6, true);
  s.frame.contact = {1, 0, 1, 1, 0, 1};
  s.frame.Fz(1) = 0.0;
  s.frame.Fz(4) = 0.0;
  local_connection(s.robot, s.frame);
  EXPECT_EQ(s.frame.A.middleCols<2>(2).norm(), 0.0);
  EXPECT_EQ(s.frame.A.middleCols<2>(8).norm(), 0.0);
  EXPECT_GT(s.frame.A.middleCols<2>(0).norm(), 0.0);
  // A foot in contact with zero load or zero friction carries no force either.
  s.frame.contact[1] = 1;
  s.robot.mu(2) = 0.0;
  local_connection(s.robot, s.frame);
  EXPECT_EQ(s.frame.A.middleCols<2>(2).norm(), 0.0);
  EXPECT_EQ(s.frame.A.middleCols<2>(4).norm(), 0.0);
}

TEST(LocalConnection, RigidMotionOfAllFeetIsReproduced) {
  // If every foot moves as −(v + ω S q) the body moves at exactly (v, ω): A·q̇ = x for every
  // rigid x, i.e. A J = I with J the stacked [I | S q_k].
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 8, trial % 2 == 0);
    local_connection(s.robot, s.frame);
    Eigen::MatrixXd J(2 * s.robot.legs(), 3);
    for (int k = 0; k < s.robot.legs(); ++k) {
      J.block<2, 2>(2 * k, 0).setIdentity();
      J(2 * k, 2) = -s.frame.q(1, k);
      J(2 * k + 1, 2) = s.frame.q(0, k);
    }
    EXPECT_LE((-s.frame.A * J - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  }
}

TEST(LocalConnection, YawInvariantAndRotationCovariant) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 2 == 0);
    local_connection(s.robot, s.frame);
    const Eigen::MatrixXd A0 = s.frame.A;
    s.frame.theta = 0.5 + trial;
    local_connection(s.robot, s.frame);
    EXPECT_LE((s.frame.A - A0).norm(), 1e-15 * A0.norm());
    // Rotating the scene by R: A' = diag(R, 1) A blockdiag(Rᵀ).
    const double a = 0.3 + trial;
    Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    for (int k = 0; k < s.robot.legs(); ++k) {
      s.frame.q.col(k).head<2>() = R * s.frame.q.col(k).head<2>();
      s.robot.w.col(k) = R * s.robot.w.col(k);
    }
    local_connection(s.robot, s.frame);
    for (int k = 0; k < s.robot.legs(); ++k) {
      Eigen::Matrix<double, 3, 2> expect = A0.middleCols<2>(2 * k) * R.transpose();
      expect.topRows<2>() = (R * expect.topRows<2>()).eval();
      EXPECT_LE((s.frame.A.middleCols<2>(2 * k) - expect).norm(), 1e-12 * A0.norm());
    }
  }
}

TEST(LocalConnection, DegenerateContactSetsAreFinite) {
  // One foot, feet at one point, no foot: finite A, and A·q̇ the solver's least-norm answer.
  for (int n : {1, 3}) {
    Scene s(n);
    for (int k = 0; k < n; ++k) {
      s.frame.q.col(k) << 0.1, 0.2, -0.1;
      s.frame.qdot.col(k) << 0.1 * k, -0.05, 0.0;
    }
    local_connection(s.robot, s.frame);
    friction::solve_viscous_coulomb(s.robot, s.frame);
    EXPECT_TRUE(s.frame.A.allFinite());
    EXPECT_LE((s.frame.A * stacked(s.frame) - s.frame.v_body).norm(), 1e-14);
    std::fill(s.frame.contact.begin(), s.frame.contact.end(), 0);
    local_connection(s.robot, s.frame);
    EXPECT_EQ(s.frame.A.norm(), 0.0);
  }
}

}  // namespace
}  // namespace slipwalk::connection
