// The batched spring support (contact/support_batch.hpp) against the one-frame route
// (spring_support on a copy of each frame) and the convex-potential oracle: where the batch
// certifies, the same contact set and status and the same state and loads to rounding, a balance
// residual computed here from the outputs at rounding level, and the potential's minimizer; where
// it does not, the one-frame route's outputs to the bit (it is what ran). Batches of any length
// (a last group of one to three frames), mixed with frames that tip, stand on one or two feet,
// or are malformed.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "contact/support_batch.hpp"
#include "core/error.hpp"
#include "support/count_allocations.hpp"
#include "support/support_scenes.hpp"

namespace {

using namespace slipwalk::testing::support_scenes;  // NOLINT(google-build-using-namespace)
using slipwalk::contact::BatchScratch;
using slipwalk::contact::spring_support_batch;
using Status = slipwalk::contact::SupportSummary::Status;
using Route = slipwalk::contact::SupportSummary::Route;

// `count` frames of the robot of `s`: its feet moved by up to `jitter` m in x and y and each
// lowered or lifted by up to `lift` m, so that the contact sets differ from frame to frame.
std::vector<Frame> frames_of(const Scene& s, int count, double jitter, double lift,
                             std::mt19937_64& rng) {
  const Robot robot = s.robot();
  std::vector<Frame> frames;
  for (int i = 0; i < count; ++i) {
    Frame f(robot);
    f.q = s.q;
    for (int j = 0; j < s.legs(); ++j) {
      f.q(0, j) += uniform(rng, -jitter, jitter);
      f.q(1, j) += uniform(rng, -jitter, jitter);
      f.q(2, j) += uniform(rng, -lift, lift);
    }
    frames.push_back(f);
  }
  return frames;
}

// The scene of frame f (its own feet, the robot's stiffnesses and weight).
Scene scene_of(const Scene& robot_scene, const Frame& f) {
  Scene t = robot_scene;
  t.q = f.q;
  return t;
}

// One batched frame against the same frame solved alone. Returns whether the batch certified it.
bool expect_like_one_frame(const Scene& s, const Frame& batched, const Frame& alone) {
  EXPECT_EQ(batched.support.status, alone.support.status) << batched.support.message;
  if (batched.support.route != Route::kNewton) {
    // Handed over: spring_support ran on it, so it is the one-frame result, bit for bit.
    EXPECT_EQ(batched.support.route, alone.support.route);
    EXPECT_EQ(batched.z, alone.z);
    EXPECT_EQ(batched.alpha, alone.alpha);
    EXPECT_EQ(batched.beta, alone.beta);
    EXPECT_EQ(batched.contact, alone.contact);
    EXPECT_EQ((batched.Fz - alone.Fz).norm(), 0.0);
    EXPECT_EQ(batched.support.message, alone.support.message);
    return false;
  }
  // Certified: the unique minimizer of U, which the one-frame route also finds.
  EXPECT_EQ(batched.support.status, Status::kBalanced);
  EXPECT_TRUE(batched.support.message.empty());
  EXPECT_GE(batched.support.newton_steps, 1);
  EXPECT_LE(batched.support.residual, 1e-10 + 100.0 * rounding_floor(s, batched));
  const Balance b = balance(s, batched);
  EXPECT_LE(b.force, 1e-10 + 100.0 * rounding_floor(s, batched));
  EXPECT_LE(b.moment, 1e-10 + 100.0 * rounding_floor(s, batched));
  const double Z = height_scale(s, alone);
  const double L = size_of(s);
  EXPECT_NEAR(batched.z, alone.z, 1e-11 * Z);
  EXPECT_NEAR(L * batched.alpha, L * alone.alpha, 1e-11 * Z);
  EXPECT_NEAR(L * batched.beta, L * alone.beta, 1e-11 * Z);
  for (int j = 0; j < s.legs(); ++j) {
    EXPECT_NEAR(batched.Fz(j), alone.Fz(j), 1e-11 * s.K(j) * Z + 1e-13 * s.Mg) << "leg " << j;
    EXPECT_EQ(batched.contact[j], alone.contact[j]) << "leg " << j;
  }
  return true;
}

struct Tally {
  int frames = 0;
  int certified = 0;
  int same_steps = 0;
};

// Solves the frames as one batch and each alone, and compares them.
Tally compare_batch(const Scene& s, std::vector<Frame> frames, BatchScratch& scratch) {
  const Robot robot = s.robot();
  std::vector<Frame> alone = frames;
  for (Frame& f : alone) {
    slipwalk::contact::spring_support(robot, f);
  }
  spring_support_batch(robot, frames, scratch);
  Tally t;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i) + " of " + std::to_string(frames.size()));
    const bool certified = expect_like_one_frame(scene_of(s, frames[i]), frames[i], alone[i]);
    ++t.frames;
    t.certified += certified ? 1 : 0;
    t.same_steps += frames[i].support.newton_steps == alone[i].support.newton_steps ? 1 : 0;
  }
  return t;
}

