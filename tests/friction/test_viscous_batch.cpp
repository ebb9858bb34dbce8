// The batched viscous-Coulomb balance and local connection (friction/viscous_batch.hpp) against
// the one-frame solve (solve_viscous_coulomb, connection::local_connection) on the same frames:
// the same velocity, forces, summary and A to rounding for every frame it solves, and the frames
// it must leave to the caller (no foot with friction, all contacts at one point, an anisotropic
// robot) untouched. Plus the balance itself, checked on the outputs: Σ F = 0 and Σ q × F = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "contact/support_batch.hpp"
#include "friction/solvers.hpp"
#include "friction/viscous_batch.hpp"
#include "support/count_allocations.hpp"

namespace slipwalk::friction {
namespace {

// A frame with its contacts and loads given (as the spring support leaves them): about a third of
// the feet in the air, loads of either sign (a negative F_z carries no friction).
contact::Frame random_frame(const contact::Robot& robot, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  contact::Frame f(robot);
  for (int k = 0; k < robot.legs(); ++k) {
    const double a = 2.0 * M_PI * k / robot.legs();
    f.q.col(k) << 0.3 * std::cos(a) + 0.05 * U(rng), 0.3 * std::sin(a) + 0.05 * U(rng), -0.1;
    f.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
    f.contact[static_cast<std::size_t>(k)] = U(rng) > -0.3 ? 1 : 0;
    f.Fz(k) = robot.Mg / robot.legs() * (1.0 + U(rng)) - (U(rng) > 0.95 ? robot.Mg : 0.0);
  }
  return f;
}

// The group's frames against the one-frame solve of copies; returns how many it solved.
int compare_group(const contact::Robot& robot, std::vector<contact::Frame>& frames,
                  contact::BatchScratch& scratch) {
  const std::vector<contact::Frame> before = frames;
  contact::Frame* lanes[4];
  const int m = static_cast<int>(frames.size());
  for (int i = 0; i < 4; ++i) {
    lanes[i] = &frames[static_cast<std::size_t>(i < m ? i : 0)];
  }
  const unsigned solved = solve_viscous_coulomb_group(robot, lanes, m, scratch);
  int count = 0;
  for (int i = 0; i < m; ++i) {
    const contact::Frame& f = frames[static_cast<std::size_t>(i)];
    contact::Frame g = before[static_cast<std::size_t>(i)];
    solve_viscous_coulomb(robot, g);
    connection::local_connection(robot, g);
    SCOPED_TRACE("frame " + std::to_string(i) + " of " + std::to_string(m));
    if ((solved >> static_cast<unsigned>(i) & 1U) == 0) {
      // Left to the caller: untouched, and a frame the one-frame solve gives no unique answer.
      const contact::Frame& b = before[static_cast<std::size_t>(i)];
      EXPECT_EQ((f.v_body - b.v_body).norm(), 0.0);
      EXPECT_EQ((f.Fxy - b.Fxy).norm(), 0.0);
      EXPECT_EQ((f.A - b.A).norm(), 0.0);
      EXPECT_TRUE(!g.friction.unique || !g.friction.message.empty() || robot.w.norm() > 0.0);
      continue;
    }
    ++count;
    EXPECT_TRUE(g.friction.unique);
    EXPECT_EQ(f.friction.converged, g.friction.converged);
    EXPECT_EQ(f.friction.unique, g.friction.unique);
    EXPECT_EQ(f.friction.message, g.friction.message);
    EXPECT_EQ(f.friction.iterations, 0);
    EXPECT_LE((f.v_body - g.v_body).norm(), 1e-12 * (g.v_body.norm() + 1e-6));
    EXPECT_LE((f.Fxy - g.Fxy).norm(), 1e-12 * (g.Fxy.norm() + 1e-6));
    EXPECT_LE((f.A - g.A).norm(), 1e-12 * g.A.norm());
    EXPECT_NEAR(f.friction.dissipation, g.friction.dissipation, 1e-12 * g.friction.dissipation);
    EXPECT_LE(f.friction.residual, 1e-13);
    // The balance on the outputs themselves: Σ F_k = 0 and Σ (q_k × F_k)_z = 0, relative to the
    // terms that cancel (the forces, and c_k q̇_k of which they are made).
    double fx = 0.0;
    double fy = 0.0;
    double mz = 0.0;
    double size = 0.0;
    for (int k = 0; k < robot.legs(); ++k) {
      fx += f.Fxy(0, k);
      fy += f.Fxy(1, k);
      mz += f.q(0, k) * f.Fxy(1, k) - f.q(1, k) * f.Fxy(0, k);
      const bool friction = f.contact[static_cast<std::size_t>(k)] != 0 && f.Fz(k) > 0.0;
      size += f.Fxy.col(k).norm() +
              (friction ? robot.mu(k) * f.Fz(k) * f.qdot.col(k).head<2>().norm() : 0.0);
    }
    EXPECT_LE(std::hypot(fx, fy), 1e-13 * size);
    EXPECT_LE(std::abs(mz), 1e-13 * 0.4 * size);
  }
  return count;
}

TEST(ViscousBatch, EveryFrameItSolvesIsTheOneFrameSolveToRounding) {
  std::mt19937 rng(11);
  int solved = 0;
  int frames = 0;
  for (const int n : {1, 2, 3, 5, 6, 8, 13, 24, 50}) {
    const contact::Robot robot = contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    contact::BatchScratch scratch(1);  // resized to the robot
    for (int trial = 0; trial < 60; ++trial) {
      std::vector<contact::Frame> group;
      const int m = 1 + trial % 4;
      for (int i = 0; i < m; ++i) {
        group.push_back(random_frame(robot, rng));
      }
      SCOPED_TRACE(std::to_string(n) + " legs, trial " + std::to_string(trial));
      const int count = compare_group(robot, group, scratch);
      if (n >= 3) {  // one or two legs: often one point in contact, the caller's case
        solved += count;
        frames += m;
      }
    }
  }
  EXPECT_GE(solved, frames * 9 / 10);
}

TEST(ViscousBatch, FramesWithoutAUniqueVelocityAreLeftToTheCaller) {
  std::mt19937 rng(13);
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.8, 10.0);
  std::vector<contact::Frame> group;
  for (int i = 0; i < 4; ++i) {
    group.push_back(random_frame(robot, rng));
    std::fill(group.back().contact.begin(), group.back().contact.end(), 1);
  }
  std::fill(group[1].contact.begin(), group[1].contact.end(), 0);  // nothing in contact
  group[2].q.row(0).setConstant(0.1);                              // all feet at one point
  group[2].q.row(1).setConstant(-0.2);
  group[3].Fz.setConstant(-1.0);  // pulled up: no friction anywhere
  contact::BatchScratch scratch(6);
  EXPECT_EQ(compare_group(robot, group, scratch), 1);
}

TEST(ViscousBatch, AnAnisotropicRobotIsLeftToTheOneFrameSolve) {
  std::mt19937 rng(17);
  contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.8, 10.0);
  robot.w(0, 3) = 0.4;
  std::vector<contact::Frame> group = {random_frame(robot, rng), random_frame(robot, rng)};
  contact::BatchScratch scratch(6);
  EXPECT_EQ(compare_group(robot, group, scratch), 0);
}

TEST(ViscousBatch, AllocatesNothingOnceTheScratchFits) {
#ifdef SLIPWALK_SANITIZED
  GTEST_SKIP() << "the sanitizers' runtime allocates on its own";
#endif
  std::mt19937 rng(19);
  const contact::Robot robot = contact::uniform_robot(6, 1000.0, 0.8, 10.0);
  std::vector<contact::Frame> group;
  for (int i = 0; i < 4; ++i) {
    group.push_back(random_frame(robot, rng));
  }
  contact::Frame* lanes[4] = {&group[0], &group[1], &group[2], &group[3]};
  contact::BatchScratch scratch(6);
  const long long before = slipwalk::testing::allocation_count();
  const unsigned solved = solve_viscous_coulomb_group(robot, lanes, 4, scratch);
  EXPECT_EQ(slipwalk::testing::allocation_count(), before);
  EXPECT_NE(solved, 0U);
}

}  // namespace
}  // namespace slipwalk::friction
