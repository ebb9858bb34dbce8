// Point kind of the referee on thesis §5.2's terrain (Figs. 5.2, 5.3):
//
//   peer_terrain  a terrain scene (studies/ch5_terrain/scenes/*.toml: its robot, gait, terrain
//                 and run) walked by our model under both laws (the scene composed as `slipwalk
//                 run` would, scene::compose) and by MuJoCo's BigANT (lib/peers/mujoco/bigant_*,
//                 with the scene's terrain: a slope as tilted gravity, stairs as tread boxes),
//                 its slides driven along the same gait. One row per sample time and source:
//                 the pose (x, y, θ: on a slope in the plane's coordinates, on stairs the world's),
//                 the body origin's world position bx, by, bz (the scene CSVs' columns), the
//                 body's pitch (nose up) and roll, the feet in contact, and MuJoCo's feet's
//                 contacts on a tread's edge or a riser (which our stairs do not have): at the
//                 sample, and the share of the run's steps with one.
//
// The scene is named relative to the spec file, so the runs follow whatever robot and gait the
// scene names. The keys that change MuJoCo alone (noslip_iterations, solref_timeconst, kp_xy,
// inertia_scale) and the gait's frequency are the checks that separate the explanations of a
// difference: soft contact (no-slip solver, stiffer contact), leg compliance, inertia and the
// quasi-static assumption (a slower gait, a lighter chassis).
//
// MuJoCo's z actuator is our leg spring (kp_z = the robot's K by default) and its contact is stiff
// against it (solref 5 ms), as in the ch3_peer base (studies/ch3_peer/fig3_14.toml). MuJoCo starts
// where our spring support puts the robot at t = 0 (on stairs pitched nose-up by the stairs' slope
// γ plus our δβ), holds the first feet for `settle` s, then walks; its poses are absolute, so a
// slide during the settling shows.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "connection/trajectory.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "scene/friction_laws.hpp"
#include "scene/scene.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/points/families.hpp"
#include "terrain/terrain.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/bigant_peer.hpp"
#include "peers/mujoco/peer.hpp"
#endif

