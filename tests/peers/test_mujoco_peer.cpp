// The MuJoCo peer (lib/peers/mujoco): the robot description without MuJoCo (inverse and forward
// kinematics, workspaces, MJCF), and with MuJoCo: the model compiles, MuJoCo's own forward
// kinematics puts the feet where our configuration has them, its contacts are our contact set,
// a robot standing still carries its weight (Σ normal force = Mg), friction opposes sliding, and
// the peer_scaling point gives sane rows, the same values (timings aside) when run again. Tests
// that need MuJoCo are skipped, saying so, in a build without it.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "peers/mujoco/legged_spec.hpp"
#include "support/point_rows.hpp"
#include "support/skip_without_mujoco.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/engine/spec.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include "peers/mujoco/peer.hpp"
#endif

namespace slipwalk::peers::mujoco {
namespace {

constexpr double kMg = 8.18 * 9.81;

contact::Robot disk(int n) { return contact::uniform_robot(n, kMg / (n * 0.01), 1.0, kMg); }

/// Random feet inside their workspaces at height z ∈ [−0.11, −0.09] and random velocities.
void random_feet(const PeerSpec& spec, sweeps::Random& rng, Eigen::Matrix3Xd& q,
                 Eigen::Matrix3Xd& qdot) {
  for (std::size_t k = 0; k < spec.legs.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    q.col(c) =
        workspace_point(spec.legs[k], rng.uniform(), rng.uniform(), rng.uniform(-0.11, -0.09));
    qdot.col(c) << rng.normal(), rng.normal(), rng.normal();
  }
}

// ---- without MuJoCo
// ------------------------------------------------------------------------------

TEST(LeggedSpec, InverseThenForwardReproducesTheFoot) {
  for (int n : {3, 6, 50}) {
    const PeerSpec spec = disk_spec(disk(n));
    sweeps::Random rng(1, static_cast<std::uint64_t>(n));
    Eigen::Matrix3Xd q(3, n), qdot(3, n);
    random_feet(spec, rng, q, qdot);
    for (int k = 0; k < n; ++k) {
      const LegSpec& leg = spec.legs[static_cast<std::size_t>(k)];
      LegJoints j, r;
      ASSERT_TRUE(leg_inverse(leg, q.col(k), qdot.col(k), j, r));
      EXPECT_LT((leg_forward(leg, j) - q.col(k)).norm(), 1e-14);
      // Inside the joint ranges (the workspace is shrunk by 5 %).
      EXPECT_LE(std::abs(j.yaw), leg.yaw_range);
      EXPECT_GE(j.pitch, leg.pitch_min);
      EXPECT_LE(j.pitch, leg.pitch_max);
      EXPECT_LE(std::abs(j.slide), leg.slide_range);
    }
  }
}

TEST(LeggedSpec, JointRatesAreTheDerivativeOfTheInverse) {
  const PeerSpec spec = disk_spec(disk(8));
  sweeps::Random rng(2, 0);
  Eigen::Matrix3Xd q(3, 8), qdot(3, 8);
  random_feet(spec, rng, q, qdot);
  const double h = 1e-6;
  for (int k = 0; k < 8; ++k) {
    const LegSpec& leg = spec.legs[static_cast<std::size_t>(k)];
    LegJoints j, r, jp, jm, unused;
    ASSERT_TRUE(leg_inverse(leg, q.col(k), qdot.col(k), j, r));
    ASSERT_TRUE(leg_inverse(leg, q.col(k) + h * qdot.col(k), qdot.col(k), jp, unused));
    ASSERT_TRUE(leg_inverse(leg, q.col(k) - h * qdot.col(k), qdot.col(k), jm, unused));
    EXPECT_NEAR(r.slide, (jp.slide - jm.slide) / (2 * h), 1e-6);
    EXPECT_NEAR(r.yaw, (jp.yaw - jm.yaw) / (2 * h), 1e-6);
    EXPECT_NEAR(r.pitch, (jp.pitch - jm.pitch) / (2 * h), 1e-6);
  }
}

TEST(LeggedSpec, WorkspacesOfNeighbouringLegsDoNotOverlap) {
  for (int n : {3, 12, 50}) {
    const PeerSpec spec = disk_spec(disk(n));
    // A foot's wedge spans its yaw range at the largest reach; its tangential half-width must
    // stay below half the distance between neighbouring hips (§3.5.3: workspaces apart).
    const LegSpec& leg = spec.legs[0];
    const double reach = leg.length * std::sin(leg.pitch_max);
    const double chord = (spec.legs[1].hip - spec.legs[0].hip).norm();
    EXPECT_LT(reach * std::sin(leg.yaw_range), 0.5 * chord) << "N = " << n;
  }
}

TEST(LeggedSpec, ReachOutsideTheLegFailsAndBadSpecsThrow) {
  const PeerSpec spec = disk_spec(disk(3));
  LegJoints j, r;
  EXPECT_FALSE(leg_inverse(spec.legs[0], spec.legs[0].hip, Eigen::Vector3d::Zero(), j, r));
  PeerSpec bad = spec;
  bad.legs[1].length = -1.0;
  EXPECT_THROW((void)mjcf(bad), core::InputError);
  bad = spec;
  bad.total_mass = 0.01;  // less than the legs
  EXPECT_THROW((void)mjcf(bad), core::InputError);
}

// ---- with MuJoCo
// ---------------------------------------------------------------------------------

TEST(MujocoPeer, ModelCompilesFromMemory) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  for (int n : {3, 50}) {
    const PeerModel model(disk_spec(disk(n)));
    EXPECT_EQ(model.legs(), n);
    EXPECT_EQ(model.mj()->nq, 7 + 3 * n);
    EXPECT_EQ(model.mj()->nu, 3 * n);
    double mass = 0.0;
    for (int b = 0; b < model.mj()->nbody; ++b) {
      mass += model.mj()->body_mass[b];
    }
    EXPECT_NEAR(mass * 9.81, kMg, 1e-9);
  }
  EXPECT_EQ(version().substr(0, 2), "2.");
#endif
}

TEST(MujocoPeer, ForwardKinematicsAndContactsMatchOurConfiguration) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const int n = 12;
  const contact::Robot robot = disk(n);
  const PeerModel model(disk_spec(robot));
  PeerData data(model);
  contact::Frame f(robot);
  sweeps::Random rng(3, 0);
  int compared = 0;
  for (int trial = 0; trial < 50; ++trial) {
    random_feet(model.spec(), rng, f.q, f.qdot);
    contact::spring_support(robot, f);
    BodyState body;
    body.x = rng.uniform(-1, 1);
    body.y = rng.uniform(-1, 1);
    body.theta = rng.uniform(-3, 3);
    body.z = f.z;
    body.alpha = f.alpha;
    body.beta = f.beta;
    ASSERT_EQ(set_state(model, data, body, f.q, f.qdot), 0);
    forward(model, data);
    read_feet(model, data);
    EXPECT_LT((data.q - f.q).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    const BodyState back = body_state(model, data);
    EXPECT_NEAR(back.alpha, body.alpha, 1e-12);
    EXPECT_NEAR(back.beta, body.beta, 1e-12);
    EXPECT_NEAR(back.theta, body.theta, 1e-12);
    // Contacts: the same feet, except where a foot is within the second-order difference between
    // eq. 3.6's small-angle plane and the exact rotation (here ≤ 1e-4 m).
    bool clear = true;
    for (int k = 0; k < n; ++k) {
      clear = clear && std::abs(contact::foot_height(f, k, f.alpha, f.beta, f.z)) > 1e-4;
    }
    if (clear) {
      ++compared;
      EXPECT_EQ(data.contact, f.contact) << "trial " << trial;
    }
  }
  EXPECT_GT(compared, 25);
#endif
}

TEST(MujocoPeer, StandingStillCarriesTheWeight) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  for (int n : {3, 6, 24}) {
    const contact::Robot robot = disk(n);
    const PeerModel model(disk_spec(robot));
    PeerData data(model);
    contact::Frame f(robot);
    for (int k = 0; k < n; ++k) {
      f.q.col(k) = workspace_point(model.spec().legs[static_cast<std::size_t>(k)], 0.5, 0.5, -0.1);
    }
    f.qdot.setZero();
    contact::spring_support(robot, f);
    BodyState body;
    body.z = f.z;
    set_state(model, data, body, f.q, f.qdot);
    for (int s = 0; s < 1500; ++s) {  // 3 s
      step(model, data);
    }
    read_feet(model, data);
    EXPECT_NEAR(data.Fz.sum(), kMg, 2e-3 * kMg) << "N = " << n;
    EXPECT_EQ(std::count(data.contact.begin(), data.contact.end(), 1), n);
    EXPECT_LT(body_state(model, data).v_body.norm(), 1e-3);
    EXPECT_LT(data.Fxy.rowwise().sum().norm(), 1e-3 * kMg);
  }
#endif
}

