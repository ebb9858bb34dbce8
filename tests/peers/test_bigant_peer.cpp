// BigANT in MuJoCo (lib/peers/mujoco/bigant_*; thesis §3.5.4, Fig. 3.14). Without MuJoCo: the
// spec's nominal points, the MJCF text, the actuator targets. With MuJoCo: the MJCF compiles with
// the robot's mass; standing still the feet carry Mg and share it as our spring support does with
// K = kp_z (the same springs, a second method); the feet track the gait within 1 cm in x and y;
// the mirror-symmetric tripod gait does not turn over a cycle; the peer_bigant point gives rows of
// every source. Tests that need MuJoCo are skipped, saying so, in a build without it.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "robots/robots.hpp"
#include "support/point_rows.hpp"
#include "support/skip_without_mujoco.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include "peers/mujoco/bigant_peer.hpp"
#endif

namespace slipwalk::peers::mujoco {
namespace {

/// rad: the most the mirror-symmetric tripod may turn over one gait cycle in MuJoCo.
constexpr double kTurnBound = 0.003;

// ---- without MuJoCo
// ------------------------------------------------------------------------------

TEST(BigAntSpec, NominalPointsAreTheGaitsMeanFeet) {
  const robots::Walker w = robots::bigant_tripod();
  const BigAntPeerSpec spec = bigant_peer_spec(w, 512);
  ASSERT_EQ(spec.legs(), 6);
  EXPECT_EQ(spec.leg_names, w.leg_names);
  EXPECT_NEAR(spec.total_mass, 8.18, 1e-12);
  // Second route: the mean by the trapezoid rule on a finer, shifted grid of the periodic path.
  Eigen::Matrix3Xd mean = Eigen::Matrix3Xd::Zero(3, 6), q(3, 6), qdot(3, 6);
  const int m = 2000;
  for (int i = 0; i < m; ++i) {
    w.feet(w.period * (i + 0.5) / m, q, qdot);
    mean += q / m;
  }
  EXPECT_LT((spec.nominal - mean).cwiseAbs().maxCoeff(), 2e-4);
  // Mirror symmetry of the legs: left and right nominal points mirror in y.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(spec.nominal(1, k), -spec.nominal(1, k + 3), 1e-9);
    EXPECT_NEAR(spec.nominal(0, k), spec.nominal(0, k + 3), 1e-9);
  }
}

TEST(BigAntSpec, MjcfNamesEveryLegAndActuatorAndRejectsBadSpecs) {
  BigAntPeerSpec spec = bigant_peer_spec(robots::bigant_metachronal());
  const std::string xml = bigant_mjcf(spec);
  for (const std::string& leg : spec.leg_names) {
    EXPECT_NE(xml.find("\"" + leg + "_foot\""), std::string::npos) << leg;
    for (const char* axis : {"_x", "_y", "_z"}) {
      EXPECT_NE(xml.find("<position joint=\"" + leg + axis + "\""), std::string::npos);
    }
  }
  EXPECT_NE(xml.find("solver=\"Newton\" iterations=\"100\""), std::string::npos);
  BigAntPeerSpec bad = spec;
  bad.kp_z = 0.0;
  EXPECT_THROW((void)bigant_mjcf(bad), core::InputError);
  bad = spec;
  bad.mu[2] = -1.0;
  EXPECT_THROW((void)bigant_mjcf(bad), core::InputError);
  bad = spec;
  bad.total_mass = 0.1;  // lighter than the legs
  EXPECT_THROW((void)bigant_mjcf(bad), core::InputError);
}

TEST(BigAntSpec, TargetsAreOffsetsFromNominalPlusTheDampingLead) {
  const BigAntPeerSpec spec = bigant_peer_spec(robots::bigant_tripod());
  Eigen::Matrix3Xd q = spec.nominal, qdot(3, 6), targets(3, 6);
  q.row(2).array() -= 0.01;
  qdot.setConstant(0.5);
  bigant_targets(spec, q, qdot, false, targets);
  EXPECT_LT((targets.row(2).array() + 0.01).abs().maxCoeff(), 1e-15);
  EXPECT_LT(targets.topRows<2>().cwiseAbs().maxCoeff(), 1e-15);
  bigant_targets(spec, q, qdot, true, targets);
  EXPECT_NEAR(targets(0, 0), 0.5 * spec.damping / spec.kp_xy, 1e-15);
  EXPECT_NEAR(targets(2, 3), -0.01 + 0.5 * spec.damping / spec.kp_z, 1e-15);
}

// ---- with MuJoCo
// ---------------------------------------------------------------------------------

#ifdef SLIPWALK_HAVE_MUJOCO
/// The study's base peer (studies/ch3_peer/fig3_14.toml): §3.5.4's actuators with the z gain our
/// BigANT's leg stiffness K and a contact stiff against it (solref time constant 5 ms), so that
/// the leg spring is the actuator, as in our model.
BigAntPeerSpec study_spec(const robots::Walker& w) {
  BigAntPeerSpec spec = bigant_peer_spec(w);
  spec.kp_z = w.robot.K(0);
  spec.solref_timeconst = 0.005;
  return spec;
}

/// Our spring support with the legs as stiff as MuJoCo's z actuators, at the gait's time t.
contact::Frame our_support(const robots::Walker& w, double kp_z, double t) {
  contact::Robot robot = w.robot;
  robot.K.setConstant(kp_z);
  contact::Frame f(robot);
  Eigen::Matrix3Xd qdot(3, robot.legs());
  w.feet(t, f.q, qdot);
  contact::spring_support(robot, f);
  return f;
}
#endif

TEST(BigAntPeer, ModelCompilesWithTheRobotsMass) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const BigAntModel model(study_spec(robots::bigant_tripod()));
  const mjModel* m = model.mj();
  EXPECT_EQ(m->nq, 7 + 18);
  EXPECT_EQ(m->nu, 18);
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) {
    mass += m->body_mass[b];
  }
  EXPECT_NEAR(mass, 8.18, 1e-9);
  EXPECT_EQ(m->opt.solver, mjSOL_NEWTON);
  EXPECT_EQ(m->opt.iterations, 100);
