// The slope point kinds of §5.2.1 (sweeps/points/slope.cpp): bad keys name themselves; the
// bisection of stall_slope keeps its invariant (progress below the bracket, none above it, the
// bracket narrower than tol_deg, stall_deg its midpoint); each of its probes is the walk
// slope_progress makes at that angle, bit for bit; and under Coulomb friction (BigANT's μ = 1)
// the tripod stalls where the slope's pull overcomes friction, tan θ = μ: θ = 45°.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {
namespace {

double num(const PointKind& f, const Cells& row, const std::string& name) {
  const Cell& c = row.at(test_support::column(f, name));
  if (const auto* d = std::get_if<double>(&c)) {
    return *d;
  }
  return static_cast<double>(std::get<long long>(c));
}

/// The rows of the single point of KIND with BODY, checked first.
PointResult run(const std::string& kind, const std::string& body) {
  const PointKind& f = test_support::point_kind(kind);
  const std::vector<Point> pts = test_support::points_of(kind, body);
  EXPECT_EQ(pts.size(), 1u);
  f.check(pts.at(0));
  return f.run(pts.at(0));
}

void expect_input_error(const std::string& kind, const std::string& body, const std::string& key) {
  const std::vector<Point> pts = test_support::points_of(kind, body);
  try {
    test_support::point_kind(kind).check(pts.at(0));
    ADD_FAILURE() << "accepted: " << body;
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

const std::string kShortWalk = "steps_per_cycle = 100\n";  // 3 cycles of 100 steps

TEST(SlopePoints, BadKeysAndValuesNameTheKey) {
  expect_input_error("slope_progress", "[params]\nlaw = \"ice\"\n", "law");
  expect_input_error("slope_progress", "[params]\nangle_deg = 90.0\n", "angle_deg");
  expect_input_error("slope_progress", "[params]\ncycles = 1\n", "cycles");
  expect_input_error("slope_progress", "[params]\nlo_deg = 1.0\n", "lo_deg");
  expect_input_error("stall_slope", "[params]\nlo_deg = 20.0\nhi_deg = 10.0\n", "hi_deg");
  expect_input_error("stall_slope", "[params]\nangle_deg = 5.0\n", "angle_deg");
  expect_input_error("stall_slope", "[params]\ntol_deg = 0.0\n", "tol_deg");
}

TEST(SlopePoints, CoulombTripodStallsWhereTheSlopeExceedsFriction) {
  const PointKind& f = test_support::point_kind("stall_slope");
  const double tol = 0.05;
  const PointResult r = run("stall_slope", "[params]\nlaw = \"coulomb\"\nlo_deg = 30.0\n" +
                                               kShortWalk + "tol_deg = 0.05\n");
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_GE(r.rows.size(), 3u);
  const double lo = num(f, r.rows[0], "bracket_lo_deg");
  const double hi = num(f, r.rows[0], "bracket_hi_deg");
  EXPECT_LE(hi - lo, tol);
  EXPECT_EQ(num(f, r.rows[0], "stall_deg"), 0.5 * (lo + hi));
  // tan θ = μ = 1: below 45° friction holds the stance feet, above it they slide.
  EXPECT_NEAR(num(f, r.rows[0], "stall_deg"), 45.0, tol);
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const Cells& row = r.rows[i];
    SCOPED_TRACE("probe " + std::to_string(i));
    EXPECT_EQ(num(f, row, "step"), static_cast<double>(i));
    EXPECT_EQ(num(f, row, "bracket_lo_deg"), lo);  // every row carries the final bracket
    EXPECT_EQ(num(f, row, "bracket_hi_deg"), hi);
    const double angle = num(f, row, "angle_deg");
    const bool progress =
        num(f, row, "sliding_frames") == 0.0 && num(f, row, "progress_per_cycle") > 0.0;
    if (angle <= lo) {
      EXPECT_TRUE(progress) << angle;
    }
    if (angle >= hi) {
      EXPECT_FALSE(progress) << angle;
    }
  }
}

// A probe of the bisection is the walk of slope_progress at the same angle: the same numbers.
TEST(SlopePoints, StallProbesAreTheProgressWalks) {
  const PointKind& stall = test_support::point_kind("stall_slope");
  const PointKind& progress = test_support::point_kind("slope_progress");
  const PointResult r =
      run("stall_slope", "[params]\nlaw = \"viscous\"\nhi_deg = 8.0\ntol_deg = 1.0\n" + kShortWalk);
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_GE(r.rows.size(), 3u);
  for (const Cells& row : r.rows) {
    const double angle = num(stall, row, "angle_deg");
    const PointResult p = run("slope_progress", "[params]\nlaw = \"viscous\"\nangle_deg = " +
                                                    core::format_double(angle) + "\n" + kShortWalk);
    ASSERT_EQ(p.rows.size(), 1u);
    SCOPED_TRACE("angle " + std::to_string(angle));
    for (const std::string name : {"angle_deg", "progress_per_cycle", "sliding_frames",
                                   "not_converged_frames", "unsupported_frames"}) {
      EXPECT_EQ(num(stall, row, name), num(progress, p.rows[0], name)) << name;
    }
  }
}

// Past the holding angle no Coulomb balance exists in any frame: every frame slides, and the
// run is marked sliding (no progress for the bisection).
TEST(SlopePoints, CoulombPastTheHoldingAngleSlidesEveryFrame) {
  const PointKind& f = test_support::point_kind("slope_progress");
  const PointResult flat =
      run("slope_progress", "[params]\nlaw = \"coulomb\"\nangle_deg = 0.0\n" + kShortWalk);
  const PointResult steep =
      run("slope_progress", "[params]\nlaw = \"coulomb\"\nangle_deg = 50.0\n" + kShortWalk);
  ASSERT_EQ(flat.rows.size(), 1u);
  ASSERT_EQ(steep.rows.size(), 1u);
  EXPECT_GT(num(f, flat.rows[0], "progress_per_cycle"), 0.0);
  EXPECT_EQ(num(f, flat.rows[0], "sliding_frames"), 0.0);
  EXPECT_EQ(num(f, steep.rows[0], "sliding_frames"), 3.0 * 100.0 + 1.0);  // every frame, t = 0 too
}

}  // namespace
}  // namespace slipwalk::sweeps
