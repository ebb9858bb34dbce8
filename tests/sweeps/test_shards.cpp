// Shards of a sweep (`--shard k/n`, `slipwalk sweep merge`): every point in exactly one shard,
// shards merged into the bytes a threaded run writes, each shard resuming on its own, and a
// merge that refuses, writing nothing, whatever it cannot vouch for.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/error.hpp"
#include "support/sweep_csv.hpp"
#include "sweeps/engine/checkpoint.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/shards.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

namespace fs = std::filesystem;
using test_support::row_ids;
using test_support::without_timing;
using testing::files_under;
using testing::read_text;
using testing::run_slipwalk;
using testing::ScratchDir;
using testing::write_text;

const std::string kSpec = test_support::mixed_spec("shards test");
constexpr long long kPoints = 54;

PreparedSweep prepared(const std::string& text = kSpec) {
  return points::prepare(parse_spec(text, "mixed.toml"));
}

RunOptions options(const fs::path& data, Shard shard = {}, bool timing = false) {
  RunOptions o;
  o.data_dir = data;
  o.jobs = 2;
  o.timing = timing;
  o.shard = shard;
  return o;
}

MergeOptions merging(const fs::path& data) {
  MergeOptions o;
  o.data_dir = data;
  return o;
}

/// Runs shards `ks` of n into `data`.
void run_shards(const PreparedSweep& sweep, const fs::path& data, long long n,
                const std::vector<long long>& ks, bool timing = false) {
  for (const long long k : ks) {
    const RunSummary s = run(sweep, options(data, {k, n, true}, timing));
    ASSERT_TRUE(s.complete) << k << "/" << n;
  }
}

/// The threaded run's CSV, the oracle every merge must reproduce.
std::string threaded_csv(const PreparedSweep& sweep, bool timing = false) {
  const ScratchDir d;
  return read_text(run(sweep, options(d.path(), {}, timing)).csv);
}

/// Expects merge_shards to refuse with InputError, writing and removing nothing; returns the
/// error's text (where: what).
std::string expect_refused(const PreparedSweep& sweep, const MergeOptions& o) {
  const std::vector<std::string> before = files_under(o.data_dir);
  std::string text;
  try {
    (void)merge_shards(sweep, o);
    ADD_FAILURE() << "the merge went through";
  } catch (const core::InputError& e) {
    text = e.where() + ": " + e.what();
  }
  EXPECT_EQ(files_under(o.data_dir), before) << text;
  return text;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Shards, EveryPointIsInExactlyOneShardAndTheMergeIsTheThreadedRun) {
  const PreparedSweep sweep = prepared();
  const std::string reference = threaded_csv(sweep);
  std::multiset<long long> all;
  for (long long id = 0; id < kPoints; ++id) {
    all.insert(id);
  }
  // 60 > 54 points: the last six shards hold no point and still merge.
  for (const long long n : {1LL, 2LL, 3LL, 7LL, 60LL}) {
    const ScratchDir d;
    std::multiset<long long> seen;
    for (long long k = 1; k <= n; ++k) {
      const RunSummary s = run(sweep, options(d.path(), {k, n, true}));
      ASSERT_TRUE(s.complete);
      const std::multiset<long long> ids = row_ids(read_text(s.csv));
      EXPECT_EQ(s.points, static_cast<long long>(ids.size())) << k << "/" << n;
      // Dealt round-robin: the shards' sizes differ by at most one point.
      EXPECT_EQ(s.points, k <= kPoints % n ? kPoints / n + 1 : kPoints / n) << k << "/" << n;
      // The shard's ids are those shard_members names.
      const std::vector<char> member = shard_members(kPoints, {k, n, true});
      for (const long long id : ids) {
        EXPECT_EQ(member[static_cast<std::size_t>(id)], 1) << "point " << id << " in " << k;
      }
      seen.insert(ids.begin(), ids.end());
    }
    EXPECT_EQ(seen, all) << n << " shards";
    // Shard 1/1 is a shard too (its own files), so that a job array of one task merges.
    const MergeSummary m = merge_shards(sweep, merging(d.path()));
    EXPECT_EQ(m.points, kPoints);
    EXPECT_EQ(m.shards, n);
    EXPECT_EQ(read_text(m.csv), reference) << n << " shards";
    // The shard files are gone: only the result and its sidecar are left.
    EXPECT_EQ(files_under(d.path()),
              (std::vector<std::string>{"test/mixed.csv", "test/mixed.json"}));
  }
}

