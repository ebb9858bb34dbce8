// Warm starts of the Coulomb solver along a trajectory (CoulombOptions::warm_start): each frame
// starts from the previous frame's answer and static feet. Oracles: the cold solve of the same
// frame (a second start to the same convex minimum, certified on its own), the smoothing path
// (fast_path = false, a second route) for the fast path's static pairs, and the certificate and
// the dissipation's bound D(v) − D* ≤ tol · max(D(v), D(0)) that it proves. The walk is BigANT's
// alternating tripod turning left (robots::bigant_tripod, steer 0.3) at 100 Hz frames (thesis
// §3.5.1.1), the spring support deciding the feet down: one static foot in most frames, a static
// pair (the inner feet of the turn) in about one in eight, none in the rest.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "robots/robots.hpp"
#include "support/count_allocations.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;

constexpr double kTol = 1e-9;  // the ch3_legged cost study's tolerance

/// Successive frames of the turning tripod walk, every `stride`-th 100 Hz frame from t = 0, the
/// spring support's loads in each (frames it cannot balance left out).
std::vector<Frame> walk(const robots::Walker& walker, int count, int stride = 1) {
  std::vector<Frame> frames;
  Frame f(walker.robot);
  for (int i = 0; static_cast<int>(frames.size()) < count; i += stride) {
    walker.feet(0.01 * i, f.q, f.qdot);
    contact::spring_support(walker.robot, f);
    if (f.support.status == contact::SupportSummary::Status::kBalanced) {
      frames.push_back(f);
    }
  }
  return frames;
}

robots::Walker turning_tripod() { return robots::bigant_tripod({.frequency = 0.38, .steer = 0.3}); }

/// D(0) = Σ μ_k F_z,k ‖q̇_xy,k‖ over the feet down: the certificate's scale with D(v).
double rest_dissipation(const Robot& robot, const Frame& f) {
  double d = 0.0;
  for (int k = 0; k < f.legs(); ++k) {
    if (f.contact[static_cast<std::size_t>(k)] != 0) {
      d += robot.mu(k) * f.Fz(k) * f.qdot.col(k).head<2>().norm();
    }
  }
  return d;
}

/// `f` and `ref` are certified answers of one frame: the same minimum (dissipation within both
/// certificates' bounds), the same static feet and, where the minimum is unique, the same body
/// velocity (~0.1 m/s; a certificate of 1e-9 places it to ~1e-6 of that, as
/// test_coulomb_supported.cpp's routes).
void expect_same_answer(const Robot& robot, const Frame& f, const Frame& ref, const char* what) {
  ASSERT_TRUE(f.friction.converged) << what << ": " << f.friction.message;
  ASSERT_TRUE(ref.friction.converged) << what << ": " << ref.friction.message;
  EXPECT_LE(f.friction.certificate, kTol) << what;
  EXPECT_LE(f.friction.residual, 1e-10) << what;
  const double scale =
      std::max({f.friction.dissipation, ref.friction.dissipation, rest_dissipation(robot, f)});
  EXPECT_NEAR(f.friction.dissipation, ref.friction.dissipation, 2.0 * kTol * scale) << what;
  EXPECT_EQ(f.friction.unique, ref.friction.unique) << what;
  if (ref.friction.unique) {
    EXPECT_LE((f.v_body - ref.v_body).norm(), 1e-6 * (1e-3 + ref.v_body.norm())) << what;
    EXPECT_EQ(f.friction.static_feet, ref.friction.static_feet) << what;
  }
}

TEST(CoulombWarm, WarmStartsAlongATurningWalkGiveTheColdAnswersInFewerSteps) {
  const robots::Walker walker = turning_tripod();
  const std::vector<Frame> frames = walk(walker, 800);  // three gait cycles
  CoulombOptions cold;
  cold.tol = kTol;
  CoulombOptions warm = cold;
  warm.warm_start = true;
  Frame g(walker.robot);  // the working frame: v_body and the static marks carry over
  long cold_steps = 0;
  long warm_steps = 0;
  int pairs = 0;
  for (const Frame& input : frames) {
    Frame f = input;
    solve_coulomb(walker.robot, f, cold);
    g.q = input.q;
    g.qdot = input.qdot;
    g.contact = input.contact;
    g.Fz = input.Fz;
    solve_coulomb(walker.robot, g, warm);
    expect_same_answer(walker.robot, g, f, "warm against cold");
    cold_steps += f.friction.iterations;
    warm_steps += g.friction.iterations;
    pairs += f.friction.static_feet == 2 ? 1 : 0;
  }
  EXPECT_GT(pairs, 50);  // the static pairs the warm start holds over are well represented
  EXPECT_LE(warm_steps, cold_steps);
}

TEST(CoulombWarm, WarmSolvesAlongTheWalkDoNotAllocate) {
#ifdef SLIPWALK_SANITIZED
  GTEST_SKIP() << "the sanitizers' runtime allocates on its own";
#endif
  const robots::Walker walker = turning_tripod();
  const std::vector<Frame> frames = walk(walker, 300);
  CoulombOptions warm;
  warm.tol = kTol;
  warm.warm_start = true;
  Frame g(walker.robot);
  long long allocations = 0;
  // Twice along the walk, counted the second time: the first message a frame gets (here "static
  // feet at distinct points", the static pairs) grows its string once.
  for (int round = 0; round < 2; ++round) {
    for (const Frame& input : frames) {
      g.q = input.q;  // same sizes: no allocation
      g.qdot = input.qdot;
      g.contact = input.contact;
      g.Fz = input.Fz;
      const long long before = slipwalk::testing::allocation_count();
      solve_coulomb(walker.robot, g, warm);
      allocations += round == 1 ? slipwalk::testing::allocation_count() - before : 0;
      ASSERT_TRUE(g.friction.converged) << g.friction.message;
    }
  }
  EXPECT_EQ(allocations, 0);
}

