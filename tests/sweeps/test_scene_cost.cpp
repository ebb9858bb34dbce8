// The scene_cost point kind (sweeps/points/scene_cost.cpp): one row per case in the order of the
// cases, the composed simulators' kernels named, and the identities its per-repeat statistics
// must keep whatever the clock says: the hand-written kernel's ratio to itself is 1, the flat
// composed scene's extra time over itself is 0, and the quartiles bracket the median. Every
// number it measures is flagged as a timing (written as 0 under --no-timing); no speed is
// asserted here (DESIGN.md: speed is measured in benchmarks and timed studies).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {
namespace {

const PointKind& fn() { return test_support::point_kind("scene_cost"); }

double num(const Cells& row, const std::string& name) {
  const Cell& c = row.at(test_support::column(fn(), name));
  if (const auto* d = std::get_if<double>(&c)) {
    return *d;
  }
  return static_cast<double>(std::get<long long>(c));
}

std::string text(const Cells& row, const std::string& name) {
  return std::get<std::string>(row.at(test_support::column(fn(), name)));
}

void expect_input_error(const std::string& body, const std::string& key) {
  const std::vector<Point> pts = test_support::points_of("scene_cost", body);
  try {
    fn().check(pts.at(0));
    ADD_FAILURE() << "accepted: " << body;
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(SceneCost, BadKeysAndValuesNameTheKey) {
  expect_input_error("[params]\nsteps = 0\n", "steps");
  expect_input_error("[params]\nrepeats = 0\n", "repeats");
  expect_input_error("[params]\nfrequency = 0.0\n", "frequency");
  expect_input_error("[params]\nlaw = \"viscous\"\n", "law");
}

TEST(SceneCost, RowsKeepTheIdentitiesOfTheirStatistics) {
  const std::vector<Point> pts =
      test_support::points_of("scene_cost", "[params]\nsteps = 20\nrepeats = 3\n");
  ASSERT_EQ(pts.size(), 1u);
  fn().check(pts[0]);
  const PointResult r = fn().run(pts[0]);
  ASSERT_FALSE(r.failed) << r.message;
  const std::vector<std::string> cases = {"handwritten", "none",   "anisotropic",
                                          "coulomb",     "filter", "residual",
                                          "noise",       "slope",  "stairs"};
  ASSERT_EQ(r.rows.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Cells& row = r.rows[i];
    SCOPED_TRACE(cases[i]);
    EXPECT_EQ(text(row, "case"), cases[i]);
    EXPECT_EQ(num(row, "steps"), 20.0);
    EXPECT_EQ(num(row, "repeats"), 3.0);
    EXPECT_FALSE(text(row, "kernel").empty());
    EXPECT_GT(num(row, "ns_per_step"), 0.0);
    EXPECT_LE(num(row, "ns_per_step_p25"), num(row, "ns_per_step"));
    EXPECT_LE(num(row, "ns_per_step"), num(row, "ns_per_step_p75"));
  }
  EXPECT_EQ(text(r.rows[0], "kernel"), "handwritten");
  EXPECT_EQ(num(r.rows[0], "ratio_to_handwritten"), 1.0);  // t / t per repeat
  EXPECT_EQ(num(r.rows[1], "extra_ns_per_step"), 0.0);     // t − t per repeat
  EXPECT_EQ(num(r.rows[1], "share_of_flat"), 0.0);
}

TEST(SceneCost, EveryMeasuredNumberIsATiming) {
  EXPECT_EQ(fn().timed, Timed::kYes);
  for (const ColumnInfo& c : fn().columns) {
    const bool label = c.name == "id" || c.name == "case" || c.name == "kernel" ||
                       c.name == "steps" || c.name == "repeats";
    EXPECT_EQ(c.timing, !label) << c.name;
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
