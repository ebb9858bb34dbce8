// MuJoCo's BigANT on §5.2's terrain (lib/peers/mujoco/bigant_spec.hpp, the point kind
// peer_terrain). Without MuJoCo: the slope's gravity is eq. 5.1 in the plane's frame (checked
// against terrain::slope_to_world's axes), the stair boxes' tops lie one foot radius below
// terrain::step_height over exactly their treads, bad terrain is refused by name, and the kind's
// keys and refusals. With MuJoCo: a robot standing on the slope with the no-slip solver holds and
// its feet carry Mg cos σ; on the stairs the feet settle on their treads' heights and the body's
// pitch is our spring support's; the kind gives rows of every source, ours on the scene's treads;
// MuJoCo's feet meet tread edges and risers on the stairs and never on the slope's plane.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <numbers>
#include <regex>
#include <string>
#include <variant>
#include <vector>

#include "core/error.hpp"
#include "peers/mujoco/bigant_spec.hpp"
#include "robots/robots.hpp"
#include "scene/scene.hpp"
#include "support/point_rows.hpp"
#include "support/skip_without_mujoco.hpp"
#include "terrain/terrain.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include "peers/mujoco/bigant_peer.hpp"
#endif

namespace slipwalk::peers::mujoco {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

BigAntPeerSpec spec_on(const terrain::Terrain& ground) {
  BigAntPeerSpec spec = bigant_peer_spec(robots::bigant_tripod());
  spec.kp_z = robots::bigant_tripod().robot.K(0);  // the leg spring (fig3_14.toml's base)
  spec.solref_timeconst = 0.005;
  spec.terrain = ground;
  return spec;
}

std::string scene_path(const char* name) {
  return (std::filesystem::path(SLIPWALK_SOURCE_DIR) / "studies" / "ch5_terrain" / "scenes" / name)
      .string();
}

// ---- without MuJoCo ----------------------------------------------------------------------------

TEST(BigAntTerrainSpec, SlopeGravityIsTheWorldsGravityInThePlanesAxes) {
  const terrain::Slope slope{.angle = 17.0 * kDeg, .heading = 30.0 * kDeg};
  const BigAntPeerSpec spec = spec_on(slope);
  const Eigen::Vector3d g = bigant_gravity(spec);
  // Second route: the plane's axes in the world (slope_to_world is linear through the origin),
  // and the world's (0, 0, −g) projected on them.
  const Eigen::Vector3d world(0.0, 0.0, -spec.gravity);
  const Eigen::Vector3d ex = terrain::slope_to_world(slope, 1.0, 0.0, 0.0);
  const Eigen::Vector3d ey = terrain::slope_to_world(slope, 0.0, 1.0, 0.0);
  const Eigen::Vector3d n = terrain::slope_to_world(slope, 0.0, 0.0, 1.0);
  EXPECT_NEAR(g(0), ex.dot(world), 1e-12);
  EXPECT_NEAR(g(1), ey.dot(world), 1e-12);
  EXPECT_NEAR(g(2), n.dot(world), 1e-12);
  // eq. 5.1: Mg cos σ along the normal, Mg sin σ downhill (−ψ).
  EXPECT_NEAR(g(2), -spec.gravity * std::cos(slope.angle), 1e-12);
  EXPECT_NEAR(g.head<2>().norm(), spec.gravity * std::sin(slope.angle), 1e-12);
  EXPECT_NEAR(std::atan2(-g(1), -g(0)), slope.heading, 1e-12);
  // The MJCF carries it, and flat ground keeps (0, 0, −g).
  std::ostringstream text;
  text.precision(17);
  text << "gravity=\"" << g(0) << ' ' << g(1) << ' ' << g(2) << '"';
  EXPECT_NE(bigant_mjcf(spec).find(text.str()), std::string::npos);
  EXPECT_EQ(bigant_gravity(spec_on(terrain::Flat{})), world);
}

TEST(BigAntTerrainSpec, StairBoxesTopOneFootRadiusBelowTheTreadOverExactlyTheirTread) {
  const terrain::Stairs stairs{.tread = 0.3, .riser = 0.12, .heading = 0.0};
  BigAntPeerSpec spec = spec_on(stairs);
  const std::string xml = bigant_mjcf(spec);
  EXPECT_EQ(xml.find("name=\"floor\""), std::string::npos);  // the boxes replace the plane
  const std::regex box(
      "name=\"tread(-?[0-9]+)\" type=\"box\" size=\"([^ ]+) ([^ ]+) ([^\"]+)\" pos=\"([^ ]+) "
      "([^ ]+) ([^\"]+)\"");
  int boxes = 0;
  double lo = 1e9, hi = -1e9;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), box); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    const double half_x = std::stod(m[2]), half_z = std::stod(m[4]);
    const double cx = std::stod(m[5]), cy = std::stod(m[6]), cz = std::stod(m[7]);
    // Just inside the box's two ends, terrain.hpp's h(p) is the box's top plus the foot radius.
    for (double dx : {-half_x + 1e-9, 0.0, half_x - 1e-9}) {
      EXPECT_NEAR(cz + half_z + spec.foot_radius, terrain::step_height(stairs, cx + dx, cy), 1e-9)
          << m[0];
    }
    lo = std::min(lo, cx - half_x);
    hi = std::max(hi, cx + half_x);
    ++boxes;
  }
  // Whole treads around the extent, no gap between them.
  EXPECT_LE(lo, spec.stairs_extent(0) + 1e-9);
  EXPECT_GE(hi, spec.stairs_extent(1) - 1e-9);
  EXPECT_NEAR(hi - lo, boxes * stairs.tread, 1e-9);
}