TEST(SupportBatch, EveryFrameOfRandomRobotsIsTheOneFrameRoutesAnswer) {
  std::mt19937_64 rng(201);
  BatchScratch scratch(3);  // resized to each robot's legs
  Tally all;
  int same_start = 0;  // frames both routes start from the all-feet cell
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 28);  // both sides of the level start's 20 legs
    const Scene s = random_supported(rng, n);
    const int count = 1 + static_cast<int>(rng() % 13);  // last groups of 1 … 4 frames
    const double delta = s.Mg / (s.K.sum() / 3.0);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " legs");
    const Tally t = compare_batch(s, frames_of(s, count, 0.01, 2.0 * delta, rng), scratch);
    all.frames += t.frames;
    all.certified += t.certified;
    if (n < 20) {  // from 20 legs the one-frame route starts from the level body instead
      all.same_steps += t.same_steps;
      same_start += t.frames;
    }
  }
  std::printf(
      "batch certified %d of %d frames; %d of %d from the same start with the one-frame "
      "route's step count\n",
      all.certified, all.frames, all.same_steps, same_start);
  // The batch is worth having only if it certifies most frames itself (otherwise everything
  // is still right, but slower than one frame at a time: this catches that). Below 20 legs its
  // steps are the one-frame route's, so the step counts agree except where rounding decides a
  // refinement.
  EXPECT_GE(all.certified, all.frames * 8 / 10);
  EXPECT_GE(all.same_steps, same_start * 95 / 100);
}

TEST(SupportBatch, CertifiedFramesAreThePotentialsMinimizer) {
  std::mt19937_64 rng(203);
  BatchScratch scratch(6);
  int certified = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Scene s = random_supported(rng, 4 + static_cast<int>(rng() % 12));
    const double delta = s.Mg / (s.K.sum() / 3.0);
    std::vector<Frame> frames = frames_of(s, 7, 0.01, delta, rng);
    spring_support_batch(s.robot(), frames, scratch);
    for (const Frame& f : frames) {
      if (f.support.route == Route::kNewton) {
        ++certified;
        expect_matches_oracle(scene_of(s, f), f, "batched");
      }
    }
  }
  EXPECT_GT(certified, 140);
}

// Frames the Newton route must not certify, in one batch with frames it does: the CoM outside
// the feet (tips), one foot down, two feet, a row of feet, a foot exactly at the balance plane
// (a tie). Each must come out as the one-frame route leaves it, and must not disturb its group.
TEST(SupportBatch, DegenerateFramesInAGroupHandOverAndLeaveTheOthersAlone) {
  std::mt19937_64 rng(207);
  const Scene s = flat_hexapod();
  std::vector<Frame> frames = frames_of(s, 12, 0.01, 0.003, rng);
  frames[1].q.row(0).array() += 1.0;  // every foot ahead of the CoM: the robot tips
  frames[2].q.row(2).array() += 0.5;  // all feet lifted but one: the body tilts onto more
  frames[2].q(2, 3) = -0.2;
  frames[5].q.row(2).array() += 0.5;  // two feet down, on a line through the CoM
  frames[5].q.col(0) << 0.2, 0.1, -0.2;
  frames[5].q.col(3) << -0.2, -0.1, -0.2;
  frames[6].q.row(1).setZero();         // all feet on the x axis: a row
  frames[10].q.row(2).array() += 0.04;  // lifted: the level body of the others' height is off
  BatchScratch scratch(6);
  const Tally t = compare_batch(s, frames, scratch);
  EXPECT_EQ(t.frames, 12);
  EXPECT_GE(t.certified, 8);
  std::vector<Frame> batched = frames;
  spring_support_batch(s.robot(), batched, scratch);
  EXPECT_EQ(batched[1].support.status, Status::kUnsupported);
  EXPECT_EQ(batched[5].support.status, Status::kLine);
  EXPECT_EQ(batched[6].support.status, Status::kLine);
  // The tie: lower a foot in the air onto the balance plane of its frame.
  std::vector<Frame> ties = frames_of(s, 5, 0.01, 0.003, rng);
  for (Frame& f : ties) {
    Frame g = f;
    slipwalk::contact::spring_support(s.robot(), g, {.newton = false});
    for (int j = 0; j < s.legs(); ++j) {
      if (g.contact[j] == 0) {
        f.q(2, j) -= slipwalk::contact::foot_height(g, j, g.alpha, g.beta, g.z);
      }
    }
  }
  compare_batch(s, ties, scratch);
}

