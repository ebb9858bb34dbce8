// The built-in walkers of robots/robots.hpp: every walker's foot velocities against
// central differences of its positions, sizes and phases, no allocation in the callables, option
// validation, and each robot's own oracles (Multipod: the mean body frame's sums and the rigid leg
// pairs; quadruped: stance lines, diagonal pairs and mirror symmetry; disk: rim geometry).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "robots/multipod.hpp"
#include "robots/robots.hpp"
#include "support/count_allocations.hpp"

namespace slipwalk::robots {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<Walker> all_walkers() {
  std::vector<Walker> w;
  w.push_back(bigant_tripod());
  TripodGait steer;
  steer.steer = -0.7;
  steer.duty = 0.6;
  steer.frequency = 0.25;
  w.push_back(bigant_tripod(steer));
  w.push_back(bigant_metachronal());
  for (int n : {6, 8, 10, 12}) {
    for (double dphi : {0.2, 1.0, 1.35, 1.8}) {
      UndulationGait g;
      g.legs = n;
      g.dphi = dphi * kPi;
      g.frequency = n == 6 ? 0.3 : 2.4;
      w.push_back(multipod(g));
    }
  }
  w.push_back(quadruped_trot());
  for (int n : {3, 6, 50}) {
    DiskGait g;
    g.legs = n;
    w.push_back(disk_robot(g));
  }
  return w;
}

TEST(Walkers, SizesNamesPeriodsAndRobots) {
  for (const Walker& w : all_walkers()) {
    SCOPED_TRACE(w.name);
    EXPECT_NO_THROW(contact::validate(w.robot));
    EXPECT_EQ(static_cast<int>(w.leg_names.size()), w.legs());
    EXPECT_GT(w.period, 0.0);
    EXPECT_TRUE(static_cast<bool>(w.feet));
    EXPECT_TRUE(static_cast<bool>(w.phase));
  }
  EXPECT_EQ(bigant_tripod().leg_names,
            (std::vector<std::string>{"HL", "ML", "FL", "HR", "MR", "FR"}));
  EXPECT_EQ(multipod().leg_names, (std::vector<std::string>{"L1", "L2", "L3", "R1", "R2", "R3"}));
  EXPECT_DOUBLE_EQ(bigant_tripod().period, 10.0);  // 0.1 Hz (§3.5.1.4)
}

TEST(Walkers, FootVelocitiesAreTheDerivativesOfThePositions) {
  for (const Walker& w : all_walkers()) {
    SCOPED_TRACE(w.name);
    const int n = w.legs();
    Eigen::Matrix3Xd q(3, n), qd(3, n), lo(3, n), hi(3, n), dlo(3, n), dhi(3, n);
    const double h = 1e-6 * w.period;
    int checked = 0;
    for (int k = 0; k < 400; ++k) {
      const double t = w.period * (-1.0 + 3.0 * (k + 0.5) / 400.0);
      w.feet(t, q, qd);
      w.feet(t - h, lo, dlo);
      w.feet(t + h, hi, dhi);
      // Gait clocks switch rates at touchdown and lift-off; skip samples that straddle one.
      if ((dhi - dlo).norm() > 1e-3 * qd.norm()) {
        continue;
      }
      ++checked;
      const Eigen::Matrix3Xd fd = (hi - lo) / (2 * h);
      EXPECT_LE((fd - qd).norm(), 1e-6 * qd.norm()) << "t " << t;
    }
    EXPECT_GT(checked, 360);  // at most a tenth of the samples are near a switch
  }
}

TEST(Walkers, PhasesAreInTheUnitIntervalAndPeriodic) {
  for (const Walker& w : all_walkers()) {
    SCOPED_TRACE(w.name);
    const int n = w.legs();
    Eigen::VectorXd p(n), p2(n);
    Eigen::Matrix3Xd q(3, n), qd(3, n), q2(3, n), qd2(3, n);
    for (int k = 0; k < 50; ++k) {
      const double t = w.period * 0.0217 * k;
      w.phase(t, p);
      EXPECT_GE(p.minCoeff(), 0.0);
      EXPECT_LT(p.maxCoeff(), 1.0);
      w.feet(t, q, qd);
      w.feet(t + w.period, q2, qd2);  // one period later the feet are where they were
      EXPECT_LT((q2 - q).norm(), 1e-12);
      EXPECT_LT((qd2 - qd).norm(), 1e-9 * (1.0 + qd.norm()));
    }
  }
}

TEST(Walkers, CallablesDoNotAllocate) {
  for (const Walker& w : all_walkers()) {
    SCOPED_TRACE(w.name);
    const int n = w.legs();
    Eigen::Matrix3Xd q(3, n), qd(3, n);
    Eigen::VectorXd p(n);
    const long long before = slipwalk::testing::allocation_count();
    for (int k = 0; k < 100; ++k) {
      w.feet(0.013 * k, q, qd);
      w.phase(0.013 * k, p);
    }
    EXPECT_EQ(slipwalk::testing::allocation_count(), before);
  }
  // The counter works.
  const long long before = slipwalk::testing::allocation_count();
  const Walker copy = multipod();
  EXPECT_GT(slipwalk::testing::allocation_count(), before);
}

// ---- option validation ------------------------------------------------------------------------

std::string error_at(const std::function<void()>& make) {
  try {
    make();
  } catch (const core::InputError& e) {
    return e.where();
  }
  return "(no error)";
}

TEST(Options, BadValuesThrowInputErrorNamingTheOption) {
  const double nan = std::nan("");
  auto tripod = [](TripodGait g) { return [g] { (void)bigant_tripod(g); }; };
  EXPECT_EQ(error_at(tripod({})), "(no error)");
  EXPECT_EQ(error_at(tripod({0.0, 0.0, 0.55, 0.35})), "bigant_tripod.frequency");
  EXPECT_EQ(error_at(tripod({-1.0, 0.0, 0.55, 0.35})), "bigant_tripod.frequency");
  EXPECT_EQ(error_at(tripod({nan, 0.0, 0.55, 0.35})), "bigant_tripod.frequency");
  EXPECT_EQ(error_at(tripod({0.1, 1.5, 0.55, 0.35})), "bigant_tripod.steer");
  EXPECT_EQ(error_at(tripod({0.1, 0.0, 0.45, 0.35})), "bigant_tripod.duty");
  EXPECT_EQ(error_at(tripod({0.1, 0.0, 1.0, 0.35})), "bigant_tripod.duty");
  EXPECT_EQ(error_at(tripod({0.1, 0.0, 0.55, 0.0})), "bigant_tripod.sweep");
  EXPECT_EQ(error_at(tripod({0.1, 0.0, 0.55, 0.65})), "bigant_tripod.sweep");

  auto meta = [](MetachronalGait g) { return [g] { (void)bigant_metachronal(g); }; };
  EXPECT_EQ(error_at(meta({})), "(no error)");
  EXPECT_EQ(error_at(meta({0.0, 0.35})), "bigant_metachronal.frequency");
  EXPECT_EQ(error_at(meta({0.1, 0.7})), "bigant_metachronal.sweep");
  EXPECT_EQ(error_at(meta({0.1, 0.0})), "bigant_metachronal.sweep");

  auto pod = [](UndulationGait g) { return [g] { (void)multipod(g); }; };
  EXPECT_EQ(error_at(pod({})), "(no error)");
  for (int legs : {0, 4, 7, 14}) {
    UndulationGait g;
    g.legs = legs;
    EXPECT_EQ(error_at(pod(g)), "multipod.legs") << legs;
  }
  UndulationGait g;
  g.frequency = 0.0;
  EXPECT_EQ(error_at(pod(g)), "multipod.frequency");
  g = {};
  g.dphi = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_at(pod(g)), "multipod.dphi");
  g = {};
  g.roll_amplitude = -0.1;
  EXPECT_EQ(error_at(pod(g)), "multipod.roll_amplitude");
  g.roll_amplitude = kPi / 2;
  EXPECT_EQ(error_at(pod(g)), "multipod.roll_amplitude");
  g = {};
  g.yaw_amplitude = 1.0;
  EXPECT_EQ(error_at(pod(g)), "multipod.yaw_amplitude");
  g = {};
  g.stiffness = 0.0;
  EXPECT_EQ(error_at(pod(g)), "multipod.stiffness");

