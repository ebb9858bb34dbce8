// The study pipeline called as a library (sweeps/engine/reproduce.hpp): a small study with a
// trace, a scene run and a sweep; every job's CSV and sidecar, the summary's counts against the
// files, the failed points listed by study and kind (known ones and expected budget stops apart),
// input errors before any file is written, and a second call that keeps every result.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "sweeps/engine/reproduce.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::ScratchDir;
using testing::write_text;

/// A study "tiny": a trace, a short tripod scene run and a 2 x 3 inchworm sweep whose analytic
/// points are stopped after 8 strokes (too few to converge: failed points, recorded).
void write_tiny_study(const fs::path& studies) {
  const fs::path dir = studies / "tiny";
  fs::create_directories(dir / "scenes");
  write_text(dir / "scenes" / "tripod.toml",
             "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = 0.1\n"
             "[run]\nduration = 0.2\ndt = 0.01\n[friction]\nlaw = \"viscous\"\n");
  write_text(dir / "vss.toml", R"(study = "tiny"
name = "vss"
kind = "inchworm_vss"
[params]
mu = 1.0
max_strokes = 8
[axes]
method = ["exact", "analytic"]
F = [20.0, 30.0, 45.0]
)");
  write_text(dir / "study.toml", R"(title = "a tiny study"
sweeps = ["vss.toml"]
[[trace]]
name = "trace"
F = 45.0
mu = 1.0
cycles = 2
dt = 0.01
[[scene]]
name = "walk"
file = "scenes/tripod.toml"
)");
}

ReproduceOptions options_for(const ScratchDir& d) {
  ReproduceOptions options;
  options.studies_dir = d / "studies";
  options.data_dir = d / "data";
  options.report = false;
  options.jobs = 2;
  options.kinds = points::all_kinds();
  return options;
}

/// Rows of a CSV (header excluded) whose `column` holds `value`.
long long rows_with(const std::string& csv, const std::string& column, const std::string& value) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, line, ',');) {
    header.push_back(line);
  }
  const auto at = std::find(header.begin(), header.end(), column) - header.begin();
  long long n = 0;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (long i = 0; i <= at; ++i) {
      std::getline(row, cell, ',');
    }
    n += cell == value ? 1 : 0;
  }
  return n;
}

TEST(Reproduce, RunsEveryJobAndCountsItsPoints) {
  const ScratchDir d;
  write_tiny_study(d / "studies");
  const ReproduceSummary s = reproduce(options_for(d));

  ASSERT_EQ(s.studies.size(), 1U);
  EXPECT_EQ(s.studies[0].title, "a tiny study");
  ASSERT_EQ(s.jobs.size(), 3U);
  const std::vector<std::string> kinds = {"trace", "scene", "sweep"};
  for (std::size_t i = 0; i < 3; ++i) {
    const JobSummary& j = s.jobs[i];
    EXPECT_EQ(j.kind, kinds[i]);
    EXPECT_EQ(j.csv.parent_path(), d / "data" / "tiny");
    EXPECT_TRUE(fs::is_regular_file(j.csv)) << j.csv;
    fs::path sidecar = j.csv;
    EXPECT_TRUE(fs::is_regular_file(sidecar.replace_extension(".json"))) << sidecar;
    EXPECT_EQ(j.resumed, 0);
  }
  // The sweep: 2 methods x 3 forces; its failed points are the rows with converged = 0, as the
  // sidecar records them.
  const JobSummary& sweep = s.jobs[2];
  EXPECT_EQ(sweep.points, 6);
  const std::string csv = read_text(sweep.csv);
  EXPECT_EQ(sweep.failed, rows_with(csv, "converged", "0"));
  EXPECT_GT(sweep.failed, 0);  // the analytic points cannot converge in 8 strokes
  EXPECT_EQ(rows_with(csv, "method", "exact") + sweep.failed, 6);
  const auto side = nlohmann::json::parse(read_text(d / "data" / "tiny" / "vss.json"));
  EXPECT_EQ(side.at("failed_point_count").get<long long>(), sweep.failed);
  EXPECT_EQ(s.failed_points(), sweep.failed);
  EXPECT_EQ(s.points(), 1 + 1 + 6);
  EXPECT_EQ(s.report, ReportOutcome::kOff);
  EXPECT_EQ(s.brief_report().find("; " + std::to_string(sweep.failed) + " sweep points failed"),
            s.brief_report().find(';'));
}

TEST(Reproduce, ListsTheFailedPointsByStudyAndKindAndKnownOnesApart) {
  const ScratchDir d;
  write_tiny_study(d / "studies");
  const ReproduceSummary s = reproduce(options_for(d));
  const JobSummary& sweep = s.jobs[2];
  ASSERT_GT(sweep.failed, 0);
  EXPECT_EQ(sweep.point_kind, "inchworm_vss");
  EXPECT_EQ(s.unexpected_failed_points(), sweep.failed);
  EXPECT_EQ(s.budget_points(), 0);
  const std::string report = s.failures_report();
  EXPECT_EQ(report.rfind("reproduce: failed points, by study and kind:\n", 0), 0U) << report;
  EXPECT_NE(report.find("  tiny/vss (kind inchworm_vss): " + std::to_string(sweep.failed) +
                        " of 6 points failed ("),
            std::string::npos)
      << report;
  EXPECT_EQ(report.find("expected"), std::string::npos) << report;

  // Named as a known failure: still counted and listed, marked, but not unexpected.
  ReproduceOptions known = options_for(d);
  known.expected_failures = {"tiny/vss"};
  const ReproduceSummary k = reproduce(known);
  EXPECT_EQ(k.failed_points(), sweep.failed);
  EXPECT_EQ(k.unexpected_failed_points(), 0);
  EXPECT_NE(k.failures_report().find("points failed, expected (--expect-failures)"),
            std::string::npos)
      << k.failures_report();

  // A study whose budget stops are expected: no failure, the stops counted apart, and an expected
  // failure that did not happen is said.
  const fs::path spec = d / "studies" / "tiny" / "vss.toml";
  write_text(spec, "budget_stops = \"expected\"\n" + read_text(spec));
  const ReproduceSummary b = reproduce(known);
  EXPECT_EQ(b.failed_points(), 0);
  EXPECT_EQ(b.budget_points(), sweep.failed);
  EXPECT_NE(b.brief_report().find(", " + std::to_string(sweep.failed) +
                                  " stopped at a budget their study sets"),
            std::string::npos)
      << b.brief_report();
  EXPECT_NE(b.failures_report().find("tiny/vss was expected to fail (--expect-failures) and did "
                                     "not"),
            std::string::npos)
      << b.failures_report();
}

