#include "sweeps/engine/shards.hpp"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/json_input.hpp"

namespace slipwalk::sweeps {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The largest shard CSV merge reads (the checkpoint's bound, checkpoint.cpp).
constexpr std::size_t kMaxShardBytes = std::size_t{16} << 30;

/// The shard counts of this sweep's shard files (finished or checkpoints) in `dir`.
std::set<long long> counts_on_disk(const fs::path& dir, const std::string& name) {
  std::set<long long> counts;
  const std::regex pattern(
      "(?:" + std::regex_replace(name, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
      R"()\.shard-(\d+)-of-(\d+)\.(?:json|csv|partial\.csv))");
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::smatch m;
    const std::string file = it->path().filename().string();
    if (std::regex_match(file, m, pattern) && m[2].length() < 8) {
      counts.insert(std::stoll(m[2].str()));
    }
  }
  return counts;
}

long long shard_count(const PreparedSweep& sweep, const MergeOptions& options) {
  if (options.shards) {
    return *options.shards;
  }
  const fs::path dir = options.data_dir / sweep.spec.study;
  const std::set<long long> counts = counts_on_disk(dir, sweep.spec.name);
  if (counts.empty()) {
    throw core::InputError(dir.string(), "no shards of " + sweep.spec.name +
                                             " here; run them with `slipwalk sweep " +
                                             sweep.spec.path + " --shard k/n` first");
  }
  if (counts.size() > 1) {
    std::string list;
    for (const long long n : counts) {
      list += (list.empty() ? "" : ", ") + std::to_string(n);
    }
    throw core::InputError(dir.string(), "shards of " + sweep.spec.name + " in " + list +
                                             " parts are here; choose one set with --shards N");
  }
  return *counts.begin();
}

/// One shard's points from its CSV, each row given to the point its id names.
void read_rows(const fs::path& csv, const std::string& header, const Shard& shard,
               const std::vector<char>& member, FinishedPoints& done) {
  const std::string text = core::read_input_file(csv, "a shard's CSV", kMaxShardBytes);
  std::size_t start = 0;
  long long line_no = 0;
  for (std::size_t nl; start < text.size(); start = nl + 1) {
    nl = text.find('\n', start);
    if (nl == std::string::npos) {
      throw core::InputError(csv.string() + ":" + std::to_string(line_no + 1),
                             "the last line is unterminated (a truncated file?)");
    }
    ++line_no;
    const std::string_view line(text.data() + start, nl - start);
    if (line_no == 1) {
      if (line != header) {
        throw core::InputError(csv.string() + ":1",
                               "the header does not match the spec's columns (" + header + ")");
      }
      continue;
    }
    std::size_t digits = 0;
    while (digits < line.size() && digits < 12 &&
           std::isdigit(static_cast<unsigned char>(line[digits])) != 0) {
      ++digits;
    }
    const long long id = digits > 0 ? std::stoll(std::string(line.substr(0, digits))) : -1;
    if (digits == 0 || digits >= line.size() || line[digits] != ',' || id < 0 ||
        id >= static_cast<long long>(member.size()) || member[static_cast<std::size_t>(id)] == 0) {
      throw core::InputError(
          csv.string() + ":" + std::to_string(line_no),
          "expected a row of a point of shard " + shard.text() + " (its id first)");
    }
    done[id].rows.append(line).push_back('\n');
  }
}

}  // namespace

MergeSummary merge_shards(const PreparedSweep& sweep, const MergeOptions& options) {
  const Spec& spec = sweep.spec;
  const long long n = shard_count(sweep, options);
  const std::string print = fingerprint(sweep);
  const std::string header = header_line(sweep);

  // Every shard must be there and finished before anything is read.
  std::string missing;
  for (long long k = 1; k <= n; ++k) {
    const SweepFiles f = sweep_files(spec, options.data_dir, {k, n, true});
    if (!fs::is_regular_file(f.csv) || !fs::is_regular_file(f.sidecar)) {
      missing += "\n  shard " + std::to_string(k) + "/" + std::to_string(n) + ": " +
                 (fs::exists(f.partial)
                      ? "unfinished (" + f.partial.string() + "); finish it with --shard " +
                            std::to_string(k) + "/" + std::to_string(n) + " --resume"
                      : "missing (no " + f.csv.string() + ")");
    }
  }
  if (!missing.empty()) {
    throw core::InputError(
        (options.data_dir / spec.study).string(),
        "cannot merge " + spec.name + " from " + std::to_string(n) + " shards:" + missing);
  }

  FinishedPoints done;
  json shards = json::array();
  std::string commit;
  bool timing = true;
  bool first = true;
  long long resumed = 0;
  double wall_s = 0.0;
  double seconds_sum = 0.0;
  json seconds_max;
  long long seconds_count = 0;
  for (long long k = 1; k <= n; ++k) {
    const Shard shard{k, n, true};
    const SweepFiles f = sweep_files(spec, options.data_dir, shard);
    const std::string where = f.sidecar.string();
    const json side = core::parse_json(core::read_json_text(f.sidecar), where);
    if (!side.is_object() || side.value("fingerprint", "") != print ||
        side.value("shard", json()) != json{{"index", k}, {"count", n}}) {
      throw core::InputError(where, "not shard " + shard.text() + " of this spec (" + spec.path +
                                        (spec.variant == Variant::kDefault
                                             ? std::string()
                                             : std::string(", --") + variant_name(spec.variant)) +
                                        "): its points differ; rerun that shard");
    }
    const std::string shard_commit =
        side.value("provenance", json::object()).value("git_commit", std::string("unknown"));
    const bool shard_timing = side.value("timing", true);
    if (first) {
      commit = shard_commit;
      timing = shard_timing;
      first = false;
    } else if (shard_commit != commit) {
      std::string what = "written by build " + shard_commit;
      what += ", shard 1 by " + commit + "; rerun the shards with one build";
      throw core::InputError(where, what);
    } else if (shard_timing != timing) {
      throw core::InputError(where, std::string("run ") + (shard_timing ? "with" : "without") +
                                        " timings, shard 1 the other way; rerun it with"
                                        " --no-timing set alike");
    }
    // The shard's points, failed ones and those at their budget with their messages, then
    // their rows.
    const std::vector<char> member = shard_members(sweep.points.size(), shard);
    for (const Point& p : sweep.points) {
      if (member[static_cast<std::size_t>(p.id)] != 0) {
        done[p.id] = Finished{};
      }
    }
    for (const json& failed : side.value("failed_points", json::array())) {
      const long long id = failed.value("id", -1LL);
      if (id < 0 || id >= static_cast<long long>(member.size()) ||
          member[static_cast<std::size_t>(id)] == 0) {
        throw core::InputError(where, "failed_points names point " + std::to_string(id) +
                                          ", which is not in shard " + shard.text());
      }
      done[id].failed = true;
      done[id].message = failed.value("message", std::string());
    }
    for (const json& stopped : side.value("budget_points", json::array())) {
      const long long id = stopped.value("id", -1LL);
      if (id < 0 || id >= static_cast<long long>(member.size()) ||
          member[static_cast<std::size_t>(id)] == 0 || done[id].failed) {
        throw core::InputError(where, "budget_points names point " + std::to_string(id) +
                                          ", which is not in shard " + shard.text() +
                                          " or is also a failed point");
      }
      done[id].at_budget = true;
      done[id].message = stopped.value("message", std::string());
    }
    read_rows(f.csv, header, shard, member, done);
    resumed += side.value("resumed_point_count", 0LL);
    wall_s = std::max(wall_s, side.value("wall_s", 0.0));
    const json seconds = side.value("point_seconds", json::object());
    seconds_sum += seconds.value("sum", 0.0);
    seconds_count += seconds.value("count", 0LL);
    if (seconds.contains("max") && seconds["max"].is_number() &&
        (seconds_max.is_null() || seconds["max"].get<double>() > seconds_max.get<double>())) {
      seconds_max = seconds["max"];
    }
    shards.push_back({{"index", k},
                      {"threads", side.value("threads", json())},
                      {"ranks", side.value("ranks", json())},
                      {"wall_s", side.value("wall_s", json())},
                      {"point_seconds", seconds},
                      {"date", side.value("date", json())},
                      {"provenance", side.value("provenance", json())}});
  }

  json sidecar = result_sidecar(sweep, Shard{}, done, timing);
  sidecar["resumed_point_count"] = resumed;
  sidecar["wall_s"] = wall_s;  // the longest shard: the elapsed time when they ran side by side
  sidecar["shards"] = shards;
  sidecar["point_seconds"] = {
      {"count", seconds_count},
      {"sum", seconds_sum},
      {"mean", seconds_count > 0 ? json(seconds_sum / static_cast<double>(seconds_count)) : json()},
      {"median", json()},  // order statistics do not merge; each shard's are in "shards"
      {"p90", json()},
      {"max", seconds_max}};
  const SweepFiles out = sweep_files(spec, options.data_dir);
  write_result(out, header, done, sidecar);

  if (!options.keep_shards) {
    for (long long k = 1; k <= n; ++k) {
      const SweepFiles f = sweep_files(spec, options.data_dir, {k, n, true});
      std::error_code ec;
      fs::remove(f.csv, ec);
      fs::remove(f.sidecar, ec);
    }
  }
  MergeSummary summary;
  summary.csv = out.csv;
  summary.sidecar = out.sidecar;
  summary.points = static_cast<long long>(done.size());
  summary.failed = sidecar.value("failed_point_count", 0LL);
  summary.at_budget = sidecar.value("budget_point_count", 0LL);
  summary.shards = n;
  return summary;
}

}  // namespace slipwalk::sweeps