  auto trot = [](TrotGait t) { return [t] { (void)quadruped_trot(t); }; };
  EXPECT_EQ(error_at(trot({})), "(no error)");
  EXPECT_EQ(error_at(trot({-2.0, 0.55, 0.15, 0.06})), "quadruped_trot.frequency");
  EXPECT_EQ(error_at(trot({1.0, 0.4, 0.15, 0.06})), "quadruped_trot.duty");
  EXPECT_EQ(error_at(trot({1.0, 0.55, 0.0, 0.06})), "quadruped_trot.stride");
  EXPECT_EQ(error_at(trot({1.0, 0.55, 0.15, 0.5})), "quadruped_trot.swing_height");

  auto disk = [](DiskGait d) { return [d] { (void)disk_robot(d); }; };
  EXPECT_EQ(error_at(disk({})), "(no error)");
  EXPECT_EQ(error_at(disk({2, 0.3, 1.0})), "disk_robot.legs");
  EXPECT_EQ(error_at(disk({6, 0.0, 1.0})), "disk_robot.radius");
  EXPECT_EQ(error_at(disk({6, 0.3, nan})), "disk_robot.frequency");
}

// ---- Multipod ---------------------------------------------------------------------------------

UndulationGait fig3_11(int legs) {  // the thesis' Fig. 3.11 gait: 0.3 Hz, Δφ = 1.35π
  UndulationGait g;
  g.legs = legs;
  g.frequency = 0.3;
  g.dphi = 1.35 * kPi;
  return g;
}