TEST(Shards, NoShardIsMadeOfOneValueOfTheLastAxis) {
  // Dealt in id order, 2 shards of a spec whose last axis has 2 values would each get one value
  // (the mixed spec's last axis is the method: one shard would get every closed form).
  const PreparedSweep sweep = prepared();
  for (const long long n : {2LL, 3LL}) {
    for (long long k = 1; k <= n; ++k) {
      const std::vector<char> member = shard_members(sweep.points.size(), {k, n, true});
      std::set<std::string> methods;
      for (const Point& p : sweep.points) {
        if (member[static_cast<std::size_t>(p.id)] != 0) {
          methods.insert(p.find("method")->text());
        }
      }
      EXPECT_EQ(methods.size(), 3U) << k << "/" << n;
    }
  }
}

TEST(Shards, WithTimingOnTheMergeDiffersOnlyInTheTimingColumns) {
  const PreparedSweep sweep = prepared();
  const std::string untimed = threaded_csv(sweep);
  const std::string timed = threaded_csv(sweep, true);
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 2, 3}, true);
  const std::string merged = read_text(merge_shards(sweep, merging(d.path())).csv);
  EXPECT_EQ(without_timing(merged, *sweep.kind), without_timing(timed, *sweep.kind));
  EXPECT_EQ(without_timing(merged, *sweep.kind), without_timing(untimed, *sweep.kind));
  // The timings were written: the comparison above dropped something.
  EXPECT_NE(merged, untimed);
}

TEST(Shards, AShardResumesFromItsOwnCheckpoint) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  RunOptions o = options(d.path(), {2, 3, true});
  o.max_points = 5;
  const RunSummary first = run(sweep, o);
  EXPECT_FALSE(first.complete);
  EXPECT_EQ(first.computed, 5);
  EXPECT_EQ(first.partial, d / "test" / "mixed.shard-2-of-3.partial.csv");
  EXPECT_TRUE(fs::exists(first.partial));
  // The other shards neither read nor disturb it.
  run_shards(sweep, d.path(), 3, {1, 3});
  EXPECT_TRUE(fs::exists(first.partial));
  o.resume = true;
  o.max_points = -1;
  const RunSummary last = run(sweep, o);
  EXPECT_TRUE(last.complete);
  EXPECT_EQ(last.resumed, 5);
  EXPECT_EQ(last.computed, last.points - 5);
  EXPECT_FALSE(fs::exists(first.partial));
  EXPECT_EQ(nlohmann::json::parse(read_text(last.sidecar)).at("resumed_point_count"), 5);
  const MergeSummary m = merge_shards(sweep, merging(d.path()));
  EXPECT_EQ(read_text(m.csv), threaded_csv(sweep));
  EXPECT_EQ(nlohmann::json::parse(read_text(m.sidecar)).at("resumed_point_count"), 5);
}

