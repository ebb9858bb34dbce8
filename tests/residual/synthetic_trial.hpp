#pragma once
// A motion trial made by the template itself (thesis §5.3.1 with a known truth): the Multipod
// walks its undulation gait (robots::multipod_gait_joints, §5.3.2) and its pose follows
//   g̊ = A(q) q̇ + B q̇ + d
// (the template's local connection, eq. 3.20, plus a chosen residual B and a constant body twist
// d), integrated on SE(2) by the midpoint rule at `substeps` steps per sample interval: each step
// holds the twist of its midpoint, pose ← pose · exp(g̊(t + h/2) h) (core/se2.hpp), second order in
// h. The trial records the pose and the gait's joint angles at the sample times, as motion capture
// and the encoders would.
#include <Eigen/Core>
#include <numbers>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/spring_support.hpp"
#include "core/se2.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"
#include "robots/multipod.hpp"
#include "robots/robots.hpp"

namespace slipwalk::testing {

struct SyntheticOptions {
  int legs = 8;
  double frequency = 1.2;                           ///< Hz
  double dphi = std::numbers::pi;                   ///< rad
  double sample_rate = 125.0;                       ///< Hz
  long long samples = 252;                          ///< n
  int substeps = 16;                                ///< integration steps per sample interval
  Eigen::Matrix<double, 3, Eigen::Dynamic> B;       ///< 3 × 2K, or empty for none
  Eigen::Vector3d drift = Eigen::Vector3d::Zero();  ///< d, body frame (m/s, m/s, rad/s)
};

struct SyntheticTrial {
  residual::MotionTrial trial;
  Eigen::MatrixX3d v_exact;     ///< (n × 3) g̊ at the sample times
  Eigen::MatrixX3d v_template;  ///< (n × 3) A(q) q̇ at the sample times (analytic q̇)
  Eigen::MatrixXd qdot;         ///< (n × 2K) analytic vec(q̇_xy)
  /// (n) whether the template's contact set stays the same over [t_{j−1}, t_{j+1}] (at every
  /// integration midpoint and sample time in it): where g̊(t) is smooth. A contact change puts a
  /// kink into g̊ (the loads are continuous, their rates are not), and a central difference
  /// across a kink is first order only.
  std::vector<bool> smooth;
};

inline SyntheticTrial make_synthetic_trial(const SyntheticOptions& o) {
  robots::UndulationGait gait;
  gait.legs = o.legs;
  gait.frequency = o.frequency;
  gait.dphi = o.dphi;
  const residual::TemplateRobot model = residual::multipod_template(o.legs);
  const int modules = o.legs / 2;
  const auto n = static_cast<Eigen::Index>(o.samples);
  contact::Frame frame(model.robot);
  std::vector<char> last_contact;
  Eigen::Vector3d v_templ = Eigen::Vector3d::Zero();
  // g̊ at time t; also whether the contact set differs from the previous evaluation's.
  const auto twist = [&](double t, bool& changed) {
    robots::multipod_feet(model.geometry, gait, t, frame.q, frame.qdot);
    contact::spring_support(model.robot, frame);
    connection::local_connection(model.robot, frame);
    changed = !last_contact.empty() && frame.contact != last_contact;
    last_contact = frame.contact;
    v_templ.setZero();
    Eigen::Vector3d extra = o.drift;
    for (int k = 0; k < o.legs; ++k) {
      v_templ += frame.A.col(2 * k) * frame.qdot(0, k) + frame.A.col(2 * k + 1) * frame.qdot(1, k);
      if (o.B.size() > 0) {
        extra += o.B.col(2 * k) * frame.qdot(0, k) + o.B.col(2 * k + 1) * frame.qdot(1, k);
      }
    }
    return Eigen::Vector3d(v_templ + extra);
  };

  SyntheticTrial s;
  residual::MotionTrial& trial = s.trial;
  trial.label = "synthetic";
  trial.t.resize(n);
  trial.pose.resize(n, 3);
  trial.joints.resize(n, 3 * modules);
  s.v_exact.resize(n, 3);
  s.v_template.resize(n, 3);
  s.qdot.resize(n, 2 * o.legs);
  std::vector<bool> kink(static_cast<std::size_t>(n), false);  // interval j: [t_j, t_{j+1}]
  robots::MultipodJoints joints(3, modules);
  robots::MultipodJoints rates(3, modules);
  core::Pose2 pose;
  const double dt = 1.0 / o.sample_rate;
  const double h = dt / o.substeps;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double t = static_cast<double>(j) * dt;
    trial.t(j) = t;
    trial.pose.row(j) << pose.x, pose.y, pose.theta;
    robots::multipod_gait_joints(gait, t, joints, rates);
    for (int i = 0; i < modules; ++i) {
      trial.joints.row(j).segment(3 * i, 3) = joints.col(i).transpose();
    }
    bool changed = false;
    s.v_exact.row(j) = twist(t, changed).transpose();
    s.v_template.row(j) = v_templ.transpose();
    for (int k = 0; k < o.legs; ++k) {
      s.qdot(j, 2 * k) = frame.qdot(0, k);
      s.qdot(j, 2 * k + 1) = frame.qdot(1, k);
    }
    if (changed && j > 0) {
      kink[static_cast<std::size_t>(j - 1)] = true;
    }
    for (int step = 0; step < o.substeps && j + 1 < n; ++step) {
      const double mid = t + (step + 0.5) * h;
      const Eigen::Vector3d v = twist(mid, changed);
      kink[static_cast<std::size_t>(j)] = kink[static_cast<std::size_t>(j)] || changed;
      pose = core::advance(pose, v, h);
    }
  }
  s.smooth.assign(static_cast<std::size_t>(n), false);
  for (Eigen::Index j = 1; j + 1 < n; ++j) {
    s.smooth[static_cast<std::size_t>(j)] =
        !kink[static_cast<std::size_t>(j - 1)] && !kink[static_cast<std::size_t>(j)];
  }
  return s;
}

}  // namespace slipwalk::testing
