// The Newton route of the spring support (contact/support_newton.cpp) against Alg. 1's path
// (SupportOptions::newton = false) and the convex-potential oracle: where it certifies it must
// end at the path's state (the unique minimizer of U), and where it does not the caller's
// result is the path's own. Degenerate supports (one or two contacts, rows, tipping, exact ties)
// must hand over, never certify a wrong state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "support/count_allocations.hpp"
#include "support/support_scenes.hpp"

namespace {

using namespace slipwalk::testing::support_scenes;  // NOLINT(google-build-using-namespace)
using Status = slipwalk::contact::SupportSummary::Status;
using Route = slipwalk::contact::SupportSummary::Route;

// The two routes' outputs agree: the same state to `rel` of the height scale, the same loads,
// the same contacts wherever a foot is clearly off its plane.
void expect_same_state(const Scene& s, const Frame& a, const Frame& b, double rel) {
  const double Z = height_scale(s, b);
  const double L = size_of(s);
  EXPECT_NEAR(a.z, b.z, rel * Z);
  EXPECT_NEAR(L * a.alpha, L * b.alpha, rel * Z);
  EXPECT_NEAR(L * a.beta, L * b.beta, rel * Z);
  for (int j = 0; j < s.legs(); ++j) {
    EXPECT_NEAR(a.Fz(j), b.Fz(j), rel * s.K(j) * Z + 1e-13 * s.Mg) << "leg " << j;
    const double h = slipwalk::contact::foot_height(b, j, b.alpha, b.beta, b.z);
    if (std::abs(h) > 1e-9 * Z) {
      EXPECT_EQ(a.contact[j], b.contact[j]) << "leg " << j << " h " << h;
    }
  }
}

// Solves with both routes; when the Newton route certified, checks it against the path.
// Returns whether it certified.
bool compare_routes(const Scene& s, double rel = 1e-11) {
  const Solved fast = solve(s);
  const Solved path = solve(s, false, false);
  EXPECT_EQ(path.frame.support.route, Route::kPath);
  if (fast.frame.support.route != Route::kNewton) {
    // Handed over: the result is the path's, bit for bit.
    EXPECT_EQ(fast.frame.support.status, path.frame.support.status);
    EXPECT_EQ(fast.frame.z, path.frame.z);
    EXPECT_EQ(fast.frame.alpha, path.frame.alpha);
    EXPECT_EQ(fast.frame.beta, path.frame.beta);
    EXPECT_EQ(fast.frame.contact, path.frame.contact);
    return false;
  }
  EXPECT_EQ(fast.frame.support.status, Status::kBalanced);
  EXPECT_EQ(path.frame.support.status, Status::kBalanced) << path.frame.support.message;
  EXPECT_GE(fast.frame.support.newton_steps, 1);
  EXPECT_LE(fast.frame.support.residual, 1e-10 + 100.0 * rounding_floor(s, fast.frame));
  const Balance b = balance(s, fast.frame);
  EXPECT_LE(b.force, 1e-10 + 100.0 * rounding_floor(s, fast.frame));
  EXPECT_LE(b.moment, 1e-10 + 100.0 * rounding_floor(s, fast.frame));
  expect_same_state(s, fast.frame, path.frame, rel);
  return true;
}

TEST(SupportNewton, RandomRobotsEndWhereThePathEnds) {
  std::mt19937_64 rng(101);
  int certified = 0;
  const int trials = 2000;
  for (int trial = 0; trial < trials; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 58);
    const Scene s = random_supported(rng, n);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " legs");
    certified += compare_routes(s) ? 1 : 0;
  }
  std::printf("Newton route certified %d of %d random robots\n", certified, trials);
  // The route is the default because it certifies almost every supported frame (if it stopped
  // certifying, everything would still be right but slow: this catches that).
  EXPECT_GE(certified, trials * 9 / 10);
}

TEST(SupportNewton, StiffnessesOverSixDecadesAndManyLegsMatchTheOracle) {
  std::mt19937_64 rng(103);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = trial < 50 ? 3 + static_cast<int>(rng() % 20) : 50 + 20 * (trial - 50);
    const Scene s = random_supported(rng, n, trial < 50 ? 6.0 : 2.0);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " legs");
    compare_routes(s, 1e-9);
    const Solved fast = solve(s);
    ASSERT_EQ(fast.frame.support.status, Status::kBalanced);
    expect_matches_oracle(s, fast.frame, "Newton route");
  }
}