TEST(BigAntTerrainSpec, BadTerrainIsRefusedByName) {
  const auto message = [](const BigAntPeerSpec& s) {
    try {
      (void)bigant_mjcf(s);
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(spec_on(terrain::Slope{.angle = 2.0})).find("terrain.angle"),
            std::string::npos);
  EXPECT_NE(message(spec_on(terrain::Stairs{.tread = 0.0})).find("terrain.tread"),
            std::string::npos);
  BigAntPeerSpec s = spec_on(terrain::Stairs{});
  s.stairs_extent = Eigen::Vector2d(1.0, -1.0);
  EXPECT_NE(message(s).find("stairs_extent"), std::string::npos);
  s.stairs_extent = Eigen::Vector2d(0.0, 1e4);  // tens of thousands of boxes
  EXPECT_NE(message(s).find("stairs_extent"), std::string::npos);
  s = spec_on(terrain::Stairs{});
  s.stairs_half_width = -1.0;
  EXPECT_NE(message(s).find("stairs_half_width"), std::string::npos);
}

TEST(PeerTerrainKind, RefusesAMissingSceneBadValuesAndUnknownKeys) {
  const sweeps::PointKind& kind = test_support::point_kind("peer_terrain");
  const auto refusal = [&](const std::string& body) {
    try {
      for (const auto& p : test_support::points_of("peer_terrain", body)) {
        kind.check(p);
      }
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string stairs = "scene = \"" + scene_path("bigant_stairs.toml") + "\"\n";
  EXPECT_EQ(refusal("[params]\n" + stairs), "accepted");
  EXPECT_NE(refusal("[params]\ncycles = 1.0\n").find("scene: required"), std::string::npos);
  EXPECT_NE(refusal("[params]\nscene = \"no/such/scene.toml\"\n").find("scene: bad scene file"),
            std::string::npos);
  EXPECT_NE(refusal("[params]\n" + stairs + "solref_timeconst = 0.001\n").find("solref_timeconst"),
            std::string::npos);
  EXPECT_NE(refusal("[params]\n" + stairs + "frequency = -1.0\n").find("frequency"),
            std::string::npos);
  EXPECT_NE(refusal("[params]\n" + stairs + "tread = 0.3\n").find("unknown key 'tread'"),
            std::string::npos);
  EXPECT_NE(refusal("[params]\n" + stairs + "cycles = 100.0\nframes = 1\n").find("unknown key"),
            std::string::npos);
}

TEST(PeerTerrainKind, OursStartsOnTheScenesTreadsPitchedByTheStairsSlope) {
  // The standard leg: MuJoCo's robot with the stairs leg (toes 0.5 m below the chassis on soft
  // sideways actuators) tips back within the settling time (the referee study's finding), so the
  // placement is checked where the robot stands.
  const sweeps::PointKind& kind = test_support::point_kind("peer_terrain");
  const auto points = test_support::points_of(
      "peer_terrain",
      "[params]\nscene = \"" + scene_path("bigant_stairs_standard.toml") + "\"\ncycles = 0.05\n");
  ASSERT_EQ(points.size(), 1u);
  const sweeps::PointResult r = kind.run(points[0]);
  ASSERT_FALSE(r.failed) << r.message;
  const auto col = [&](const char* name) { return test_support::column(kind, name); };
  const double gamma = std::atan(0.12 / 0.3);
  int ours = 0, mujoco = 0;
  for (const auto& row : r.rows) {
    const std::string source = std::get<std::string>(row[col("source")]);
    EXPECT_NEAR(std::get<double>(row[col("ground_slope_deg")]), gamma / kDeg, 1e-9);
    if (source == "mujoco") {
      ++mujoco;
#ifdef SLIPWALK_HAVE_MUJOCO
      // MuJoCo starts where ours does: pitched nose-up near the stairs' slope.
      EXPECT_NEAR(std::get<double>(row[col("pitch")]), gamma, 5.0 * kDeg);
#endif
      continue;
    }
    ++ours;
    // Our body pitches with the stairs (γ less a small δβ) and stands above its hind treads.
    EXPECT_NEAR(std::get<double>(row[col("pitch")]), gamma, 5.0 * kDeg) << source;
    EXPECT_GT(std::get<double>(row[col("bz")]), 0.0) << source;
  }
  EXPECT_GE(ours, 2);
  EXPECT_GE(mujoco, 1);
}

TEST(PeerTerrainKind, MujocosFeetMeetEdgesOnTheStairsAndNeverOnTheSlope) {
  SKIP_WITHOUT_MUJOCO();
  const sweeps::PointKind& kind = test_support::point_kind("peer_terrain");
  const auto share = [&](const char* scene) {
    const auto points = test_support::points_of(
        "peer_terrain", std::string("[params]\nscene = \"") + scene_path(scene) +
                            "\"\ncycles = 1.0\nours = \"none\"\nsample = 1.0\n"
                            "noslip_iterations = 20\nkp_xy = 10000.0\n");
    const sweeps::PointResult r = kind.run(points.at(0));
    EXPECT_FALSE(r.failed) << r.message;
    return std::get<double>(r.rows.at(0).at(test_support::column(kind, "edge_share")));
  };
  // A returning toe meets a 12 cm riser (the toes lift a few cm); a plane has no edge.
  EXPECT_GT(share("bigant_stairs.toml"), 0.05);
  EXPECT_EQ(share("bigant_slope17.toml"), 0.0);
}

// ---- with MuJoCo -------------------------------------------------------------------------------

#ifdef SLIPWALK_HAVE_MUJOCO
/// Our first frame of a flat or slope scene: (z, α, β) as bigant_place takes them.
Eigen::Vector3d our_start(const std::string& file) {
  scene::Simulator sim = scene::compose(scene::read_scene(file));
  sim.options.steps = 0;
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  (void)sim.run(
      [&](const connection::TrajectoryStep& s) { out << s.frame.z, s.frame.alpha, s.frame.beta; });
  return out;
}

/// Holds the gait's t = 0 feet for `seconds`.
void hold(const BigAntModel& model, BigAntData& data, const Eigen::Vector3d& start,
          double seconds) {
  const robots::Walker w = robots::bigant_tripod();
  BigAntDriveOptions options;
  options.settle = seconds;
  options.duration = 0.01;
  const robots::FootKinematics frozen = [&w](double, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qd) {
    w.feet(0.0, q, qd);
    qd.setZero();
  };
  (void)bigant_drive(model, data, frozen, start(0), start(1), start(2), options, {});
  mj_forward(model.mj(), data.mj());
  bigant_read_legs(model, data);
}
#endif

TEST(BigAntTerrainPeer, StandingOnTheSlopeWithNoSlipFeetHoldsAndTheFeetCarryMgCosSigma) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const double sigma = 17.0 * kDeg;
  BigAntPeerSpec spec = spec_on(terrain::Slope{.angle = sigma});
  spec.noslip_iterations = 20;
  spec.kp_xy = 1e4;  // stiff legs: the feet's sway under the downhill load is not the point here
  const BigAntModel model(spec);
  BigAntData data(model);
  const Eigen::Vector3d start = our_start(scene_path("bigant_slope17.toml"));
  BigAntData early(model);
  hold(model, early, start, 1.0);
  hold(model, data, start, 3.0);  // the same placement and settling, then two seconds more
  // Two more seconds standing: no creep downhill (a soft contact without no-slip creeps).
  const double Mg = spec.total_mass * spec.gravity;
  EXPECT_LT((bigant_position(data) - bigant_position(early)).head<2>().norm(), 1e-3);
  EXPECT_NEAR(data.Fz.sum(), Mg * std::cos(sigma), 0.01 * Mg);
  // The planar friction balances the slope's pull: Mg sin σ uphill in total (within 2 % of Mg:
  // the chassis still rocks by mm/s on its springs, and the forces are one step's).
  EXPECT_NEAR(data.Fxy.rowwise().sum()(0), Mg * std::sin(sigma), 0.02 * Mg);
  EXPECT_LT(std::abs(data.Fxy.rowwise().sum()(1)), 0.02 * Mg);
#endif
}

TEST(BigAntTerrainPeer, OnTheStairsTheFeetSettleOnTheirTreadsAndTheBodyPitchesAsOurs) {
  SKIP_WITHOUT_MUJOCO();
#ifdef SLIPWALK_HAVE_MUJOCO
  const terrain::Stairs stairs{.tread = 0.3, .riser = 0.12};
  BigAntPeerSpec spec = spec_on(stairs);
  spec.kp_xy = 1e4;
  const BigAntModel model(spec);
  BigAntData data(model);
  scene::Simulator sim = scene::compose(scene::read_scene(scene_path("bigant_stairs.toml")));
  sim.options.steps = 0;
  double our_pitch = 0.0;
  Eigen::Vector3d start;
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    our_pitch = terrain::stair_pitch(stairs, 0.0) - s.frame.beta;
    start << s.frame.z, s.frame.alpha, -our_pitch;
  });
  hold(model, data, start, 2.0);
  int down = 0;
  for (int k = 0; k < 6; ++k) {
    if (data.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    ++down;
    // A foot centre at rest on a tread lies at the tread's height (less the contact's sinkage).
    const std::ptrdiff_t geom = model.foot_geom[static_cast<std::size_t>(k)];
    const mjtNum* c = data.mj()->geom_xpos + 3 * geom;
    EXPECT_NEAR(c[2], terrain::step_height(stairs, c[0], c[1]), 3e-3) << "leg " << k;
  }
  EXPECT_GE(down, 3);
  // The same springs at rest: MuJoCo's pitch is our spring support's on the stairs.
  EXPECT_NEAR(bigant_tilt(data)(1), our_pitch, 1.0 * kDeg);
#endif
}

}  // namespace
}  // namespace slipwalk::peers::mujoco
