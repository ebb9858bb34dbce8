// Every output of every command, given every kind of bad destination, is refused before any work
// (exit 2, the option named) or, on a full device, fails (exit 1) — and leaves nothing new behind;
// a command killed by SIGINT or SIGTERM while writing leaves no temporary, and one killed by
// SIGKILL leaves one that the next run removes with a note.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "cli/command.hpp"

namespace {

namespace fs = std::filesystem;
using namespace slipwalk::testing;  // NOLINT(google-build-using-namespace): test helpers

const char* kScene = R"([robot]
name = "disk"
legs = 6
radius = 0.3
[gait]
kind = "disk"
[run]
duration = 0.5
dt = 0.01
[friction]
law = "viscous"
)";

const char* kFrame = R"({"q": [[0.3, 0.2, -0.1], [-0.3, 0.2, -0.1], [0.0, -0.25, -0.1]],
 "qdot": [[-0.1, 0, 0], [-0.1, 0.01, 0], [-0.12, 0, 0]], "Mg": 9.81})";

const char* kSpec = R"(study = "test"
name = "grid"
kind = "inchworm_vss"
[axes]
mu = [1.0, 0.2]
F_frac = [0.5]
)";

/// Everything under a folder, folders included.
std::vector<std::string> entries_under(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    out.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// A command with one output option, and the input file it reads (empty if none).
struct OutputOption {
  std::string name;    // for messages
  std::string option;  // as the error must name it
  bool folder;         // the option names a folder, not a file
  std::function<std::vector<std::string>(const ScratchDir&, const std::string&)> args;
  std::string input;  // file name in the scratch folder
};

std::vector<OutputOption> output_options() {
  const auto trace = [](const ScratchDir&, const std::string& out) {
    return std::vector<std::string>{"inchworm", "trace",    "--force", "45",    "--mu",
                                    "1",        "--cycles", "1",       "--out", out};
  };
  const auto run = [](const ScratchDir& d, const std::string& out) {
    return std::vector<std::string>{"run", (d / "scene.toml").string(), "--out", out};
  };
  const auto model = [](const ScratchDir& d, const std::string& out) {
    return std::vector<std::string>{"model", "--in", (d / "frame.json").string(), "--out", out};
  };
  const auto sweep = [](const ScratchDir& d, const std::string& out) {
    return std::vector<std::string>{"sweep", (d / "grid.toml").string(), "--data", out};
  };
  const auto reproduce = [](const std::string& option) {
    return [option](const ScratchDir& d, const std::string& out) {
      std::vector<std::string> args{"reproduce",   "--studies", (d / "studies").string(),
                                    "--no-report", option,      out};
      if (option != "--data") {
        args.insert(args.end(), {"--data", (d / "data").string()});
      }
      return args;
    };
  };
  return {
      {"inchworm trace --out", "--out", false, trace, ""},
      {"run --out", "--out", false, run, "scene.toml"},
      {"model --out", "--out", false, model, "frame.json"},
      {"sweep --data", "--data", true, sweep, "grid.toml"},
      {"reproduce --data", "--data", true, reproduce("--data"), "grid.toml"},
      {"reproduce --report", "--report", true, reproduce("--report"), "grid.toml"},
  };
}

void write_inputs(const ScratchDir& d) {
  write_text(d / "scene.toml", kScene);
  write_text(d / "frame.json", kFrame);
  write_text(d / "grid.toml", kSpec);
  fs::create_directories(d / "studies");
  fs::create_directories(d / "sub");
}

TEST(CliOutputs, EveryBadDestinationOfEveryOutputIsRefusedAndLeavesNothingNew) {
  int tried = 0;
  for (const OutputOption& o : output_options()) {
    const ScratchDir d;
    write_inputs(d);
    std::vector<std::pair<std::string, std::string>> bad = {
        {"empty", ""},
        {"a 300-character name", (d / std::string(300, 'n')).string()},
        {"/dev/full", "/dev/full"},
    };
    if (o.folder) {
      bad.emplace_back("a file", (d / "frame.json").string());
      bad.emplace_back("the input", (d / o.input).string());
    } else {
      bad.emplace_back("a folder", (d / "sub").string());
      bad.emplace_back("a folder/", (d / "sub").string() + "/");
      bad.emplace_back("a missing parent", (d / "none" / "x.csv").string());
      bad.emplace_back("a file as parent", (d / "frame.json" / "x.csv").string());
      if (!o.input.empty()) {
        bad.emplace_back("the input", (d / o.input).string());
        bad.emplace_back("the input by another name", (d / "sub" / ".." / o.input).string());
      }
    }
    const auto before = entries_under(d.path());
    const std::string input_text = o.input.empty() ? "" : read_text(d / o.input);
    for (const auto& [label, out] : bad) {
      ++tried;
      const CommandResult r = run_slipwalk(o.args(d, out));
      const std::string what = o.name + " given " + label + ": " + r.err;
      // A full device is an I/O failure of a file output; for a folder it is no folder.
      const bool io_failure = out == "/dev/full" && !o.folder;
      EXPECT_EQ(r.exit_code, io_failure ? 1 : 2) << what;
      EXPECT_EQ(r.err.rfind("slipwalk: error: ", 0), 0U) << what;
      EXPECT_NE(r.err.find(io_failure ? "failed" : o.option), std::string::npos) << what;
      EXPECT_EQ(r.err.find("basic_filebuf"), std::string::npos) << what;
      EXPECT_EQ(entries_under(d.path()), before) << what;
      if (!o.input.empty()) {
        EXPECT_EQ(read_text(d / o.input), input_text) << what;
      }
    }
    EXPECT_FALSE(fs::exists("/dev/full.json"));
  }
  EXPECT_GE(tried, 40);
}

TEST(CliOutputs, WhatGoesToAFullStdoutIsAFailure) {
  const ScratchDir d;
  write_inputs(d);
  const std::vector<std::vector<std::string>> commands = {
      {"inchworm", "vss", "--force", "45", "--mu", "1"},
      {"inchworm", "vss", "--force", "45", "--mu", "1", "--json"},
      {"inchworm", "trace", "--force", "45", "--mu", "1", "--cycles", "1", "--out", "-"},
      {"inchworm", "trace", "--force", "45", "--mu", "1", "--cycles", "50", "--out", "-"},
      {"model", "--in", (d / "frame.json").string()},
      {"model", "--in", (d / "frame.json").string(), "--out", "-"},
      {"kinds"},
      {"--help"},
      {"--help-all"},
      {"run", "--help"},
      {"inchworm", "vss", "--help"},
  };
  for (const auto& args : commands) {
    std::string command = shell_quote(SLIPWALK_BINARY);
    for (const auto& a : args) {
      command += ' ' + shell_quote(a);
    }
    const int ok = std::system((command + " >/dev/null 2>/dev/null").c_str());
    EXPECT_TRUE(WIFEXITED(ok) && WEXITSTATUS(ok) == 0) << command;
    const int full = std::system((command + " >/dev/full 2>/dev/null").c_str());
    EXPECT_TRUE(WIFEXITED(full) && WEXITSTATUS(full) == 1) << command;
  }
}

TEST(CliOutputs, AMessageQuotingAHugeValueStaysShort) {
  // Every way a message can quote the user: an option's value, a subcommand, a file name.
  const std::string huge(60'000, 'x');  // one argument may hold at most 128 KiB
  const std::vector<std::vector<std::string>> commands = {
      {"inchworm", "vss", "--mu", "1", "--force=" + huge},
      {"inchworm", "vss", "--mu", "1", "--force", "1" + std::string(60'000, '0')},
      {huge},
      {"run", huge, "--out", "o.csv"},
      {"model", "--in", huge},
  };
  for (const auto& args : commands) {
    const CommandResult r = run_slipwalk(args);
    EXPECT_EQ(r.exit_code, 2) << args.size();
    EXPECT_EQ(r.err.rfind("slipwalk: error: ", 0), 0U);
    EXPECT_LT(r.err.size(), 2000U) << r.err.substr(0, 200);
  }
}

/// Starts the binary with `args` in `dir` (stdout and stderr to files there: they are expected).
pid_t spawn(const fs::path& dir, const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0 || std::freopen("stdout.txt", "w", stdout) == nullptr ||
        std::freopen("stderr.txt", "w", stderr) == nullptr) {
      ::_exit(127);
    }
    std::vector<char*> argv{const_cast<char*>(SLIPWALK_BINARY)};  // NOLINT: execv's signature
    for (const auto& a : args) {
      argv.push_back(const_cast<char*>(a.c_str()));  // NOLINT
    }
    argv.push_back(nullptr);
    ::execv(SLIPWALK_BINARY, argv.data());
    ::_exit(127);
  }
  return pid;
}

/// Waits until a temporary `out.csv.tmp.<pid>` has data (the command is writing), up to 30 s.
bool wait_for_writing(const fs::path& dir, pid_t pid) {
  const fs::path temp = dir / ("out.csv.tmp." + std::to_string(pid));
  for (int k = 0; k < 3000; ++k) {
    std::error_code ec;
    if (fs::exists(temp, ec) && fs::file_size(temp, ec) > 0) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

/// Long-running writers: a trace of many samples and a scene run of many frames.
std::vector<std::vector<std::string>> long_writers(const ScratchDir& d) {
  std::string scene = kScene;
  scene.replace(scene.find("duration = 0.5"), 14, "duration = 400");
  scene.replace(scene.find("dt = 0.01"), 9, "dt = 0.001");
  write_text(d / "long.toml", scene);
  return {
      {"inchworm", "trace", "--force", "45", "--mu", "1", "--cycles", "200", "--dt", "1e-5",
       "--out", "out.csv"},
      {"run", "long.toml", "--out", "out.csv"},
  };
}

TEST(CliOutputs, ACommandInterruptedWhileWritingLeavesNoTemporary) {
  const ScratchDir d;
  for (const auto& args : long_writers(d)) {
    for (const int sig : {SIGINT, SIGTERM}) {
      const auto before = entries_under(d.path());
      const pid_t pid = spawn(d.path(), args);
      ASSERT_TRUE(wait_for_writing(d.path(), pid)) << args[0];
      ::kill(pid, sig);
      int status = 0;
      ::waitpid(pid, &status, 0);
      // The signal still ends the process (its status says so), and only after the cleanup.
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << args[0] << " " << sig;
      auto after = entries_under(d.path());
      std::erase_if(after, [](const std::string& e) { return e.ends_with(".txt"); });
      auto expected = before;
      std::erase_if(expected, [](const std::string& e) { return e.ends_with(".txt"); });
      EXPECT_EQ(after, expected) << args[0] << " " << sig;
    }
  }
}

TEST(CliOutputs, ATemporaryLeftByAKilledRunIsRemovedByTheNextWithANote) {
  const ScratchDir d;
  for (const auto& args : long_writers(d)) {
    const pid_t pid = spawn(d.path(), args);
    ASSERT_TRUE(wait_for_writing(d.path(), pid)) << args[0];
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    const fs::path stale = d / ("out.csv.tmp." + std::to_string(pid));
    ASSERT_TRUE(fs::exists(stale));
    const CommandResult r = run_slipwalk({"inchworm", "trace", "--force", "45", "--mu", "1",
                                          "--cycles", "1", "--out", (d / "out.csv").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_NE(r.err.find("slipwalk: note: removed '" + stale.string() + "'"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("left by process " + std::to_string(pid)), std::string::npos) << r.err;
  }
}

}  // namespace
