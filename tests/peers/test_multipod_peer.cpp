// The "real" Multipod of thesis §5.3 in MuJoCo (lib/peers/mujoco/multipod_*). Without MuJoCo:
// the asymmetry draw (deterministic, linear in its scale, exactly nominal at scale 0, with the
// documented spreads), the MJCF text, bad specs named. With MuJoCo: the model has the template's
// weight; standing on the 8 feet the load and each spring's compression agree with our spring
// support on the same legs (a second method); the recorded pose is the template's mean frame
// (MuJoCo's feet seen from it are the template's feet from the measured joints); the joints track
// the gait; the symmetric robot walks straight at Δφ = π and the asymmetric one does not.
// Tests that need MuJoCo are skipped, saying so, in a build without it.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <string>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "core/se2.hpp"
#include "peers/mujoco/multipod_spec.hpp"
#include "robots/multipod.hpp"
#include "robots/robots.hpp"
#include "support/skip_without_mujoco.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include "peers/mujoco/multipod_peer.hpp"
#endif

namespace slipwalk::peers::mujoco {
namespace {

/// The message of the InputError `f` throws ("" if it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

/// x from ρ(x) (multipod_spec.hpp's asymmetry_ratio).
double inverse_ratio(double r) { return r >= 1.0 ? r - 1.0 : 1.0 - 1.0 / r; }

// ---- without MuJoCo
// ------------------------------------------------------------------------------

TEST(MultipodAsymmetry, TheRatioIsPositiveAndInvertsItsOwnSign) {
  EXPECT_EQ(asymmetry_ratio(0.0), 1.0);
  EXPECT_EQ(asymmetry_ratio(0.25), 1.25);
  EXPECT_EQ(asymmetry_ratio(-0.25), 0.8);  // 1 / 1.25
  EXPECT_GT(asymmetry_ratio(-100.0), 0.0);
  for (double x : {-2.0, -0.3, 0.0, 0.7}) {
    EXPECT_NEAR(inverse_ratio(asymmetry_ratio(x)), x, 1e-15);
  }
}

TEST(MultipodAsymmetry, ScaleZeroIsExactlyTheSymmetricRobotWhateverTheSeed) {
  for (std::uint64_t seed : {0ULL, 1ULL, 12345ULL}) {
    const MultipodAsymmetry a = draw_asymmetry(8, seed, 0.0);
    for (int k = 0; k < 8; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      EXPECT_EQ(a.stiffness[kk], 1000.0);
      EXPECT_EQ(a.mu[kk], 1.0);
      EXPECT_EQ(a.mount_yaw[kk], 0.0);
      EXPECT_EQ(a.foot_drop[kk], 0.0);
    }
  }
}

TEST(MultipodAsymmetry, DrawsAreDeterministicPerSeedAndLinearInTheScale) {
  const MultipodAsymmetry a = draw_asymmetry(8, 7, 1.0);
  const MultipodAsymmetry b = draw_asymmetry(8, 7, 1.0);
  const MultipodAsymmetry half = draw_asymmetry(8, 7, 0.5);
  const MultipodAsymmetry other = draw_asymmetry(8, 8, 1.0);
  EXPECT_EQ(a.stiffness, b.stiffness);
  EXPECT_EQ(a.mu, b.mu);
  EXPECT_EQ(a.mount_yaw, b.mount_yaw);
  EXPECT_EQ(a.foot_drop, b.foot_drop);
  EXPECT_NE(a.stiffness, other.stiffness);
  for (std::size_t k = 0; k < 8; ++k) {
    // The same z at both scales: the offsets from nominal halve.
    EXPECT_NEAR(inverse_ratio(half.stiffness[k] / 1000.0),
                0.5 * inverse_ratio(a.stiffness[k] / 1000.0), 1e-12);
    EXPECT_NEAR(inverse_ratio(half.mu[k]), 0.5 * inverse_ratio(a.mu[k]), 1e-12);
    EXPECT_NEAR(half.mount_yaw[k], 0.5 * a.mount_yaw[k], 1e-15);
    EXPECT_NEAR(half.foot_drop[k], 0.5 * a.foot_drop[k], 1e-15);
  }
}

TEST(MultipodAsymmetry, DrawsHaveTheDocumentedSpreadsAndStayBounded) {
  // 4000 seeds × 8 legs: the sample standard deviation of z within 3 % of 1, its mean within
  // 0.03 (standard errors ≈ 0.6 % and 0.006), every z within ±2√3.
  const double bound = 2.0 * std::sqrt(3.0);
  double sum[4] = {0, 0, 0, 0}, sum_sq[4] = {0, 0, 0, 0};
  int n = 0;
  for (std::uint64_t seed = 0; seed < 4000; ++seed) {
    const MultipodAsymmetry a = draw_asymmetry(8, seed, 1.0);
    for (std::size_t k = 0; k < 8; ++k) {
      const double z[4] = {inverse_ratio(a.stiffness[k] / 1000.0) / kStiffnessSpread,
                           inverse_ratio(a.mu[k]) / kFrictionSpread,
                           a.mount_yaw[k] / kMountYawSpread, a.foot_drop[k] / kFootDropSpread};
      for (int p = 0; p < 4; ++p) {
        ASSERT_LE(std::abs(z[p]), bound + 1e-12);
        sum[p] += z[p];
        sum_sq[p] += z[p] * z[p];
      }
      ++n;
    }
  }
  for (int p = 0; p < 4; ++p) {
    const double mean = sum[p] / n;
    EXPECT_NEAR(mean, 0.0, 0.03) << p;
    EXPECT_NEAR(std::sqrt(sum_sq[p] / n - mean * mean), 1.0, 0.03) << p;
  }
}

TEST(MultipodSpec, MjcfNamesEveryJointActuatorAndFoot) {
  const MultipodPeerSpec spec = multipod_peer_spec(8, 1, 1.0);
  const std::string xml = multipod_mjcf(spec);
  for (int i = 1; i <= 4; ++i) {
    for (const char* j : {"yaw1_", "roll_", "yaw2_"}) {
      EXPECT_NE(xml.find("<position joint=\"" + std::string(j) + std::to_string(i) + "\""),
                std::string::npos);
    }
  }
  for (const std::string leg : {"L1", "L4", "R1", "R4"}) {
    EXPECT_NE(xml.find("name=\"" + leg + "_spring\""), std::string::npos) << leg;
    EXPECT_NE(xml.find("<geom name=\"" + leg + "_foot\""), std::string::npos) << leg;
  }
  EXPECT_EQ(xml.find("forcerange"), std::string::npos);  // unlimited motors by default
  MultipodPeerSpec limited = spec;
  limited.torque_limit = 1.5;
  EXPECT_NE(multipod_mjcf(limited).find("forcelimited=\"true\" forcerange=\"-1.5 1.5\""),
            std::string::npos);
  EXPECT_EQ(multipod_leg_name(8, 0), "L1");
  EXPECT_EQ(multipod_leg_name(8, 7), "R4");
  // The weight is the template's N newtons, the sections carry what the other bodies leave.
  EXPECT_NEAR(spec.weight, 8.0, 0.0);
  EXPECT_GT(spec.section_mass(), 0.0);
}

TEST(MultipodSpec, BadSpecsThrowNamingTheField) {
  const MultipodPeerSpec good = multipod_peer_spec(8, 1, 1.0);
  MultipodPeerSpec bad = good;
  bad.kp = 0.0;
  EXPECT_NE(input_error([&] { (void)multipod_mjcf(bad); }).find("multipod peer spec.kp"),
            std::string::npos);
  bad = good;
  bad.asymmetry.mu[3] = -0.1;
  EXPECT_NE(input_error([&] { (void)multipod_mjcf(bad); }).find("asymmetry.mu[3]"),
            std::string::npos);
  bad = good;
  bad.asymmetry.stiffness.pop_back();
  EXPECT_NE(input_error([&] { validate(bad); }).find("asymmetry"), std::string::npos);
  bad = good;
  bad.weight = 0.5;  // lighter than feet, leg pairs, connectors and stubs
  EXPECT_NE(input_error([&] { validate(bad); }).find(".weight"), std::string::npos);
  bad = good;
  bad.timestep = 0.005;
  EXPECT_NE(input_error([&] { validate(bad); }).find(".timestep"), std::string::npos);
  EXPECT_NE(input_error([] { (void)draw_asymmetry(8, 1, -0.1); }).find("asymmetry.scale"),
            std::string::npos);
  EXPECT_NE(input_error([] { (void)draw_asymmetry(8, 1, 2.5); }).find("asymmetry.scale"),
            std::string::npos);
  EXPECT_NE(input_error([] { (void)draw_asymmetry(7, 1, 1.0); }).find("multipod.legs"),
            std::string::npos);
}

// ---- with MuJoCo
// ---------------------------------------------------------------------------------

#ifdef SLIPWALK_HAVE_MUJOCO

robots::UndulationGait gait8(double frequency, double dphi_pi) {
  robots::UndulationGait g;
  g.legs = 8;
  g.frequency = frequency;
  g.dphi = dphi_pi * std::numbers::pi;
  return g;
}

/// MuJoCo's foot centres (world) seen from `pose`, planar (2 × N).
Eigen::Matrix2Xd feet_in(const MultipodModel& model, const MultipodData& data,
                         const core::Pose2& pose) {
  Eigen::Matrix2Xd out(2, model.legs());
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  for (int k = 0; k < model.legs(); ++k) {
    const mjtNum* p = data.mj()->geom_xpos +
                      3 * static_cast<std::ptrdiff_t>(model.foot_geom[static_cast<std::size_t>(k)]);
    const double dx = p[0] - pose.x, dy = p[1] - pose.y;
    out.col(k) << c * dx + s * dy, -s * dx + c * dy;
  }
  return out;
}

/// The template's feet (planar, mean frame) from joint angles.
Eigen::Matrix2Xd template_feet(const robots::MultipodJoints& joints) {
  const auto m = joints.cols();
  Eigen::Matrix3Xd q(3, 2 * m), qdot(3, 2 * m);
  const robots::MultipodJoints rates = robots::MultipodJoints::Zero(3, m);
  robots::multipod_feet_from_joints(robots::MultipodGeometry{}, joints, rates, q, qdot);
  return q.topRows<2>();
}

/// Mean body velocity (v_x, v_y, ω) over the samples from t_from on: the body-frame twist of
/// each sample step, averaged.
Eigen::Vector3d mean_body_velocity(const residual::MotionTrial& trial, double t_from) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (Eigen::Index j = 0; j + 1 < trial.samples(); ++j) {
    if (trial.t(j) < t_from - 1e-9) {
      continue;
    }
    const core::Pose2 a{trial.pose(j, 0), trial.pose(j, 1), trial.pose(j, 2)};
    const core::Pose2 b{trial.pose(j + 1, 0), trial.pose(j + 1, 1), trial.pose(j + 1, 2)};
    const core::Pose2 rel = core::compose(core::inverse(a), b);
    sum += Eigen::Vector3d(rel.x, rel.y, rel.theta) / (trial.t(j + 1) - trial.t(j));
    ++n;
  }
  return sum / n;
}

#endif

TEST(MultipodPeer, ModelCompilesWithTheTemplatesWeight) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const MultipodModel model(multipod_peer_spec(8, 1, 1.0));
  const mjModel* m = model.mj();
  EXPECT_EQ(m->nq, 7 + 12 + 8);  // free joint, 3 motors per module, a spring per leg
  EXPECT_EQ(m->nu, 12);
  EXPECT_NEAR(mj_getTotalmass(m) * 9.81, 8.0, 1e-9);
  EXPECT_EQ(m->opt.cone, mjCONE_ELLIPTIC);
#endif
}