// From 20 legs the one-frame route starts from the level body, the batch from all feet: two
// routes to the same certified minimizer.
TEST(SupportBatch, ManyLeggedRobotsEndWhereTheOneFrameLevelStartEnds) {
  std::mt19937_64 rng(209);
  BatchScratch scratch(24);
  for (const int n : {20, 24, 50, 200}) {
    const Scene s = random_supported(rng, n);
    SCOPED_TRACE(std::to_string(n) + " legs");
    const Tally t = compare_batch(s, frames_of(s, 9, 0.01, s.Mg / s.K.sum(), rng), scratch);
    EXPECT_GE(t.certified, 8);
  }
}

TEST(SupportBatch, AMalformedFrameThrowsAsTheOneFrameRouteDoes) {
  std::mt19937_64 rng(211);
  const Scene s = random_supported(rng, 6);
  BatchScratch scratch(6);
  for (int bad = 0; bad < 3; ++bad) {
    std::vector<Frame> frames = frames_of(s, 6, 0.01, 0.001, rng);
    if (bad == 0) {
      frames[4].q(1, 2) = std::nan("");
    } else if (bad == 1) {
      frames[4].q(2, 5) = 1e9;  // outside limits::kPosition
    } else {
      frames[4].qdot(0, 1) = std::numeric_limits<double>::infinity();
    }
    Frame alone = frames[4];
    EXPECT_THROW(slipwalk::contact::spring_support(s.robot(), alone), slipwalk::core::InputError);
    EXPECT_THROW(spring_support_batch(s.robot(), frames, scratch), slipwalk::core::InputError)
        << "case " << bad;
  }
  // A frame of another robot (5 legs for a 6-legged robot).
  std::vector<Frame> frames = frames_of(s, 3, 0.01, 0.001, rng);
  frames.emplace_back(slipwalk::contact::uniform_robot(5));
  EXPECT_THROW(spring_support_batch(s.robot(), frames, scratch), slipwalk::core::InputError);
}

TEST(SupportBatch, AllocatesNothingOnceTheScratchFitsTheRobot) {
#ifdef SLIPWALK_SANITIZED
  GTEST_SKIP() << "the sanitizers' runtime allocates on its own";
#endif
  std::mt19937_64 rng(213);
  for (const int n : {3, 6, 12}) {
    Robot robot = slipwalk::contact::uniform_robot(n, 1000.0, 0.8, 10.0);
    std::vector<Frame> frames(13, Frame(robot));
    for (Frame& f : frames) {
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * kPi * k / n;
        f.q.col(k) << 0.3 * std::cos(a) + 0.05 * uniform(rng, -1.0, 1.0),
            0.3 * std::sin(a) + 0.05 * uniform(rng, -1.0, 1.0), -0.1 + 0.01 * uniform(rng, -1, 1);
      }
    }
    BatchScratch scratch(n);
    const long long before = slipwalk::testing::allocation_count();
    spring_support_batch(robot, frames, scratch);
    EXPECT_EQ(slipwalk::testing::allocation_count() - before, 0) << n << " legs";
    for (const Frame& f : frames) {
      EXPECT_EQ(f.support.route, Route::kNewton) << n << " legs";
    }
  }
}

TEST(SupportBatch, AnEmptyBatchDoesNothing) {
  const Robot robot = slipwalk::contact::uniform_robot(6);
  std::vector<Frame> none;
  BatchScratch scratch(6);
  spring_support_batch(robot, none, scratch);
  EXPECT_TRUE(scratch.holds(6));
}

}  // namespace