TEST(Shards, TheMergedSidecarListsTheShards) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 2, 3}, true);
  const auto shard_side = nlohmann::json::parse(read_text(d / "test" / "mixed.shard-2-of-3.json"));
  EXPECT_EQ(shard_side.at("shard"), (nlohmann::json{{"index", 2}, {"count", 3}}));
  EXPECT_EQ(shard_side.at("fingerprint"), fingerprint(sweep));
  EXPECT_EQ(shard_side.at("point_count"), 18);

  const MergeSummary m = merge_shards(sweep, merging(d.path()));
  const auto j = nlohmann::json::parse(read_text(m.sidecar));
  EXPECT_EQ(j.at("point_count"), kPoints);
  EXPECT_EQ(j.at("points").size(), static_cast<std::size_t>(kPoints));
  EXPECT_EQ(j.at("name"), "mixed");
  EXPECT_EQ(j.at("timing"), true);
  const auto& shards = j.at("shards");
  ASSERT_EQ(shards.size(), 3U);
  double longest = 0.0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(shards[k].at("index"), k + 1);
    EXPECT_EQ(shards[k].at("threads"), 2);
    EXPECT_EQ(shards[k].at("ranks"), 1);
    EXPECT_EQ(shards[k].at("point_seconds").at("count"), 18);
    for (const char* key : {"wall_s", "date", "provenance"}) {
      EXPECT_TRUE(shards[k].contains(key)) << key;
    }
    longest = std::max(longest, shards[k].at("wall_s").get<double>());
  }
  EXPECT_EQ(j.at("wall_s"), longest);
  // Every point was computed once, in one of the shards; order statistics do not merge.
  EXPECT_EQ(j.at("point_seconds").at("count"), kPoints);
  EXPECT_TRUE(j.at("point_seconds").at("median").is_null());
  EXPECT_TRUE(j.at("point_seconds").at("p90").is_null());
  EXPECT_GT(j.at("point_seconds").at("sum").get<double>(), 0.0);
}

TEST(Shards, MergeRefusesAMissingOrUnfinishedShard) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 3});
  std::string text = expect_refused(sweep, merging(d.path()));
  EXPECT_TRUE(contains(text, "shard 2/3: missing")) << text;
  EXPECT_FALSE(contains(text, "shard 1/3")) << text;

  RunOptions o = options(d.path(), {2, 3, true});
  o.max_points = 4;
  (void)run(sweep, o);
  text = expect_refused(sweep, merging(d.path()));
  EXPECT_TRUE(contains(text, "shard 2/3: unfinished")) << text;
  EXPECT_TRUE(contains(text, "--shard 2/3 --resume")) << text;

  o.resume = true;
  o.max_points = -1;
  (void)run(sweep, o);
  EXPECT_EQ(read_text(merge_shards(sweep, merging(d.path())).csv), threaded_csv(sweep));
}

TEST(Shards, MergeRefusesAShardOfAnotherSpec) {
  const PreparedSweep sweep = prepared();
  // One point edited: the same columns and point count, another fingerprint.
  std::string text = kSpec;
  text.replace(text.find("mu = [1.0, 0.2]"), 15, "mu = [1.0, 0.3]");
  const PreparedSweep edited = prepared(text);
  ASSERT_EQ(edited.points.size(), sweep.points.size());
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 3});
  run_shards(edited, d.path(), 3, {2});
  const std::string error = expect_refused(sweep, merging(d.path()));
  EXPECT_TRUE(contains(error, "mixed.shard-2-of-3.json")) << error;
  EXPECT_TRUE(contains(error, "not shard 2/3 of this spec")) << error;
  // Merged by the edited spec, shards 1 and 3 are the strangers.
  EXPECT_TRUE(contains(expect_refused(edited, merging(d.path())), "mixed.shard-1-of-3.json"));
}

