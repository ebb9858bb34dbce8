// The scaling benchmark's point kinds (sweeps/points/scale_out.cpp), run through the binary as the
// study runs them: every mode of scale_out reproduces the serial CSV byte for byte, and the
// coordinator's counts add up; noop does nothing but write its row.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/json_input.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::read_text;
using testing::run_slipwalk;
using testing::ScratchDir;
using testing::write_text;

/// The CSV's rows as maps from column name to cell.
std::vector<std::map<std::string, std::string>> rows_of(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream s(text);
    for (std::string cell; std::getline(s, cell, ',');) {
      cells.push_back(cell);
    }
    if (!text.empty() && text.back() == ',') {
      cells.emplace_back();
    }
    return cells;
  };
  const std::vector<std::string> header = split(line);
  std::vector<std::map<std::string, std::string>> out;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) {
      row[header[i]] = cells[i];
    }
    out.push_back(row);
  }
  return out;
}

const char* const kWorkload = R"(study = "w"
name = "w"
kind = "inchworm_vss"
[params]
rtol = 1e-8
[axes]
F_frac = { linspace = [0.1, 0.9], n = 3 }
method = ["exact", "analytic"]
)";

TEST(ScaleOut, EveryModeWritesTheSerialRunsBytesAndReportsItsTime) {
  const ScratchDir dir;
  write_text(dir / "w.toml", kWorkload);
  write_text(dir / "s.toml",
             "study = \"so\"\nname = \"e\"\nkind = \"scale_out\"\n[params]\nworkload = "
             "\"w.toml\"\nranks = 2\nrepeats = 2\n");
  const auto r = run_slipwalk(
      {"sweep", (dir / "s.toml").string(), "--data", (dir / "data").string(), "--jobs", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = rows_of(read_text(dir / "data" / "so" / "e.csv"));
  ASSERT_EQ(rows.size(), 8U);  // 2 rounds × 4 modes
  std::map<std::string, int> seen;
  for (const auto& row : rows) {
    ++seen[row.at("mode")];
    EXPECT_EQ(row.at("points"), "6");
    EXPECT_EQ(row.at("workers"), row.at("mode") == "serial" ? "1" : "2");
    if (row.at("mode") == "mpi" && !mpi::available()) {
      EXPECT_EQ(row.at("exit_code"), "-1");
      continue;
    }
    EXPECT_EQ(row.at("exit_code"), "0") << row.at("message");
    EXPECT_EQ(row.at("same_bytes"), "1") << row.at("mode");
    EXPECT_GT(std::stod(row.at("wall_s")), 0.0);
    EXPECT_GE(std::stod(row.at("process_wall_s")), std::stod(row.at("wall_s")));
  }
  for (const char* mode : {"serial", "threads", "mpi", "shards"}) {
    EXPECT_EQ(seen[mode], 2) << mode;
  }
  // Rounds rotate the order: round 0 starts with serial, round 1 with threads.
  EXPECT_EQ(rows[0].at("mode"), "serial");
  EXPECT_EQ(rows[4].at("mode"), "threads");
}

TEST(ScaleOut, TheCoordinatorHandsEveryPointToAnotherRankWhenItOnlyCoordinates) {
  if (!mpi::available()) {
    GTEST_SKIP() << "this build has no MPI (the kind's rows say so; see the scale_out test)";
  }
  const ScratchDir dir;
  write_text(dir / "c.toml",
             "study = \"so\"\nname = \"c\"\nkind = \"coordinator_throughput\"\n[params]\npoints "
             "= 3000\nranks = 3\nrepeats = 1\n");
  const auto r = run_slipwalk(
      {"sweep", (dir / "c.toml").string(), "--data", (dir / "data").string(), "--jobs", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = rows_of(read_text(dir / "data" / "so" / "c.csv"));
  ASSERT_EQ(rows.size(), 1U);
  const auto& row = rows[0];
  EXPECT_EQ(row.at("exit_code"), "0") << row.at("message");
  EXPECT_EQ(row.at("remote_points"), "3000");  // rank 0 computed none
  const double messages = std::stod(row.at("messages"));
  EXPECT_GE(messages, 2.0);  // at least one from each computing rank
  EXPECT_NEAR(std::stod(row.at("points_per_message")), 3000.0 / messages, 1e-9);
  EXPECT_GT(std::stod(row.at("points_per_cpu_s")), 0.0);
  EXPECT_NEAR(std::stod(row.at("points_per_s")), 3000.0 / std::stod(row.at("wall_s")), 1e-6);
}

TEST(ScaleOut, KindsThatRunTheBinaryRefuseToRunInsideAnotherProgram) {
  const ScratchDir dir;
  write_text(dir / "w.toml", kWorkload);
  const auto points = test_support::points_of(
      "scale_out", "[params]\nworkload = \"" + (dir / "w.toml").string() + "\"\nrepeats = 1\n");
  ASSERT_EQ(points.size(), 1U);
  EXPECT_THROW((void)test_support::point_kind("scale_out").run(points[0]), std::logic_error);
}

TEST(ScaleOut, AMissingWorkloadIsRefusedAtItsValue) {
  const auto points =
      test_support::points_of("scale_out", "[params]\nworkload = \"no-such.toml\"\n");
  try {
    test_support::point_kind("scale_out").check(points[0]);
    ADD_FAILURE() << "a missing workload passed the check";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "peer.toml:5:12") << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

TEST(Noop, WritesOneRowWithItsIdAndValue) {
  const auto points = test_support::points_of("noop", "[axes]\ni = [3.5, 7]\n");
  ASSERT_EQ(points.size(), 2U);
  const PointResult r = test_support::point_kind("noop").run(points[1]);
  ASSERT_EQ(r.rows.size(), 1U);
  EXPECT_EQ(std::get<long long>(r.rows[0][0]), 1);
  EXPECT_EQ(std::get<double>(r.rows[0][1]), 7.0);
  EXPECT_FALSE(r.failed);
}

}  // namespace
}  // namespace slipwalk::sweeps
