// friction::ViscousSystem, the viscous balance M x = −b of eq. 3.20 assembled and factorized once.
// Oracles: M and b summed by hand from their definition (friction/balance.hpp,
// M = Σ c_k J_kᵀ G_k J_k, b = Σ c_k J_kᵀ G_k q̇_k with J_k = [I | S q_k]), the Moore–Penrose
// conditions when the contacts are one point, solve_viscous_coulomb(robot, frame) to the bit, and
// the frame's own feet to the bit where the system reads the support's rows.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "friction/viscous_system.hpp"

namespace slipwalk::friction {
namespace {

struct Case {
  contact::Robot robot;
  contact::Frame frame;
};

// n feet at random positions and velocities, random loads, anisotropic when asked; foot 0 in the
// air so that a zero weight is covered.
Case random_case(int n, bool anisotropic, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  contact::Robot robot = contact::uniform_robot(n, 100.0, 0.7, 9.81);
  for (int k = 0; k < n; ++k) {
    robot.mu(k) = 0.4 + 0.3 * (U(rng) + 1.0);
    if (anisotropic) {
      robot.w.col(k) << 0.6 * U(rng), 0.6 * U(rng);
    }
  }
  contact::Frame f(robot);
  for (int k = 0; k < n; ++k) {
    f.q.col(k) << 0.4 * U(rng), 0.3 * U(rng), -0.1;
    f.qdot.col(k) << 0.2 * U(rng), 0.2 * U(rng), 0.0;
    f.contact[static_cast<std::size_t>(k)] = k == 0 ? 0 : 1;
    f.Fz(k) = k == 0 ? 0.0 : 1.0 + U(rng);
  }
  return {robot, f};
}

// M and b from their definition, unscaled, with Eigen's matrices.
void by_hand(const Case& c, Eigen::Matrix3d& M, Eigen::Vector3d& b) {
  M.setZero();
  b.setZero();
  for (int k = 0; k < c.robot.legs(); ++k) {
    if (c.frame.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    const double ck = c.robot.mu(k) * c.frame.Fz(k);
    const Eigen::Vector2d w = c.robot.w.col(k);
    const Eigen::Matrix2d G = Eigen::Matrix2d::Identity() + w * w.transpose();
    Eigen::Matrix<double, 2, 3> J;
    J << 1.0, 0.0, -c.frame.q(1, k), 0.0, 1.0, c.frame.q(0, k);
    M += ck * J.transpose() * G * J;
    b += ck * J.transpose() * G * c.frame.qdot.col(k).head<2>();
  }
}

TEST(ViscousSystem, InverseAndWeightsMatchTheBalanceSummedByHand) {
  std::mt19937 rng(7);
  for (bool anisotropic : {false, true}) {
    for (int n : {3, 4, 6, 9}) {
      for (int trial = 0; trial < 20; ++trial) {
        Case c = random_case(n, anisotropic, rng);
        Eigen::Matrix3d M;
        Eigen::Vector3d b;
        by_hand(c, M, b);
        const ViscousSystem system(c.robot, c.frame);
        EXPECT_EQ(system.anisotropic(), anisotropic);
        for (int k = 0; k < n; ++k) {
          const double expected = k == 0 ? 0.0 : c.robot.mu(k) * c.frame.Fz(k);
          EXPECT_EQ(system.weight(k), expected);
          EXPECT_EQ(system.weights()[k], expected);
        }
        const Eigen::Matrix3d P = system.inverse();
        EXPECT_LT((P * M - Eigen::Matrix3d::Identity()).norm(), 1e-10);
        // The body velocity the system gives is −M⁻¹ b, as solve_viscous_coulomb writes it.
        solve_viscous_coulomb(c.robot, c.frame, system);
        EXPECT_LT((c.frame.v_body + P * b).norm(), 1e-12 * (1.0 + (P * b).norm()));
      }
    }
  }
}

TEST(ViscousSystem, SolveFromTheSystemIsTheSolveToTheBit) {
  std::mt19937 rng(8);
  for (bool anisotropic : {false, true}) {
    for (int trial = 0; trial < 50; ++trial) {
      Case c = random_case(6, anisotropic, rng);
      contact::Frame g = c.frame;
      const ViscousSystem system(c.robot, c.frame);
      solve_viscous_coulomb(c.robot, c.frame, system);
      solve_viscous_coulomb(c.robot, g);
      EXPECT_EQ((c.frame.v_body - g.v_body).norm(), 0.0);
      EXPECT_EQ((c.frame.Fxy - g.Fxy).norm(), 0.0);
      EXPECT_EQ(c.frame.friction.residual, g.friction.residual);
      EXPECT_EQ(c.frame.friction.dissipation, g.friction.dissipation);
      EXPECT_EQ(c.frame.friction.unique, g.friction.unique);
    }
  }
}

// FeetSource::kSupportRows reads the rows of the support's last Newton route, so it must fall
// back to the frame's own where the support's last call took Alg. 1's path: the rows then still
// hold an earlier frame's feet.
TEST(ViscousSystem, ReadsTheSupportsRowsOnlyWhereItsNewtonRouteWroteTheFrame) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.8, 10.0);
  contact::Frame f(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * M_PI * k / 6.0;
    f.q.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1 + 0.01 * U(rng);
    f.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
  }
  contact::spring_support(robot, f);
  ASSERT_EQ(f.support.route, contact::SupportSummary::Route::kNewton);
  const ViscousSystem newton_rows(robot, f, FeetSource::kSupportRows);
  const ViscousSystem own(robot, f, FeetSource::kFrame);
  EXPECT_EQ((newton_rows.inverse() - own.inverse()).norm(), 0.0);