TEST(MultipodPeer, StandingTheFeetCarryTheWeightAsOurSpringSupportSays) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // Symmetric legs: each foot Mg/8. Uneven stiffness and leg lengths: the loads of our spring
  // support (§3.3) on the same legs — a rigid body on springs K_k with feet e_k lower — since the
  // motors hold the chain rigid. The feet hang below the springs: a foot on the floor carries its
  // spring's force K_k s_k (s_k its compression, the slide's qpos) plus its own weight, and the
  // springs carry Mg less the feet's weight (a foot in the air hangs on its spring, which then
  // carries its weight instead: a 0.1 N difference, shared by the others). The roll motors
  // and the contacts are stiffened here: at the default gains their compliance in series with the
  // legs (0.12² m² / kp = 0.07 mm per newton at a foot through its roll joint) moves the uneven
  // robot's loads by up to 0.3 N from the rigid body's.
  for (double scale : {0.0, 1.0}) {
    MultipodPeerSpec spec = multipod_peer_spec(8, 3, scale);
    std::fill(spec.asymmetry.mount_yaw.begin(), spec.asymmetry.mount_yaw.end(), 0.0);
    spec.kp = 2000.0;
    spec.solref_timeconst = 0.002;
    const MultipodModel model(spec);
    MultipodData data(model);
    const robots::MultipodJoints zero = robots::MultipodJoints::Zero(3, 4);
    multipod_place(model, data, zero);
    multipod_hold(model, data, 1.5);
    mj_forward(model.mj(), data.mj());
    multipod_loads(model, data);
    EXPECT_NEAR(data.Fz.sum(), 8.0, 0.01) << scale;

    const double foot_weight = spec.foot_mass * spec.gravity;
    contact::Robot robot = contact::uniform_robot(8, 1000.0, 1.0, 8.0 - 8.0 * foot_weight);
    contact::Frame frame(robot);
    Eigen::Matrix3Xd qdot(3, 8);
    robots::multipod_feet_from_joints(spec.geometry, zero, zero, frame.q, qdot);
    for (int k = 0; k < 8; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      robot.K(k) = spec.asymmetry.stiffness[kk];
      frame.q(2, k) -= spec.asymmetry.foot_drop[kk];
    }
    contact::spring_support(robot, frame);
    int down = 0;
    for (int k = 0; k < 8; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const double spring = data.mj()->qpos[model.qpos_spring[kk]] * spec.asymmetry.stiffness[kk];
      if (data.Fz(k) > 0.0) {
        ++down;
        EXPECT_NEAR(spring + foot_weight, data.Fz(k), 0.01) << k;  // the spring is K_k
      } else {
        EXPECT_NEAR(spring, -foot_weight, 0.01) << k;  // hanging
      }
      const double ours = frame.Fz(k) > 0.0 ? frame.Fz(k) + foot_weight : 0.0;
      EXPECT_NEAR(data.Fz(k), ours, 0.06) << "leg " << k << ", scale " << scale;
      if (scale == 0.0) {
        EXPECT_NEAR(data.Fz(k), 1.0, 0.01) << k;  // Mg / 8
      }
    }
    if (scale == 0.0) {
      EXPECT_EQ(down, 8);
    }
  }