TEST(SupportNewton, FlatHexapodNeedsNoContactChanges) {
  const Scene s = flat_hexapod();
  const Solved r = solve(s);
  EXPECT_EQ(r.frame.support.route, Route::kNewton);
  EXPECT_LE(r.frame.support.newton_steps, 2);  // the step, and a refinement if rounding needs it
  EXPECT_EQ(r.frame.support.iterations, 0);
  EXPECT_NEAR(r.frame.z, 0.12 - 30.0 / 12000.0, 1e-15);
}

// Supports the route must not certify: one foot, two feet, feet in a row, the CoM outside, a
// foot under the CoM alone, two feet on a diagonal with the others exactly lifted by the tilt
// range (a see-saw). The default call must return the path's status and state.
TEST(SupportNewton, DegenerateSupportsHandOverToThePath) {
  const std::vector<Scene> scenes = {
      from_feet({{0.0, 0.0, -0.2}}, {500.0}, 10.0),
      from_feet({{0.1, 0.05, -0.2}}, {500.0}, 10.0),
      from_feet({{-0.2, 0.1, -0.1}, {0.4, -0.2, -0.13}}, {300.0, 4000.0}, 12.0),
      from_feet({{0.1, 0.05, -0.2}, {0.1, -0.05, -0.21}}, {500.0, 90.0}, 10.0),
      from_feet({{-0.3, 0.0, -0.1},
                 {0.1, 0.0, -0.1},
                 {0.4, 0.0, -0.102},
                 {0.0, 0.3, -0.05},
                 {0.05, -0.3, -0.05}},
                {1000.0}, 10.0),
      from_feet({{0.3, 0.1, -0.1}, {0.0, 0.0, -0.2}, {-0.2, 0.2, -0.1}}, {500.0}, 10.0),
      from_feet({{1.0, 1.0, -5.0}, {-1.0, 1.0, -10.0}, {-1.0, -1.0, -10.0}, {1.0, -1.0, -10.0}},
                {1.0}, 4.0),
  };
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    SCOPED_TRACE("scene " + std::to_string(i));
    const Solved fast = solve(scenes[i]);
    EXPECT_EQ(fast.frame.support.route, Route::kPath);
    compare_routes(scenes[i]);
  }
}

// Exact ties: a coarse grid of feet (rows, duplicates, feet under the CoM, all at one height),
// stiffnesses over six decades, and feet moved to touch the balance plane exactly.
TEST(SupportNewton, TiesAndGridsAgreeWithThePath) {
  std::mt19937_64 rng(107);
  int certified = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 12);
    Scene s;
    s.q.resize(3, n);
    s.K.resize(n);
    s.Mg = std::pow(10.0, uniform(rng, -2.0, 3.0));
    const int kind = static_cast<int>(rng() % 3);
    for (int j = 0; j < n; ++j) {
      s.K(j) = kind == 2 ? 1.0 : std::pow(10.0, uniform(rng, -1.0, 5.0));
      s.q(0, j) = 0.25 * static_cast<double>(static_cast<int>(rng() % 7) - 3);
      s.q(1, j) = 0.25 * static_cast<double>(static_cast<int>(rng() % 7) - 3);
      s.q(2, j) = kind == 0 ? -0.5 : -0.125 * static_cast<double>(rng() % 4);
    }
    SCOPED_TRACE("trial " + std::to_string(trial) + " kind " + std::to_string(kind));
    certified += compare_routes(s, 1e-9) ? 1 : 0;
  }
  std::printf("Newton route certified %d of 3000 grid robots\n", certified);
  std::mt19937_64 rng2(109);
  for (int trial = 0; trial < 300; ++trial) {
    Scene t = random_supported(rng2, 4 + static_cast<int>(rng2() % 30));
    const Solved first = solve(t, false, false);
    for (int j = 0; j < t.legs(); ++j) {
      const Frame& g = first.frame;
      if (g.contact[j] == 0) {  // lower every foot in the air onto the balance plane
        t.q(2, j) -= slipwalk::contact::foot_height(g, j, g.alpha, g.beta, g.z);
      }
    }
    SCOPED_TRACE("touching trial " + std::to_string(trial));
    compare_routes(t, 1e-9);
  }
}