TEST(MujocoPeer, FrictionOpposesSliding) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const int n = 24;
  const contact::Robot robot = disk(n);
  const PeerModel model(disk_spec(robot));
  PeerData data(model);
  contact::Frame f(robot);
  for (int k = 0; k < n; ++k) {
    f.q.col(k) = workspace_point(model.spec().legs[static_cast<std::size_t>(k)], 0.5, 0.5, -0.1);
  }
  f.qdot.setZero();
  contact::spring_support(robot, f);
  BodyState body;
  body.z = f.z;
  body.theta = 0.7;  // the planar forces are read in the body frame: rotate them back
  set_state(model, data, body, f.q, f.qdot);
  for (int s = 0; s < 500; ++s) {
    step(model, data);
  }
  // Push the settled robot along the world's +x: the floor's friction must brake it.
  data.mj()->qvel[0] = 0.2;
  double strongest = 0.0, sideways = 0.0;
  for (int s = 0; s < 15; ++s) {
    step(model, data);
    read_feet(model, data);
    const Eigen::Vector2d Fb = data.Fxy.rowwise().sum();
    const double th = body_state(model, data).theta;
    const Eigen::Vector2d Fw(std::cos(th) * Fb(0) - std::sin(th) * Fb(1),
                             std::sin(th) * Fb(0) + std::cos(th) * Fb(1));
    if (Fw(0) < strongest) {
      strongest = Fw(0);
      sideways = Fw(1);
    }
  }
  EXPECT_LT(strongest, -0.25 * kMg);
  EXPECT_LT(std::abs(sideways), 0.05 * std::abs(strongest));
  EXPECT_LT(data.mj()->qvel[0], 0.2);
