// Point kind of the plan replay (thesis §5.5, beyond it): does a plan survive a full dynamics
// simulator?
//
//   plan_replay  plans one of the thesis' three goals (§5.5: walk straight at 0.2 m/s, turn in
//                place at 0.2 rad/s, move diagonally at (0.05, 0.02) m/s with the heading held)
//                with planning::plan (PlanOptions' defaults, `steps` planning steps of τ = 5 ms,
//                from planning::tripod_start of BigANT), then replays its shaft angles open-loop on
//                MuJoCo's BigANT (peers/mujoco/plan_replay.hpp) from the plan's start pose. One row
//                per step time t_0 … t_S: the plan's pose (x, y, theta) and MuJoCo's (x_mujoco,
//                y_mujoco, theta_mujoco), and on every row the run's summary:
//                  plan_path       m, the plan's path length Σ |Δp| over the samples
//                  plan_yaw        rad, the plan's yaw change θ_S − θ_0
//                  gap_final       m, |p_mujoco − p_plan| at t_S;  gap_rms: RMS over the samples
//                  yaw_gap_final   rad, θ_mujoco − θ_plan at t_S;  yaw_gap_rms: RMS
//                  gap_rel         gap_final / plan_path (NaN for a plan that hardly moves, the
//                                  turn: its yaw_rel is the measure)
//                  yaw_rel         |yaw_gap_final| / |plan_yaw| (NaN when |plan_yaw| < 0.01 rad)
//                  progress        MuJoCo's progress along the goal over the plan's: the
//                                  displacement along the goal twist's direction (straight,
//                                  diagonal), the yaw change (turn)
//                  rmse_x, rmse_y  m, how well MuJoCo's slides follow the planned feet
//                  mean_contacts   feet in contact in MuJoCo, mean over its steps
// Checks: `law` = coulomb plans with Coulomb friction (MuJoCo's law) instead of the viscous-Coulomb
// ansatz; `slowdown` = k replays the plan k times slower (planning::slowed: the quasi-static plan
// predicts the same path at any pace, so a gap that shrinks with k is a rate effect — inertia,
// damping); t is then the slowed time.
// Without MuJoCo the plan still runs; MuJoCo's columns are NaN and every row says why.
#include <Eigen/Core>
#include <cmath>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "core/se2.hpp"
#include "planning/goal.hpp"
#include "planning/plan_robot.hpp"
#include "planning/planner.hpp"
#include "planning/replay_feet.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/points/families.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/peer.hpp"
#include "peers/mujoco/plan_replay.hpp"
#endif

namespace slipwalk::sweeps::points {

namespace {

const double kNaN = std::nan("");

const std::vector<std::string_view> kKeys = {
    "goal",  "steps", "label",   "settle",           "timestep",
    "kp_xy", "kp_z",  "damping", "solref_timeconst", "solref_dampratio",
    "lead",  "law",   "slowdown"};

struct Inputs {
  std::string goal = "straight";
  long long steps = 300;
  std::string label = "base";
  double settle = 1.0;
  double timestep = 0.001;
  double kp_xy = 100.0;
  double kp_z = 2675.0;
  double damping = 10.0;
  double solref_timeconst = 0.005;
  double solref_dampratio = 1.0;
  bool lead = false;
  bool coulomb = false;  // plan with Coulomb friction instead of the viscous-Coulomb ansatz
  double slowdown = 1.0;
};

Inputs read(const Point& point) {
  const Reader r(point, "plan_replay", kKeys);
  Inputs in;
  in.goal = r.choice("goal", {"straight", "turn", "diagonal"});
  in.steps = r.integer("steps", 300, 1, 100000);
  in.label = r.text("label").value_or("base");
  in.settle = r.number("settle", 1.0, 0.0, 60.0, true);
  in.timestep = r.number("timestep", 0.001, core::closed(1e-6, 0.005, "s"));
  in.kp_xy = r.number("kp_xy", 100.0, 0.0, 1e9);
  in.kp_z = r.number("kp_z", 2675.0, 0.0, 1e9);
  in.damping = r.number("damping", 10.0, 0.0, 1e9, true);
  in.solref_timeconst = r.number("solref_timeconst", 0.005, 0.0, 10.0);
  in.solref_dampratio = r.number("solref_dampratio", 1.0, 0.0, 100.0);
  in.lead = r.choice("lead", {"off", "on"}) == "on";
  in.coulomb = r.choice("law", {"viscous", "coulomb"}) == "coulomb";
  in.slowdown = static_cast<double>(r.integer("slowdown", 1, 1, 100));
  // MuJoCo samples at the plan's step times: its timestep must divide τ (PlanOptions' default).
  const planning::PlanOptions defaults;
  const double tau = static_cast<double>(defaults.execute) * defaults.horizon /
                     static_cast<double>(defaults.substeps);
  const double per_step = in.slowdown * tau / in.timestep;
  if (std::abs(per_step - std::round(per_step)) > 1e-9 * per_step) {
    r.fail("timestep", "must divide the plan's step duration " + core::format_double(tau) + " s");
  }
  r.limit_work("timestep", "(settle + steps · τ) / timestep",
               (in.settle + static_cast<double>(in.steps) * in.slowdown * tau) / in.timestep, 1e8);
  return in;
}

struct ReplayRow {
  long long id = 0;
  std::string goal;
  std::string label;
  long long steps = 0;
  double kp_xy = 0.0;
  double solref_timeconst = 0.0;
  bool lead = false;
  std::string law;
  long long slowdown = 1;
  double t = 0.0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  double x_mujoco = kNaN;
  double y_mujoco = kNaN;
  double theta_mujoco = kNaN;
  double plan_path = 0.0;
  double plan_yaw = 0.0;
  double gap_final = kNaN;
  double gap_rms = kNaN;
  double yaw_gap_final = kNaN;
  double yaw_gap_rms = kNaN;
  double gap_rel = kNaN;
  double yaw_rel = kNaN;
  double progress = kNaN;
  double rmse_x = kNaN;
  double rmse_y = kNaN;
  double mean_contacts = kNaN;
  std::string peer_name = "none";
  std::string message;

