// core/atomic_file: every bad destination is refused before any work, naming the option; a
// failed or abandoned file leaves nothing new behind (not even the folders it created); a full
// device is a write failure; stale temporaries of dead processes are removed.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace slipwalk::core {
namespace {

namespace fs = std::filesystem;
using testing::files_under;
using testing::ScratchDir;
using testing::write_text;

/// Everything under a folder, folders included, so that "nothing new" covers created folders.
std::vector<std::string> entries_under(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    out.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The bad destinations of a file output inside `dir`, each with what the message must say.
struct BadDestination {
  std::string label;
  fs::path path;
  std::string says;
};

std::vector<BadDestination> bad_destinations(const ScratchDir& dir, const fs::path& input) {
  fs::create_directories(dir / "sub");
  std::vector<BadDestination> cases = {
      {"empty", "", "empty string"},
      {"folder", dir / "sub", "is a folder"},
      {"folder/", (dir / "sub").string() + "/", "is a folder"},
      {"dot", dir / "sub" / ".", "is a folder"},
      {"dotdot", dir / "sub" / "..", "is a folder"},
      {"missing parent", dir / "none" / "x.csv", "does not exist"},
      {"missing grandparent", dir / "none" / "deeper" / "x.csv", "does not exist"},
      {"parent is a file", input / "x.csv", "is not a folder"},
      {"the input", input, "is the input file"},
      {"the input by another name", dir / "sub" / ".." / input.filename(), "is the input file"},
  };
  // Names from one past the limit to far past it, and a whole path past PATH_MAX.
  for (const std::size_t n : {241UL, 255UL, 256UL, 300UL, 1000UL}) {
    cases.push_back({"name of " + std::to_string(n), dir / std::string(n, 'a'), "too long"});
  }
  std::string deep = dir.path().string();
  while (deep.size() < 5000) {
    deep += "/" + std::string(200, 'd');
  }
  cases.push_back({"path of 5000", deep + "/x.csv", "too long"});
  return cases;
}

TEST(CheckOutputPath, RefusesEveryBadDestinationNamingTheOptionAndWritesNothing) {
  const ScratchDir dir;
  const fs::path input = dir / "scene.toml";
  write_text(input, "x = 1\n");
  const auto cases = bad_destinations(dir, input);
  const std::array<fs::path, 2> inputs{"-", input};
  const auto before = entries_under(dir.path());
  for (const auto& c : cases) {
    try {
      check_output_path(c.path, "--out", inputs);
      ADD_FAILURE() << c.label << ": accepted " << c.path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "--out") << c.label;
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos)
          << c.label << ": " << e.what();
    }
  }
  EXPECT_EQ(entries_under(dir.path()), before);
  EXPECT_EQ(testing::read_text(input), "x = 1\n");
}

TEST(CheckOutputPath, AcceptsNewFilesExistingFilesDevicesAndTheLongestName) {
  const ScratchDir dir;
  write_text(dir / "old.csv", "1\n");
  for (const fs::path& ok : {dir / "new.csv", dir / "old.csv", dir / std::string(240, 'b'),
                             fs::path("/dev/null"), fs::path("/dev/full")}) {
    EXPECT_NO_THROW(check_output_path(ok, "--out")) << ok;
  }
  // A folder created on open is allowed only when asked for.
  EXPECT_NO_THROW(check_output_path(dir / "a" / "b" / "x.csv", "--data", {}, true));
  EXPECT_THROW(check_output_path(dir / "old.csv" / "b" / "x.csv", "--data", {}, true), InputError);
}

TEST(CheckOutputDir, RefusesAFileAnEmptyNameAndTooLongNames) {
  const ScratchDir dir;
  write_text(dir / "file", "");
  EXPECT_NO_THROW(check_output_dir(dir / "new" / "data", "--data"));
  EXPECT_NO_THROW(check_output_dir(dir.path(), "--data"));
  for (const fs::path& bad :
       {fs::path(""), dir / "file", fs::path("/dev/full"), dir / std::string(256, 'c') / "data"}) {
    try {
      check_output_dir(bad, "--data");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "--data");
    }
  }
}

TEST(AtomicFile, AFailureLeavesNeitherTheTemporaryNorTheFoldersItCreated) {
  const ScratchDir dir;
  for (int depth = 0; depth <= 4; ++depth) {
    fs::path target = dir.path();
    for (int k = 0; k < depth; ++k) {
      target /= "level" + std::to_string(k);
    }
    target /= "out.csv";
    try {
      AtomicFile f(target);
      f.stream() << "half a row";
      EXPECT_TRUE(fs::exists(target.parent_path())) << depth;
      throw std::runtime_error("computation failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_TRUE(entries_under(dir.path()).empty()) << depth;
  }
}

TEST(AtomicFile, FinishedFilesAppearOnlyOnCommit) {
  const ScratchDir dir;
  {
    AtomicFile a(dir / "a.csv");
    AtomicFile b(dir / "a.json");
    a.stream() << "1\n";
    b.stream() << "{}\n";
    a.finish();
    b.finish();
    EXPECT_TRUE(files_under(dir.path()).size() == 2);  // the two temporaries
    a.commit();
    b.commit();
  }
  EXPECT_EQ(files_under(dir.path()), (std::vector<std::string>{"a.csv", "a.json"}));
}

TEST(AtomicFile, AFullDeviceIsAWriteFailureAndADeviceNodeIsNeverReplaced) {
  // From one byte to well past any stream buffer: every size fails at the latest on commit.
  for (const std::size_t bytes : {1UL, 100UL, 4096UL, 65536UL, 1UL << 20}) {
    AtomicFile f("/dev/full");
    f.stream() << std::string(bytes, 'x');
    try {
      f.commit();
      ADD_FAILURE() << bytes << " bytes to /dev/full committed";
    } catch (const ComputationError& e) {
      EXPECT_NE(std::string(e.what()).find("write failed"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  write_file_atomically("/dev/null", "discarded\n");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(AtomicFile, StaleTemporariesOfDeadProcessesAreRemovedWithANote) {
  const ScratchDir dir;
  const fs::path target = dir / "out.csv";
  // Dead processes: children that have exited and been reaped.
  std::vector<pid_t> dead;
  for (int k = 0; k < 3; ++k) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::_exit(0);
    }
    ::waitpid(pid, nullptr, 0);
    dead.push_back(pid);
  }
  for (const pid_t pid : dead) {
    write_text(dir / ("out.csv.tmp." + std::to_string(pid)), "stale");
  }
  // Kept: a live process's (ours: the parent of this test), another target's, not a pid.
  const std::string live = "out.csv.tmp." + std::to_string(::getppid());
  for (const std::string& keep : {live, std::string("other.csv.tmp.") + std::to_string(dead[0]),
                                  std::string("out.csv.tmp.x1"), std::string("out.csv.tmpl")}) {
    write_text(dir / keep, "keep");
  }
  std::ostringstream notes;
  set_note_stream(&notes);
  write_file_atomically(target, "fresh\n");
  set_note_stream(nullptr);
  std::vector<std::string> expected{"other.csv.tmp." + std::to_string(dead[0]), "out.csv", live,
                                    "out.csv.tmp.x1", "out.csv.tmpl"};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(files_under(dir.path()), expected);
  for (const pid_t pid : dead) {
    EXPECT_NE(notes.str().find("left by process " + std::to_string(pid)), std::string::npos)
        << notes.str();
  }
}

}  // namespace
}  // namespace slipwalk::core