namespace slipwalk::sweeps::points {

namespace {

namespace peer = peers::mujoco;

const std::vector<std::string_view> kKeys = {
    "scene", "frequency",     "cycles",  "sample",           "settle",     "timestep",
    "kp_xy", "kp_z",          "damping", "solref_timeconst", "iterations", "noslip_iterations",
    "ours",  "inertia_scale", "label"};

struct Inputs {
  scene::Scene scene;  ///< as read, frequency and run length as the point says
  std::string scene_name;
  double frequency = 0.1;  ///< Hz
  double cycles = 3.0;
  double sample = 0.1;  ///< s
  double settle = 0.5;  ///< s, MuJoCo only
  double timestep = 0.002;
  double kp_xy = 100.0;
  double kp_z = 0.0;  ///< N/m; the robot's K unless given
  double damping = 10.0;
  double solref_timeconst = 0.005;
  int iterations = 100;
  int noslip_iterations = 0;
  double inertia_scale = 1.0;  ///< MuJoCo chassis' rotational inertia × this
  bool ours = true;
  std::string label = "base";
};

/// The gait's frequency, whichever gait the scene names.
double& gait_frequency(scene::Gait& gait) {
  return std::visit([](auto& g) -> double& { return g.frequency; }, gait);
}

Inputs read(const Point& point) {
  const Reader r(point, "peer_terrain", kKeys);
  Inputs in;
  const auto file = r.text("scene");
  if (!file) {
    r.fail("scene", "required (a scene file with a [terrain], relative to the spec file)");
  }
  in.scene_name = std::filesystem::path(*file).stem().string();
  const std::filesystem::path path =
      std::filesystem::path(point.source).parent_path() / std::filesystem::path(*file);
  try {
    in.scene = scene::read_scene(path);
  } catch (const core::InputError& e) {
    r.fail("scene", std::string("bad scene file: ") + e.what());
  }
  if (in.scene.friction.anisotropic) {
    r.fail("scene", "the scene's law is anisotropic; the referee runs the isotropic laws");
  }
  // The scene's run in gait cycles (at its own frequency) is the default at any frequency.
  double& f = gait_frequency(in.scene.gait);
  const double scene_cycles = in.scene.duration * f;
  in.frequency = r.number("frequency", f, core::closed(1e-3, 10.0, "Hz"));
  f = in.frequency;
  in.cycles = r.number("cycles", scene_cycles, 0.0, 100.0);
  in.sample = r.number("sample", 0.1, 0.0, 60.0);
  in.settle = r.number("settle", 0.5, 0.0, 60.0, true);
  in.timestep = r.number("timestep", 0.002, core::closed(1e-5, 0.01, "s"));
  in.kp_xy = r.number("kp_xy", 100.0, 0.0, 1e9);
  in.kp_z = r.number("kp_z", 0.0, 0.0, 1e9, true);  // 0: the robot's K
  in.damping = r.number("damping", 10.0, 0.0, 1e9, true);
  in.solref_timeconst = r.number("solref_timeconst", 0.005, 0.0, 10.0);
  in.iterations = static_cast<int>(r.integer("iterations", 100, 1, 100000));
  in.noslip_iterations = static_cast<int>(r.integer("noslip_iterations", 0, 0, 100000));
  in.inertia_scale = r.number("inertia_scale", 1.0, core::closed(1e-3, 1e3, ""));
  in.ours = r.choice("ours", {"both", "none"}) == "both";
  in.label = r.text("label").value_or("base");
  if (in.solref_timeconst < 2.0 * in.timestep) {
    r.fail("solref_timeconst", "must be at least twice timestep (MuJoCo's stability bound)");
  }
  const double duration = in.cycles / in.frequency;
  in.scene.steps = std::llround(duration / in.scene.dt);
  in.scene.duration = static_cast<double>(in.scene.steps) * in.scene.dt;
  if (in.scene.steps < 1) {
    r.fail("cycles", "the run must be at least one of the scene's dt steps long");
  }
  if (in.sample < in.scene.dt || in.sample < in.timestep) {
    r.fail("sample", "must be at least the scene's dt and timestep");
  }
  r.limit_work("cycles", "duration / dt", static_cast<double>(in.scene.steps), 1e7);
  r.limit_work("timestep", "(settle + duration) / timestep",
               (in.settle + in.scene.duration) / in.timestep, 1e8);
  return in;
}

/// One row per sample time and source (ours_viscous, ours_coulomb, mujoco).
struct TerrainPeerRow {
  long long id = 0;
  std::string scene;
  std::string label;
  std::string source;
  std::string terrain;
  double heading_deg = 0.0;       ///< ψ: uphill (slope) or rising (stairs); 0 on flat ground
  double ground_slope_deg = 0.0;  ///< σ, or the stairs' slope atan(riser/tread); 0 flat
  double frequency = 0.0;
  double cycles = 0.0;
  double kp_xy = 0.0;
  double kp_z = 0.0;
  double solref_timeconst = 0.0;
  long long noslip_iterations = 0;
  double inertia_scale = 1.0;
  double t = 0.0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  double bx = 0.0;
  double by = 0.0;
  double bz = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
  long long contacts = 0;
  long long edge_contacts = 0;  ///< MuJoCo: feet on a tread's edge or a riser, at the sample
  double edge_share = 0.0;      ///< MuJoCo: share of the run's steps with such a contact; ours 0
  std::string peer_name = "none";
  std::string message;

