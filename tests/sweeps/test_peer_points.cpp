// The speed-comparison point kinds of §3.5.3 (sweeps/points/peer.cpp): their keys are checked
// (bad keys and values name the spec key); both kinds are timed and flag exactly their measured
// times (ns) as timing columns; parallel_overhead's rows hold what the figure relies on: one row
// per trajectory and thread count, the same increments and poses on every thread count, the
// prefix product equal to the sequential one, and the same values (timings aside) when run again.
// (peer_scaling's rows are tested with the peer, tests/peers/test_mujoco_peer.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {
namespace {

std::vector<Point> points(const std::string& kind, const std::string& body) {
  return test_support::points_of(kind, body);
}

const PointKind& fn(const std::string& name) { return test_support::point_kind(name); }

std::size_t col(const PointKind& f, const std::string& name) {
  return test_support::column(f, name);
}

void expect_input_error(const std::string& kind, const std::string& body, const std::string& key) {
  const auto pts = points(kind, body);
  try {
    fn(kind).check(pts.at(0));
    ADD_FAILURE() << "no error for " << body;
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    EXPECT_EQ(e.where().rfind("peer.toml", 0), 0u) << e.where();  // file[:line:col]
  }
}

TEST(PeerPoints, BadKeysAndValuesNameTheKey) {
  expect_input_error("peer_scaling", "[params]\nconfigs = 3\n", "N");  // N is required
  expect_input_error("peer_scaling", "[params]\nN = 2\n", "N");
  expect_input_error("peer_scaling", "[params]\nN = 3\nwarmstart = \"hot\"\n", "warmstart");
  expect_input_error("peer_scaling", "[params]\nN = 3\nlegs = 3\n", "legs");
  expect_input_error("parallel_overhead", "[params]\nmax_threads = 0\n", "max_threads");
  expect_input_error("parallel_overhead", "[params]\nsteps = 0.5\n", "steps");
  expect_input_error("parallel_overhead", "[params]\ndt = -1\n", "dt");
}

TEST(PeerPoints, TimedKindsFlagTheirMeasuredTimes) {
  for (const char* kind : {"peer_scaling", "parallel_overhead"}) {
    const PointKind& f = fn(kind);
    EXPECT_EQ(f.timed, Timed::kYes) << kind;
    ASSERT_FALSE(f.columns.empty());
    EXPECT_EQ(f.column_names().front(), "id");
    int timings = 0;
    for (const ColumnInfo& c : f.columns) {
      // The measured times are the time_*_ns columns; everything else is a value.
      const bool measured = c.name.starts_with("time_") && c.name.ends_with("_ns");
      EXPECT_EQ(c.timing, measured) << kind << ": " << c.name;
      if (c.timing) {
        EXPECT_EQ(c.unit, "ns") << kind << ": " << c.name;
        ++timings;
      }
    }
    EXPECT_GE(timings, 3) << kind;
  }
}

TEST(PeerPoints, ParallelOverheadRowsAreConsistent) {
  const PointKind& f = fn("parallel_overhead");
  const auto pts = points("parallel_overhead",
                          "[params]\ntrajectories = 3\nsteps = 500\nmax_threads = 3\nblocks = 8\n");
  ASSERT_EQ(pts.size(), 1u);
  f.check(pts[0]);
  const PointResult r = f.run(pts[0]);
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_EQ(r.rows.size(), 9u);  // 3 trajectories × M = 1, 2, 3
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const Cells& row = r.rows[i];
    ASSERT_EQ(row.size(), f.columns.size());
    EXPECT_EQ(std::get<long long>(row[col(f, "trajectory")]), static_cast<long long>(i / 3));
    EXPECT_EQ(std::get<long long>(row[col(f, "threads")]), static_cast<long long>(i % 3 + 1));
    EXPECT_EQ(std::get<long long>(row[col(f, "same_as_one_thread")]), 1);
    EXPECT_LE(std::get<double>(row[col(f, "scan_max_diff")]), 1e-12);
    EXPECT_EQ(std::get<long long>(row[col(f, "unsupported")]), 0);
    for (const char* t :
         {"time_increments_ns", "time_sequential_ns", "time_scan_ns", "time_cpu_increments_ns"}) {
      EXPECT_GT(std::get<double>(row[col(f, t)]), 0.0) << t;
    }
    // Every thread count reports the same end pose of a trajectory (bitwise, also in the CSV).
    const Cells& first = r.rows[i - i % 3];
    EXPECT_EQ(std::get<double>(row[col(f, "end_x")]), std::get<double>(first[col(f, "end_x")]));
    // The body moves: 500 steps of 0.01 s at ~0.1 m/s.
    EXPECT_GT(
        std::hypot(std::get<double>(row[col(f, "end_x")]), std::get<double>(row[col(f, "end_y")])),
        0.05);
  }
  // Run again: every value column is the same to the bit (the CSV under --no-timing is).
  const PointResult again = f.run(pts[0]);
  EXPECT_EQ(test_support::first_value_difference(f, r, again), "");
}

}  // namespace
}  // namespace slipwalk::sweeps