#endif
}

TEST(MultipodPeer, ThePoseIsTheTemplatesMeanFrameOfMujocosSections) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // Placed with arbitrary joint angles (θ_y1 ≠ θ_y2 too), MuJoCo's feet seen from the recorded
  // pose are the template's feet from the same joints: two routes through the kinematics (the
  // template's chain and mean frame; MuJoCo's bodies), exact for the symmetric robot at rest.
  const MultipodModel model(multipod_peer_spec(8, 1, 0.0));
  MultipodData data(model);
  robots::MultipodJoints joints(3, 4);
  for (int trial = 0; trial < 3; ++trial) {
    joints.setRandom();
    joints *= 0.4;
    multipod_place(model, data, joints);
    robots::MultipodJoints measured(3, 4);
    multipod_measured_joints(model, data, measured);
    EXPECT_LT((measured - joints).cwiseAbs().maxCoeff(), 1e-15);
    const core::Pose2 pose = multipod_pose(model, data);
    EXPECT_LT((feet_in(model, data, pose) - template_feet(joints)).cwiseAbs().maxCoeff(), 1e-12);
  }
  // Walking, at the end of a trial: the same within the tilt and the springs' travel (the rolled
  // springs move their feet sideways by a few mm).
  const residual::MotionTrial trial = record_trial(model, data, gait8(1.2, 1.0), {2.0, 125.0, 0.2});
  mj_kinematics(model.mj(), data.mj());
  const Eigen::Index last = trial.samples() - 1;
  const core::Pose2 pose = multipod_pose(model, data);
  EXPECT_NEAR(core::wrap_angle(pose.theta - trial.pose(last, 2)), 0.0, 1e-12);
  EXPECT_NEAR(pose.x, trial.pose(last, 0), 1e-12);
  for (Eigen::Index i = 0; i < 4; ++i) {
    joints.col(i) = trial.joints.block<1, 3>(last, 3 * i).transpose();
  }
  EXPECT_LT((feet_in(model, data, pose) - template_feet(joints)).cwiseAbs().maxCoeff(), 0.01);
