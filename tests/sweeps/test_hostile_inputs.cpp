// The hostile-input campaign (sweeps/points/hostile_inputs.hpp) on the real binary: a sample of
// every class keeps the command-line contract — no crash, no hang, the right exit code with the
// place named, no false success, no changed input, nothing left behind. Every bad case is
// reported with a shell line that replays it. The judges themselves are shown to bite on a
// stand-in binary (/bin/sh) that misbehaves in each way.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <string>

#include "sweeps/points/hostile_inputs.hpp"

namespace {

namespace fs = std::filesystem;
using slipwalk::sweeps::hostile::Case;
using slipwalk::sweeps::hostile::classes;
using slipwalk::sweeps::hostile::find_class;
using slipwalk::sweeps::hostile::replay_line;
using slipwalk::sweeps::hostile::run_case;
using slipwalk::sweeps::hostile::Verdict;

constexpr std::uint64_t kSeed = 20240615;

/// Runs `count` cases of class `id` and expects each to be clean.
void expect_class_keeps_the_contract(const std::string& id, long long count) {
  const auto* cls = find_class(id);
  ASSERT_NE(cls, nullptr) << id;
  for (long long i = 0; i < count; ++i) {
    const Case c = cls->generate(kSeed, i);
    const Verdict v = run_case(SLIPWALK_BINARY, c, fs::temp_directory_path());
    EXPECT_TRUE(v.clean()) << id << " case " << i << " (" << c.title << "): " << v.detail
                           << "\n  replay: " << replay_line(c);
  }
}

TEST(HostileInputs, DeepNestingLongStringsAndHugeNumbersAreRefusedWithoutACrash) {
  expect_class_keeps_the_contract("depth", 24);
}

TEST(HostileInputs, ExtremeStepsTolerancesAndDurationsEndWithinTheirLimit) {
  expect_class_keeps_the_contract("runaway", 12);
}

TEST(HostileInputs, ExtremeMagnitudesAreRefusedOrGiveFiniteResults) {
  expect_class_keeps_the_contract("magnitude", 48);
}

TEST(HostileInputs, SignalsAndLateFailuresLeaveNothingBeyondTheContract) {
  expect_class_keeps_the_contract("signals", 8);
}

TEST(HostileInputs, PathsThatAreNoPlainFilesAreBadInputNamingTheOption) {
  expect_class_keeps_the_contract("paths", 36);
}

TEST(HostileInputs, FullDevicesSelfOverwritesDuplicateKeysAndCrlfLoseNothingSilently) {
  expect_class_keeps_the_contract("loss", 36);
}

TEST(HostileInputs, EveryCaseIsTheSameForTheSameSeedAndIndexAndVariesOtherwise) {
  for (const auto& cls : classes()) {
    std::set<std::string> lines;
    for (long long i = 0; i < 20; ++i) {
      const std::string a = replay_line(cls.generate(kSeed, i));
      EXPECT_EQ(a, replay_line(cls.generate(kSeed, i))) << cls.id << " case " << i;
      lines.insert(a);
    }
    EXPECT_GT(lines.size(), 10U) << cls.id << ": twenty cases, too few distinct";
  }
}

/// A case for /bin/sh as the binary: `script` is its -c argument.
Case shell_case(const std::string& script, std::set<int> exits = {0, 1, 2}) {
  Case c;
  c.title = script;
  c.run.args = {"-c", script};
  c.exits = std::move(exits);
  c.limit_s = 2.0;
  return c;
}

TEST(HostileInputs, TheJudgesCatchEveryKindOfBreach) {
  const fs::path sh = "/bin/sh";
  const fs::path tmp = fs::temp_directory_path();
  EXPECT_TRUE(run_case(sh, shell_case("exit 0"), tmp).clean());
  EXPECT_TRUE(run_case(sh, shell_case("kill -SEGV $$"), tmp).crash);
  EXPECT_TRUE(run_case(sh, shell_case("exit 134"), tmp).crash);
  Case hang = shell_case("sleep 30");
  hang.limit_s = 0.3;
  const Verdict h = run_case(sh, hang, tmp);
  EXPECT_TRUE(h.hang);
  EXPECT_LT(h.wall_s, 5.0);
  EXPECT_TRUE(
      run_case(sh, shell_case("echo 'slipwalk: error: x' >&2; exit 1", {2}), tmp).wrong_exit);
  EXPECT_TRUE(run_case(sh, shell_case("exit 2"), tmp).no_place);  // no message at all
  Case place = shell_case("echo 'slipwalk: error: --m: bad' >&2; exit 2");
  place.place = "--force";
  EXPECT_TRUE(run_case(sh, place, tmp).no_place);
  place.place = "--m";
  EXPECT_TRUE(run_case(sh, place, tmp).clean());
  Case line = shell_case("echo 'slipwalk: error: s.toml: bad' >&2; exit 2");
  line.place = "s.toml";
  line.place_line = true;
  EXPECT_TRUE(run_case(sh, line, tmp).no_place);
  Case full = shell_case("exit 0");
  full.run.stdout_to = "/dev/full";
  EXPECT_TRUE(run_case(sh, full, tmp).false_success);
  Case nan = shell_case("echo '{\"converged\": true, \"v\": NaN}'");
  nan.output_kind = slipwalk::sweeps::hostile::Output::kJson;
  EXPECT_TRUE(run_case(sh, nan, tmp).false_success);
  Case missing = shell_case("exit 0");
  missing.outputs = {"out.csv"};
  EXPECT_TRUE(run_case(sh, missing, tmp).false_success);
  Case clobber = shell_case("echo x > in.txt; exit 2");
  clobber.files = {{"in.txt", "data\n", ""}};
  EXPECT_TRUE(run_case(sh, clobber, tmp).clobbered);
  EXPECT_TRUE(run_case(sh,
                       shell_case("echo x > out.csv.tmp.1; echo 'slipwalk: error: y' >&2; "
                                  "exit 1"),
                       tmp)
                  .leftovers);
  Case signal = shell_case("echo x > out.csv.tmp.1; sleep 5");
  signal.run.signal = SIGTERM;
  signal.run.signal_after_s = 0.1;
  EXPECT_TRUE(run_case(sh, signal, tmp).leftovers);  // a shell does not clean up for us
}

}  // namespace