#endif
}

TEST(BigAntPeer, StandingStillTheFeetCarryMgAsOurSpringSupportShares) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  for (const robots::Walker& w : {robots::bigant_tripod(), robots::bigant_metachronal()}) {
    // Stiff horizontal legs: on the tilted chassis a leg's load has a component along its x and y
    // slides, and with §3.5.4's kp_xy = 100 N/m the feet sway by millimetres (the tripod's body
    // shifts ~1 cm sideways over them), which the small-angle spring support does not model.
    BigAntPeerSpec spec = study_spec(w);
    spec.kp_xy = 1e4;
    const BigAntModel model(spec);
    BigAntData data(model);
    const contact::Frame ours = our_support(w, spec.kp_z, 0.0);
    ASSERT_EQ(ours.support.status, contact::SupportSummary::Status::kBalanced);
    // Hold the gait's t = 0 feet for 3 s: the body's bounce on the legs decays.
    BigAntDriveOptions options;
    options.settle = 3.0;
    options.duration = 0.01;
    const robots::FootKinematics frozen = [&w](double, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qd) {
      w.feet(0.0, q, qd);
      qd.setZero();
    };
    (void)bigant_drive(model, data, frozen, ours.z, ours.alpha, ours.beta, options, {});
    mj_forward(model.mj(), data.mj());
    bigant_read_legs(model, data);
    const double Mg = w.robot.Mg;
    EXPECT_NEAR(data.Fz.sum(), Mg, 0.005 * Mg) << w.name;
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(data.contact[static_cast<std::size_t>(k)] != 0,
                ours.contact[static_cast<std::size_t>(k)] != 0)
          << w.name << " leg " << k;
      EXPECT_NEAR(data.Fz(k), ours.Fz(k), 0.02 * Mg) << w.name << " leg " << k;
    }
    // MuJoCo's soft contact adds its own sinkage, F_z / k_c with k_c ~ m_foot / (d_c timeconst²)
    // (about 0.7 mm at 5 ms for the tripod's load): the chassis sits that much lower than ours.
    EXPECT_LT(bigant_height(data), ours.z) << w.name;
    EXPECT_GT(bigant_height(data), ours.z - 2e-3) << w.name;
    // At rest the planar forces of the floor on the feet balance (nothing else acts sideways on
    // the robot) and no foot moves over the floor.
    EXPECT_LT(data.Fxy.rowwise().sum().norm(), 1e-3 * Mg) << w.name;
    EXPECT_LT(data.slip.cwiseAbs().maxCoeff(), 1e-3) << w.name;
  }
#endif
}

