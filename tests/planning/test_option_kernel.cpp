// The planner's fast inner loop (planning/fast_kernel.hpp) against the reference loop
// (integrate_option_reference: contact::spring_support and friction::solve_viscous_coulomb per
// substep): the same feasibility and end poses to rounding over random nodes and options,
// including nodes whose support needs the reference's path search (few legs down, legs on a
// line) and anisotropic robots; no allocation per planning step; the same plan on 1, 2, 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "planning/fast_kernel.hpp"
#include "planning/option_kernel.hpp"
#include "planning/planner.hpp"
#include "support/count_allocations.hpp"

namespace slipwalk::planning {
namespace {

struct Comparison {
  int options = 0;
  int feasible = 0;
  int disagree = 0;    // feasibility differs
  double worst = 0.0;  // largest relative end-pose difference
};

/// Integrates `count` random options of the node at `phi` both ways from a random pose.
void compare_node(const PlanRobot& robot, const PlanOptions& options, const Eigen::VectorXd& phi,
                  int count, std::mt19937& rng, Comparison& out) {
  NodeTable table;
  size_node(robot, options, table);
  contact::Frame frame(robot.robot);
  build_node(robot, options, phi, table, frame);
  std::uniform_int_distribution<int> digit(0, table.columns - 2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<int, kMaxPlanLegs> digits{};
  std::array<int, kMaxPlanLegs> columns{};
  for (int o = 0; o < count; ++o) {
    for (int i = 0; i < robot.legs(); ++i) {
      digits[static_cast<std::size_t>(i)] = digit(rng);
    }
    option_columns(table, digits.data(), columns.data());
    const core::Pose2 start{0.5 * u(rng), 0.5 * u(rng), 4.0 * u(rng)};
    core::Pose2 fast = start;
    core::Pose2 ref = start;
    const bool ok_fast =
        integrate_option(robot, options, table, columns.data(), table.substeps, fast, frame);
    const bool ok_ref = integrate_option_reference(robot, options, table, columns.data(),
                                                   table.substeps, ref, frame);
    ++out.options;
    if (ok_fast != ok_ref) {
      ++out.disagree;
      continue;
    }
    if (!ok_ref) {
      continue;
    }
    ++out.feasible;
    // Relative to the end pose (its coordinates carry the rounding of every substep's update).
    const double size = std::abs(ref.x) + std::abs(ref.y) + std::abs(ref.theta);
    const double diff =
        std::abs(fast.x - ref.x) + std::abs(fast.y - ref.y) + std::abs(fast.theta - ref.theta);
    out.worst = std::max(out.worst, diff / size);
  }
}

Eigen::VectorXd random_phi(int legs, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd phi(legs);
  for (int i = 0; i < legs; ++i) {
    phi(i) = u(rng);
  }
  return phi;
}

TEST(OptionKernel, FastAndReferenceAgreeToRoundingOnRandomNodesOfEveryRobotSize) {
  std::mt19937 rng(7);
  for (const int legs : {6, 8, 10, 12}) {
    const PlanRobot robot = bigant_plan_robot(legs);
    PlanOptions options;
    options.contact = ContactRule::kAll;  // every leg's speed varies: the most distinct motions
    Comparison c;
    for (int node = 0; node < 40; ++node) {
      compare_node(robot, options, random_phi(legs, rng), 20, rng, c);
    }
    EXPECT_EQ(c.disagree, 0) << legs << " legs";
    EXPECT_GT(c.feasible, c.options / 4) << legs << " legs";
    EXPECT_LE(c.worst, 1e-12) << legs << " legs";
    std::printf("%d legs: %d options, %d feasible, worst relative difference %.2e\n", legs,
                c.options, c.feasible, c.worst);
  }
}

/// A test robot: foot i at (x_i + 0.03 sin 2πφ, y_i), height −0.1 + 0.02 (1 − cos 2πφ) below the
/// body (φ = 0 lowest); K = 1000 N/m, μ = 0.8, Mg = 50 N.
PlanRobot foot_robot(const std::vector<Eigen::Vector2d>& feet) {
  PlanRobot r;
  const int n = static_cast<int>(feet.size());
  r.name = "test";
  r.robot = contact::uniform_robot(n, 1000.0, 0.8, 50.0);
  r.leg_names.assign(static_cast<std::size_t>(n), std::string("leg"));
  r.toe = [feet](int leg, double phi, Eigen::Ref<Eigen::Vector3d> q,
                 Eigen::Ref<Eigen::Vector3d> dq) {
    const double a = 2.0 * std::numbers::pi * phi;
    const Eigen::Vector2d& p = feet[static_cast<std::size_t>(leg)];
    q << p.x() + 0.03 * std::sin(a), p.y(), -0.1 + 0.02 * (1.0 - std::cos(a));
    dq << 0.03 * 2.0 * std::numbers::pi * std::cos(a), 0.0,
        0.02 * 2.0 * std::numbers::pi * std::sin(a);
  };
  return r;
}

/// Random options through the fast route, four to a batch, with its counts.
detail::FastCounts count_routes(const PlanRobot& robot, const PlanOptions& options, int nodes,
                                std::mt19937& rng) {
  detail::FastCounts counts;
  NodeTable table;
  size_node(robot, options, table);
  contact::Frame frame(robot.robot);
  std::array<int, kMaxPlanLegs> digits{};
  std::uniform_int_distribution<int> digit(0, static_cast<int>(options.speeds.size()) - 1);
  for (int node = 0; node < nodes; ++node) {
    build_node(robot, options, random_phi(robot.legs(), rng), table, frame);
    for (int o = 0; o < 4; ++o) {
      std::array<std::array<int, kMaxPlanLegs>, detail::kBatch> batch{};
      std::array<const int*, detail::kBatch> pointers{};
      std::array<core::Pose2, detail::kBatch> poses{};
      std::array<bool, detail::kBatch> ok{};
      for (int l = 0; l < detail::kBatch; ++l) {
        for (int i = 0; i < robot.legs(); ++i) {
          digits[static_cast<std::size_t>(i)] = digit(rng);
        }
        option_columns(table, digits.data(), batch[static_cast<std::size_t>(l)].data());
        pointers[static_cast<std::size_t>(l)] = batch[static_cast<std::size_t>(l)].data();
      }
      detail::integrate_batch(robot, options, table, pointers.data(), detail::kBatch,
                              table.substeps, poses.data(), ok.data(), frame, &counts);
    }
  }
  return counts;
}

TEST(OptionKernel, FastAndReferenceAgreeWhereTheSupportNeedsItsPathSearch) {
  // Feet on a line (the support balances on it, status "line": the Newton route cannot certify,
  // the path search decides), a square (contacts come and go), and feet all ahead of the centre
  // of mass (the robot tips: every option infeasible).
  PlanOptions options;
  options.contact = ContactRule::kAll;
  std::mt19937 rng(11);
  const PlanRobot line = foot_robot({{-0.3, 0.0}, {-0.1, 0.0}, {0.1, 0.0}, {0.3, 0.0}});
  const PlanRobot square = foot_robot({{-0.3, -0.2}, {0.3, -0.2}, {0.3, 0.2}, {-0.3, 0.2}});
  const PlanRobot ahead = foot_robot({{0.2, -0.2}, {0.4, -0.2}, {0.4, 0.2}, {0.2, 0.2}});
  const PlanRobot bigant = bigant_plan_robot(6);
  for (const PlanRobot* robot : {&line, &square, &ahead, &bigant}) {
    Comparison c;
    for (int node = 0; node < 20; ++node) {
      compare_node(*robot, options, random_phi(robot->legs(), rng), 16, rng, c);
    }
    EXPECT_EQ(c.disagree, 0);
    EXPECT_LE(c.worst, 1e-12);
    const detail::FastCounts counts = count_routes(*robot, options, 20, rng);
    std::printf(
        "%d options, %d feasible, worst relative difference %.2e; %lld substeps, %lld by the "
        "scalar route, %lld support and %lld friction fallbacks\n",
        c.options, c.feasible, c.worst, counts.substeps, counts.scalar, counts.support_fallbacks,
        counts.friction_fallbacks);
    if (robot == &line) {
      EXPECT_EQ(c.feasible, c.options);
      // Every substep but the first (the node's own support, which the reference solved).
      const long long later = counts.substeps - counts.substeps / options.substeps;
      EXPECT_GE(counts.support_fallbacks, later);
    } else if (robot == &ahead) {
      EXPECT_EQ(c.feasible, 0);
    } else {
      EXPECT_EQ(c.feasible, c.options);
      EXPECT_LT(counts.support_fallbacks, counts.substeps / 10);
      EXPECT_LT(counts.scalar, counts.substeps / 4);
    }
  }
}

TEST(OptionKernel, AnOptionsResultDoesNotDependOnTheOptionsBesideItInItsBatch) {
  // Each option alone (integrate_option: a batch of one) and in batches of 1 … 4 with random
  // neighbours, every lane position: the same bits. The scalar route, a second implementation of
  // the same substeps, agrees to rounding.
  std::mt19937 rng(5);
  for (const int legs : {6, 10}) {
    const PlanRobot robot = bigant_plan_robot(legs);
    PlanOptions options;
    options.contact = ContactRule::kAll;
    NodeTable table;
    size_node(robot, options, table);
    contact::Frame frame(robot.robot);
    std::uniform_int_distribution<int> digit(0, table.columns - 2);
    std::uniform_int_distribution<int> how_many(1, detail::kBatch);
    double worst = 0.0;
    int compared = 0;
    for (int node = 0; node < 10; ++node) {
      build_node(robot, options, random_phi(legs, rng), table, frame);
      for (int trial = 0; trial < 20; ++trial) {
        const int count = how_many(rng);
        std::array<std::array<int, kMaxPlanLegs>, detail::kBatch> columns{};
        std::array<const int*, detail::kBatch> pointers{};
        std::array<core::Pose2, detail::kBatch> poses{};
        std::array<bool, detail::kBatch> ok{};
        for (int l = 0; l < count; ++l) {
          std::array<int, kMaxPlanLegs> digits{};
          for (int i = 0; i < legs; ++i) {
            digits[static_cast<std::size_t>(i)] = digit(rng);
          }
          option_columns(table, digits.data(), columns[static_cast<std::size_t>(l)].data());
          pointers[static_cast<std::size_t>(l)] = columns[static_cast<std::size_t>(l)].data();
          poses[static_cast<std::size_t>(l)] = {0.1 * l, -0.2, 0.3 * l};
        }
        const std::array<core::Pose2, detail::kBatch> start = poses;
        integrate_options(robot, options, table, pointers.data(), count, table.substeps,
                          poses.data(), ok.data(), frame);
        for (int l = 0; l < count; ++l) {
          const auto u = static_cast<std::size_t>(l);
          core::Pose2 alone = start[u];
          const bool ok_alone = integrate_option(robot, options, table, columns[u].data(),
                                                 table.substeps, alone, frame);
          EXPECT_EQ(ok[u], ok_alone);
          EXPECT_EQ(poses[u].x, alone.x);
          EXPECT_EQ(poses[u].y, alone.y);
          EXPECT_EQ(poses[u].theta, alone.theta);
          core::Pose2 scalar = start[u];
          const bool ok_scalar = detail::integrate_option_scalar(
              robot, options, table, columns[u].data(), table.substeps, scalar, frame);
          EXPECT_EQ(ok_scalar, ok_alone);
          const double size = std::abs(alone.x) + std::abs(alone.y) + std::abs(alone.theta);
          worst = std::max(worst, (std::abs(scalar.x - alone.x) + std::abs(scalar.y - alone.y) +
                                   std::abs(scalar.theta - alone.theta)) /
                                      size);
          ++compared;
        }
      }
    }
    EXPECT_LE(worst, 1e-12) << legs << " legs, " << compared << " options";
  }
}

TEST(OptionKernel, AnAnisotropicRobotTakesTheReferenceAndAgreesExactly) {
  PlanRobot robot = bigant_plan_robot(6);
  for (int i = 0; i < robot.legs(); ++i) {
    robot.robot.w.col(i) = Eigen::Vector2d(0.3, -0.1 * i);
  }
  PlanOptions options;
  std::mt19937 rng(3);
  Comparison c;
  for (int node = 0; node < 10; ++node) {
    compare_node(robot, options, random_phi(6, rng), 16, rng, c);
  }
  EXPECT_EQ(c.disagree, 0);
  EXPECT_EQ(c.worst, 0.0);
}

TEST(OptionKernel, APlanningStepAllocatesNothingOnceItsBuffersAreSized) {
#ifdef SLIPWALK_SANITIZED
  GTEST_SKIP() << "the sanitizers' runtime allocates on its own";
#endif
  const PlanRobot robot = bigant_plan_robot(6);
  for (const bool dedup : {true, false}) {
    PlanOptions options;
    options.deduplicate = dedup;
    options.threads = 2;
    Goal goal;
    goal.twist = {0.2, 0.0, 0.0};
    PlanData data(robot, options);
    PlanState state = tripod_start(robot);
    StepChoice choice;
    plan_step(robot, options, goal, state, data, choice);  // sizes the choice's vectors
    execute(robot, options, choice, state, data);
    const long long before = testing::allocation_count();
    for (int step = 0; step < 5; ++step) {
      plan_step(robot, options, goal, state, data, choice);
      execute(robot, options, choice, state, data);
    }
    EXPECT_EQ(testing::allocation_count() - before, 0) << "deduplicate " << dedup;
  }
}

TEST(OptionKernel, ThePlanIsTheSameOnOneTwoAndThreeThreads) {
  const PlanRobot robot = bigant_plan_robot(6);
  Goal goal;
  goal.twist = {0.15, 0.0, 0.4};
  std::vector<std::vector<double>> runs;
  for (const int threads : {1, 2, 3}) {
    PlanOptions options;
    options.steps = 30;
    options.threads = threads;
    std::vector<double> rows;
    plan(robot, options, goal, tripod_start(robot), [&](const StepRecord& r) {
      rows.insert(rows.end(), {static_cast<double>(r.choice.option), r.choice.cost, r.state.pose.x,
                               r.state.pose.y, r.state.pose.theta});
    });
    runs.push_back(rows);
  }
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_EQ(runs[0], runs[2]);
}

}  // namespace
}  // namespace slipwalk::planning
