// Point function of the sim-to-sim accuracy comparison of thesis §3.5.4 (Fig. 3.14, issue 7):
//
//   peer_bigant  BigANT walking a gait (tripod or metachronal) in our model (viscous-Coulomb and
//                Coulomb, connection::integrate) and in MuJoCo (lib/peers/mujoco/bigant_peer: a
//                plate chassis, feet on x/y/z slides driven by position actuators along the same
//                foot trajectories); one row per sample time and source, x, y, θ relative to the
//                start, and for MuJoCo the tracking RMSE of the feet per axis and, per leg L
//                (contact_L, Fz_L, Fx_L, Fy_L, slip_x_L, slip_y_L, as a scene run's columns,
//                scene/run_writer.hpp), MuJoCo's contact flag, the normal and planar forces of
//                the floor on the foot (mj_contactForce turned from the contact frame to the
//                world, planar parts in the chassis' yaw frame) and the foot centre's velocity
//                over the floor in that frame (mj_objectVelocity of the foot geom); with the
//                contacts, of the physics step just taken (the state h before the sample's pose).
//                Our rows leave the per-leg columns NaN (the ch3_robots scene runs have ours).
//
// Our leg stiffness defaults to the MuJoCo z actuator's kp (K = kp_z, key K): MuJoCo's z slide
// with target q_z is our leg spring with rest point q_z (eq. 3.7), so matching them compares the
// friction and dynamics, not two different suspensions. A point with ours = "none" runs MuJoCo
// only (the sensitivity blocks, which vary MuJoCo's own parameters).
#include <Eigen/Core>
#include <cmath>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "connection/trajectory.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "robots/robots.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/points/families.hpp"
#include "sweeps/points/legacy.hpp"
#include "sweeps/engine/point_reader.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/bigant_peer.hpp"
#include "peers/mujoco/peer.hpp"
#endif

