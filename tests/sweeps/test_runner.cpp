// The sweep runner: deterministic output whatever the thread count, checkpoints and resume,
// failed points recorded, the sidecar, and the command line (`slipwalk sweep`, `reproduce`).
#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "events/exact_backend.hpp"
#include "inchworm/simulate.hpp"
#include "inchworm/vss.hpp"
#include "sweeps/engine/job.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/engine/study.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::files_under;
using testing::read_text;
using testing::run_slipwalk;
using testing::ScratchDir;
using testing::write_text;

// 2 × 12 × 2 = 48 points, a mix of closed forms and simulations.
const std::string kSpec = R"(study = "test"
name = "grid"
kind = "inchworm_vss"
description = "runner test"
[params]
rtol = 1e-9
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.02, 1.0], n = 12 }
method = ["exact", "analytic"]
)";

PreparedSweep prepared(const std::string& text = kSpec) {
  return points::prepare(parse_spec(text, "grid.toml"));
}

RunOptions options(const std::filesystem::path& data, unsigned jobs, bool timing = false) {
  RunOptions o;
  o.data_dir = data;
  o.jobs = jobs;
  o.timing = timing;
  return o;
}

/// The CSV without its timing columns (wall_s, cpu_s).
std::string without_wall(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<bool> timing;
  for (std::size_t p = 0;;) {
    const std::size_t e = line.find(',', p);
    const std::string name = line.substr(p, e == std::string::npos ? std::string::npos : e - p);
    timing.push_back(name == "wall_s" || name == "cpu_s");
    if (e == std::string::npos) {
      break;
    }
    p = e + 1;
  }
  std::string out;
  in.seekg(0);
  while (std::getline(in, line)) {
    std::string kept;
    std::size_t k = 0;
    for (std::size_t p = 0;; ++k) {
      const std::size_t e = line.find(',', p);
      if (k >= timing.size() || !timing[k]) {
        if (k > 0) {
          kept.push_back(',');
        }
        kept.append(line, p, e == std::string::npos ? std::string::npos : e - p);
      }
      if (e == std::string::npos) {
        break;
      }
      p = e + 1;
    }
    out += kept + "\n";
  }
  return out;
}

TEST(Runner, SameBytesWithOneOrTwoThreads) {
  const ScratchDir a;
  const ScratchDir b;
  const PreparedSweep sweep = prepared();
  const RunSummary one = run(sweep, options(a.path(), 1));
  const RunSummary two = run(sweep, options(b.path(), 2));
  ASSERT_TRUE(one.complete);
  ASSERT_TRUE(two.complete);
  EXPECT_EQ(two.jobs, 2U);
  EXPECT_EQ(one.points, 48);
  const std::string csv = read_text(one.csv);
  EXPECT_EQ(csv, read_text(two.csv));
  // Rows sorted by id, one per point.
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("id,mu,mu_s,F,f_tilde,F_frac,method,", 0), 0U);
  EXPECT_NE(line.find(",wall_s,message,model,alpha,swap_stopped"), std::string::npos) << line;
  for (long long id = 0; std::getline(in, line); ++id) {
    EXPECT_EQ(line.rfind(std::to_string(id) + ",", 0), 0U);
  }
  // With timing on, only wall_s differs.
  const ScratchDir c;
  const RunSummary timed = run(sweep, options(c.path(), 2, true));
  EXPECT_EQ(without_wall(read_text(timed.csv)), without_wall(csv));
  EXPECT_NE(without_wall(csv), csv);
  // Nothing else left behind.
  EXPECT_EQ(files_under(a.path()), (std::vector<std::string>{"test/grid.csv", "test/grid.json"}));
}

