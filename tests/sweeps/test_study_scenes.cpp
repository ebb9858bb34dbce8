// [[scene]] entries of a study: a scene file run into <data>/<study>/<name>.csv with
// the `slipwalk run` columns, its overrides (law, filter, duration, dt, quick_duration) equal to
// writing them in the scene file, and every bad entry named file:line:col.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "sweeps/engine/job.hpp"
#include "sweeps/engine/study.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::read_text;
using testing::run_slipwalk;
using testing::ScratchDir;
using testing::write_text;

// A short tripod run; {LAW} and {EXTRA} are filled per test.
std::string scene_text(const std::string& law, const std::string& extra = "") {
  return "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = 0.1\n"
         "[run]\nduration = 0.3\ndt = 0.01\n[friction]\nlaw = \"" +
         law + "\"\n" + extra;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    out.push_back(line);
  }
  return out;
}

TEST(StudyScenes, OverridesApplyAndEqualTheSceneFileSaysSo) {
  const ScratchDir d;
  std::filesystem::create_directories(d / "scenes");
  write_text(d / "scenes" / "tripod.toml", scene_text("viscous"));
  write_text(d / "scenes" / "tripod_coulomb.toml", scene_text("coulomb"));
  write_text(d / "scenes" / "tripod_filter.toml", scene_text("viscous", "[filter]\ngamma = 0.3\n"));
  write_text(d / "study.toml", R"(title = "robots"
[[scene]]
name = "as_file"
file = "scenes/tripod.toml"
[[scene]]
name = "coulomb_override"
file = "scenes/tripod.toml"
law = "coulomb"
[[scene]]
name = "coulomb_file"
file = "scenes/tripod_coulomb.toml"
[[scene]]
name = "filter_override"
file = "scenes/tripod.toml"
gamma = 0.3
[[scene]]
name = "filter_file"
file = "scenes/tripod_filter.toml"
[[scene]]
name = "filter_off"
file = "scenes/tripod_filter.toml"
filter = false
duration = 0.5
dt = 0.005
quick_duration = 0.05
)");
  const Study study = load_study(d.path());
  ASSERT_EQ(study.scenes.size(), 6U);
  EXPECT_EQ(study.scenes[0].scene.steps, 30);
  EXPECT_EQ(study.scenes[1].scene.friction.law, connection::FrictionLaw::kCoulomb);
  ASSERT_TRUE(study.scenes[3].scene.filter.has_value());
  EXPECT_EQ(study.scenes[3].scene.filter->gamma, 0.3);
  EXPECT_FALSE(study.scenes[5].scene.filter.has_value());
  EXPECT_EQ(study.scenes[5].scene.steps, 100);
  ASSERT_TRUE(study.scenes[5].quick_duration.has_value());

  const auto data = d / "data";
  std::vector<std::string> csv;
  for (const auto& job : study.scenes) {
    csv.push_back(read_text(write_scene_job(study, job, data, false).csv));
  }
  // An override is the scene file written with it: byte-identical trajectories.
  EXPECT_EQ(csv[1], csv[2]);
  EXPECT_EQ(csv[3], csv[4]);
  EXPECT_NE(csv[0], csv[1]);  // the laws differ (a test that cannot fail is a defect)
  EXPECT_NE(csv[0], csv[3]);
  // Rows: header + steps + 1 frames; the filter's model columns only with the filter.
  EXPECT_EQ(lines_of(csv[0]).size(), 1U + 31U);
  EXPECT_EQ(lines_of(csv[5]).size(), 1U + 101U);
  EXPECT_EQ(lines_of(csv[4])[0].find("vx_model") == std::string::npos, false);
  EXPECT_EQ(lines_of(csv[5])[0].find("vx_model"), std::string::npos);
  // Quick mode runs quick_duration (0.05 s at dt 0.005: 11 frames); without one, the duration.
  EXPECT_EQ(lines_of(read_text(write_scene_job(study, study.scenes[5], data, true).csv)).size(),
            12U);
  EXPECT_EQ(lines_of(read_text(write_scene_job(study, study.scenes[0], data, true).csv)).size(),
            32U);

  const auto side = nlohmann::json::parse(read_text(data / study.id / "coulomb_override.json"));
  EXPECT_EQ(side.at("kind"), "scene_run");
  EXPECT_EQ(side.at("scene").at("friction").at("law"), "coulomb");
  EXPECT_EQ(side.at("spec").at("law"), "coulomb");
  EXPECT_EQ(side.at("columns").size(),
            static_cast<std::size_t>(std::count(
                csv[1].begin(), csv[1].begin() + static_cast<long>(csv[1].find('\n')), ',')) +
                1U);
}

