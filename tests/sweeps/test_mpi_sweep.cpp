// Sweeps over MPI ranks (`mpirun -np R slipwalk sweep`), through the binary: the CSV of any
// number of ranks is the threaded run's, a checkpoint moves between ranks and threads both ways,
// a spec error is said once, a rank killed mid-run leaves a checkpoint that resumes, and what
// must not run under a launcher is refused. Skipped, with the reason, in a build without MPI.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli/command.hpp"
#include "support/sweep_csv.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): for posix_spawn

namespace slipwalk::sweeps {
namespace {

namespace fs = std::filesystem;
using test_support::without_timing;
using testing::CommandResult;
using testing::files_under;
using testing::read_text;
using testing::run_slipwalk;
using testing::ScratchDir;
using testing::shell_quote;
using testing::write_text;

const std::string kSpec = test_support::mixed_spec("MPI test");

// Slow enough (about 1 s on one thread) for a rank to be killed while points remain.
const std::string kSlowSpec = R"(study = "test"
name = "mpi_killed_rank"
kind = "inchworm_vss"
[params]
rtol = 1e-11
method = "cvode"
repeats = 3
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.05, 1.0], n = 60 }
)";

PreparedSweep prepared(const std::string& text) {
  return points::prepare(parse_spec(text, "spec.toml"));
}

/// The threaded run's CSV, the oracle every MPI run must reproduce.
std::string threaded_csv(const std::string& spec, bool timing = false) {
  const ScratchDir d;
  RunOptions o;
  o.data_dir = d.path();
  o.jobs = 2;
  o.timing = timing;
  return read_text(run(prepared(spec), o).csv);
}

/// The shell command `mpirun ... -np ranks slipwalk args`.
std::string mpirun_command(int ranks, const std::vector<std::string>& args) {
  std::string command = shell_quote(SLIPWALK_MPIEXEC) + " --oversubscribe --bind-to none -np " +
                        std::to_string(ranks) + " " + shell_quote(SLIPWALK_BINARY);
  for (const auto& a : args) {
    command += ' ';
    command += shell_quote(a);
  }
  return command;
}

/// Runs `slipwalk args` on `ranks` MPI ranks, capturing mpirun's stdout, stderr and exit code.
CommandResult run_mpi(int ranks, const std::vector<std::string>& args) {
  return testing::run_command_line(mpirun_command(ranks, args));
}

long long occurrences(const std::string& text, const std::string& part) {
  long long n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++n;
  }
  return n;
}

/// A file's bytes with its NULs as newlines (/proc/<pid>/cmdline and environ); empty if it
/// cannot be read (the process ended, or is not ours).
std::string proc_text(const fs::path& path) {
  std::string text = read_text(path);
  for (char& c : text) {
    c = c == '\0' ? '\n' : c;
  }
  return text;
}

/// The pid of the MPI rank `rank` whose command line names `marker`, or -1.
pid_t rank_pid(const std::string& marker, int rank) {
  std::error_code ec;
  for (fs::directory_iterator it("/proc", ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    if (proc_text(it->path() / "cmdline").find(marker) == std::string::npos) {
      continue;
    }
    std::string env(1, '\n');
    env.append(proc_text(it->path() / "environ"));
    std::string variable("\nOMPI_COMM_WORLD_RANK=");
    variable.append(std::to_string(rank)).push_back('\n');
    if (env.find(variable) != std::string::npos) {
      return static_cast<pid_t>(std::stol(name));
    }
  }
  return -1;
}

class MpiSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!mpi::available()) {
      GTEST_SKIP() << "this build has no MPI support (CMake found no MPI)";
    }
    if (std::string(SLIPWALK_MPIEXEC).empty()) {
      GTEST_SKIP() << "CMake found no MPI launcher (SLIPWALK_MPIEXEC is empty)";
    }
    // The tests may run as root (containers, CI), which Open MPI refuses unless told.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    spec_ = dir_ / "mixed.toml";
    write_text(spec_, kSpec);
  }

  [[nodiscard]] std::vector<std::string> sweep_args(const fs::path& data,
                                                    std::vector<std::string> more = {}) const {
    std::vector<std::string> args = {"sweep",       spec_.string(), "--data",
                                     data.string(), "--jobs",       "1"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }

  ScratchDir dir_;
  fs::path spec_;
};

