// Point kind of the sim-to-sim accuracy comparison of thesis §3.5.4 (Fig. 3.14):
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
#include <array>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "connection/trajectory.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "robots/robots.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/points/families.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/bigant_peer.hpp"
#include "peers/mujoco/peer.hpp"
#endif

namespace slipwalk::sweeps::points {

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
  in.frequency = r.number("frequency", 0.1, core::closed(1e-6, 10.0, "Hz"));
  in.duration = r.number("duration", 40.0, 0.0, 3600.0);
  in.settle = r.number("settle", 1.0, 0.0, 60.0, true);
  in.sample = r.number("sample", 0.1, 0.0, 60.0);
  in.dt = r.number("dt", 0.01, core::closed(1e-6, 1.0, "s"));
  in.mu = r.number("mu", 1.0, contact::limits::kFriction);  // the robot's own check
  in.timestep = r.number("timestep", 0.002, core::closed(1e-6, 0.05, "s"));
  in.kp_xy = r.number("kp_xy", 100.0, 0.0, 1e9);
  in.kp_z = r.number("kp_z", 1000.0, 0.0, 1e9);
  in.damping = r.number("damping", 10.0, 0.0, 1e9, true);
  in.solref_timeconst = r.number("solref_timeconst", 0.02, 0.0, 10.0);
  in.solref_dampratio = r.number("solref_dampratio", 1.0, 0.0, 100.0);
  in.iterations = static_cast<int>(r.integer("iterations", 100, 1, 100000));
  in.K = r.number("K", in.kp_z, core::closed(1e-3, 1e9, "N/m"));
  in.lead = r.choice("lead", {"off", "on"}) == "on";
  in.ours = r.choice("ours", {"both", "none"}) == "both";
  in.label = r.text("label").value_or("base");
  if (in.sample < in.dt || in.sample < in.timestep) {
    r.fail("sample", "must be at least dt and timestep");
  }
  // Our model takes (settle + duration) / dt steps, MuJoCo as many of its timestep.
  r.limit_work("dt", "duration / dt", in.duration / in.dt, 1e7);
  r.limit_work("timestep", "(settle + duration) / timestep",
               (in.settle + in.duration) / in.timestep, 1e8);
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

/// BigANT's legs (robots::bigant_tripod and bigant_metachronal alike): the per-leg column groups.
constexpr std::size_t kBigAntLegs = 6;

/// A per-leg group with no data: NaN for every leg.
constexpr std::array<double, kBigAntLegs> kNoLegData = [] {
  std::array<double, kBigAntLegs> a{};
  a.fill(std::numeric_limits<double>::quiet_NaN());
  return a;
}();

/// BigANT's leg names (HL, ML, …), checked against kBigAntLegs.
std::vector<std::string> bigant_leg_names() {
  std::vector<std::string> names = robots::bigant_tripod().leg_names;
  if (names.size() != kBigAntLegs) {
    throw std::logic_error("peer_bigant: BigANT has " + std::to_string(names.size()) +
                           " legs, the per-leg columns are sized for " +
                           std::to_string(kBigAntLegs));
  }
  return names;
}

/// One row per sample time and source. The tracking columns (rmse_*, mean_contacts,
/// max_Fz_error) are MuJoCo's and NaN in our rows; the per-leg groups are MuJoCo's and NaN in our
/// rows and wherever MuJoCo was not run.
struct BigAntRow {
  long long id = 0;
  std::string gait;
  std::string source;  ///< ours_viscous, ours_coulomb or mujoco
  std::string label;
  double mu = 0.0;
  double timestep = 0.0;
  double solref_timeconst = 0.0;
  double solref_dampratio = 0.0;
  double kp_xy = 0.0;
  double kp_z = 0.0;
  double K = 0.0;
  bool lead = false;
  double t = 0.0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  double z = 0.0;
  long long contacts = 0;
  double Fz_sum = 0.0;
  double rmse_x = kNaN;
  double rmse_y = kNaN;
  double rmse_z = kNaN;
  double rmse_z_swing = kNaN;
  double rmse_xy_foot_max = kNaN;
  double mean_contacts = kNaN;
  double max_Fz_error = kNaN;  ///< max |ΣF_z − Mg| / Mg
  std::string peer_name = "none";
  std::string message;
  // Per leg, in robots::bigant_tripod().leg_names' order.
  std::array<double, kBigAntLegs> contact = kNoLegData;  ///< 1 in contact, 0 not
  std::array<double, kBigAntLegs> Fz = kNoLegData;       ///< N, floor on foot
  std::array<double, kBigAntLegs> Fx = kNoLegData;       ///< N, chassis yaw frame
  std::array<double, kBigAntLegs> Fy = kNoLegData;       ///< N, chassis yaw frame
  std::array<double, kBigAntLegs> slip_x = kNoLegData;   ///< m/s, foot over the floor
  std::array<double, kBigAntLegs> slip_y = kNoLegData;   ///< m/s