TEST(CoulombWarm, TheFastPathsStaticPairsAgreeWithTheSmoothingPath) {
  const robots::Walker walker = turning_tripod();
  CoulombOptions fast;
  fast.tol = kTol;
  CoulombOptions path = fast;
  path.fast_path = false;
  int pairs = 0;
  int fallbacks = 0;
  for (const Frame& input : walk(walker, 150, 7)) {  // 10.5 s, frames 70 ms apart
    Frame f = input;
    solve_coulomb(walker.robot, f, fast);
    Frame ref = input;
    solve_coulomb(walker.robot, ref, path);
    expect_same_answer(walker.robot, f, ref, "fast path against the smoothing path");
    pairs += f.friction.static_feet == 2 ? 1 : 0;
    fallbacks += f.friction.route == contact::FrictionSummary::Route::kFallback ? 1 : 0;
  }
  EXPECT_GT(pairs, 10);
  // The pairs certify on the fast path (before the pair polish, all of them fell back); the
  // walk's rare frame whose pair neither trigger finds still does (1 here, 4 in 4200 at 100 Hz).
  EXPECT_LE(fallbacks, 2);
}

TEST(CoulombWarm, AGarbageStartStillConvergesAndIsCertified) {
  const robots::Walker walker = turning_tripod();
  CoulombOptions cold;
  cold.tol = kTol;
  CoulombOptions warm = cold;
  warm.warm_start = true;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector3d> starts = {
      Eigen::Vector3d(nan, 0.0, 0.0), Eigen::Vector3d(1e12, -1e12, 1e12),
      Eigen::Vector3d(0.0, 0.0, std::numeric_limits<double>::infinity()),
      Eigen::Vector3d(-3.0, 2.0, 50.0)};
  for (const Frame& input : walk(walker, 40, 13)) {
    Frame ref = input;
    solve_coulomb(walker.robot, ref, cold);
    for (const Eigen::Vector3d& start : starts) {
      for (const int mark : {0, 1, -1, 7}) {  // every foot sliding, static, inactive, nonsense
        Frame f = input;
        f.v_body = start;
        std::fill(f.work_idx.begin(), f.work_idx.end(), mark);
        solve_coulomb(walker.robot, f, warm);
        expect_same_answer(walker.robot, f, ref, "garbage start");
      }
    }
  }
}

TEST(CoulombWarm, SolvingAFrameAgainFromItsOwnAnswerGivesThatAnswer) {
  // A foot static in the answer is exactly at rest there: the fast path cannot start at it.
  const robots::Walker walker = turning_tripod();
  CoulombOptions warm;
  warm.tol = kTol;
  warm.warm_start = true;
  for (const Frame& input : walk(walker, 40, 13)) {
    Frame f = input;
    solve_coulomb(walker.robot, f, warm);
    Frame again = f;
    solve_coulomb(walker.robot, again, warm);
    expect_same_answer(walker.robot, again, f, "solved again");
  }
}

TEST(CoulombWarm, WithoutWarmStartsWhatAFrameHoldsFromBeforeChangesNothing) {
  const robots::Walker walker = turning_tripod();
  CoulombOptions cold;
  cold.tol = kTol;
  const std::vector<Frame> frames = walk(walker, 30, 17);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    Frame clean = frames[i];
    solve_coulomb(walker.robot, clean, cold);
    Frame used = frames[(i + 1) % frames.size()];  // another frame's answer and marks left in it
    solve_coulomb(walker.robot, used, cold);
    used.q = frames[i].q;
    used.qdot = frames[i].qdot;
    used.contact = frames[i].contact;
    used.Fz = frames[i].Fz;
    solve_coulomb(walker.robot, used, cold);
    EXPECT_EQ(used.v_body, clean.v_body);
    EXPECT_EQ(used.Fxy, clean.Fxy);
    EXPECT_EQ(used.friction.iterations, clean.friction.iterations);
  }
}

TEST(CoulombWarm, WarmStartsUphillGiveTheColdAnswers) {
  // §5.2.1's 17° slope, walking uphill: gravity's planar part loads every frame (the loaded
  // solver warm-starts the same way).
  const robots::Walker walker = turning_tripod();
  const terrain::Slope slope{17.0 * M_PI / 180.0, 0.0, 0.0};
  Robot support = walker.robot;
  support.Mg = walker.robot.Mg * std::cos(slope.angle);
  const Eigen::Vector3d load = terrain::slope_load(slope, walker.robot.Mg, 0.0);
  CoulombOptions cold;
  cold.tol = kTol;
  CoulombOptions warm = cold;
  warm.warm_start = true;
  Frame g(walker.robot);
  Frame f(walker.robot);
  long cold_steps = 0;
  long warm_steps = 0;
  for (int i = 0; i < 300; ++i) {
    walker.feet(0.01 * i, f.q, f.qdot);
    contact::spring_support(support, f);
    if (f.support.status != contact::SupportSummary::Status::kBalanced) {
      continue;
    }
    g.q = f.q;
    g.qdot = f.qdot;
    g.contact = f.contact;
    g.Fz = f.Fz;
    solve_coulomb_loaded(walker.robot, f, load, cold);
    solve_coulomb_loaded(walker.robot, g, load, warm);
    expect_same_answer(walker.robot, g, f, "uphill, warm against cold");
    cold_steps += f.friction.iterations;
    warm_steps += g.friction.iterations;
  }
  EXPECT_LE(warm_steps, cold_steps);
}

}  // namespace
}  // namespace slipwalk::friction