TEST(Runner, Sidecar) {
  const ScratchDir d;
  const RunSummary s = run(prepared(), options(d.path(), 2));
  const auto j = nlohmann::json::parse(read_text(s.sidecar));
  EXPECT_EQ(j.at("study"), "test");
  EXPECT_EQ(j.at("name"), "grid");
  EXPECT_EQ(j.at("kind"), "inchworm_vss");
  EXPECT_EQ(j.at("point_count"), 48);
  EXPECT_EQ(j.at("failed_point_count"), 0);
  EXPECT_EQ(j.at("threads"), 2);
  EXPECT_EQ(j.at("points").size(), 48U);
  EXPECT_EQ(j.at("points")[47].at("method"), "analytic");
  EXPECT_EQ(j.at("spec").at("axes").at("mu")[1], 0.2);
  EXPECT_TRUE(j.at("provenance").contains("git_commit"));
  for (const char* key : {"wall_s", "date", "columns", "description", "spec_file"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
}

TEST(Runner, InterruptedThenResumedIsByteIdentical) {
  const PreparedSweep sweep = prepared();
  const ScratchDir full;
  const std::string reference = read_text(run(sweep, options(full.path(), 2)).csv);

  for (unsigned jobs : {1U, 2U}) {
    const ScratchDir d;
    RunOptions o = options(d.path(), jobs);
    o.max_points = 17;
    const RunSummary first = run(sweep, o);
    EXPECT_FALSE(first.complete);
    EXPECT_EQ(first.computed, 17);
    EXPECT_FALSE(std::filesystem::exists(first.csv));
    EXPECT_TRUE(std::filesystem::exists(first.partial));
    // A second interruption, then the rest.
    o.resume = true;
    o.max_points = 9;
    const RunSummary second = run(sweep, o);
    EXPECT_EQ(second.resumed, 17);
    EXPECT_EQ(second.computed, 9);
    // A run killed while writing leaves a half line behind: it is ignored.
    {
      std::ofstream partial(second.partial, std::ios::app);
      partial << "40,1,1,12.5,0.8";
    }
    o.max_points = -1;
    const RunSummary last = run(sweep, o);
    EXPECT_TRUE(last.complete);
    EXPECT_EQ(last.resumed, 26);
    EXPECT_EQ(last.computed, 22);
    EXPECT_EQ(read_text(last.csv), reference);
    EXPECT_FALSE(std::filesystem::exists(last.partial));
    EXPECT_EQ(nlohmann::json::parse(read_text(last.sidecar)).at("resumed_point_count"), 26);
  }
}

TEST(Runner, CorruptEndMarksInACheckpointResumeTheirPointsAsUnfinished) {
  // A point counts as finished only under a well-formed `#done,<id>,<0|1|2>,<message>` line: an
  // overflowing or signed id, another outcome or a missing comma is read as no mark, so its rows
  // are dropped and the point is run again (never a clamped or wrapped id).
  const PreparedSweep sweep = prepared();
  const ScratchDir full;
  const std::string reference = read_text(run(sweep, options(full.path(), 2)).csv);
  const ScratchDir d;
  RunOptions o = options(d.path(), 1);
  o.max_points = 17;
  const RunSummary first = run(sweep, o);
  ASSERT_FALSE(first.complete);
  std::string text = read_text(first.partial);
  const std::vector<std::function<std::string(const std::string&)>> spoil = {
      [](const std::string& id) { return "#done,99999999999999999999" + id + ",0,"; },
      [](const std::string& id) { return "#done," + id + ",3,"; },
      [](const std::string& id) { return "#done,+" + id + ",0,"; },
      [](const std::string& id) { return "#done," + id + ",0"; },
  };
  std::size_t at = 0;
  for (const auto& bad : spoil) {
    at = text.find("\n#done,", at);
    ASSERT_NE(at, std::string::npos);
    const std::size_t begin = at + 1;
    const std::size_t end = text.find('\n', begin);
    const std::size_t id_end = text.find(',', begin + 6);
    const std::string id = text.substr(begin + 6, id_end - begin - 6);
    const std::string mark = bad(id);
    text.replace(begin, end - begin, mark);
    at = begin + mark.size();
  }
  write_text(first.partial, text);
  o.resume = true;
  o.max_points = -1;
  const RunSummary last = run(sweep, o);
  EXPECT_TRUE(last.complete);
  EXPECT_EQ(last.resumed, 17 - static_cast<long long>(spoil.size()));
  EXPECT_EQ(last.computed, 48 - last.resumed);
  EXPECT_EQ(read_text(last.csv), reference);
}

TEST(Runner, ResumeWithTimingDiffersOnlyInWallTime) {
  const PreparedSweep sweep = prepared();
  const ScratchDir full;
  const std::string reference = read_text(run(sweep, options(full.path(), 2, true)).csv);
  const ScratchDir d;
  RunOptions o = options(d.path(), 2, true);
  o.max_points = 20;
  (void)run(sweep, o);
  o.max_points = -1;
  o.resume = true;
  EXPECT_EQ(without_wall(read_text(run(sweep, o).csv)), without_wall(reference));
}

TEST(Runner, ResumeRefusesACheckpointOfTheOtherTimingSetting) {
  // Resumed rows keep the timings they were written with: a --no-timing result must not hold
  // timed rows, nor a timed result zeros.
  const PreparedSweep sweep = prepared();
  for (const bool first : {true, false}) {
    const ScratchDir d;
    RunOptions o = options(d.path(), 2, first);
    o.max_points = 10;
    (void)run(sweep, o);
    o.max_points = -1;
    o.resume = true;
    o.timing = !first;
    try {
      (void)run(sweep, o);
      ADD_FAILURE() << "a checkpoint of the other timing setting was resumed";
    } catch (const core::InputError& e) {
      EXPECT_NE(
          std::string(e.what()).find(first ? "written with timings" : "written with --no-timing"),
          std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(csv_path(sweep.spec, d.path())));
  }
}

TEST(Runner, WithoutResumeACheckpointIsDiscarded) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  RunOptions o = options(d.path(), 2);
  o.max_points = 10;
  (void)run(sweep, o);
  o.max_points = -1;
  const RunSummary s = run(sweep, o);
  EXPECT_EQ(s.resumed, 0);
  EXPECT_EQ(s.computed, 48);
}

TEST(Runner, ResumeRefusesAnotherSpecsCheckpoint) {
  const ScratchDir d;
  RunOptions o = options(d.path(), 2);
  o.max_points = 10;
  (void)run(prepared(), o);
  o.resume = true;
  o.max_points = -1;
  // Same columns, other points.
  std::string other = kSpec;
  other.replace(other.find("n = 12"), 6, "n = 13");
  EXPECT_THROW((void)run(prepared(other), o), core::InputError);
  // Other columns.
  const std::filesystem::path partial = partial_path(prepared().spec, d.path());
  std::string text = read_text(partial);
  text.replace(0, 2, "ID");
  write_text(partial, text);
  try {
    (void)run(prepared(), o);
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), partial.string());
    EXPECT_NE(std::string(e.what()).find("header"), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(csv_path(prepared().spec, d.path())));
}

TEST(Runner, FailedPointsAreWrittenAndCounted) {
  const ScratchDir d;
  const PreparedSweep sweep = prepared(R"(study = "test"
name = "fail"
kind = "inchworm_vss"
[params]
F = 73.575
mu = 0.05
method = "analytic"
[axes]
max_strokes = [8, 100000]
)");
  const RunSummary s = run(sweep, options(d.path(), 2));
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.failed, 1);
  const std::string csv = read_text(s.csv);
  EXPECT_NE(csv.find("no convergence within 8 strokes"), std::string::npos) << csv;
  const auto j = nlohmann::json::parse(read_text(s.sidecar));
  EXPECT_EQ(j.at("failed_point_count"), 1);
  EXPECT_EQ(j.at("failed_points")[0].at("id"), 0);
}