#endif
}

TEST(MujocoPeer, ScalingPointGivesSaneRows) {
  const sweeps::PointKind* fn = &test_support::point_kind("peer_scaling");
  const auto points =
      test_support::points_of("peer_scaling",
                              "[params]\nconfigs = 20\n"
                              "batches = 1\nmin_batch_us = 1\n[axes]\nN = [3, 16]\n");
  ASSERT_EQ(points.size(), 2u);
  const auto col = [&](const std::string& name) { return test_support::column(*fn, name); };
  for (const auto& p : points) {
    fn->check(p);
    const sweeps::PointResult r = fn->run(p);
    ASSERT_FALSE(r.failed) << r.message;
    ASSERT_EQ(r.rows.size(), 20u);
    int same_contacts = 0;
    for (const auto& row : r.rows) {
      ASSERT_EQ(row.size(), fn->columns.size());
      const double ours = std::get<double>(row[col("time_ours_ns")]);
      EXPECT_GT(ours, 0.0);
      EXPECT_LT(ours, 1e7);
      const long long contacts = std::get<long long>(row[col("contacts")]);
      EXPECT_GE(contacts, 3);
#ifdef SLIPWALK_HAVE_MUJOCO
      const double mj = std::get<double>(row[col("time_mujoco_ns")]);
      EXPECT_GT(mj, 0.0);
      EXPECT_LT(mj, 1e8);
      EXPECT_LT(std::get<double>(row[col("time_rewind_ns")]), mj);
      EXPECT_EQ(std::get<long long>(row[col("unreachable")]), 0);
      EXPECT_GE(std::get<long long>(row[col("mujoco_iter")]), 0);
      same_contacts += std::get<long long>(row[col("mujoco_contacts")]) == contacts ? 1 : 0;
      EXPECT_EQ(std::get<std::string>(row[col("message")]), "");
#else
      EXPECT_TRUE(std::isnan(std::get<double>(row[col("time_mujoco_ns")])));
      EXPECT_NE(std::get<std::string>(row[col("message")]).find("without MuJoCo"),
                std::string::npos);
      ++same_contacts;
#endif
    }
    EXPECT_GE(same_contacts, 18);  // the rare foot within 1e-4 m of the floor may differ
    // Run again: every value column (MuJoCo's contacts and iterations included) is the same to
    // the bit, so the CSV under --no-timing is.
    EXPECT_EQ(test_support::first_value_difference(*fn, r, fn->run(p)), "");
  }
}

}  // namespace
}  // namespace slipwalk::peers::mujoco