#endif
}

TEST(MultipodPeer, TheMeasuredJointsTrackTheGait) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // The stated tracking (multipod_peer.hpp): RMS within 0.005 rad, every sample within 0.02 rad,
  // at 2.4 Hz, the fastest gait.
  const MultipodModel model(multipod_peer_spec(8, 1, 1.0));
  MultipodData data(model);
  const robots::UndulationGait gait = gait8(2.4, 0.9);
  const residual::MotionTrial trial = record_trial(model, data, gait, {4.0, 125.0, 0.3});
  ASSERT_EQ(trial.samples(), 209);  // 4 / 2.4 s at 125 Hz, both ends
  EXPECT_NEAR(trial.t(208), 1.664, 1e-12);
  robots::MultipodJoints target(3, 4), rate(3, 4);
  double sum_sq = 0.0, worst = 0.0;
  for (Eigen::Index j = 0; j < trial.samples(); ++j) {
    robots::multipod_gait_joints(gait, trial.t(j), target, rate);
    for (int i = 0; i < 4; ++i) {
      for (int r = 0; r < 3; ++r) {
        const double e = trial.joints(j, 3 * i + r) - target(r, i);
        sum_sq += e * e;
        worst = std::max(worst, std::abs(e));
      }
    }
  }
  EXPECT_LT(std::sqrt(sum_sq / (12.0 * static_cast<double>(trial.samples()))), 0.005);
  EXPECT_LT(worst, 0.02);