  static std::vector<Column<ReplayRow>> columns() {
    using R = ReplayRow;
    return {value("id", &R::id),
            value("goal", &R::goal),
            value("label", &R::label),
            value("steps", &R::steps),
            value("kp_xy", &R::kp_xy, "N/m"),
            value("solref_timeconst", &R::solref_timeconst, "s"),
            value("lead", &R::lead),
            value("law", &R::law),
            value("slowdown", &R::slowdown),
            value("t", &R::t, "s"),
            value("x", &R::x, "m"),
            value("y", &R::y, "m"),
            value("theta", &R::theta, "rad"),
            value("x_mujoco", &R::x_mujoco, "m"),
            value("y_mujoco", &R::y_mujoco, "m"),
            value("theta_mujoco", &R::theta_mujoco, "rad"),
            value("plan_path", &R::plan_path, "m"),
            value("plan_yaw", &R::plan_yaw, "rad"),
            value("gap_final", &R::gap_final, "m"),
            value("gap_rms", &R::gap_rms, "m"),
            value("yaw_gap_final", &R::yaw_gap_final, "rad"),
            value("yaw_gap_rms", &R::yaw_gap_rms, "rad"),
            value("gap_rel", &R::gap_rel),
            value("yaw_rel", &R::yaw_rel),
            value("progress", &R::progress),
            value("rmse_x", &R::rmse_x, "m"),
            value("rmse_y", &R::rmse_y, "m"),
            value("mean_contacts", &R::mean_contacts),
            value("peer", &R::peer_name),
            value("message", &R::message)};
  }
};

/// The plan's rows (its pose at t_0 … t_S) and the plan's own summary columns.
Rows<ReplayRow> plan_rows(const Point& point, const Inputs& in, const planning::PlanTrack& track) {
  Rows<ReplayRow> out;
  const long long s = track.steps();
  double path = 0.0;
  for (long long n = 0; n <= s; ++n) {
    const core::Pose2& p = n < s ? track.pose[static_cast<std::size_t>(n)] : track.end_pose;
    ReplayRow r;
    r.id = point.id;
    r.goal = in.goal;
    r.label = in.label;
    r.steps = in.steps;
    r.kp_xy = in.kp_xy;
    r.solref_timeconst = in.solref_timeconst;
    r.lead = in.lead;
    r.law = in.coulomb ? "coulomb" : "viscous";
    r.slowdown = std::llround(in.slowdown);
    r.t = n < s ? track.t[static_cast<std::size_t>(n)] : track.end_time();
    r.x = p.x;
    r.y = p.y;
    r.theta = p.theta;
    if (n > 0) {
      const ReplayRow& prev = out.rows.back();
      path += std::hypot(r.x - prev.x, r.y - prev.y);
    }
    out.rows.push_back(r);
  }
  const double yaw = out.rows.back().theta - out.rows.front().theta;
  for (ReplayRow& r : out.rows) {
    r.plan_path = path;
    r.plan_yaw = yaw;
  }
  return out;
}

#ifdef SLIPWALK_HAVE_MUJOCO
/// MuJoCo's columns and the gaps.
void add_mujoco(const Inputs& in, const peers::mujoco::PlanReplay& replay, Rows<ReplayRow>& out) {
  if (replay.mujoco.size() != out.rows.size()) {
    out.failed = true;
    out.message = "MuJoCo gave " + std::to_string(replay.mujoco.size()) + " samples for " +
                  std::to_string(out.rows.size()) + " step times";
    for (ReplayRow& r : out.rows) {
      r.message = out.message;
    }
    return;
  }
  double sq = 0.0, yaw_sq = 0.0;
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    ReplayRow& r = out.rows[i];
    const core::Pose2& m = replay.mujoco[i];
    r.x_mujoco = m.x;
    r.y_mujoco = m.y;
    r.theta_mujoco = m.theta;
    sq += std::pow(std::hypot(m.x - r.x, m.y - r.y), 2);
    yaw_sq += std::pow(m.theta - r.theta, 2);
  }
  const ReplayRow& first = out.rows.front();
  const ReplayRow& last = out.rows.back();
  const double n = static_cast<double>(out.rows.size());
  const double gap_final = std::hypot(last.x_mujoco - last.x, last.y_mujoco - last.y);
  const double yaw_gap_final = last.theta_mujoco - last.theta;
  double progress = kNaN;
  const Eigen::Vector3d twist = planning::thesis_goal(in.goal).twist;
  if (in.goal == "turn") {
    progress = (last.theta_mujoco - first.theta_mujoco) / (last.theta - first.theta);
  } else {
    // The goal's direction in the world: the twist's (v_x, v_y) turned by the start heading.
    const Eigen::Vector2d v = twist.head<2>().normalized();
    const double c = std::cos(first.theta), s = std::sin(first.theta);
    const Eigen::Vector2d u(c * v(0) - s * v(1), s * v(0) + c * v(1));
    const double ours = u.dot(Eigen::Vector2d(last.x - first.x, last.y - first.y));
    const double theirs =
        u.dot(Eigen::Vector2d(last.x_mujoco - first.x_mujoco, last.y_mujoco - first.y_mujoco));
    progress = theirs / ours;
  }
  const Eigen::Vector3d rmse = replay.drive.tracking.rmse();
  const std::string name = "mujoco " + peers::mujoco::version();
  for (ReplayRow& r : out.rows) {
    r.gap_final = gap_final;
    r.gap_rms = std::sqrt(sq / n);
    r.yaw_gap_final = yaw_gap_final;
    r.yaw_gap_rms = std::sqrt(yaw_sq / n);
    // A turn in place hardly moves the body: its relative measure is the yaw's.
    r.gap_rel = r.plan_path > 0.01 ? gap_final / r.plan_path : kNaN;
    r.yaw_rel = std::abs(r.plan_yaw) > 0.01 ? std::abs(yaw_gap_final) / std::abs(r.plan_yaw) : kNaN;
    r.progress = progress;
    r.rmse_x = rmse(0);
    r.rmse_y = rmse(1);
    r.mean_contacts = replay.drive.mean_contacts;
    r.peer_name = name;
  }
}
#endif

Rows<ReplayRow> run(const Point& point) {
  const Inputs in = read(point);
  const planning::PlanRobot robot = planning::bigant_plan_robot();
  planning::PlanOptions options;
  options.steps = in.steps;
  if (in.coulomb) {
    options.law = connection::FrictionLaw::kCoulomb;
  }
  const planning::PlanState start = planning::tripod_start(robot);
  planning::Goal goal = planning::thesis_goal(in.goal);
  goal.start = start.pose;
  const planning::PlanTrack track =
      planning::slowed(planning::plan_track(robot, options, goal, start), in.slowdown);
  Rows<ReplayRow> out = plan_rows(point, in, track);
#ifdef SLIPWALK_HAVE_MUJOCO
  peers::mujoco::PlanReplayOptions replay;
  replay.settle = in.settle;
  replay.timestep = in.timestep;
  replay.kp_xy = in.kp_xy;
  replay.kp_z = in.kp_z;
  replay.damping = in.damping;
  replay.solref_timeconst = in.solref_timeconst;
  replay.solref_dampratio = in.solref_dampratio;
  replay.lead = in.lead;
  add_mujoco(in, peers::mujoco::replay_plan(robot, track, replay), out);
#else
  const std::string message =
      "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): MuJoCo not run";
  static std::once_flag warned;
  std::call_once(warned,
                 [&] { std::cerr << "slipwalk: warning: plan_replay: " << message << '\n'; });
  for (ReplayRow& r : out.rows) {
    r.message = message;
  }
#endif
  return out;
}

}  // namespace

std::vector<PointKind> plan_replay_kinds() {
  return {make_point_kind<ReplayRow>(
      "plan_replay",
      "§5.5: a plan of one of the thesis' goals replayed open-loop on MuJoCo's BigANT (the feet "
      "follow the plan's shaft angles); one row per step time: the plan's pose and MuJoCo's, "
      "and the gaps between them",
      Timed::kNo, [](const Point& p) { (void)read(p); }, run)};
}

}  // namespace slipwalk::sweeps::points