TEST(Reproduce, ASecondCallKeepingFinishedJobsRecomputesNothing) {
  const ScratchDir d;
  write_tiny_study(d / "studies");
  ReproduceOptions keep = options_for(d);
  keep.keep_finished = true;
  const ReproduceSummary first = reproduce(keep);
  std::vector<std::string> bytes;
  std::vector<fs::file_time_type> times;
  for (const auto& j : first.jobs) {
    bytes.push_back(read_text(j.csv));
    times.push_back(fs::last_write_time(j.csv));
  }

  const ReproduceSummary second = reproduce(keep);
  ASSERT_EQ(second.jobs.size(), first.jobs.size());
  for (std::size_t i = 0; i < second.jobs.size(); ++i) {
    const JobSummary& j = second.jobs[i];
    EXPECT_EQ(j.resumed, j.points) << j.name;
    EXPECT_EQ(j.points, first.jobs[i].points) << j.name;
    EXPECT_EQ(j.failed, first.jobs[i].failed) << j.name;
    EXPECT_EQ(read_text(j.csv), bytes[i]) << j.name;
    EXPECT_EQ(fs::last_write_time(j.csv), times[i]) << j.name << ": rewritten";
  }
  EXPECT_EQ(second.resumed_points(), second.points());

  // Changed inputs are rerun: another force list makes the sweep's points differ.
  const fs::path spec = d / "studies" / "tiny" / "vss.toml";
  std::string text = read_text(spec);
  text.replace(text.find("45.0"), 4, "40.0");
  write_text(spec, text);
  const ReproduceSummary third = reproduce(keep);
  EXPECT_EQ(third.jobs[0].resumed, 1);
  EXPECT_EQ(third.jobs[2].resumed, 0);

  // By default, and with --fresh, every job runs again.
  for (const auto& j : reproduce(options_for(d)).jobs) {
    EXPECT_EQ(j.resumed, 0) << j.name;
  }
  ReproduceOptions fresh = keep;
  fresh.resume = false;
  for (const auto& j : reproduce(fresh).jobs) {
    EXPECT_EQ(j.resumed, 0) << j.name;
  }
}

/// Expects `options` to throw an InputError whose where() contains `where`, leaving no data.
void expect_input_error_and_no_data(const ReproduceOptions& options, const std::string& where,
                                    const ScratchDir& d) {
  try {
    (void)reproduce(options);
    ADD_FAILURE() << "no error, expected one at " << where;
  } catch (const core::InputError& e) {
    EXPECT_NE(e.where().find(where), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(d / "data")) << where;
}

TEST(Reproduce, BadOptionsAndStudiesThrowBeforeAnythingIsWritten) {
  const ScratchDir d;
  write_tiny_study(d / "studies");

  ReproduceOptions jobs = options_for(d);
  jobs.jobs = -1;
  ASSERT_TRUE(jobs.validate().has_value());
  EXPECT_EQ(jobs.validate()->where(), "--jobs");
  expect_input_error_and_no_data(jobs, "--jobs", d);

  ReproduceOptions missing = options_for(d);
  missing.names = {"tiny", "nonesuch"};
  expect_input_error_and_no_data(missing, "STUDY", d);

  ReproduceOptions no_folder = options_for(d);
  no_folder.studies_dir = d / "nowhere";
  expect_input_error_and_no_data(no_folder, "--studies", d);

  ReproduceOptions no_kinds = options_for(d);
  no_kinds.kinds = {};
  expect_input_error_and_no_data(no_kinds, "kinds", d);

  ReproduceOptions both = options_for(d);
  both.quick = true;
  both.full = true;
  expect_input_error_and_no_data(both, "--full", d);

  ReproduceOptions unknown_failure = options_for(d);
  unknown_failure.expected_failures = {"tiny/nonesuch"};
  expect_input_error_and_no_data(unknown_failure, "--expect-failures", d);

  EXPECT_FALSE(options_for(d).validate().has_value());

  // A second study ("zz", run after "tiny") with a bad sweep spec: tiny's jobs do not run either.
  fs::create_directories(d / "studies" / "zz");
  write_text(d / "studies" / "zz" / "bad.toml",
             "study = \"zz\"\nname = \"bad\"\nkind = \"inchworm_vss\"\n[params]\nF = 45.0\n"
             "mu = 1.0\nnonesuch = 1\n");
  write_text(d / "studies" / "zz" / "study.toml", "title = \"bad\"\nsweeps = [\"bad.toml\"]\n");
  expect_input_error_and_no_data(options_for(d), "bad.toml", d);

  // A study file with an unknown key.
  write_text(d / "studies" / "zz" / "study.toml", "title = \"bad\"\nsweep = []\n");
  expect_input_error_and_no_data(options_for(d), "study.toml:2:1", d);
}

}  // namespace
}  // namespace slipwalk::sweeps