TEST(Shards, MergeRefusesACorruptRowNamingItsLine) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 2, 3});
  const fs::path csv = d / "test" / "mixed.shard-2-of-3.csv";
  const std::string good = read_text(csv);
  const auto line_start = [&](int line) {
    std::size_t at = 0;
    for (int i = 1; i < line; ++i) {
      at = good.find('\n', at) + 1;
    }
    return at;
  };
  struct Case {
    std::string what, text, where;
  };
  const std::size_t third = line_start(3);
  const std::size_t fourth = line_start(4);
  // line 3 no longer starts with an id
  std::string garbage = good.substr(0, third);
  garbage.append("garbage\n").append(good, fourth);
  // line 4 is a point of shard 1 (id 0)
  std::string foreign = good.substr(0, fourth);
  foreign.append("0").append(good, good.find(',', fourth));
  // the last line cut short, as by a full disk: its number is the count of newlines
  std::string last_line(":");
  last_line.append(std::to_string(std::count(good.begin(), good.end(), '\n')));
  for (const Case& c :
       std::vector<Case>{{"garbage", garbage, ":3"},
                         {"foreign id", foreign, ":4"},
                         {"truncated", good.substr(0, good.size() - 5), last_line}}) {
    write_text(csv, c.text);
    const std::string error = expect_refused(sweep, merging(d.path()));
    EXPECT_TRUE(contains(error, csv.string() + c.where + ": ")) << c.what << ": " << error;
  }
  write_text(csv, good);
  EXPECT_EQ(read_text(merge_shards(sweep, merging(d.path())).csv), threaded_csv(sweep));
}

TEST(Shards, MergeRefusesShardsRunWithAndWithoutTimings) {
  const PreparedSweep sweep = prepared();
  const ScratchDir d;
  run_shards(sweep, d.path(), 3, {1, 3});
  run_shards(sweep, d.path(), 3, {2}, true);
  const std::string error = expect_refused(sweep, merging(d.path()));
  EXPECT_TRUE(contains(error, "mixed.shard-2-of-3.json")) << error;
  EXPECT_TRUE(contains(error, "--no-timing")) << error;
}

TEST(Shards, SeveralShardCountsOnDiskNeedShards) {
  const PreparedSweep sweep = prepared();
  const std::string reference = threaded_csv(sweep);
  const ScratchDir d;
  run_shards(sweep, d.path(), 2, {1, 2});
  run_shards(sweep, d.path(), 3, {1, 2, 3});
  const std::string error = expect_refused(sweep, merging(d.path()));
  EXPECT_TRUE(contains(error, "2, 3")) << error;
  EXPECT_TRUE(contains(error, "--shards N")) << error;
  // --shards picks a set and removes only its files; the other set is then alone on disk.
  MergeOptions three = merging(d.path());
  three.shards = 3;
  EXPECT_EQ(read_text(merge_shards(sweep, three).csv), reference);
  EXPECT_EQ(
      files_under(d.path()),
      (std::vector<std::string>{"test/mixed.csv", "test/mixed.json", "test/mixed.shard-1-of-2.csv",
                                "test/mixed.shard-1-of-2.json", "test/mixed.shard-2-of-2.csv",
                                "test/mixed.shard-2-of-2.json"}));
  EXPECT_EQ(merge_shards(sweep, merging(d.path())).shards, 2);
  EXPECT_EQ(read_text(d / "test" / "mixed.csv"), reference);
  // A count with no shard on disk at all: every shard is missing.
  MergeOptions five = merging(d.path());
  five.shards = 5;
  EXPECT_TRUE(contains(expect_refused(sweep, five), "shard 5/5: missing"));
}

TEST(Shards, NoShardsOnDiskIsAnError) {
  const ScratchDir d;
  const std::string error = expect_refused(prepared(), merging(d.path()));
  EXPECT_TRUE(contains(error, "--shard k/n")) << error;
}

// --- the command line ---------------------------------------------------------------------------