TEST(SupportNewton, DiskRobotsOfTheBenchmarkCertifyWithoutAllocating) {
  std::mt19937_64 rng(113);
  for (const int n : {3, 6, 12, 24, 50, 200}) {
    Robot robot = slipwalk::contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    Frame f(robot);
    int certified = 0;
    for (int trial = 0; trial < 200; ++trial) {
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * kPi * k / n;
        f.q.col(k) << 0.3 * std::cos(a) + 0.05 * uniform(rng, -1.0, 1.0),
            0.3 * std::sin(a) + 0.05 * uniform(rng, -1.0, 1.0), -0.1 + 0.01 * uniform(rng, -1, 1);
      }
      const long long before = slipwalk::testing::allocation_count();
      slipwalk::contact::spring_support(robot, f);
      const long long allocations = slipwalk::testing::allocation_count() - before;
      if (f.support.route == Route::kNewton) {
        ++certified;
        EXPECT_EQ(allocations, 0);
      }
      EXPECT_LE(f.support.newton_steps, 12);
    }
    // Frames where a Newton step leaves fewer than three feet down tilt onto the next foot as
    // Alg. 1 would (support_newton.cpp, tilt_step), so every one of these certifies.
    EXPECT_EQ(certified, 200) << n << " legs";
  }
}

// The level start (support_newton.cpp, from 20 legs) on the benchmark's disks: the feet below a
// height just under the level balance already hold the cell the answer stands on, bar the tilt, so
// the steps per frame stay flat in N. The all-feet start halves its cell per step (3.2 steps at 12
// legs, 4.0 at 24, 4.7 at 50); a mean above 3 here means the start no longer reaches the answer's
// cell. Below 20 legs the all-feet start runs: fewer instructions there, but more time.
TEST(SupportNewton, TheLevelStartKeepsTheStepsFlatInTheLegs) {
  std::mt19937_64 rng(117);
  for (const int n : {20, 24, 50, 200}) {
    Robot robot = slipwalk::contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    Frame f(robot);
    int steps = 0;
    const int trials = 400;
    for (int trial = 0; trial < trials; ++trial) {
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * kPi * k / n;
        f.q.col(k) << 0.3 * std::cos(a) + 0.05 * uniform(rng, -1.0, 1.0),
            0.3 * std::sin(a) + 0.05 * uniform(rng, -1.0, 1.0), -0.1 + 0.01 * uniform(rng, -1, 1);
      }
      slipwalk::contact::spring_support(robot, f);
      ASSERT_EQ(f.support.route, Route::kNewton) << n << " legs, trial " << trial;
      steps += f.support.newton_steps;
    }
    const double mean = static_cast<double>(steps) / trials;
    std::printf("%d legs: %.2f Newton steps per frame\n", n, mean);
    EXPECT_LE(mean, 3.0) << n << " legs";
  }
}

// Frames whose first Newton step (from the all-feet plane) leaves two feet or one down: the route
// tilts onto the next foot (eqs. 3.11, 3.12) and must still end where the path ends, certified.
TEST(SupportNewton, OvershootsTiltOntoTheNextFootAndEndWhereThePathEnds) {
  std::mt19937_64 rng(127);
  int tilted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 4 + static_cast<int>(rng() % 5);
    Scene s;
    s.q.resize(3, n);
    s.K = Eigen::VectorXd::Constant(n, 1000.0);
    s.Mg = 10.0;
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * kPi * j / n;
      s.q.col(j) << 0.3 * std::cos(a) + 0.05 * uniform(rng, -1.0, 1.0),
          0.3 * std::sin(a) + 0.05 * uniform(rng, -1.0, 1.0), -0.1 + 0.01 * uniform(rng, -1, 1);
    }
    const Solved path = solve(s, false, false);
    if (path.frame.support.status != Status::kBalanced) {
      continue;
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_TRUE(compare_routes(s, 1e-9));
    // A contact set of three on a robot of four or more whose feet were all drawn near one
    // height is one the all-feet plane overshoots past more often than not.
    tilted += std::count(path.frame.contact.begin(), path.frame.contact.end(), 1) == 3 ? 1 : 0;
  }
  EXPECT_GT(tilted, 300);
}

// ---- the warm start (SupportOptions::warm_start) ------------------------------------------------

// Solves the frame's current feet from its current state (warm) or from the all-feet cell.
void solve_frame(const Robot& robot, Frame& f, bool warm) {
  SupportOptions opt;
  opt.warm_start = warm;
  slipwalk::contact::spring_support(robot, f, opt);
}