  // Another frame, supported by Alg. 1 only: the Newton rows are stale.
  f.q.row(0) *= 0.5;
  f.q.row(1) *= 1.5;
  contact::SupportOptions path_only;
  path_only.newton = false;
  contact::spring_support(robot, f, path_only);
  ASSERT_EQ(f.support.route, contact::SupportSummary::Route::kPath);
  contact::Frame g = f;
  const ViscousSystem after_path(robot, f, FeetSource::kSupportRows);
  const ViscousSystem by_frame(robot, g, FeetSource::kFrame);
  EXPECT_EQ((after_path.inverse() - by_frame.inverse()).norm(), 0.0);
  solve_viscous_coulomb(robot, f, after_path);
  solve_viscous_coulomb(robot, g, by_frame);
  EXPECT_EQ((f.v_body - g.v_body).norm(), 0.0);
  EXPECT_EQ((f.Fxy - g.Fxy).norm(), 0.0);
}

TEST(ViscousSystem, ContactsAtOnePointGiveThePseudoInverse) {
  // Two feet at the same point: M has rank 2 (the rotation about the point is free); M⁺ must
  // satisfy the Moore–Penrose conditions of the scaled system, which for D M̃⁺ D read
  // M P M = M and P M P = P, with P symmetric.
  std::mt19937 rng(9);
  Case c = random_case(3, true, rng);
  c.frame.q.col(2) = c.frame.q.col(1);
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  by_hand(c, M, b);
  const ViscousSystem system(c.robot, c.frame);
  const Eigen::Matrix3d P = system.inverse();
  EXPECT_LT((M * P * M - M).norm(), 1e-10 * M.norm());
  EXPECT_LT((P * M * P - P).norm(), 1e-10 * P.norm());
  EXPECT_LT((P - P.transpose()).norm(), 1e-12 * P.norm());
  solve_viscous_coulomb(c.robot, c.frame, system);
  EXPECT_FALSE(c.frame.friction.unique);
  EXPECT_TRUE(c.frame.v_body.allFinite());
}

// A definite system is solved in body coordinates (the lever scale L is then off the solve's
// serial path) and judged in the scaled ones: the answer is the scaled system's, to rounding, at
// every robot size. Oracle: M̃ = D M D and b̃ = D b by hand (D = diag(1, 1, 1/L)), solved by a
// pivoted LU and scaled back.
TEST(ViscousSystem, SolvesADefiniteSystemUnscaledToTheScaledSolvesRoundingAtEverySize) {
  std::mt19937 rng(43);
  for (bool anisotropic : {false, true}) {
    for (const double size : {1e-3, 1.0, 1e3}) {
      for (int trial = 0; trial < 20; ++trial) {
        Case c = random_case(6, anisotropic, rng);
        c.frame.q.topRows(2) *= size;
        c.frame.qdot.topRows(2) *= size;
        Eigen::Matrix3d M;
        Eigen::Vector3d b;
        by_hand(c, M, b);
        double L = 0.0;
        for (int k = 1; k < 6; ++k) {  // foot 0 is in the air
          L = std::max(L, c.frame.q.col(k).head<2>().norm());
        }
        const Eigen::DiagonalMatrix<double, 3> D(1.0, 1.0, 1.0 / L);
        const Eigen::Matrix3d Ms = D * M * D;
        const Eigen::Vector3d y = Ms.fullPivLu().solve(-(D * b));
        solve_viscous_coulomb(c.robot, c.frame);
        ASSERT_TRUE(c.frame.friction.unique);
        // Compared in the scaled coordinates, where every component is a velocity.
        const Eigen::Vector3d got = D.inverse() * c.frame.v_body;
        EXPECT_LE((got - y).norm(), 1e-13 * y.norm()) << size << " m";
        EXPECT_LT(
            (ViscousSystem(c.robot, c.frame).inverse() * M - Eigen::Matrix3d::Identity()).norm(),
            1e-10);
      }
    }
  }
}

// The rank test is the scaled system's (balance.hpp: contacts closer than ~1e-6 L are one point),
// whichever coordinates the system is then solved in: two feet 1e-4 L apart fix the rotation and
// two 1e-9 L apart do not, at every robot size.
TEST(ViscousSystem, JudgesTheRankInScaledCoordinatesAtEveryRobotSize) {
  for (const double size : {1e-3, 1.0, 1e3}) {
    for (const double apart : {1e-4, 1e-9}) {
      const contact::Robot robot = contact::uniform_robot(2, 100.0, 0.7, 9.81);
      contact::Frame f(robot);
      f.q.col(0) << 0.3 * size, 0.1 * size, -0.1;
      f.q.col(1) << 0.3 * size, (0.1 + 0.3 * apart) * size, -0.1;
      f.qdot.col(0) << 0.1 * size, -0.05 * size, 0.0;
      f.qdot.col(1) << 0.02 * size, 0.07 * size, 0.0;
      for (int k = 0; k < 2; ++k) {
        f.contact[static_cast<std::size_t>(k)] = 1;
        f.Fz(k) = 4.9;
      }
      solve_viscous_coulomb(robot, f);
      EXPECT_EQ(f.friction.unique, apart > 1e-6) << size << " m, " << apart << " L apart";
      EXPECT_TRUE(f.v_body.allFinite());
    }
  }
}

// The isotropic kernels (balance.cpp: the feet as rows, the forces four at a time) against the
// general loop: a robot whose only anisotropic foot is in the air takes the general loop, and its
// answer is the isotropic robot's, to rounding (the two sum in different orders).
TEST(ViscousSystem, TheIsotropicKernelsAgreeWithTheGeneralLoop) {
  std::mt19937 rng(41);
  for (const int n : {2, 3, 4, 5, 7, 8, 13, 50}) {
    Case iso = random_case(n, false, rng);
    Case general = iso;
    general.robot.w.col(0) << 0.5, -0.3;  // foot 0 is in the air (random_case)
    solve_viscous_coulomb(iso.robot, iso.frame);
    solve_viscous_coulomb(general.robot, general.frame);
    const double V = iso.frame.v_body.norm() + 1e-300;
    EXPECT_LE((iso.frame.v_body - general.frame.v_body).norm(), 1e-13 * V) << n << " legs";
    const double F = iso.frame.Fxy.cwiseAbs().maxCoeff() + 1e-300;
    EXPECT_LE((iso.frame.Fxy - general.frame.Fxy).cwiseAbs().maxCoeff(), 1e-13 * F) << n;
    EXPECT_NEAR(iso.frame.friction.dissipation, general.frame.friction.dissipation,
                1e-13 * std::abs(general.frame.friction.dissipation));
    EXPECT_LE(iso.frame.friction.residual, 1e-14) << n << " legs";
    EXPECT_EQ(iso.frame.friction.unique, general.frame.friction.unique);
    // Both balance: Σ F = 0 and Σ q × F = 0 to rounding (the forces' own check).
    double fx = 0.0, fy = 0.0, mz = 0.0, scale = 0.0;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d Fk = iso.frame.Fxy.col(k);
      fx += Fk(0);
      fy += Fk(1);
      mz += iso.frame.q(0, k) * Fk(1) - iso.frame.q(1, k) * Fk(0);
      scale += Fk.norm();
    }
    if (n >= 3) {
      EXPECT_LE(std::abs(fx) + std::abs(fy) + std::abs(mz), 1e-13 * scale) << n << " legs";
    }
  }
}

}  // namespace
}  // namespace slipwalk::friction
