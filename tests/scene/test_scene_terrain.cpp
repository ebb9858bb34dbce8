// The [terrain] table of a scene (§5.2): every field, every error class at file:line:col
// (unknown key with the nearest name, wrong type, out of range, missing field, a parameter of
// another terrain kind), and compose() picking the terrain's kernel.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {
namespace {

const std::string kBase = R"([robot]
name = "bigant"

[gait]
kind = "tripod"
frequency = 0.5

[run]
duration = 0.4
dt = 0.02

[friction]
law = "viscous"

)";  // 14 lines; [terrain] starts on line 15

void expect_error(const std::string& terrain, const std::string& at, const std::string& part) {
  const std::string text = kBase + terrain;
  try {
    (void)parse_scene(text, "scene.toml");
    ADD_FAILURE() << "no error for:\n" << terrain;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "scene.toml:" + at) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(SceneTerrain, ReadsEachKind) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  const Scene flat = parse_scene(kBase, "s.toml");
  EXPECT_TRUE(std::holds_alternative<terrain::Flat>(flat.terrain));
  const Scene slope = parse_scene(
      kBase + "[terrain]\nkind = \"slope\"\nangle_deg = 17\nheading_deg = 90\ncom_height = 0.1\n",
      "s.toml");
  const auto& s = std::get<terrain::Slope>(slope.terrain);
  EXPECT_DOUBLE_EQ(s.angle, 17.0 * kDeg);
  EXPECT_DOUBLE_EQ(s.heading, 90.0 * kDeg);
  EXPECT_EQ(s.com_height, 0.1);
  EXPECT_EQ(to_json(slope)["terrain"]["kind"], "slope");
  const Scene stairs =
      parse_scene(kBase + "[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = 0.12\n", "s.toml");
  const auto& st = std::get<terrain::Stairs>(stairs.terrain);
  EXPECT_EQ(st.tread, 0.3);
  EXPECT_EQ(st.riser, 0.12);
  EXPECT_EQ(st.heading, 0.0);
  EXPECT_EQ(to_json(stairs)["terrain"]["riser"], 0.12);
}

TEST(SceneTerrain, Errors) {
  // unknown key, nearest name
  expect_error("[terrain]\nkind = \"slope\"\nangel_deg = 17\n", "17:1", "did you mean 'angle_deg'");
  expect_error("[terran]\nkind = \"slope\"\n", "15:2", "did you mean [terrain]");
  // unknown kind, nearest suggested
  expect_error("[terrain]\nkind = \"slop\"\n", "16:8", "slope");
  // wrong type
  expect_error("[terrain]\nkind = \"slope\"\nangle_deg = \"steep\"\n", "17:13", "angle_deg");
  expect_error("[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = true\n", "18:9", "riser");
  // out of range
  expect_error("[terrain]\nkind = \"slope\"\nangle_deg = 90\n", "17:13", "[0, 90)");
  expect_error("[terrain]\nkind = \"slope\"\nangle_deg = -1\n", "17:13", "[0, 90)");
  expect_error("[terrain]\nkind = \"slope\"\nangle_deg = 5\ncom_height = -0.1\n", "18:14",
               "com_height");
  expect_error("[terrain]\nkind = \"stairs\"\ntread = 0\nriser = 0.1\n", "17:9", "tread");
  expect_error("[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = -0.1\n", "18:9", "riser");
  // missing required fields
  expect_error("[terrain]\nangle_deg = 5\n", "15:1", "kind");
  expect_error("[terrain]\nkind = \"slope\"\n", "15:1", "angle_deg");
  expect_error("[terrain]\nkind = \"stairs\"\nriser = 0.1\n", "15:1", "tread");
  // a parameter of another kind
  expect_error("[terrain]\nkind = \"slope\"\nangle_deg = 5\ntread = 0.3\n", "18:9", "stairs");
  expect_error("[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = 0.1\nangle_deg = 3\n", "19:13",
               "slope");
  expect_error("[terrain]\nkind = \"flat\"\nheading_deg = 3\n", "17:15", "slope");
}

TEST(SceneTerrain, ComposePicksTheTerrainKernel) {
  const Scene flat = parse_scene(kBase, "s.toml");
  const Scene level = parse_scene(kBase + "[terrain]\nkind = \"slope\"\nangle_deg = 0\n", "s.toml");
  const Scene steep =
      parse_scene(kBase + "[terrain]\nkind = \"slope\"\nangle_deg = 20\n", "s.toml");
  EXPECT_EQ(compose(steep).kernel_name, "viscous+slope");
  EXPECT_EQ(compose(flat).kernel_name, "viscous");
  std::vector<double> a;
  std::vector<double> b;
  std::vector<double> c;
  (void)compose(flat).run([&](const connection::TrajectoryStep& s) { a.push_back(s.pose.x); });
  (void)compose(level).run([&](const connection::TrajectoryStep& s) { b.push_back(s.pose.x); });
  (void)compose(steep).run([&](const connection::TrajectoryStep& s) { c.push_back(s.pose.x); });
  EXPECT_EQ(a, b);                // a slope of angle 0 is flat ground, bit for bit
  EXPECT_LT(c.back(), a.back());  // 20° pulls the walker back (viscous law: it creeps downhill)
}

}  // namespace
}  // namespace slipwalk::scene