TEST(BigAntPeer, FootForcesOpposeSlipInsideTheFrictionCone) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // The metachronal gait slips most (§3.5.1.5). Oracles for the per-leg columns: friction
  // dissipates, so a slipping foot's planar force points against its slip (F·u < 0, which also
  // fixes the sign of the contact frame's turn into the world), and MuJoCo's forces lie in its
  // cone, |F_xy| ≤ μ F_z (pyramidal: |f_t1| + |f_t2| ≤ μ f_n); a foot without contact carries
  // nothing.
  const robots::Walker w = robots::bigant_metachronal();
  const BigAntPeerSpec spec = study_spec(w);
  const BigAntModel model(spec);
  BigAntData data(model);
  const contact::Frame start = our_support(w, spec.kp_z, 0.0);
  BigAntDriveOptions options;
  options.duration = 10.0;
  options.sample = 0.02;
  int slipping = 0, against = 0;
  (void)bigant_drive(
      model, data, w.feet, start.z, start.alpha, start.beta, options, [&](const BigAntSample&) {
        for (int k = 0; k < 6; ++k) {
          const Eigen::Vector2d F = data.Fxy.col(k), u = data.slip.col(k);
          if (data.contact[static_cast<std::size_t>(k)] == 0) {
            EXPECT_EQ(F.norm(), 0.0);
            EXPECT_EQ(data.Fz(k), 0.0);
            continue;
          }
          EXPECT_LE(F.norm(),
                    spec.mu[static_cast<std::size_t>(k)] * data.Fz(k) * (1.0 + 1e-6) + 1e-9);
          if (u.norm() > 0.005 && data.Fz(k) > 0.05 * w.robot.Mg) {
            ++slipping;
            against += F.dot(u) < 0.0 ? 1 : 0;
          }
        }
      });
  EXPECT_GT(slipping, 20);  // not vacuous: the gait makes feet slip
  EXPECT_EQ(against, slipping);
#endif
}

TEST(BigAntPeer, FootSlipIsTheFootsDisplacementOverAStep) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // Second route for the slip columns: MuJoCo's Euler step moves positions by h times the new
  // velocities, so a foot geom's displacement over one step, turned into the yaw frame, is the
  // slip that bigant_read_legs gives after the step (up to the chassis' turn within the step).
  // Checked every 0.1 s over half a cycle, the targets held where the drive left them.
  const robots::Walker w = robots::bigant_tripod();
  const BigAntPeerSpec spec = study_spec(w);
  const BigAntModel model(spec);
  BigAntData data(model);
  const contact::Frame start = our_support(w, spec.kp_z, 0.0);
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  const double h = m->opt.timestep;
  double fastest = 0.0;
  for (int i = 1; i <= 50; ++i) {
    BigAntDriveOptions options;
    options.duration = 0.1 * i;
    options.sample = options.duration;
    (void)bigant_drive(model, data, w.feet, start.z, start.alpha, start.beta, options, {});
    mj_forward(m, d);
    Eigen::Matrix2Xd before(2, 6);
    for (int k = 0; k < 6; ++k) {
      const int g = model.foot_geom[static_cast<std::size_t>(k)];
      before.col(k) << d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1];
    }
    mj_step(m, d);
    mj_forward(m, d);
    bigant_read_legs(model, data);
    const double yaw = bigant_pose(data).theta;
    for (int k = 0; k < 6; ++k) {
      const int g = model.foot_geom[static_cast<std::size_t>(k)];
      const Eigen::Vector2d dw((d->geom_xpos[3 * g] - before(0, k)) / h,
                               (d->geom_xpos[3 * g + 1] - before(1, k)) / h);
      const Eigen::Vector2d body(std::cos(yaw) * dw(0) + std::sin(yaw) * dw(1),
                                 -std::sin(yaw) * dw(0) + std::cos(yaw) * dw(1));
      EXPECT_LT((body - data.slip.col(k)).norm(), 1e-4) << "t " << 0.1 * i << " leg " << k;
      fastest = std::max(fastest, body.norm());
    }
  }
  EXPECT_GT(fastest, 0.01);  // swinging feet move: the comparison is not of zeros
#endif
}

TEST(BigAntPeer, FeetTrackTheGaitWithinOneCentimetre) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const robots::Walker w = robots::bigant_tripod();
  const BigAntPeerSpec spec = study_spec(w);
  const BigAntModel model(spec);
  BigAntData data(model);
  const contact::Frame start = our_support(w, spec.kp_z, 0.0);
  BigAntDriveOptions options;
  options.duration = 5.0;  // half a cycle: the swing tripod's whole return
  const BigAntDriveSummary s =
      bigant_drive(model, data, w.feet, start.z, start.alpha, start.beta, options, {});
  const Eigen::Vector3d rmse = s.tracking.rmse();
  EXPECT_LT(rmse(0), 0.01);
  EXPECT_LT(rmse(1), 0.01);
  EXPECT_LT(s.tracking.swing_z_rmse(), 0.01);
  EXPECT_GT(s.tracking.swing_steps.sum(), 0.0);
  // In stance the z error is the leg spring's deflection F_z / kp_z (≈ Mg / 3 / kp_z on a
  // tripod), our model's compression too: present, and not more than a full tripod load's.
  EXPECT_GT(rmse(2), 0.2 * w.robot.Mg / 6.0 / spec.kp_z);
  EXPECT_LT(rmse(2), w.robot.Mg / 3.0 / spec.kp_z);