TEST(Runner, AStopAtABudgetTheSpecExpectsIsCountedApartAndSurvivesAResume) {
  const std::string text = R"(study = "test"
name = "budget"
kind = "inchworm_vss"
budget_stops = "expected"
[params]
F = 73.575
mu = 0.05
method = "analytic"
[axes]
max_strokes = [8, 100000, 8]
)";
  const PreparedSweep sweep = prepared(text);
  const ScratchDir d;
  const RunSummary s = run(sweep, options(d.path(), 2));
  EXPECT_EQ(s.failed, 0);
  EXPECT_EQ(s.at_budget, 2);
  const std::string csv = read_text(s.csv);
  EXPECT_NE(csv.find(",stroke budget\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",converged\n"), std::string::npos) << csv;
  const auto j = nlohmann::json::parse(read_text(s.sidecar));
  EXPECT_EQ(j.at("failed_point_count"), 0);
  EXPECT_EQ(j.at("budget_point_count"), 2);
  EXPECT_EQ(j.at("budget_points")[1].at("id"), 2);
  EXPECT_NE(j.at("budget_points")[0].at("message").get<std::string>().find("8 strokes"),
            std::string::npos);

  // Interrupted after one point, then resumed: the checkpoint keeps the outcome.
  const ScratchDir r;
  RunOptions o = options(r.path(), 1);
  o.max_points = 1;
  (void)run(sweep, o);
  o.resume = true;
  o.max_points = -1;
  const RunSummary resumed = run(sweep, o);
  EXPECT_EQ(resumed.resumed, 1);
  EXPECT_EQ(resumed.at_budget, 2);
  EXPECT_EQ(read_text(resumed.csv), csv);

  // The same points without budget_stops are failures, with the same rows.
  std::string as_failures = text;
  as_failures.erase(as_failures.find("budget_stops"),
                    std::string("budget_stops = \"expected\"\n").size());
  const ScratchDir f;
  const RunSummary failed = run(prepared(as_failures), options(f.path(), 2));
  EXPECT_EQ(failed.failed, 2);
  EXPECT_EQ(failed.at_budget, 0);
  EXPECT_EQ(read_text(failed.csv), csv);
}

/// A kind whose run throws (a bug in a kind, or a limit reached), for the runner's failure path.
PointKind throwing_kind() {
  struct Row {
    long long id = 0;
    static std::vector<Column<Row>> columns() { return {value("id", &Row::id)}; }
  };
  return make_point_kind<Row>(
      "throws", "a test kind whose every point throws", Timed::kNo, [](const Point&) {},
      [](const Point&) -> Rows<Row> { throw core::ComputationError("the kind gave up"); });
}

TEST(Runner, ARunThatFinishesNoPointLeavesNoFolderBehind) {
  const ScratchDir d;
  const std::vector<PointKind> kinds = {throwing_kind()};
  const PreparedSweep sweep = sweeps::prepare(
      parse_spec("study = \"new_study\"\nname = \"x\"\nkind = \"throws\"\n[axes]\nk = [1, 2, 3]\n",
                 "x.toml"),
      kinds);
  try {
    (void)run(sweep, options(d / "data", 2));
    ADD_FAILURE() << "a throwing point did not stop the sweep";
  } catch (const core::ComputationError& e) {
    EXPECT_NE(std::string(e.what()).find("the kind gave up"), std::string::npos) << e.what();
  }
  // Neither the checkpoint nor the study folder the run created is left.
  EXPECT_FALSE(std::filesystem::exists(d / "data" / "new_study"));
  // A study folder that existed before the run stays.
  std::filesystem::create_directories(d / "data" / "new_study");
  EXPECT_THROW((void)run(sweep, options(d / "data", 1)), core::ComputationError);
  EXPECT_TRUE(std::filesystem::is_directory(d / "data" / "new_study"));
  EXPECT_TRUE(files_under(d / "data").empty());
}

TEST(Runner, TheCsvIsRenamedAfterItsSidecar) {
  // An earlier result is replaced as a pair; when the CSV cannot be renamed (its name is taken
  // by a folder) the new sidecar stands alone, which no reader takes for a result, and no CSV
  // of another run is left beside it.
  const ScratchDir d;
  write_text(d / "r.csv", "old\n");
  write_text(d / "r.json", "{\"old\": true}\n");
  {
    core::AtomicFile csv(d / "r.csv");
    csv.stream() << "new\n";
    core::AtomicFile side(d / "r.json");
    side.stream() << "{}\n";
    core::commit_with_sidecar(csv, side);
  }
  EXPECT_EQ(read_text(d / "r.csv"), "new\n");
  EXPECT_EQ(read_text(d / "r.json"), "{}\n");
  {
    core::AtomicFile csv(d / "q.csv");
    csv.stream() << "new\n";
    core::AtomicFile side(d / "q.json");
    side.stream() << "{}\n";
    std::filesystem::create_directories(d / "q.csv" / "taken");
    EXPECT_THROW(core::commit_with_sidecar(csv, side), core::ComputationError);
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(d / "q.json"));
  EXPECT_FALSE(std::filesystem::is_regular_file(d / "q.csv"));
}

TEST(Runner, ProgressLines) {
  const ScratchDir d;
  std::ostringstream progress;
  RunOptions o = options(d.path(), 1);
  o.progress = &progress;
  o.progress_interval_s = 0.0;  // every point
  (void)run(prepared(), o);
  const std::string text = progress.str();
  EXPECT_NE(text.find("[test/grid] 1/48 points, "), std::string::npos) << text;
  EXPECT_NE(text.find("[test/grid] 48/48 points, "), std::string::npos) << text;
  EXPECT_NE(text.find(", ETA "), std::string::npos) << text;
  // With an interval longer than the sweep, no progress line at all.
  std::ostringstream quiet;
  o.progress = &quiet;
  o.progress_interval_s = 1e9;
  (void)run(prepared(), o);
  EXPECT_EQ(quiet.str().find("/48 points"), std::string::npos) << quiet.str();
}

/// The convergence point kind follows the simulation's own arithmetic.
TEST(Runner, ConvergenceRowsMatchTheSimulation) {
  const PreparedSweep sweep = prepared(R"(study = "test"
name = "conv"
kind = "inchworm_convergence"
[params]
F = 73.575
mu = 0.05
cycles = 30
)");
  const PointResult r = sweep.kind->run(sweep.points[0]);
  ASSERT_FALSE(r.failed) << r.message;
  ASSERT_EQ(r.rows.size(), 30U);
  inchworm::Params p;
  p.F = 73.575;
  p.mu = 0.05;
  events::ExactBackend backend;
  inchworm::SimulationOptions so;
  so.target = -1.0;  // never stop
  so.max_strokes = 60;
  const auto cycles = inchworm::steady_state_by_simulation(p, backend, so, true);
  ASSERT_EQ(cycles.cycle_averages.size(), 30U);
  for (std::size_t i = 0; i < 30; ++i) {
    EXPECT_EQ(std::get<long long>(r.rows[i][4]), static_cast<long long>(i + 1));
    EXPECT_EQ(std::get<double>(r.rows[i][5]), cycles.cycle_averages[i]);
  }
  events::ExactBackend backend2;
  so.estimator = inchworm::Estimator::kRunningMean;
  const auto running = inchworm::steady_state_by_simulation(p, backend2, so);
  EXPECT_EQ(std::get<double>(r.rows.back()[6]), running.v_ss);
}

/// The force grid kind: the closed form at every multiple of the step above mu m g, the same
/// forces for every mu.
TEST(Runner, ForceGridRowsAreTheClosedFormAtTheStepsMultiplesAboveMuMg) {
  const PreparedSweep sweep = prepared(R"(study = "test"
name = "grid"
kind = "inchworm_force_grid"
[params]
F_step = 2.5
F_end = 20.0
method = "exact"
[axes]
mu = [0.5, 0.1]
)");
  ASSERT_EQ(sweep.points.size(), 2U);
  for (const Point& point : sweep.points) {
    const PointResult r = sweep.kind->run(point);
    ASSERT_FALSE(r.failed) << r.message;
    inchworm::Params p;
    p.mu = std::get<double>(r.rows.front()[1]);
    // mu m g = 4.905 N at mu = 0.5 (from 5 N), 0.981 N at mu = 0.1 (from 2.5 N)
    const double first = p.mu > 0.3 ? 5.0 : 2.5;
    ASSERT_EQ(r.rows.size(), static_cast<std::size_t>((20.0 - first) / 2.5) + 1);
    for (std::size_t i = 0; i < r.rows.size(); ++i) {
      p.F = first + 2.5 * static_cast<double>(i);
      EXPECT_EQ(std::get<double>(r.rows[i][2]), p.F);
      const inchworm::VssResult exact = inchworm::solve_vss(p, inchworm::Method::kExact);
      EXPECT_EQ(std::get<double>(r.rows[i][13]), exact.v_ss) << "F = " << p.F;
      EXPECT_EQ(std::get<long long>(r.rows[i][14]), static_cast<long long>(exact.regime));
      EXPECT_EQ(std::get<std::string>(r.rows[i][16]), "converged");
    }
  }
}

TEST(Runner, AForceGridWithNoForceAboveMuMgIsRefusedAtItsEnd) {
  const std::string spec = R"(study = "test"
name = "grid"
kind = "inchworm_force_grid"
[params]
F_step = 1.0
F_end = 4.0
mu = 0.5
)";
  try {
    (void)prepared(spec);
    FAIL() << "accepted a grid with no force above mu m g";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("F_end"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mu_s m g"), std::string::npos) << e.what();
  }
}

// --- the command line ---------------------------------------------------------------------------

TEST(SweepCli, RunsResumesAndKeepsProgressOffStdout) {
  const ScratchDir d;
  const auto spec = d / "grid.toml";
  write_text(spec, kSpec);
  const auto data = (d / "data").string();
  const auto r1 = run_slipwalk(
      {"sweep", spec.string(), "--data", data, "--jobs", "2", "--no-timing", "--max-points", "11"});
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_EQ(files_under(d / "data"), std::vector<std::string>{"test/grid.partial.csv"});
  const auto r2 = run_slipwalk({"sweep", spec.string(), "--data", data, "--no-timing", "--resume"});
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_NE(r2.out.find("11 resumed"), std::string::npos) << r2.out;
  const std::string resumed = read_text(d / "data" / "test" / "grid.csv");
  const auto r3 = run_slipwalk({"sweep", spec.string(), "--data", data, "--no-timing", "-j", "1"});
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  EXPECT_EQ(read_text(d / "data" / "test" / "grid.csv"), resumed);
  EXPECT_EQ(files_under(d / "data"), (std::vector<std::string>{"test/grid.csv", "test/grid.json"}));

  // Progress (a line after every point here) goes to stderr, never stdout.
  const auto r4 = run_slipwalk(
      {"sweep", spec.string(), "--data", data, "--jobs", "1", "--progress-interval", "0"});
  ASSERT_EQ(r4.exit_code, 0) << r4.err;
  EXPECT_EQ(r4.out.find("ETA"), std::string::npos) << r4.out;
  EXPECT_NE(r4.err.find("[test/grid] "), std::string::npos) << r4.err;
  EXPECT_NE(r4.err.find(" points, "), std::string::npos) << r4.err;
  EXPECT_NE(r4.err.find("ETA"), std::string::npos) << r4.err;
}

TEST(SweepCli, BadSpecsWriteNothing) {
  const ScratchDir d;
  const auto data = d / "data";
  struct Case {
    std::string text, where;
  };
  for (const Case& c : std::vector<Case>{
           {"study = \"t\"\nname = \"x\"\nkind = \"inchworm_vss\"\n[axes\n", "bad.toml:4:"},
           {"study = \"t\"\nname = \"x\"\nkind = \"nope\"\n", "bad.toml:3:8"},
           {kSpec + "bogus = 1\n", "bad.toml:"},
           // one bad value among many points
           {"study = \"t\"\nname = \"x\"\nkind = \"inchworm_vss\"\n[axes]\n"
            "F = [45.0, 50.0, 60.0, 9.0, 70.0]\nmu = [1.0]\n",
            "bad.toml:5:"},
       }) {
    const auto spec = d / "bad.toml";
    write_text(spec, c.text);
    const auto r = run_slipwalk({"sweep", spec.string(), "--data", data.string()});
    EXPECT_EQ(r.exit_code, 2) << c.text << r.err;
    EXPECT_EQ(r.err.rfind("slipwalk: error: " + d.path().string() + "/" + c.where, 0), 0U) << r.err;
    EXPECT_FALSE(std::filesystem::exists(data)) << c.text;
  }
  const auto missing = run_slipwalk({"sweep", (d / "none.toml").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(run_slipwalk({"sweep"}).exit_code, 2);
  write_text(d / "ok.toml", kSpec);
  EXPECT_EQ(run_slipwalk({"sweep", (d / "ok.toml").string(), "--jobs", "-1"}).exit_code, 2);
  EXPECT_EQ(run_slipwalk({"sweep", (d / "ok.toml").string(), "--jobs", "x"}).exit_code, 2);
}

TEST(SweepCli, ReproduceRunsAStudy) {
  const ScratchDir d;
  const auto study = d / "studies" / "demo";
  std::filesystem::create_directories(study);
  const std::string demo = R"(title = "demo"
sweeps = ["grid.toml"]
[[trace]]
name = "trace"
F = 45.0
mu = 1.0
cycles = 2
dt = 0.01
)";
  write_text(study / "study.toml", demo);
  std::string spec = kSpec;
  spec.replace(spec.find("\"test\""), 6, "\"demo\"");
  write_text(study / "grid.toml", spec);
  const auto data = d / "data";
  const std::vector<std::string> base = {"reproduce", "--studies",   (d / "studies").string(),
                                         "--data",    data.string(), "--no-report"};
  auto args = base;
  args.push_back("demo");
  const auto r = run_slipwalk(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_under(data), (std::vector<std::string>{"demo/grid.csv", "demo/grid.json",
                                                         "demo/trace.csv", "demo/trace.json"}));
  // A failed point: everything written, the failure listed, exit 1; named as a known failure, 0.
  const auto failing = study / "failing.toml";
  write_text(failing, R"(study = "demo"
name = "failing"
kind = "inchworm_vss"
[params]
F = 73.575
mu = 0.05
method = "analytic"
max_strokes = 8
)");
  write_text(study / "study.toml", "title = \"demo\"\nsweeps = [\"failing.toml\"]\n");
  args = base;
  args.push_back("demo");
  const auto fails = run_slipwalk(args);
  EXPECT_EQ(fails.exit_code, 1) << fails.err;
  EXPECT_NE(fails.out.find("  demo/failing (kind inchworm_vss): 1 of 1 points failed"),
            std::string::npos)
      << fails.out;
  EXPECT_NE(fails.err.find("slipwalk: error: 1 sweep points failed"), std::string::npos)
      << fails.err;
  EXPECT_TRUE(std::filesystem::exists(data / "demo" / "failing.csv"));
  args.insert(args.end(), {"--expect-failures", "demo/failing"});
  const auto known = run_slipwalk(args);
  EXPECT_EQ(known.exit_code, 0) << known.err;
  EXPECT_NE(known.out.find("1 of 1 points failed, expected"), std::string::npos) << known.out;
  write_text(study / "study.toml", demo);
  std::filesystem::remove(failing);
  std::filesystem::remove_all(data);

  // An unknown study, a bad study file: exit 2 and nothing new written.
  args = base;
  args.push_back("nope");
  EXPECT_EQ(run_slipwalk(args).exit_code, 2);
  std::filesystem::remove_all(data);
  write_text(study / "study.toml", "title = \"demo\"\nsweeps = [\"missing.toml\"]\n");
  const auto bad = run_slipwalk(base);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("study.toml:2:"), std::string::npos) << bad.err;
  write_text(study / "study.toml",
             "title = \"demo\"\n[[trace]]\nname = \"t\"\nF = 5.0\nmu = 1.0\n");
  const auto bad_trace = run_slipwalk(base);
  EXPECT_EQ(bad_trace.exit_code, 2);
  EXPECT_NE(bad_trace.err.find("study.toml:4:"), std::string::npos) << bad_trace.err;
  EXPECT_FALSE(std::filesystem::exists(data));
}

TEST(Study, TracesTakeTheSwapModel) {
  const ScratchDir d;
  write_text(d / "study.toml", R"(title = "dm"
[[trace]]
name = "instant"
F = 12.0
mu = 1.0
[[trace]]
name = "dm5"
F = 12.0
mu = 1.0
model = "dm"
alpha = 5.0
cycles = 2
dt = 0.01
)");
  const Study study = load_study(d.path());
  ASSERT_EQ(study.traces.size(), 2U);
  EXPECT_EQ(study.traces[0].params.model, inchworm::SwapModel::kInstant);
  EXPECT_EQ(study.traces[1].params.model, inchworm::SwapModel::kMass);
  EXPECT_EQ(study.traces[1].params.alpha, 5.0);
  const auto csv = write_trace_job(study, study.traces[1], d / "data").csv;
  EXPECT_NE(read_text(csv).find("arrival_after"), std::string::npos);
  const auto side = nlohmann::json::parse(read_text(d / "data" / study.id / "dm5.json"));
  EXPECT_EQ(side.at("params").at("model"), "dm");
  EXPECT_EQ(side.at("params").at("alpha"), 5.0);

  // Bad model keys: file:line:col of the key's value.
  struct Case {
    std::string body, where;
  };
  for (const Case& c : std::vector<Case>{
           {"model = \"slow\"\n", ":6:9"},
           {"alpha = 5.0\n", ":6:9"},                      // alpha with the instant model
           {"model = \"dm\"\nalpha = 0.0\n", ":7:9"},      // alpha must be positive
           {"model = \"dm\"\nalpha = \"one\"\n", ":7:9"},  // not a number
       }) {
    write_text(d / "study.toml",
               "title = \"dm\"\n[[trace]]\nname = \"t\"\nF = 12.0\nmu = 1.0\n" + c.body);
    try {
      (void)load_study(d.path());
      ADD_FAILURE() << c.body;
    } catch (const core::InputError& e) {
      EXPECT_NE(e.where().find("study.toml" + c.where), std::string::npos)
          << c.body << " -> " << e.what();
      EXPECT_NE(
          std::string(e.what()).find(c.body.find("alpha") != std::string::npos ? "alpha" : "model"),
          std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