  static std::vector<Column<TerrainPeerRow>> columns() {
    using R = TerrainPeerRow;
    return {value("id", &R::id),
            value("scene", &R::scene),
            value("label", &R::label),
            value("source", &R::source),
            value("terrain", &R::terrain),
            value("heading_deg", &R::heading_deg, "deg"),
            value("ground_slope_deg", &R::ground_slope_deg, "deg"),
            value("frequency", &R::frequency, "Hz"),
            value("cycles", &R::cycles),
            value("kp_xy", &R::kp_xy, "N/m"),
            value("kp_z", &R::kp_z, "N/m"),
            value("solref_timeconst", &R::solref_timeconst, "s"),
            value("noslip_iterations", &R::noslip_iterations),
            value("inertia_scale", &R::inertia_scale),
            value("t", &R::t, "s"),
            value("x", &R::x, "m"),
            value("y", &R::y, "m"),
            value("theta", &R::theta, "rad"),
            value("bx", &R::bx, "m"),
            value("by", &R::by, "m"),
            value("bz", &R::bz, "m"),
            value("pitch", &R::pitch, "rad"),
            value("roll", &R::roll, "rad"),
            value("contacts", &R::contacts),
            value("edge_contacts", &R::edge_contacts),
            value("edge_share", &R::edge_share),
            value("peer", &R::peer_name),
            value("message", &R::message)};
  }
};

TerrainPeerRow base_row(const Point& point, const Inputs& in, const std::string& source) {
  TerrainPeerRow r;
  r.id = point.id;
  r.scene = in.scene_name;
  r.label = in.label;
  r.source = source;
  r.terrain = terrain::kind_name(in.scene.terrain);
  const double deg = 180.0 / std::numbers::pi;
  if (const auto* slope = std::get_if<terrain::Slope>(&in.scene.terrain)) {
    r.heading_deg = slope->heading * deg;
    r.ground_slope_deg = slope->angle * deg;
  } else if (const auto* st = std::get_if<terrain::Stairs>(&in.scene.terrain)) {
    r.heading_deg = st->heading * deg;
    r.ground_slope_deg = std::atan(st->riser / st->tread) * deg;
  }
  r.frequency = in.frequency;
  r.cycles = in.cycles;
  r.kp_xy = in.kp_xy;
  r.kp_z = in.kp_z;
  r.solref_timeconst = in.solref_timeconst;
  r.noslip_iterations = in.noslip_iterations;
  r.inertia_scale = in.inertia_scale;
  return r;
}

/// The body's nose-up pitch of one of our frames: on stairs the stairs' slope γ less δβ
/// (terrain.hpp: β₀ = −γ), elsewhere −β (eq. 3.6), relative to the ground or the slope's plane.
double our_pitch(const terrain::Terrain& ground, const core::Pose2& pose, const contact::Frame& f) {
  if (const auto* st = std::get_if<terrain::Stairs>(&ground)) {
    return terrain::stair_pitch(*st, pose.theta) - f.beta;
  }
  return -f.beta;
}

/// The scene under `law` ("viscous" or "coulomb"), a row every sample.
void run_ours(const Point& point, const Inputs& in, std::string_view law,
              Rows<TerrainPeerRow>& out) {
  scene::Scene sc = in.scene;
  sc.friction.law = scene::find_friction_law(law)->law;
  const scene::Simulator sim = scene::compose(sc);
  const long long every = std::max(1LL, std::llround(in.sample / sc.dt));
  const std::string source = "ours_" + std::string(law);
  const std::size_t first = out.rows.size();
  const connection::TrajectorySummary summary = sim.run([&](const connection::TrajectoryStep& s) {
    if (s.n % every != 0 && s.n != sim.options.steps) {
      return;
    }
    TerrainPeerRow r = base_row(point, in, source);
    r.t = s.t;
    r.x = s.pose.x;
    r.y = s.pose.y;
    r.theta = s.pose.theta;
    const Eigen::Vector3d b = terrain::body_world(in.scene.terrain, s.pose, s.frame);
    r.bx = b(0);
    r.by = b(1);
    r.bz = b(2);
    r.pitch = our_pitch(in.scene.terrain, s.pose, s.frame);
    r.roll = s.frame.alpha;
    for (char c : s.frame.contact) {
      r.contacts += c != 0 ? 1 : 0;
    }
    out.rows.push_back(std::move(r));
  });
  const std::string& message = summary.non_finite.empty() ? summary.message : summary.non_finite;
  for (std::size_t i = first; i < out.rows.size(); ++i) {
    out.rows[i].message = message;
  }
}

#ifdef SLIPWALK_HAVE_MUJOCO
/// MuJoCo's BigANT on the scene's terrain, from our support at t = 0.
void run_mujoco(const Point& point, const Inputs& in, Rows<TerrainPeerRow>& out) {
  const scene::Simulator sim = scene::compose(in.scene);
  const robots::Walker& w = sim.walker;
  peer::BigAntPeerSpec spec = peer::bigant_peer_spec(w);
  spec.timestep = in.timestep;
  spec.kp_xy = in.kp_xy;
  spec.kp_z = in.kp_z > 0.0 ? in.kp_z : w.robot.K.mean();
  spec.damping = in.damping;
  spec.solref_timeconst = in.solref_timeconst;
  spec.iterations = in.iterations;
  spec.noslip_iterations = in.noslip_iterations;
  spec.chassis_inertia *= in.inertia_scale;
  spec.terrain = in.scene.terrain;
  const peer::BigAntModel model(spec);
  peer::BigAntData data(model);

  // Our frame at t = 0 (spring support on this terrain) places MuJoCo's chassis.
  scene::Simulator first = sim;
  first.options.steps = 0;
  double z = 0.0, alpha = 0.0, beta = 0.0;
  (void)first.run([&](const connection::TrajectoryStep& s) {
    z = s.frame.z;
    alpha = s.frame.alpha;
    beta = -our_pitch(in.scene.terrain, s.pose, s.frame);  // bigant_place's β: nose-down
  });
  peer::BigAntDriveOptions options;
  options.duration = in.scene.duration;
  options.settle = in.settle;
  options.sample = in.sample;
  const terrain::Terrain& ground = in.scene.terrain;
  const auto* slope = std::get_if<terrain::Slope>(&ground);
  const std::string name = "mujoco " + peer::version();
  const std::size_t first_row = out.rows.size();
  const peer::BigAntDriveSummary summary = peer::bigant_drive(
      model, data, w.feet, z, alpha, beta, options, [&](const peer::BigAntSample& s) {
        TerrainPeerRow r = base_row(point, in, "mujoco");
        r.kp_z = spec.kp_z;
        const Eigen::Vector3d p = peer::bigant_position(data);
        const Eigen::Vector2d tilt = peer::bigant_tilt(data);
        r.t = s.t;
        r.x = p(0);
        r.y = p(1);
        r.theta = s.pose.theta;  // unwrapped, from the settled yaw
        const Eigen::Vector3d b =
            slope != nullptr ? terrain::slope_to_world(*slope, p(0), p(1), p(2)) : p;
        r.bx = b(0);
        r.by = b(1);
        r.bz = b(2);
        r.roll = tilt(0);
        r.pitch = tilt(1);
        r.contacts = s.contacts;
        r.edge_contacts = peer::bigant_edge_contacts(model, data);
        r.peer_name = name;
        out.rows.push_back(std::move(r));
      });
  const double share = static_cast<double>(summary.edge_steps) /
                       static_cast<double>(std::max(1LL, summary.tracking.steps));
  for (std::size_t i = first_row; i < out.rows.size(); ++i) {
    out.rows[i].edge_share = share;
  }
}
#endif

Rows<TerrainPeerRow> run(const Point& point) {
  Inputs in = read(point);
  if (in.kp_z == 0.0) {
    in.kp_z = scene::compose(in.scene).walker.robot.K.mean();
  }
  Rows<TerrainPeerRow> out;
  if (in.ours) {
    run_ours(point, in, "viscous", out);
    run_ours(point, in, "coulomb", out);
  }
#ifdef SLIPWALK_HAVE_MUJOCO
  run_mujoco(point, in, out);
#else
  const std::string message =
      "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): MuJoCo not run";
  static std::once_flag warned;
  std::call_once(warned,
                 [&] { std::cerr << "slipwalk: warning: peer_terrain: " << message << '\n'; });
  TerrainPeerRow r = base_row(point, in, "mujoco");
  const double nan = std::nan("");
  r.t = r.x = r.y = r.theta = r.bx = r.by = r.bz = r.pitch = r.roll = nan;
  r.contacts = -1;
  r.edge_contacts = -1;
  r.edge_share = nan;
  r.message = message;
  out.rows.push_back(std::move(r));
#endif
  return out;
}

}  // namespace

std::vector<PointKind> peer_terrain_kinds() {
  return {make_point_kind<TerrainPeerRow>(
      "peer_terrain",
      "§5.2, Figs. 5.2-5.3: a terrain scene (slope, stairs) walked by our model (viscous-Coulomb, "
      "Coulomb) and by MuJoCo's BigANT on the same terrain, driven by the same feet (one row per "
      "sample and source: pose, body world position, pitch, roll, contacts)",
      Timed::kNo, [](const Point& p) { (void)read(p); }, run)};
}

}  // namespace slipwalk::sweeps::points
