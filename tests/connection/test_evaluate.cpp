// connection::evaluate, the whole frame: spring support, then the friction balance and A. Checked
// against the stages run by hand and against the physics of a symmetric robot.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "support/count_allocations.hpp"

namespace slipwalk::connection {
namespace {

contact::Frame hexapod_frame(const contact::Robot& robot, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  contact::Frame f(robot);
  for (int k = 0; k < robot.legs(); ++k) {
    const double a = 2.0 * M_PI * k / robot.legs();
    f.q.col(k) << 0.3 * std::cos(a) + 0.03 * U(rng), 0.3 * std::sin(a) + 0.03 * U(rng),
        -0.1 + 0.01 * U(rng);
    f.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
  }
  return f;
}

TEST(ConnectionEvaluate, IsSpringSupportThenTheFrictionLaw) {
  // evaluate() factorizes the viscous system once for A and the viscous-Coulomb balance; the
  // stages run by hand assemble it twice. Same bits either way, isotropic and anisotropic.
  std::mt19937 rng(1);
  contact::Robot anisotropic = contact::uniform_robot(6, 100.0, 0.8, 9.81);
  for (int k = 0; k < 6; ++k) {
    anisotropic.w.col(k) << 0.5 * std::cos(k), 0.3 * std::sin(k);
  }
  const std::vector<contact::Robot> robots = {contact::uniform_robot(6, 100.0, 0.8, 9.81),
                                              anisotropic};
  for (const contact::Robot& robot : robots) {
    for (int trial = 0; trial < 50; ++trial) {
      contact::Frame f = hexapod_frame(robot, rng);
      contact::Frame g = f;
      for (FrictionLaw law : {FrictionLaw::kViscousCoulomb, FrictionLaw::kCoulomb}) {
        evaluate(robot, f, law);
        contact::spring_support(robot, g);
        EXPECT_EQ(f.contact, g.contact);
        EXPECT_EQ((f.Fz - g.Fz).norm(), 0.0);
        if (law == FrictionLaw::kViscousCoulomb) {
          friction::solve_viscous_coulomb(robot, g);
        } else {
          friction::solve_coulomb(robot, g);
        }
        EXPECT_EQ((f.v_body - g.v_body).norm(), 0.0);
        EXPECT_EQ((f.Fxy - g.Fxy).norm(), 0.0);
        EXPECT_EQ(f.friction.dissipation, g.friction.dissipation);
        EXPECT_EQ(f.friction.residual, g.friction.residual);
        EXPECT_EQ(f.friction.unique, g.friction.unique);
        EXPECT_TRUE(f.friction.converged);
        EXPECT_LE(f.friction.residual, 1e-10);
        local_connection(robot, g);
        EXPECT_EQ((f.A - g.A).norm(), 0.0);
        for (int k = 0; k < robot.legs(); ++k) {
          if (f.contact[static_cast<std::size_t>(k)] == 0) {
            EXPECT_EQ(f.A.middleCols<2>(2 * static_cast<Eigen::Index>(k)).norm(), 0.0);
            EXPECT_EQ(f.Fxy.col(k).norm(), 0.0);
          }
        }
      }
    }
  }
}

TEST(ConnectionEvaluate, ReadsTheSupportsRowsToTheSameBitsAtEveryLegCount) {
  // evaluate() assembles the viscous system from the padded rows the support's Newton route left
  // (friction::FeetSource::kSupportRows); the stages by hand read the frame's q, contact and F_z.
  // Every count of legs modulo four (a full last group of four, or one, two, three feet in it),
  // feet lifted at random so that the contact flags vary within a group.
  std::mt19937 rng(3);
  std::bernoulli_distribution lifted(0.3);
  for (const int n : {3, 4, 5, 6, 7, 8, 13, 50}) {
    const contact::Robot robot = contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    int newton = 0;
    for (int trial = 0; trial < 40; ++trial) {
      contact::Frame f = hexapod_frame(robot, rng);
      for (int k = 0; k < n; ++k) {
        f.q(2, k) += lifted(rng) ? 0.2 : 0.0;
      }
      contact::Frame g = f;
      evaluate(robot, f, FrictionLaw::kViscousCoulomb);
      contact::spring_support(robot, g);
      newton += g.support.route == contact::SupportSummary::Route::kNewton ? 1 : 0;
      friction::solve_viscous_coulomb(robot, g);
      local_connection(robot, g);
      EXPECT_EQ(f.contact, g.contact) << n << " legs";
      EXPECT_EQ((f.v_body - g.v_body).norm(), 0.0) << n << " legs";
      EXPECT_EQ((f.Fxy - g.Fxy).norm(), 0.0) << n << " legs";
      EXPECT_EQ((f.A - g.A).norm(), 0.0) << n << " legs";
      EXPECT_EQ(f.friction.residual, g.friction.residual) << n << " legs";
    }
    EXPECT_GT(newton, 20) << n << " legs: the rows are read only where the Newton route certified";
  }
}

TEST(ConnectionEvaluate, SymmetricRobotPushingBackwardsMovesForward) {
  // Six legs on a circle, all on the ground with equal loads, all sweeping backwards at 0.1 m/s:
  // every law gives v = (0.1, 0, 0).
  const contact::Robot robot = contact::uniform_robot(6);
  contact::Frame f(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * M_PI * k / 6.0;
    f.q.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1;
    f.qdot.col(k) << -0.1, 0.0, 0.0;
  }
  for (FrictionLaw law : {FrictionLaw::kViscousCoulomb, FrictionLaw::kCoulomb}) {
    evaluate(robot, f, law);
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(f.contact[static_cast<std::size_t>(k)], 1);
    }
    EXPECT_NEAR(f.v_body(0), 0.1, 1e-14);
    EXPECT_NEAR(f.v_body(1), 0.0, 1e-14);
    EXPECT_NEAR(f.v_body(2), 0.0, 1e-13);
  }
}

// No allocation per frame (the model's contract, contact/robot.hpp): once a Frame exists, every
// evaluation of any odd or even count of legs, with feet lifting and landing between frames, runs
// on the frame's own scratch — the support's rows, the viscous rows, the Coulomb rows.
TEST(ConnectionEvaluate, ABatchIsFrameByFrameToRounding) {
  // evaluate_batch: the spring support four frames at a time (contact::spring_support_batch, its
  // own tests), then each frame's connection and balance. Against evaluate() frame by frame: the
  // same contact sets and statuses, every output to rounding; batches of every length mod 4, both
  // laws, robots below and above the level start's 20 legs.
  std::mt19937 rng(5);
  std::bernoulli_distribution lifted(0.3);
  for (const int n : {3, 5, 6, 8, 13, 24}) {
    const contact::Robot robot = contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    contact::BatchScratch scratch(n);
    for (const int count : {1, 2, 3, 4, 7, 41}) {
      std::vector<contact::Frame> frames;
      for (int i = 0; i < count; ++i) {
        frames.push_back(hexapod_frame(robot, rng));
        for (int k = 0; k < n; ++k) {
          frames.back().q(2, k) += lifted(rng) ? 0.2 : 0.0;
        }
      }
      for (FrictionLaw law : {FrictionLaw::kViscousCoulomb, FrictionLaw::kCoulomb}) {
        std::vector<contact::Frame> batched = frames;
        evaluate_batch(robot, batched, law, scratch);
        for (int i = 0; i < count; ++i) {
          contact::Frame& g = frames[static_cast<std::size_t>(i)];
          evaluate(robot, g, law);
          const contact::Frame& f = batched[static_cast<std::size_t>(i)];
          SCOPED_TRACE(std::to_string(n) + " legs, frame " + std::to_string(i) + " of " +
                       std::to_string(count));
          EXPECT_EQ(f.support.status, g.support.status);
          EXPECT_EQ(f.contact, g.contact);
          EXPECT_EQ(f.friction.converged, g.friction.converged);
          EXPECT_EQ(f.friction.unique, g.friction.unique);
          EXPECT_LE((f.Fz - g.Fz).norm(), 1e-12 * robot.Mg);
          EXPECT_LE((f.v_body - g.v_body).norm(), 1e-11 * (g.v_body.norm() + 1e-3));
          EXPECT_LE((f.Fxy - g.Fxy).norm(), 1e-11 * (g.Fxy.norm() + 1e-3));
          EXPECT_LE((f.A - g.A).norm(), 1e-11 * g.A.norm());
        }
      }
    }
  }
}

TEST(ConnectionEvaluate, EvaluatesFrameAfterFrameWithoutAllocating) {
#ifdef SLIPWALK_SANITIZED
  GTEST_SKIP() << "the sanitizers' runtime allocates on its own";
#endif
  std::mt19937 rng(31);
  for (const int n : {3, 5, 6, 8, 13, 50}) {
    const contact::Robot robot = contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    std::vector<contact::Frame> inputs;
    inputs.reserve(200);
    for (int frame = 0; frame < 200; ++frame) {
      inputs.push_back(hexapod_frame(robot, rng));
    }
    contact::Frame f = inputs.front();
    evaluate(robot, f, FrictionLaw::kViscousCoulomb);  // a first call may size messages
    evaluate(robot, f, FrictionLaw::kCoulomb);
    long long balanced = 0;
    const long long before = slipwalk::testing::allocation_count();
    for (std::size_t frame = 0; frame < inputs.size(); ++frame) {
      f.q = inputs[frame].q;  // same sizes: Eigen assigns in place
      f.qdot = inputs[frame].qdot;
      evaluate(robot, f, frame % 2 == 0 ? FrictionLaw::kViscousCoulomb : FrictionLaw::kCoulomb);
      balanced += f.support.status == contact::SupportSummary::Status::kBalanced ? 1 : 0;
    }
    EXPECT_EQ(slipwalk::testing::allocation_count(), before) << n << " legs";
    EXPECT_GT(balanced, 100) << n << " legs";
  }
}

}  // namespace
}  // namespace slipwalk::connection