TEST(ShardsCli, ShardsMergeIntoTheSingleRunsBytesAndKeepShardsKeepsThem) {
  const ScratchDir d;
  const fs::path spec = d / "mixed.toml";
  write_text(spec, kSpec);
  const std::string data = (d / "data").string();
  const auto single =
      run_slipwalk({"sweep", spec.string(), "--data", (d / "single").string(), "--no-timing"});
  ASSERT_EQ(single.exit_code, 0) << single.err;
  for (const std::string k : {"1", "2"}) {
    const auto r = run_slipwalk(
        {"sweep", spec.string(), "--data", data, "--no-timing", "--shard", k + "/2", "-j", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "mixed.shard-" + k + "-of-2.csv: 27 points")) << r.out;
  }
  const auto merged =
      run_slipwalk({"sweep", "merge", spec.string(), "--data", data, "--keep-shards"});
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_TRUE(contains(merged.out, "54 points (0 failed) merged from 2 shards")) << merged.out;
  EXPECT_EQ(read_text(d / "data" / "test" / "mixed.csv"),
            read_text(d / "single" / "test" / "mixed.csv"));
  EXPECT_EQ(
      files_under(d / "data"),
      (std::vector<std::string>{"test/mixed.csv", "test/mixed.json", "test/mixed.shard-1-of-2.csv",
                                "test/mixed.shard-1-of-2.json", "test/mixed.shard-2-of-2.csv",
                                "test/mixed.shard-2-of-2.json"}));
  // Merged again without --keep-shards: the same result, the shards gone.
  const auto again = run_slipwalk({"sweep", "merge", spec.string(), "--data", data});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(read_text(d / "data" / "test" / "mixed.csv"),
            read_text(d / "single" / "test" / "mixed.csv"));
  EXPECT_EQ(files_under(d / "data"),
            (std::vector<std::string>{"test/mixed.csv", "test/mixed.json"}));
}

TEST(ShardsCli, AnUnfinishedShardIsNamedWithHowToFinishIt) {
  const ScratchDir d;
  const fs::path spec = d / "mixed.toml";
  write_text(spec, kSpec);
  const std::string data = (d / "data").string();
  ASSERT_EQ(run_slipwalk({"sweep", spec.string(), "--data", data, "--shard", "1/2"}).exit_code, 0);
  ASSERT_EQ(
      run_slipwalk({"sweep", spec.string(), "--data", data, "--shard", "2/2", "--max-points", "3"})
          .exit_code,
      0);
  const std::vector<std::string> before = files_under(d / "data");
  const auto r = run_slipwalk({"sweep", "merge", spec.string(), "--data", data});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "shard 2/2: unfinished")) << r.err;
  EXPECT_TRUE(contains(r.err, "--shard 2/2 --resume")) << r.err;
  EXPECT_EQ(files_under(d / "data"), before);
}

TEST(ShardsCli, BadShardAndMergeOptionsExitTwoWritingNothing) {
  const ScratchDir d;
  const fs::path spec = d / "mixed.toml";
  write_text(spec, kSpec);
  const std::string data = (d / "data").string();
  const std::string s = spec.string();
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"sweep", "--quick", "merge", s, "--data", data},
           {"sweep", "--data", data, "merge", s},
           {"sweep", "--no-timing", "merge", s, "--data", data},
           {"sweep", "merge", s, "--data", data, "--shards", "-1"},
           {"sweep", "merge", s, "--data", data, "--shards", "x"},
           {"sweep", "merge", s, "--data", data, "--shard", "1/2"},
           {"sweep", "merge", "--data", data},
           {"sweep", s, "--data", data, "--shard", "0/3"},
           {"sweep", s, "--data", data, "--shard", "4/3"},
           {"sweep", s, "--data", data, "--shard", "x"},
           {"sweep", s, "--data", data, "--shard", "1/0"},
           {"sweep", s, "--data", data, "--shard", "1/"},
           // Given but empty is a bad k/n, not "no shard" (which would run the whole sweep).
           {"sweep", s, "--data", data, "--shard", ""},
           // Nothing but two decimal integers: no blanks, no sign, no overflow clamped.
           {"sweep", s, "--data", data, "--shard", " 1/2"},
           {"sweep", s, "--data", data, "--shard", "+1/2"},
           {"sweep", s, "--data", data, "--shard", "1/99999999999999999999"},
       }) {
    std::string line;
    for (const auto& a : args) {
      line += " " + a;
    }
    const auto r = run_slipwalk(args);
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("slipwalk: error: ", 0), 0U) << line << "\n" << r.err;
    EXPECT_FALSE(fs::exists(d / "data")) << line;
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