#endif
}

TEST(BigAntPeer, SymmetricTripodDoesNotTurnOverACycle) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const robots::Walker w = robots::bigant_tripod();
  const BigAntPeerSpec spec = study_spec(w);
  const BigAntModel model(spec);
  BigAntData data(model);
  const contact::Frame start = our_support(w, spec.kp_z, 0.0);
  BigAntDriveOptions options;
  options.duration = w.period;
  double max_abs_theta = 0.0;
  const BigAntDriveSummary s = bigant_drive(
      model, data, w.feet, start.z, start.alpha, start.beta, options, [&](const BigAntSample& x) {
        max_abs_theta = std::max(max_abs_theta, std::abs(x.pose.theta));
      });
  // It walks forward (a stride is 2 × 145 mm of toe travel per cycle) ...
  EXPECT_GT(s.end.x, 0.1);
  // ... and the mirror image of the first half cycle is the second: no net turn, and no more than
  // a few degrees of sway within the cycle.
  EXPECT_LT(std::abs(s.end.theta), kTurnBound);
  EXPECT_LT(max_abs_theta, 0.05);
  EXPECT_LT(std::abs(s.end.y), 0.05 * s.end.x);
#endif
}

TEST(BigAntPeer, PointGivesRowsOfEverySource) {
  const sweeps::PointKind* fn = &test_support::point_kind("peer_bigant");
  const auto points = test_support::points_of(
      "peer_bigant",
      "[params]\nduration = 1.0\n"
      "sample = 0.5\nsettle = 0.2\nkp_z = 2675.0\nsolref_timeconst = 0.005\n[axes]\ngait = "
      "[\"tripod\", \"metachronal\"]\n");
  ASSERT_EQ(points.size(), 2u);
  const auto col = [&](const std::string& name) { return test_support::column(*fn, name); };
  // No measured times: not a timed kind, no timing column; every column named once.
  EXPECT_EQ(fn->timed, sweeps::Timed::kNo);
  const std::vector<std::string> names = fn->column_names();
  for (const sweeps::ColumnInfo& c : fn->columns) {
    EXPECT_FALSE(c.timing) << c.name;
    EXPECT_EQ(std::count(names.begin(), names.end(), c.name), 1) << c.name;
  }
  for (const auto& p : points) {
    fn->check(p);
    const sweeps::PointResult r = fn->run(p);
    ASSERT_FALSE(r.failed) << r.message;
    int ours = 0, mujoco = 0;
    for (const auto& row : r.rows) {
      ASSERT_EQ(row.size(), fn->columns.size());
      const std::string source = std::get<std::string>(row[col("source")]);
      ours += source.rfind("ours_", 0) == 0 ? 1 : 0;
      mujoco += source == "mujoco" ? 1 : 0;
      if (source == "mujoco") {
        EXPECT_LT(std::get<double>(row[col("rmse_x")]), 0.01);
        // The per-leg columns add up to the row's totals.
        double Fz = 0.0;
        double down = 0.0;
        for (const std::string& leg : robots::bigant_tripod().leg_names) {
          Fz += std::get<double>(row[col("Fz_" + leg)]);
          const double contact = std::get<double>(row[col("contact_" + leg)]);
          EXPECT_TRUE(contact == 0.0 || contact == 1.0) << leg << ": " << contact;
          down += contact;
          EXPECT_TRUE(std::isfinite(std::get<double>(row[col("slip_x_" + leg)])));
        }
        EXPECT_NEAR(Fz, std::get<double>(row[col("Fz_sum")]), 1e-9);
        EXPECT_EQ(down, static_cast<double>(std::get<long long>(row[col("contacts")])));
      } else {
        // Our rows carry no per-leg data: every leg's group is NaN.
        for (const std::string& leg : robots::bigant_tripod().leg_names) {
          for (const char* group : {"contact_", "Fz_", "Fx_", "Fy_", "slip_x_", "slip_y_"}) {
            EXPECT_TRUE(std::isnan(std::get<double>(row[col(group + leg)]))) << group << leg;
          }
        }
      }
    }
    EXPECT_EQ(ours, 2 * 3);  // t = 0, 0.5, 1 for both laws
#ifdef SLIPWALK_HAVE_MUJOCO
    EXPECT_EQ(mujoco, 3);
#else
    EXPECT_EQ(mujoco, 0);
    EXPECT_NE(std::get<std::string>(r.rows.front()[col("message")]).find("without MuJoCo"),
              std::string::npos);
#endif
  }
}

}  // namespace
}  // namespace slipwalk::peers::mujoco