#endif
}

TEST(MultipodPeer, TheSymmetricRobotWalksStraightAndTheAsymmetricOnesDrift) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  // Δφ = π: the gait half a cycle later is the mirror image (every angle changes sign), so the
  // symmetric robot's side velocity and yaw rate average out over a cycle; an asymmetric robot's
  // need not. Drift: the sideways speed of the robot's ends, |v_y| + |ω| L/2 with its length
  // L ≈ 0.43 m, against the forward speed. The first cycle is a transient and is left out. Four
  // asymmetric robots (seeds 1–4): in our runs they drift by 2.5, 5, 10 and 9 % of their forward
  // speed (6.7 % on average; seeds 5 and 6 by 43 and 26 %), the symmetric one by 0.05 %.
  const robots::UndulationGait gait = gait8(0.6, 1.0);
  const TrialOptions options{4.0, 125.0, 0.5};
  const auto drift = [&](std::uint64_t seed, double scale) {
    const MultipodModel model(multipod_peer_spec(8, seed, scale));
    MultipodData data(model);
    const Eigen::Vector3d v =
        mean_body_velocity(record_trial(model, data, gait, options), 1.0 / gait.frequency);
    EXPECT_GT(v.x(), 0.08) << seed << ' ' << scale;  // it walks forward (the template: 0.10 m/s)
    return (std::abs(v.y()) + 0.5 * 0.43 * std::abs(v.z())) / v.x();
  };
  EXPECT_LT(drift(1, 0.0), 0.01);
  double asymmetric = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    asymmetric += drift(seed, 1.0) / 4.0;
  }
  EXPECT_GT(asymmetric, 0.04);
#endif
}

TEST(MultipodPeer, TrialsRepeatExactlyAndBadOptionsThrow) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const MultipodModel model(multipod_peer_spec(8, 2, 1.0));
  MultipodData data(model);
  const TrialOptions options{1.0, 125.0, 0.1};
  const residual::MotionTrial a = record_trial(model, data, gait8(2.4, 0.5), options);
  const residual::MotionTrial b = record_trial(model, data, gait8(2.4, 0.5), options);
  EXPECT_EQ(a.pose, b.pose);  // the data is reset: no memory of the last trial
  EXPECT_EQ(a.joints, b.joints);
  EXPECT_EQ(a.modules(), 4);
  EXPECT_NE(input_error([&] {
              (void)record_trial(model, data, gait8(2.4, 0.5), {1.0, 300.0, 0.1});
            }).find("trial.sample_rate"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              (void)record_trial(model, data, gait8(2.4, 0.5), {0.0, 125.0, 0.1});
            }).find("trial.cycles"),
            std::string::npos);
  // Motors far too stiff for the timestep: the explicit position gain diverges, and the trial
  // says so instead of returning MuJoCo's reset state.
  MultipodPeerSpec unstable = multipod_peer_spec(8, 2, 1.0);
  unstable.kp = 1e7;
  unstable.armature = 0.0;
  unstable.joint_damping = 0.0;
  const MultipodModel bad_model(unstable);
  MultipodData bad_data(bad_model);
  std::string message;
  // MuJoCo's own warning would go to stdout and MUJOCO_LOG.TXT in the working directory: muted
  // while this trial runs (the test reads the count MuJoCo keeps in the data instead).
  void (*const warning)(const char*) = mju_user_warning;
  mju_user_warning = [](const char*) {};
  try {
    (void)record_trial(bad_model, bad_data, gait8(2.4, 0.5), options);
  } catch (const core::ComputationError& e) {
    message = e.what();
  }
  mju_user_warning = warning;
  EXPECT_NE(message.find("MuJoCo Multipod"), std::string::npos) << message;
  robots::UndulationGait six = gait8(1.0, 1.0);
  six.legs = 6;
  EXPECT_NE(
      input_error([&] { (void)record_trial(model, data, six, options); }).find("multipod.legs"),
      std::string::npos);
#endif
}

}  // namespace
}  // namespace slipwalk::peers::mujoco