namespace slipwalk::sweeps {

namespace {

namespace peer = peers::mujoco;
const double kNaN = std::nan("");

const std::vector<std::string_view> kKeys = {"gait",   "frequency", "duration", "settle",
                                             "sample", "dt",        "mu",       "timestep",
                                             "kp_xy",  "kp_z",      "damping",  "solref_timeconst",
                                             "K",      "lead",      "ours",     "solref_dampratio",
                                             "label",  "iterations"};

struct Inputs {
  std::string gait = "tripod";
  double frequency = 0.1;
  double duration = 40.0;
  double settle = 1.0;
  double sample = 0.1;
  double dt = 0.01;
  double mu = 1.0;
  double timestep = 0.002;
  double kp_xy = 100.0;
  double kp_z = 1000.0;
  double damping = 10.0;
  double solref_timeconst = 0.02;
  double solref_dampratio = 1.0;
  int iterations = 100;
  double K = 1000.0;  // ours; kp_z unless given
  bool lead = false;
  bool ours = true;
  std::string label = "base";
};

Inputs read(const Point& point) {
  const Reader r(point, "peer_bigant", kKeys);
  Inputs in;
  in.gait = r.choice("gait", {"tripod", "metachronal"});
  in.frequency = r.number("frequency", 0.1, 0.0, 10.0);
  in.duration = r.number("duration", 40.0, 0.0, 3600.0);
  in.settle = r.number("settle", 1.0, 0.0, 60.0, true);
  in.sample = r.number("sample", 0.1, 0.0, 60.0);
  in.dt = r.number("dt", 0.01, 0.0, 1.0);
  in.mu = r.number("mu", 1.0, 0.0, 100.0, true);
  in.timestep = r.number("timestep", 0.002, 0.0, 0.05);
  in.kp_xy = r.number("kp_xy", 100.0, 0.0, 1e9);
  in.kp_z = r.number("kp_z", 1000.0, 0.0, 1e9);
  in.damping = r.number("damping", 10.0, 0.0, 1e9, true);
  in.solref_timeconst = r.number("solref_timeconst", 0.02, 0.0, 10.0);
  in.solref_dampratio = r.number("solref_dampratio", 1.0, 0.0, 100.0);
  in.iterations = static_cast<int>(r.integer("iterations", 100, 1, 100000));
  in.K = r.number("K", in.kp_z, 0.0, 1e9);
  in.lead = r.choice("lead", {"off", "on"}) == "on";
  in.ours = r.choice("ours", {"both", "none"}) == "both";
  in.label = r.text("label").value_or("base");
  if (in.sample < in.dt || in.sample < in.timestep) {
    r.fail("sample", "must be at least dt and timestep");
  }
  return in;
}

robots::Walker walker(const Inputs& in) {
  robots::Walker w =
      in.gait == "tripod"
          ? robots::bigant_tripod(robots::TripodGait{.frequency = in.frequency})
          : robots::bigant_metachronal(robots::MetachronalGait{.frequency = in.frequency});
  w.robot.mu.setConstant(in.mu);
  return w;
}

const std::vector<std::string> kBaseColumns = {"id",
                                               "gait",
                                               "source",
                                               "label",
                                               "mu",
                                               "timestep",
                                               "solref_timeconst",
                                               "solref_dampratio",
                                               "kp_xy",
                                               "kp_z",
                                               "K",
                                               "lead",
                                               "t",
                                               "x",
                                               "y",
                                               "theta",
                                               "z",
                                               "contacts",
                                               "Fz_sum",
                                               "rmse_x",
                                               "rmse_y",
                                               "rmse_z",
                                               "rmse_z_swing",
                                               "rmse_xy_foot_max",
                                               "mean_contacts",
                                               "max_Fz_error",
                                               "peer",
                                               "message"};
constexpr std::size_t kMessage = 27;  // index of "message"; per-leg columns follow it
const std::vector<std::string_view> kLegColumns = {"contact_", "Fz_",     "Fx_",
                                                   "Fy_",      "slip_x_", "slip_y_"};

/// The base columns, then kLegColumns for each of BigANT's legs (both gaits name them alike).
std::vector<std::string> columns() {
  std::vector<std::string> out = kBaseColumns;
  for (const std::string& leg : robots::bigant_tripod().leg_names) {
    for (std::string_view c : kLegColumns) {
      out.push_back(std::string(c) + leg);
    }
  }
  return out;
}

Row row(const Point& point, const Inputs& in, const std::string& source, double t,
        const core::Pose2& pose, double z, long long contacts, double Fz_sum) {
  return Row{point.id,
             in.gait,
             source,
             in.label,
             in.mu,
             in.timestep,
             in.solref_timeconst,
             in.solref_dampratio,
             in.kp_xy,
             in.kp_z,
             in.K,
             in.lead ? 1LL : 0LL,
             t,
             pose.x,
             pose.y,
             pose.theta,
             z,
             contacts,
             Fz_sum,
             kNaN,
             kNaN,
             kNaN,
             kNaN,
             kNaN,
             kNaN,
             kNaN,
             std::string("none"),
             std::string()};
}

/// Appends the per-leg columns as NaN: our rows, or MuJoCo's when it was not run.
void append_nan_legs(Row& r, int legs) {
  r.insert(r.end(), kLegColumns.size() * static_cast<std::size_t>(legs), Cell{kNaN});
}

#ifdef SLIPWALK_HAVE_MUJOCO
/// Appends MuJoCo's per-leg columns from `data` (bigant_read_legs), in kLegColumns' order.
void append_mujoco_legs(Row& r, const peer::BigAntData& data) {
  for (Eigen::Index k = 0; k < data.Fz.size(); ++k) {
    r.emplace_back(static_cast<long long>(data.contact[static_cast<std::size_t>(k)] != 0));
    r.emplace_back(data.Fz(k));
    r.emplace_back(data.Fxy(0, k));
    r.emplace_back(data.Fxy(1, k));
    r.emplace_back(data.slip(0, k));
    r.emplace_back(data.slip(1, k));
  }
}
#endif

/// Our model along the gait, from the origin, K and μ as the point says; a row every sample.
template <class Law>
void run_ours(const Point& point, const Inputs& in, const robots::Walker& w, const Law& law,
              const std::string& source, PointResult& out) {
  contact::Robot robot = w.robot;
  robot.K.setConstant(in.K);
  connection::TrajectoryOptions options;
  options.dt = in.dt;
  options.steps = std::llround(in.duration / in.dt);
  const long long every = std::max(1LL, std::llround(in.sample / in.dt));
  connection::TrajectoryData data(robot);
  const auto summary = connection::integrate(
      robot, w.feet, options, law, connection::NoFilter{}, data,
      [&](const connection::TrajectoryStep& s) {
        if (s.n % every != 0 && s.n != options.steps) {
          return;
        }
        long long down = 0;
        for (char c : s.frame.contact) {
          down += c != 0 ? 1 : 0;
        }
        out.rows.push_back(row(point, in, source, s.t, s.pose, s.frame.z, down, s.frame.Fz.sum()));
        append_nan_legs(out.rows.back(), robot.legs());
      });
  if (!summary.message.empty()) {
    for (Row& r : out.rows) {
      if (std::get<std::string>(r[2]) == source) {
        r[kMessage] = summary.message;
      }
    }
  }
}

PointResult run(const Point& point) {
  const Inputs in = read(point);
  const robots::Walker w = walker(in);
  PointResult out;
  if (in.ours) {
    run_ours(point, in, w, connection::ViscousCoulombKernel{}, "ours_viscous", out);
    run_ours(point, in, w, connection::CoulombKernel{}, "ours_coulomb", out);
  }
#ifdef SLIPWALK_HAVE_MUJOCO
  peer::BigAntPeerSpec spec = peer::bigant_peer_spec(w);
  spec.timestep = in.timestep;
  spec.kp_xy = in.kp_xy;
  spec.kp_z = in.kp_z;
  spec.damping = in.damping;
  spec.solref_timeconst = in.solref_timeconst;
  spec.solref_dampratio = in.solref_dampratio;
  spec.iterations = in.iterations;
  const peer::BigAntModel model(spec);
  peer::BigAntData data(model);
  // Start where our model's spring support puts a robot with legs as stiff as the z actuators.
  contact::Robot stand = w.robot;
  stand.K.setConstant(in.kp_z);
  contact::Frame f(stand);
  Eigen::Matrix3Xd qdot(3, stand.legs());
  w.feet(0.0, f.q, qdot);
  contact::spring_support(stand, f);
  peer::BigAntDriveOptions options;
  options.duration = in.duration;
  options.settle = in.settle;
  options.sample = in.sample;
  options.lead = in.lead;
  const std::size_t first = out.rows.size();
  const auto summary = peer::bigant_drive(
      model, data, w.feet, f.z, f.alpha, f.beta, options, [&](const peer::BigAntSample& s) {
        out.rows.push_back(row(point, in, "mujoco", s.t, s.pose, s.z, s.contacts, s.Fz_sum));
        append_mujoco_legs(out.rows.back(), data);
      });
  const Eigen::Vector3d rmse = summary.tracking.rmse();
  const Eigen::Matrix3Xd per_foot = summary.tracking.rmse_per_foot();
  const double xy_foot_max = per_foot.topRows<2>().colwise().norm().maxCoeff();
  const std::string name = "mujoco " + peer::version();
  for (std::size_t i = first; i < out.rows.size(); ++i) {
    Row& r = out.rows[i];
    r[19] = rmse(0);
    r[20] = rmse(1);
    r[21] = rmse(2);
    r[22] = summary.tracking.swing_z_rmse();
    r[23] = xy_foot_max;
    r[24] = summary.mean_contacts;
    r[25] = summary.max_Fz_error;
    r[26] = name;
  }
#else
  const std::string message =
      "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): MuJoCo not run";
  static std::once_flag warned;
  std::call_once(warned,
                 [&] { std::cerr << "slipwalk: warning: peer_bigant: " << message << '\n'; });
  if (out.rows.empty()) {  // MuJoCo only was asked for: one row that says why there is none
    out.rows.push_back(
        row(point, in, "mujoco", kNaN, core::Pose2{kNaN, kNaN, kNaN}, kNaN, -1, kNaN));
    append_nan_legs(out.rows.back(), w.robot.legs());
  }
  for (Row& r : out.rows) {
    r[kMessage] = message;
  }
#endif
  return out;
}

}  // namespace

std::vector<PointKind> points::peer_bigant_kinds() {
  return legacy_kinds({{"peer_bigant",
          "§3.5.4, Fig. 3.14: BigANT along a gait in our model (viscous-Coulomb, Coulomb) and in "
          "MuJoCo driven by the same foot trajectories (one row per sample and source; MuJoCo's "
          "rows carry the feet's tracking RMSE)",
          columns(), [](const Point& p) { (void)read(p); },
          [](const Point& p) { return run(p); }}});
}

}  // namespace slipwalk::sweeps