TEST(Multipod, MeanBodyFrameCentresTheModules) {
  // In the mean frame the module centres sum to zero and the module headings average zero. A
  // module's centre and heading are read back from its two feet: the pair is rigid, so the left
  // minus the right foot is 2w cos θ_r along the module's normal, and the midpoint is the centre
  // shifted by h sin θ_r along that normal.
  const MultipodGeometry geo;
  for (int legs : {6, 8, 10, 12}) {
    const UndulationGait g = fig3_11(legs);
    const Walker w = multipod(g);
    const int n = legs / 2;
    Eigen::Matrix3Xd q(3, legs), qd(3, legs);
    for (int k = 0; k < 40; ++k) {
      const double t = 0.0813 * k;
      w.feet(t, q, qd);
      Eigen::Vector2d centres = Eigen::Vector2d::Zero();
      double headings = 0.0;
      for (int i = 0; i < n; ++i) {
        const double roll = g.roll_amplitude * std::sin(2 * kPi * g.frequency * t + i * g.dphi);
        const Eigen::Vector3d across = q.col(i) - q.col(i + n);
        EXPECT_NEAR(across.head<2>().norm(), 2 * geo.foot_lateral * std::cos(roll), 1e-12);
        EXPECT_NEAR(across.z(), 2 * geo.foot_lateral * std::sin(roll), 1e-12);
        const Eigen::Vector2d normal = across.head<2>().normalized();
        centres +=
            0.5 * (q.col(i) + q.col(i + n)).head<2>() - geo.foot_depth * std::sin(roll) * normal;
        headings += std::atan2(-normal.x(), normal.y());
      }
      EXPECT_LT(centres.norm(), 1e-12) << legs << " legs, t " << t;
      EXPECT_NEAR(headings, 0.0, 1e-12);
    }
  }
}

TEST(Multipod, WithoutRollTheFootVelocitiesSumToZero) {
  // With θ_r,0 = 0 each pair's midpoint is its module centre, so Σ q = 0 and Σ q̇ = 0 in the
  // mean frame at every instant, whatever the yaw motion.
  for (int legs : {6, 12}) {
    UndulationGait g = fig3_11(legs);
    g.roll_amplitude = 0.0;
    const Walker w = multipod(g);
    Eigen::Matrix3Xd q(3, legs), qd(3, legs);
    for (int k = 0; k < 40; ++k) {
      w.feet(0.0917 * k, q, qd);
      EXPECT_LT(q.topRows<2>().rowwise().sum().norm(), 1e-12);
      EXPECT_LT(qd.topRows<2>().rowwise().sum().norm(), 1e-12);
      EXPECT_GT(qd.norm(), 0.01);  // the feet do move
    }
  }
}