  static std::vector<Column<BigAntRow>> columns() {
    using R = BigAntRow;
    std::vector<Column<R>> out = {value("id", &R::id),
                                  value("gait", &R::gait),
                                  value("source", &R::source),
                                  value("label", &R::label),
                                  value("mu", &R::mu),
                                  value("timestep", &R::timestep, "s"),
                                  value("solref_timeconst", &R::solref_timeconst, "s"),
                                  value("solref_dampratio", &R::solref_dampratio),
                                  value("kp_xy", &R::kp_xy, "N/m"),
                                  value("kp_z", &R::kp_z, "N/m"),
                                  value("K", &R::K, "N/m"),
                                  value("lead", &R::lead),
                                  value("t", &R::t, "s"),
                                  value("x", &R::x, "m"),
                                  value("y", &R::y, "m"),
                                  value("theta", &R::theta, "rad"),
                                  value("z", &R::z, "m"),
                                  value("contacts", &R::contacts),
                                  value("Fz_sum", &R::Fz_sum, "N"),
                                  value("rmse_x", &R::rmse_x, "m"),
                                  value("rmse_y", &R::rmse_y, "m"),
                                  value("rmse_z", &R::rmse_z, "m"),
                                  value("rmse_z_swing", &R::rmse_z_swing, "m"),
                                  value("rmse_xy_foot_max", &R::rmse_xy_foot_max, "m"),
                                  value("mean_contacts", &R::mean_contacts),
                                  value("max_Fz_error", &R::max_Fz_error),
                                  value("peer", &R::peer_name),
                                  value("message", &R::message)};
    const std::vector<std::string> legs = bigant_leg_names();
    for (std::size_t k = 0; k < kBigAntLegs; ++k) {
      const std::string& leg = legs[k];
      out.push_back(value_at("contact_" + leg, &R::contact, k));
      out.push_back(value_at("Fz_" + leg, &R::Fz, k, "N"));
      out.push_back(value_at("Fx_" + leg, &R::Fx, k, "N"));
      out.push_back(value_at("Fy_" + leg, &R::Fy, k, "N"));
      out.push_back(value_at("slip_x_" + leg, &R::slip_x, k, "m/s"));
      out.push_back(value_at("slip_y_" + leg, &R::slip_y, k, "m/s"));
    }
    return out;
  }
};

/// A row's inputs and pose; the tracking and per-leg columns stay NaN.
BigAntRow base_row(const Point& point, const Inputs& in, const std::string& source, double t,
                   const core::Pose2& pose, double z, long long contacts, double Fz_sum) {
  BigAntRow r;
  r.id = point.id;
  r.gait = in.gait;
  r.source = source;
  r.label = in.label;
  r.mu = in.mu;
  r.timestep = in.timestep;
  r.solref_timeconst = in.solref_timeconst;
  r.solref_dampratio = in.solref_dampratio;
  r.kp_xy = in.kp_xy;
  r.kp_z = in.kp_z;
  r.K = in.K;
  r.lead = in.lead;
  r.t = t;
  r.x = pose.x;
  r.y = pose.y;
  r.theta = pose.theta;
  r.z = z;
  r.contacts = contacts;
  r.Fz_sum = Fz_sum;
  return r;
}

#ifdef SLIPWALK_HAVE_MUJOCO
/// MuJoCo's per-leg columns from `data` (bigant_read_legs).
void set_mujoco_legs(BigAntRow& r, const peer::BigAntData& data) {
  for (std::size_t k = 0; k < kBigAntLegs; ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    r.contact[k] = data.contact[k] != 0 ? 1.0 : 0.0;
    r.Fz[k] = data.Fz(i);
    r.Fx[k] = data.Fxy(0, i);
    r.Fy[k] = data.Fxy(1, i);
    r.slip_x[k] = data.slip(0, i);
    r.slip_y[k] = data.slip(1, i);
  }
}
#endif

/// Our model along the gait, from the origin, K and μ as the point says; a row every sample.
template <class Law>
void run_ours(const Point& point, const Inputs& in, const robots::Walker& w, const Law& law,
              const std::string& source, Rows<BigAntRow>& out) {
  contact::Robot robot = w.robot;
  robot.K.setConstant(in.K);
  connection::TrajectoryOptions options;
  options.dt = in.dt;
  options.steps = std::llround(in.duration / in.dt);
  const long long every = std::max(1LL, std::llround(in.sample / in.dt));
  connection::TrajectoryData data(robot);
  const auto summary =
      connection::integrate(robot, w.feet, options, law, connection::NoFilter{}, data,
                            [&](const connection::TrajectoryStep& s) {
                              if (s.n % every != 0 && s.n != options.steps) {
                                return;
                              }
                              long long down = 0;
                              for (char c : s.frame.contact) {
                                down += c != 0 ? 1 : 0;
                              }
                              out.rows.push_back(base_row(point, in, source, s.t, s.pose, s.frame.z,
                                                          down, s.frame.Fz.sum()));
                            });
  const std::string& message = summary.non_finite.empty() ? summary.message : summary.non_finite;
  if (!message.empty()) {
    for (BigAntRow& r : out.rows) {
      if (r.source == source) {
        r.message = message;
      }
    }
  }
}

Rows<BigAntRow> run(const Point& point) {
  const Inputs in = read(point);
  const robots::Walker w = walker(in);
  if (w.robot.legs() != static_cast<int>(kBigAntLegs)) {
    throw std::logic_error("peer_bigant: the walker has " + std::to_string(w.robot.legs()) +
                           " legs, the per-leg columns are sized for " +
                           std::to_string(kBigAntLegs));
  }
  Rows<BigAntRow> out;
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
        out.rows.push_back(base_row(point, in, "mujoco", s.t, s.pose, s.z, s.contacts, s.Fz_sum));
        set_mujoco_legs(out.rows.back(), data);
      });
  const Eigen::Vector3d rmse = summary.tracking.rmse();
  const Eigen::Matrix3Xd per_foot = summary.tracking.rmse_per_foot();
  const double xy_foot_max = per_foot.topRows<2>().colwise().norm().maxCoeff();
  const std::string name = "mujoco " + peer::version();
  for (std::size_t i = first; i < out.rows.size(); ++i) {
    BigAntRow& r = out.rows[i];
    r.rmse_x = rmse(0);
    r.rmse_y = rmse(1);
    r.rmse_z = rmse(2);
    r.rmse_z_swing = summary.tracking.swing_z_rmse();
    r.rmse_xy_foot_max = xy_foot_max;
    r.mean_contacts = summary.mean_contacts;
    r.max_Fz_error = summary.max_Fz_error;
    r.peer_name = name;
  }
#else
  const std::string message =
      "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): MuJoCo not run";
  static std::once_flag warned;
  std::call_once(warned,
                 [&] { std::cerr << "slipwalk: warning: peer_bigant: " << message << '\n'; });
  if (out.rows.empty()) {  // MuJoCo only was asked for: one row that says why there is none
    out.rows.push_back(
        base_row(point, in, "mujoco", kNaN, core::Pose2{kNaN, kNaN, kNaN}, kNaN, -1, kNaN));
  }
  for (BigAntRow& r : out.rows) {
    r.message = message;
  }
#endif
  return out;
}

}  // namespace

std::vector<PointKind> peer_bigant_kinds() {
  return {make_point_kind<BigAntRow>(
      "peer_bigant",
      "§3.5.4, Fig. 3.14: BigANT along a gait in our model (viscous-Coulomb, Coulomb) and in "
      "MuJoCo driven by the same foot trajectories (one row per sample and source; MuJoCo's "
      "rows carry the feet's tracking RMSE)",
      Timed::kNo, [](const Point& p) { (void)read(p); }, run)};
}

}  // namespace slipwalk::sweeps::points