TEST_F(MpiSweep, TwoAndThreeRanksWriteTheThreadedRunsBytes) {
  const std::string reference = threaded_csv(kSpec);
  for (const int ranks : {2, 3}) {
    const fs::path data = dir_ / ("data" + std::to_string(ranks));
    const CommandResult r = run_mpi(ranks, sweep_args(data, {"--no-timing"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("54 points (0 failed, 0 resumed)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("on " + std::to_string(ranks) + " ranks"), std::string::npos) << r.out;
    // One summary line: only rank 0 speaks.
    EXPECT_EQ(occurrences(r.out, "mixed.csv:"), 1) << r.out;
    EXPECT_EQ(read_text(data / "test" / "mixed.csv"), reference) << ranks << " ranks";
    EXPECT_EQ(files_under(data), (std::vector<std::string>{"test/mixed.csv", "test/mixed.json"}));
    const auto side = nlohmann::json::parse(read_text(data / "test" / "mixed.json"));
    EXPECT_EQ(side.at("ranks"), ranks);
    EXPECT_EQ(side.at("threads_per_rank").size(), static_cast<std::size_t>(ranks));
    EXPECT_EQ(side.at("point_seconds").at("count"), 54);
    // The other ranks did compute: the comparison above is not of rank 0 alone.
    EXPECT_GT(side.at("coordinator").at("remote_points").get<long long>(), 0) << side.dump();
    EXPECT_GT(side.at("coordinator").at("messages").get<long long>(), 0) << side.dump();
  }
  // With timing on, only the timing columns differ from the threaded run.
  const PreparedSweep sweep = prepared(kSpec);
  const fs::path timed = dir_ / "timed";
  const CommandResult r = run_mpi(3, sweep_args(timed));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = read_text(timed / "test" / "mixed.csv");
  EXPECT_EQ(without_timing(csv, *sweep.kind),
            without_timing(threaded_csv(kSpec, true), *sweep.kind));
  EXPECT_NE(csv, reference);  // the timings were written
}

TEST_F(MpiSweep, StoppedOnTwoRanksResumesOnThreeRanksOrOnThreads) {
  const std::string reference = threaded_csv(kSpec);
  const fs::path data = dir_ / "data";
  const CommandResult first = run_mpi(2, sweep_args(data, {"--no-timing", "--max-points", "20"}));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("continue with --resume"), std::string::npos) << first.out;
  ASSERT_EQ(files_under(data), std::vector<std::string>{"test/mixed.partial.csv"});
  const std::string partial = read_text(data / "test" / "mixed.partial.csv");
  const long long kept = occurrences(partial, "\n#done,");
  EXPECT_GE(kept, 20);
  EXPECT_LT(kept, 54);
  const fs::path copy = dir_ / "copy";
  fs::copy(data, copy, fs::copy_options::recursive);

  const CommandResult ranks = run_mpi(3, sweep_args(data, {"--no-timing", "--resume"}));
  ASSERT_EQ(ranks.exit_code, 0) << ranks.err;
  EXPECT_EQ(read_text(data / "test" / "mixed.csv"), reference);
  EXPECT_EQ(
      nlohmann::json::parse(read_text(data / "test" / "mixed.json")).at("resumed_point_count"),
      kept);

  const CommandResult threads = run_slipwalk(
      {"sweep", spec_.string(), "--data", copy.string(), "--jobs", "2", "--no-timing", "--resume"});
  ASSERT_EQ(threads.exit_code, 0) << threads.err;
  EXPECT_EQ(read_text(copy / "test" / "mixed.csv"), reference);
  EXPECT_EQ(files_under(copy), (std::vector<std::string>{"test/mixed.csv", "test/mixed.json"}));
}

TEST_F(MpiSweep, AThreadedRunStoppedMidwayResumesOnTwoRanks) {
  const PreparedSweep sweep = prepared(kSpec);
  const fs::path data = dir_ / "data";
  RunOptions o;
  o.data_dir = data;
  o.jobs = 2;
  o.timing = false;
  o.max_points = 17;
  ASSERT_FALSE(run(sweep, o).complete);
  const CommandResult r = run_mpi(2, sweep_args(data, {"--no-timing", "--resume"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("17 resumed"), std::string::npos) << r.out;
  EXPECT_EQ(read_text(data / "test" / "mixed.csv"), threaded_csv(kSpec));
  EXPECT_EQ(files_under(data), (std::vector<std::string>{"test/mixed.csv", "test/mixed.json"}));
}

TEST_F(MpiSweep, ASpecErrorIsSaidOnceAndWritesNothing) {
  const fs::path bad = dir_ / "bad.toml";
  // One bad value among many points (F_frac must be in [0, 1]).
  write_text(bad,
             "study = \"test\"\nname = \"bad\"\nkind = \"inchworm_vss\"\n[axes]\n"
             "F_frac = [0.1, 0.5, 1.5, 0.9]\nmu = [1.0]\n");
  const fs::path data = dir_ / "data";
  const CommandResult r =
      run_mpi(3, {"sweep", bad.string(), "--data", data.string(), "--jobs", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(occurrences(r.err, "slipwalk: error: "), 1) << r.err;
  EXPECT_NE(r.err.find("slipwalk: error: " + bad.string() + ":5:"), std::string::npos) << r.err;
  EXPECT_EQ(occurrences(r.err, "F_frac"), 1) << r.err;
  EXPECT_FALSE(fs::exists(data));
}

TEST_F(MpiSweep, AKilledRankLeavesACheckpointThatResumes) {
  const fs::path spec = dir_ / "mpi_killed_rank.toml";
  write_text(spec, kSlowSpec);
  const fs::path data = dir_ / "data";
  const fs::path partial = data / "test" / "mpi_killed_rank.partial.csv";
  const fs::path out = dir_ / "out";
  const fs::path err = dir_ / "err";
  // mpirun in the background (exec'd by the shell, so that its pid is the child's).
  const std::string command =
      "exec " +
      mpirun_command(
          2, {"sweep", spec.string(), "--data", data.string(), "--jobs", "1", "--no-timing"}) +
      " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
  std::vector<std::string> argv_text = {"/bin/sh", "-c", command};
  std::vector<char*> argv;
  for (std::string& a : argv_text) {
    argv.push_back(a.data());
  }
  argv.push_back(nullptr);
  pid_t mpirun = -1;
  ASSERT_EQ(::posix_spawn(&mpirun, "/bin/sh", nullptr, nullptr, argv.data(), environ), 0);

  // Once a few points are checkpointed, rank 1 (found by the spec's path, unique to this test,
  // in its command line) is killed the hard way, as by the out-of-memory killer.
  pid_t victim = -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    if (occurrences(read_text(partial), "\n#done,") >= 5) {
      victim = rank_pid(spec.string(), 1);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (victim > 0) {
    EXPECT_EQ(::kill(victim, SIGKILL), 0);
  } else {
    ::kill(mpirun, SIGTERM);  // leave nothing running behind a failed test
  }
  int status = 0;
  ASSERT_EQ(::waitpid(mpirun, &status, 0), mpirun);
  ASSERT_GT(victim, 0) << "no rank 1 found, or no point checkpointed in time";
  const std::string errors = read_text(err);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0) << errors;
  EXPECT_EQ(occurrences(errors, "stopped by a signal"), 1) << errors;
  EXPECT_NE(errors.find("[test/mpi_killed_rank] stopped by a signal (a rank died, or the job was "
                        "cancelled); the points finished so far are kept in " +
                        partial.string() +
                        "; run the same command again with --resume (on any number of ranks or "
                        "threads)"),
            std::string::npos)
      << errors;
  // The checkpoint holds what was done, and no result was written.
  EXPECT_EQ(files_under(data), std::vector<std::string>{"test/mpi_killed_rank.partial.csv"});
  const long long kept = occurrences(read_text(partial), "\n#done,");
  EXPECT_GE(kept, 5);
  EXPECT_LT(kept, 120) << "the sweep finished before the rank was killed";

  const CommandResult resumed = run_mpi(2, {"sweep", spec.string(), "--data", data.string(),
                                            "--jobs", "1", "--no-timing", "--resume"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find(std::to_string(kept) + " resumed"), std::string::npos) << resumed.out;
  EXPECT_EQ(read_text(data / "test" / "mpi_killed_rank.csv"), threaded_csv(kSlowSpec));
}

TEST_F(MpiSweep, ACoordinatorThatOnlyCoordinatesGivesTheSameBytes) {
  const fs::path data = dir_ / "data";
  const CommandResult r = run_mpi(2, sweep_args(data, {"--no-timing", "--coordinator-jobs", "0"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(data / "test" / "mixed.csv"), threaded_csv(kSpec));
  const auto side = nlohmann::json::parse(read_text(data / "test" / "mixed.json"));
  EXPECT_EQ(side.at("threads"), 0);
  // Every point was computed by rank 1.
  EXPECT_EQ(side.at("coordinator").at("remote_points"), 54);
}

TEST_F(MpiSweep, AnotherSubcommandOrAMergeUnderMpirunIsRefusedOnce) {
  const fs::path data = dir_ / "data";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", spec_.string(), "--data", data.string()},
        std::vector<std::string>{"sweep", "merge", spec_.string(), "--data", data.string()}}) {
    const CommandResult r = run_mpi(2, args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(occurrences(r.err, "only `slipwalk sweep SPEC` runs under mpirun"), 1) << r.err;
    EXPECT_FALSE(fs::exists(data));
  }
}

// Needs no MPI: the options that only an MPI run takes, without one.
TEST(MpiOptions, CoordinatorJobsWithoutALauncherIsRefused) {
  const ScratchDir d;
  write_text(d / "mixed.toml", kSpec);
  const fs::path data = d / "data";
  const CommandResult r = run_slipwalk(
      {"sweep", (d / "mixed.toml").string(), "--data", data.string(), "--coordinator-jobs", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("slipwalk: error: --coordinator-jobs", 0), 0U) << r.err;
  EXPECT_FALSE(fs::exists(data));
  EXPECT_EQ(run_slipwalk({"sweep", (d / "mixed.toml").string(), "--data", data.string(),
                          "--coordinator-jobs", "-2"})
                .exit_code,
            2);
  if (!mpi::available()) {
    const CommandResult no_mpi =
        run_slipwalk({"sweep", (d / "mixed.toml").string(), "--data", data.string(), "--mpi"});
    EXPECT_EQ(no_mpi.exit_code, 2) << no_mpi.err;
    EXPECT_NE(no_mpi.err.find("without MPI support"), std::string::npos) << no_mpi.err;
  }
  EXPECT_FALSE(fs::exists(data));
}

}  // namespace
}  // namespace slipwalk::sweeps