TEST(Multipod, FeetFromJointsAreTheGaitsFeetWhenTheJointsAreTheGaits) {
  // multipod_feet is the gait's joints through multipod_feet_from_joints: the same numbers.
  const MultipodGeometry geo;
  const UndulationGait g = fig3_11(8);
  Eigen::Matrix3Xd joints(3, 4), rates(3, 4);
  Eigen::Matrix3Xd q1(3, 8), qd1(3, 8), q2(3, 8), qd2(3, 8);
  for (int k = 0; k < 20; ++k) {
    const double t = 0.173 * k;
    multipod_gait_joints(g, t, joints, rates);
    multipod_feet_from_joints(geo, joints, rates, q1, qd1);
    multipod_feet(geo, g, t, q2, qd2);
    EXPECT_EQ(q1, q2);
    EXPECT_EQ(qd1, qd2);
  }
}

TEST(Multipod, FootVelocitiesFromUnequalYawJointsAreTheDerivativeOfTheFeet) {
  // A measured robot's two yaw joints differ: along a joint path with θ_y1 ≠ θ_y2 (each joint
  // its own frequency and phase) the analytic q̇ equals the central difference of q (h = 1e-5 s,
  // error O(h²) ≈ 1e-9 for these rates).
  const MultipodGeometry geo;
  const int n = 5;
  auto path = [n](double t, Eigen::Matrix3Xd& joints, Eigen::Matrix3Xd& rates) {
    for (int i = 0; i < n; ++i) {
      for (int r = 0; r < 3; ++r) {
        const double w = 1.0 + 0.37 * r + 0.21 * i;
        const double a = 0.3 - 0.05 * r;
        joints(r, i) = a * std::sin(w * t + 0.7 * i + r);
        rates(r, i) = a * w * std::cos(w * t + 0.7 * i + r);
      }
    }
  };
  Eigen::Matrix3Xd joints(3, n), rates(3, n), q(3, 2 * n), qd(3, 2 * n);
  Eigen::Matrix3Xd qp(3, 2 * n), qm(3, 2 * n), unused(3, 2 * n);
  const double h = 1e-5;
  for (int k = 0; k < 10; ++k) {
    const double t = 0.31 * k;
    path(t, joints, rates);
    ASSERT_GT((joints.row(0) - joints.row(2)).norm(), 0.01);
    multipod_feet_from_joints(geo, joints, rates, q, qd);
    path(t + h, joints, rates);
    multipod_feet_from_joints(geo, joints, rates, qp, unused);
    path(t - h, joints, rates);
    multipod_feet_from_joints(geo, joints, rates, qm, unused);
    const Eigen::Matrix3Xd fd = (qp - qm) / (2 * h);
    EXPECT_LT((fd - qd).cwiseAbs().maxCoeff(), 1e-8) << "t " << t;
  }
}

TEST(Multipod, StandingStraightIsARectangleOfFeet) {
  UndulationGait g = fig3_11(8);
  g.roll_amplitude = 0.0;
  g.yaw_amplitude = 0.0;
  const Walker w = multipod(g);
  Eigen::Matrix3Xd q(3, 8), qd(3, 8);
  w.feet(1.7, q, qd);
  for (int i = 0; i < 4; ++i) {
    const double x = 0.12 * (1.5 - i);  // module pitch 0.07 + 0.05 m, head first
    EXPECT_LT((q.col(i) - Eigen::Vector3d(x, 0.12, -0.08)).norm(), 1e-14);
    EXPECT_LT((q.col(i + 4) - Eigen::Vector3d(x, -0.12, -0.08)).norm(), 1e-14);
  }
  EXPECT_EQ(qd.norm(), 0.0);
}

TEST(Multipod, RollLiftsOneSideAndPhasesFollowTheModules) {
  const UndulationGait g = fig3_11(6);
  const Walker w = multipod(g);
  Eigen::Matrix3Xd q(3, 6), qd(3, 6);
  Eigen::VectorXd phase(6);
  for (int k = 0; k < 20; ++k) {
    const double t = 0.173 * k;
    w.feet(t, q, qd);
    w.phase(t, phase);
    for (int i = 0; i < 3; ++i) {
      const double s = g.frequency * t + i * g.dphi / (2 * kPi);
      EXPECT_NEAR(phase(i), s - std::floor(s), 1e-12);
      EXPECT_EQ(phase(i), phase(i + 3));
      // θ_r > 0 (sin > 0) lifts the left foot above the right one.
      EXPECT_EQ(q(2, i) > q(2, i + 3), std::sin(2 * kPi * s) > 0.0);
    }
  }
  EXPECT_EQ(w.robot.Mg, 6.0);  // Mg = N, μ = 1 (§3.5.2.1)
  EXPECT_EQ(w.robot.mu.minCoeff(), 1.0);
}