TEST(StudyScenes, SameRowsAsTheRunCommand) {
  const ScratchDir d;
  std::filesystem::create_directories(d / "scenes");
  write_text(d / "scenes" / "tripod.toml", scene_text("viscous"));
  write_text(d / "study.toml", "[[scene]]\nname = \"r\"\nfile = \"scenes/tripod.toml\"\n");
  const Study study = load_study(d.path());
  const std::string ours =
      read_text(write_scene_job(study, study.scenes[0], d / "data", false).csv);
  const auto run = run_slipwalk(
      {"run", (d / "scenes" / "tripod.toml").string(), "--out", (d / "run.csv").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_text(d / "run.csv"), ours);
}

TEST(StudyScenes, BadEntriesNameFileLineColumn) {
  const ScratchDir d;
  std::filesystem::create_directories(d / "scenes");
  write_text(d / "scenes" / "tripod.toml", scene_text("viscous"));
  struct Case {
    std::string body, where, what;
  };
  const std::string head =
      "title = \"t\"\n[[scene]]\nname = \"s\"\nfile = \"scenes/tripod.toml\"\n";
  for (const Case& c : std::vector<Case>{
           {"lawn = \"coulomb\"\n", "study.toml:5:1", "unknown key 'lawn'"},
           {"law = \"dry\"\n", "study.toml:5:7", "law"},
           {"filter = false\ngamma = 0.2\n", "study.toml:6:9", "gamma"},
           {"gamma = 1.5\n", "study.toml:5:9", "gamma"},
           {"filter = 1\n", "study.toml:5:10", "filter"},
           {"duration = 0.305\n", "study.toml:5:12", "whole number"},
           {"duration = -1.0\n", "study.toml:5:12", "duration"},
           {"quick_duration = 0.015\n", "study.toml:5:18", "quick_duration"},
           {"gamma = nan\n", "study.toml:5:9", "gamma: must be in [0, 1)"},
           {"dt = 1e-320\n", "study.toml:5:6", "dt: must be in [1e-09, 1000] s"},
           {"duration = 1e308\n", "study.toml:5:12", "duration: must be in [1e-09, 1000000000] s"},
           // The override's run would write 13 GB: refused at the override, with the estimate.
           {"duration = 1e4\ndt = 1e-3\n", "study.toml:6:6",
            "dt: the run would write 10000001 rows"},
       }) {
    write_text(d / "study.toml", head + c.body);
    try {
      (void)load_study(d.path());
      ADD_FAILURE() << c.body;
    } catch (const core::InputError& e) {
      EXPECT_NE(e.where().find(c.where), std::string::npos) << c.body << " -> " << e.where();
      EXPECT_NE(std::string(e.what()).find(c.what), std::string::npos) << e.what();
    }
  }
  // A missing scene file is named at the entry's `file`; a missing name at the table.
  write_text(d / "study.toml", "[[scene]]\nname = \"s\"\nfile = \"scenes/none.toml\"\n");
  EXPECT_THROW((void)load_study(d.path()), core::InputError);
  try {
    (void)load_study(d.path());
  } catch (const core::InputError& e) {
    EXPECT_NE(e.where().find("study.toml:3:8"), std::string::npos) << e.where();
  }
  write_text(d / "study.toml", "[[scene]]\nfile = \"scenes/tripod.toml\"\n");
  EXPECT_THROW((void)load_study(d.path()), core::InputError);
  // An error inside the scene file names the scene file.
  write_text(d / "scenes" / "bad.toml", scene_text("viscous", "[filter]\ngama = 0.1\n"));
  write_text(d / "study.toml", "[[scene]]\nname = \"s\"\nfile = \"scenes/bad.toml\"\n");
  try {
    (void)load_study(d.path());
    ADD_FAILURE() << "bad scene file accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(e.where().find("bad.toml:12:"), std::string::npos) << e.where();
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
