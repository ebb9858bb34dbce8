// A plan's shaft angles as foot kinematics (replay_feet.hpp).
#include "planning/replay_feet.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace slipwalk::planning {

namespace {

using core::wrap_turns;

/// The step that holds time t: −1 before the first, S at or after the end, else n with
/// t_n ≤ t < t_{n+1} (t_S = the end). No allocation.
long long step_at(const PlanTrack& track, double t) {
  if (t < track.t.front()) {
    return -1;
  }
  if (t >= track.end_time()) {
    return track.steps();
  }
  const auto it = std::upper_bound(track.t.begin(), track.t.end(), t);
  return static_cast<long long>(it - track.t.begin()) - 1;
}

/// Leg i's shaft angle and its rate at t.
void leg_phase(const PlanTrack& track, long long n, int i, double t, double& phi, double& rate) {
  if (n < 0) {
    phi = track.phi(i, 0);
    rate = 0.0;
  } else if (n >= track.steps()) {
    phi = track.end_phi(i);
    rate = 0.0;
  } else {
    rate = track.speed(i, n);
    phi = wrap_turns(track.phi(i, n) + rate * (t - track.t[static_cast<std::size_t>(n)]));
  }
}

}  // namespace

PlanTrack plan_track(const PlanRobot& robot, const PlanOptions& options, const Goal& goal,
                     const PlanState& start) {
  PlanTrack track;
  track.step_duration = static_cast<double>(options.execute) * options.horizon /
                        static_cast<double>(options.substeps);
  const auto steps = static_cast<Eigen::Index>(std::max<long long>(options.steps, 0));
  track.phi.resize(robot.legs(), steps);
  track.speed.resize(robot.legs(), steps);
  track.t.reserve(static_cast<std::size_t>(steps));
  track.pose.reserve(static_cast<std::size_t>(steps));
  const PlanSummary summary = plan(robot, options, goal, start, [&](const StepRecord& r) {
    const auto n = static_cast<Eigen::Index>(r.step);
    track.t.push_back(r.state.t);
    track.pose.push_back(r.state.pose);
    track.phi.col(n) = r.state.phi;
    track.speed.col(n) = r.choice.speed;
  });
  track.end_pose = summary.end.pose;
  track.end_phi = summary.end.phi;
  return track;
}

void validate(const PlanRobot& robot, const PlanTrack& track) {
  const auto bad = [](const std::string& what) { throw core::InputError("plan track", what); };
  const long long s = track.steps();
  if (s < 1) {
    bad("a replay needs at least one planning step");
  }
  if (!(track.step_duration > 0.0) || !std::isfinite(track.step_duration)) {
    bad("the step duration must be positive");
  }
  if (track.legs() != robot.legs() || track.phi.cols() != s || track.speed.rows() != robot.legs() ||
      track.speed.cols() != s || static_cast<long long>(track.pose.size()) != s ||
      track.end_phi.size() != robot.legs()) {
    bad("phi, speed and end_phi must have one row per leg (" + std::to_string(robot.legs()) +
        ") and as many columns as times (" + std::to_string(s) + ")");
  }
  if (!track.phi.allFinite() || !track.speed.allFinite() || !track.end_phi.allFinite()) {
    bad("shaft angles and speeds must be finite");
  }
  for (long long n = 0; n < s; ++n) {
    const double t = track.t[static_cast<std::size_t>(n)];
    if (!std::isfinite(t) || (n > 0 && !(t > track.t[static_cast<std::size_t>(n - 1)]))) {
      bad("times must be finite and increasing (step " + std::to_string(n) + ")");
    }
  }
}

PlanTrack slowed(PlanTrack track, double factor) {
  if (!(factor >= 1.0) || !std::isfinite(factor)) {
    throw core::InputError("plan track", "a slow-down factor must be >= 1");
  }
  const double t0 = track.t.empty() ? 0.0 : track.t.front();
  for (double& t : track.t) {
    t = t0 + factor * (t - t0);
  }
  track.step_duration *= factor;
  track.speed /= factor;
  return track;
}

void replay_phase(const PlanTrack& track, double t, Eigen::VectorXd& phi) {
  const long long n = step_at(track, t);
  double rate = 0.0;
  for (int i = 0; i < track.legs(); ++i) {
    leg_phase(track, n, i, t, phi(i), rate);
  }
}

robots::Walker replay_walker(const PlanRobot& robot, const PlanTrack& track) {
  validate(robot);
  validate(robot, track);
  robots::Walker w;
  w.name = robot.name + "_plan_replay";
  w.robot = robot.robot;
  w.leg_names = robot.leg_names;
  w.period = track.end_time() - track.t.front();
  w.feet = [toe = robot.toe, track](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    const long long n = step_at(track, t);
    Eigen::Vector3d dq_dphi;
    for (int i = 0; i < track.legs(); ++i) {
      double phi = 0.0, rate = 0.0;
      leg_phase(track, n, i, t, phi, rate);
      toe(i, phi, q.col(i), dq_dphi);
      qdot.col(i) = dq_dphi * rate;  // q̇ = dq/dφ · φ̇
    }
  };
  w.phase = [track](double t, Eigen::VectorXd& phi) { replay_phase(track, t, phi); };
  return w;
}

}  // namespace slipwalk::planning