// The warm start is a start only: where it certifies, the state is the cold start's to rounding,
// on the path's oracle's terms (expect_same_state); frames of a walk whose feet moved a little
// since the previous balance take fewer steps than from the all-feet cell.
TEST(SupportNewton, AWarmStartEndsWhereTheColdStartEndsAlongAWalk) {
  std::mt19937_64 rng(131);
  long long warm_steps = 0;
  long long cold_steps = 0;
  int frames = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 30);
    Scene s = random_supported(rng, n);
    const Robot robot = s.robot();
    Frame warm(robot);
    warm.q = s.q;
    slipwalk::contact::spring_support(robot, warm);  // the first frame: cold
    if (warm.support.status != Status::kBalanced) {
      continue;
    }
    const double step = 0.02 * size_of(s);
    for (int frame = 0; frame < 10; ++frame) {
      // The feet move a little, some up, some down by a fraction of the deepest compression.
      const double sink = (warm.Fz.array() / s.K.array()).maxCoeff();
      for (int j = 0; j < n; ++j) {
        s.q(0, j) += uniform(rng, -step, step);
        s.q(1, j) += uniform(rng, -step, step);
        s.q(2, j) += uniform(rng, -0.2, 0.2) * sink;
      }
      warm.q = s.q;
      const long long before = slipwalk::testing::allocation_count();
      solve_frame(robot, warm, true);
      if (warm.support.route == Route::kNewton) {
        EXPECT_EQ(slipwalk::testing::allocation_count(), before);
      }
      const Solved cold = solve(s);
      if (cold.frame.support.status != Status::kBalanced) {
        break;  // the walk left the support polygon
      }
      SCOPED_TRACE("trial " + std::to_string(trial) + ", frame " + std::to_string(frame));
      ASSERT_EQ(warm.support.status, Status::kBalanced);
      expect_same_state(s, warm, cold.frame, 1e-11);
      if (warm.support.route == Route::kNewton && cold.frame.support.route == Route::kNewton) {
        warm_steps += warm.support.newton_steps;
        cold_steps += cold.frame.support.newton_steps;
        ++frames;
      }
    }
  }
  std::printf("%d frames: %.2f Newton steps warm, %.2f cold\n", frames,
              static_cast<double>(warm_steps) / frames, static_cast<double>(cold_steps) / frames);
  EXPECT_GT(frames, 1000);
  EXPECT_LT(warm_steps * 4, cold_steps * 3);  // a quarter fewer steps at least
}

// From the frame's own balance the start cell is the answer's: one step (its residual is the
// start's rounding, which it no longer halves), no contact change, and the same state to rounding.
TEST(SupportNewton, AWarmStartFromTheFramesOwnBalanceCertifiesInOneStep) {
  std::mt19937_64 rng(137);
  int certified = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 40));
    const Solved cold = solve(s);
    if (cold.frame.support.route != Route::kNewton) {
      continue;
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    Frame f = cold.frame;
    solve_frame(cold.robot, f, true);
    EXPECT_EQ(f.support.route, Route::kNewton);
    EXPECT_EQ(f.support.newton_steps, 1);
    EXPECT_EQ(f.support.iterations, 0);
    expect_same_state(s, f, cold.frame, 1e-13);
    ++certified;
  }
  EXPECT_GT(certified, 250);
}

// A previous state the feet are nowhere near (the body far above them: no foot below its plane)
// gives no start; the cold start then runs, to the same bits as without the warm start. So does a
// frame whose balance was forgotten (a new run) or whose last search ended unbalanced.
TEST(SupportNewton, AWarmStartWithoutAUsableBalanceIsTheColdStartToTheBit) {
  std::mt19937_64 rng(139);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 40));
    const Solved cold = solve(s);
    SCOPED_TRACE("trial " + std::to_string(trial));
    for (int how = 0; how < 3; ++how) {
      Frame f = cold.frame;
      if (how == 0) {
        f.z = 10.0 * height_scale(s, cold.frame);  // h_j = q_z,j + z > 0 for every foot
        f.support.status = Status::kBalanced;
      } else if (how == 1) {
        slipwalk::contact::forget_balance(f);
      } else {
        f.support.status = Status::kUnsupported;
      }
      solve_frame(cold.robot, f, true);
      EXPECT_EQ(f.support.status, cold.frame.support.status);
      EXPECT_EQ(f.support.route, cold.frame.support.route);
      EXPECT_EQ(f.support.newton_steps, cold.frame.support.newton_steps);
      EXPECT_EQ(f.z, cold.frame.z);
      EXPECT_EQ(f.alpha, cold.frame.alpha);
      EXPECT_EQ(f.beta, cold.frame.beta);
      EXPECT_EQ(f.Fz, cold.frame.Fz);
      EXPECT_EQ(f.contact, cold.frame.contact);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 900);
}

}  // namespace