// ---- quadruped and disk -----------------------------------------------------------------------

TEST(Quadruped, DiagonalPairsTrotOnStanceLines) {
  const TrotGait gait;
  const Walker w = quadruped_trot(gait);
  Eigen::Matrix3Xd q(3, 4), qd(3, 4), q2(3, 4), qd2(3, 4);
  const Eigen::Vector3d mirror(1.0, -1.0, 1.0);
  Eigen::VectorXd phase(4);
  for (int k = 0; k < 100; ++k) {
    const double t = w.period * (k + 0.37) / 100.0;
    w.feet(t, q, qd);
    w.phase(t, phase);
    // [HL, FL, HR, FR]: FL and HR move alike, HL and FR alike, half a cycle apart.
    EXPECT_LT((qd.col(1) - qd.col(2)).norm(), 1e-12);
    EXPECT_LT((qd.col(0) - qd.col(3)).norm(), 1e-12);
    w.feet(t + 0.5 * w.period, q2, qd2);
    EXPECT_LT((q2.col(2) - mirror.cwiseProduct(q.col(0))).norm(), 1e-12);  // HR(t + T/2) = M HL(t)
    for (int j = 0; j < 4; ++j) {
      // Phase 0 is mid-stance. Stance: on the line z = −0.30, backward at stride · f / duty;
      // swing: above the line, forward.
      const double since_touchdown = std::fmod(phase(j) + 0.5 * gait.duty, 1.0);
      if (since_touchdown < gait.duty) {
        EXPECT_EQ(q(2, j), -0.30);
        EXPECT_NEAR(qd(0, j), -gait.stride * gait.frequency / gait.duty, 1e-12);
        EXPECT_EQ(qd(2, j), 0.0);
      } else {
        EXPECT_GT(q(2, j), -0.30);
        EXPECT_GT(qd(0, j), 0.0);
      }
    }
  }
  // At t = 0 the pair {FL, HR} is in mid-stance and carries the robot alone.
  contact::Frame f(w.robot);
  w.feet(0.0, f.q, f.qdot);
  contact::spring_support(w.robot, f);
  EXPECT_EQ(f.contact, (std::vector<char>{0, 1, 1, 0}));
}

TEST(Disk, LegsOnTheRimAndScatteredPhases) {
  for (int n : {3, 6, 50}) {
    DiskGait g;
    g.legs = n;
    const Walker w = disk_robot(g);
    Eigen::Matrix3Xd q(3, n), qd(3, n), mean = Eigen::Matrix3Xd::Zero(3, n);
    const int samples = 64;
    for (int k = 0; k < samples; ++k) {
      w.feet(w.period * k / samples, q, qd);
      mean += q / samples;
    }
    for (int j = 0; j < n; ++j) {  // each ellipse is centred on its hip on the rim
      const double a = 2 * kPi * j / n;
      EXPECT_LT((mean.col(j) - Eigen::Vector3d(0.3 * std::cos(a), 0.3 * std::sin(a), -0.09)).norm(),
                1e-12);
    }
    // The robot stands at every sampled pose: balanced, on three or more feet or (even N, two
    // opposite feet low together) on a line through the centre.
    contact::Frame f(w.robot);
    for (int k = 0; k < 32; ++k) {
      w.feet(w.period * (k + 0.5) / 32, f.q, f.qdot);
      contact::spring_support(w.robot, f);
      EXPECT_TRUE(f.support.status == contact::SupportSummary::Status::kBalanced ||
                  f.support.status == contact::SupportSummary::Status::kLine)
          << n << " legs: " << contact::status_name(f.support.status);
      EXPECT_LT(f.support.residual, 1e-9);
    }
  }
}

}  // namespace
}  // namespace slipwalk::robots
