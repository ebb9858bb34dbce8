#include "sweeps/engine/checkpoint.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/provenance.hpp"
#include "sweeps/engine/random.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {

namespace {

/// The largest checkpoint --resume reads: a sweep's CSV of kMaxPoints points of a few hundred
/// bytes each.
constexpr std::size_t kMaxCheckpointBytes = std::size_t{16} << 30;
constexpr long long kMaxShards = 1'000'000;

std::string join(const std::vector<std::string>& columns) {
  std::string out;
  for (const auto& c : columns) {
    out += (out.empty() ? "" : ",") + c;
  }
  return out;
}

std::string format_cell(const Cell& cell) {
  std::ostringstream out;
  core::CsvWriter writer(out, {""});  // one empty header line, then the cell
  if (const auto* d = std::get_if<double>(&cell)) {
    writer.cell(*d);
  } else if (const auto* i = std::get_if<long long>(&cell)) {
    writer.cell(*i);
  } else {
    writer.cell(std::get<std::string>(cell));
  }
  return out.str().substr(1);  // drop the header's newline
}

std::string format_rows(const PointResult& r, const std::vector<ColumnInfo>& columns, bool timing) {
  std::string out;
  for (const Cells& row : r.rows) {
    if (row.size() != columns.size()) {
      throw std::logic_error("point kind returned " + std::to_string(row.size()) + " cells for " +
                             std::to_string(columns.size()) + " columns");
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      out += i ? "," : "";
      out += columns[i].timing && !timing ? std::string("0") : format_cell(row[i]);
    }
    out += '\n';
  }
  return out;
}

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

/// Held while a point of a timed kind runs: process-wide, so timed points of concurrent sweeps
/// take turns too.
std::mutex& timed_points_mutex() {
  static std::mutex m;
  return m;
}

std::string timing_line(bool timing) { return std::string("#timing,") + (timing ? "1" : "0"); }

// A point's end mark in a checkpoint, "#done,<id>,<outcome>,<message>" (outcome 0 done, 1 failed,
// 2 at its budget): the id, the outcome and where the message starts. False for a malformed line
// (std::from_chars: no sign, no blanks, an overflow fails), which then marks nothing finished.
bool parse_done(const std::string& line, long long& id, int& outcome, std::size_t& message) {
  const char* const begin = line.data();
  const char* const end = begin + line.size();
  constexpr std::size_t kTag = 6;  // "#done,"
  if (line.size() <= kTag) {
    return false;
  }
  const auto parsed_id = std::from_chars(begin + kTag, end, id);
  if (parsed_id.ec != std::errc() || parsed_id.ptr == end || *parsed_id.ptr != ',') {
    return false;
  }
  int flag = -1;
  const auto parsed_flag = std::from_chars(parsed_id.ptr + 1, end, flag);
  if (parsed_flag.ec != std::errc() || parsed_flag.ptr == end || *parsed_flag.ptr != ',' ||
      flag < 0 || flag > 2) {
    return false;
  }
  outcome = flag;
  message = static_cast<std::size_t>(parsed_flag.ptr + 1 - begin);
  return true;
}

FinishedPoints read_partial(const std::filesystem::path& path, const std::string& header,
                            const std::string& print, bool timing, long long n_points) {
  const std::string text = core::read_input_file(path, "a sweep checkpoint", kMaxCheckpointBytes);
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1) {
    lines.push_back(text.substr(start, nl - start));  // an unterminated last line is dropped
  }
  const std::string where = path.string();
  if (lines.empty() || lines[0] != header) {
    throw core::InputError(where, "the checkpoint's header does not match the spec's columns (" +
                                      header + "); rerun without --resume to start afresh");
  }
  if (lines.size() < 2 || lines[1] != "#spec," + print) {
    throw core::InputError(where,
                           "the checkpoint was written for a different spec (its points differ); "
                           "rerun without --resume to start afresh");
  }
  if (lines.size() < 3 || lines[2].rfind("#timing,", 0) != 0) {
    throw core::InputError(where,
                           "the checkpoint was written by an older slipwalk; rerun without "
                           "--resume to start afresh");
  }
  if (lines[2] != timing_line(timing)) {
    throw core::InputError(where, std::string("the checkpoint was written ") +
                                      (timing ? "with --no-timing" : "with timings") +
                                      "; resume it with the same setting, or rerun without "
                                      "--resume to start afresh");
  }
  FinishedPoints done;
  std::string rows;
  for (std::size_t i = 3; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.rfind("#done,", 0) != 0) {
      rows += line + '\n';
      continue;
    }
    long long id = -1;
    int outcome = 0;
    std::size_t consumed = 0;
    if (parse_done(line, id, outcome, consumed) && id >= 0 && id < n_points) {
      // Every row of the point must carry its id.
      const std::string prefix = std::to_string(id) + ",";
      bool ok = true;
      for (std::size_t p = 0; p < rows.size(); p = rows.find('\n', p) + 1) {
        ok = ok && rows.compare(p, prefix.size(), prefix) == 0;
      }
      if (ok) {
        done[id] = Finished{rows, outcome == 1, outcome == 2, line.substr(consumed)};
      }
    }
    rows.clear();
  }
  return done;
}

void append_point(std::string& out, long long id, const Finished& f) {
  out += f.rows;
  const char* outcome = f.failed ? "1" : (f.at_budget ? "2" : "0");
  out += "#done," + std::to_string(id) + "," + outcome + "," + f.message + "\n";
}

}  // namespace

std::vector<char> shard_members(std::size_t points, const Shard& shard) {
  if (shard.whole()) {
    return std::vector<char>(points, 1);
  }
  std::vector<std::pair<double, std::size_t>> order(points);
  for (std::size_t id = 0; id < points; ++id) {
    order[id] = {Random(1, id).uniform(), id};
  }
  std::sort(order.begin(), order.end());
  std::vector<char> member(points, 0);
  const auto n = static_cast<std::size_t>(shard.count);
  for (std::size_t position = static_cast<std::size_t>(shard.index - 1); position < points;
       position += n) {
    member[order[position].second] = 1;
  }
  return member;
}

std::string Shard::text() const { return std::to_string(index) + "/" + std::to_string(count); }

Shard parse_shard(const std::string& text, const std::string& option) {
  // Two plain decimal integers around one '/', nothing else (std::from_chars: no sign, no
  // blanks, an overflow is an error, not a clamped value).
  long long k = 0;
  long long n = 0;
  const std::size_t slash = text.find('/');
  const auto whole = [&text](std::size_t from, std::size_t to, long long& value) {
    const char* const first = text.data() + from;
    const char* const last = text.data() + to;
    const auto [end, error] = std::from_chars(first, last, value);
    return first != last && error == std::errc() && end == last;
  };
  if (slash == std::string::npos || !whole(0, slash, k) || !whole(slash + 1, text.size(), n) ||
      n < 1 || n > kMaxShards || k < 1 || k > n) {
    throw core::InputError(option,
                           "expected k/n with 1 <= k <= n <= " + std::to_string(kMaxShards) +
                               " (the k-th of n shards), "
                               "got '" +
                               text + "'");
  }
  return {k, n, true};
}

SweepFiles sweep_files(const Spec& spec, const std::filesystem::path& data, const Shard& shard) {
  std::string stem = spec.name;
  if (!shard.whole()) {
    stem += ".shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
  }
  const std::filesystem::path dir = data / spec.study;
  return {dir / (stem + ".csv"), dir / (stem + ".json"), dir / (stem + ".partial.csv")};
}

std::string header_line(const PreparedSweep& sweep) { return join(sweep.kind->column_names()); }

std::string fingerprint(const PreparedSweep& s) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&](const std::string& text) {
    for (unsigned char c : text) {
      h = (h ^ c) * 1099511628211ULL;
    }
    h = (h ^ 0xffU) * 1099511628211ULL;
  };
  mix(s.spec.kind);
  mix(join(s.kind->column_names()));
  for (const Point& p : s.points) {
    mix(p.to_json().dump());
  }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

Finished compute_point(const PreparedSweep& sweep, const Point& point, bool timing) {
  const PointKind& kind = *sweep.kind;
  const auto start = std::chrono::steady_clock::now();
  PointResult r;
  if (kind.timed == Timed::kYes) {
    const std::lock_guard lock(timed_points_mutex());
    r = kind.run(point);
  } else {
    r = kind.run(point);
  }
  Finished f;
  f.rows = format_rows(r, kind.columns, timing);
  const bool expected_stop = r.at_budget && sweep.spec.budget_stops_expected;
  f.failed = r.failed || (r.at_budget && !expected_stop);
  f.at_budget = expected_stop && !r.failed;
  f.message = one_line(r.message);
  f.seconds = seconds_since(start);
  return f;
}

Checkpoint::Checkpoint(std::filesystem::path path, const std::string& header,
                       const std::string& print, bool timing, long long points, bool resume)
    : path_(std::move(path)) {
  if (resume && std::filesystem::exists(path_)) {
    done_ = read_partial(path_, header, print, timing, points);
  }
  resumed_ = static_cast<long long>(done_.size());
  const std::filesystem::path folder = path_.parent_path();
  std::error_code ec;
  folder_existed_ = folder.empty() || std::filesystem::exists(folder, ec);
  // Rewritten with what was kept: a torn last point of a killed run is gone from the file too.
  std::string text = header + "\n#spec," + print + "\n" + timing_line(timing) + "\n";
  for (const auto& [id, f] : done_) {
    append_point(text, id, f);
  }
  core::write_file_atomically(path_, text);
  out_.open(path_, std::ios::out | std::ios::app | std::ios::binary);
  if (!out_) {
    throw core::InputError(path_.string(), "cannot open for appending");
  }
}

void Checkpoint::append(std::vector<std::pair<long long, Finished>>& points) {
  std::string text;
  for (const auto& [id, f] : points) {
    append_point(text, id, f);
  }
  out_ << text;
  out_.flush();
  if (!out_) {
    throw core::ComputationError(path_.string() + ": write failed");
  }
  for (auto& [id, f] : points) {
    done_[id] = std::move(f);
  }
}

void Checkpoint::discard_if_empty() {
  if (done_.empty()) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    if (!folder_existed_) {
      std::filesystem::remove(path_.parent_path(), ec);  // only if empty
    }
  }
}

void Checkpoint::remove() {
  out_.close();
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

nlohmann::json point_seconds_json(std::vector<double> seconds) {
  double sum = 0.0;
  for (const double s : seconds) {
    sum += s;
  }
  std::sort(seconds.begin(), seconds.end());
  const auto n = static_cast<double>(seconds.size());
  const auto or_null = [&](double x) {
    return seconds.empty() ? nlohmann::json() : nlohmann::json(x);
  };
  return {{"count", seconds.size()},
          {"sum", sum},
          {"mean", or_null(sum / n)},
          {"median", or_null(quantile_of_sorted(seconds, 0.5))},
          {"p90", or_null(quantile_of_sorted(seconds, 0.9))},
          {"max", or_null(seconds.empty() ? 0.0 : seconds.back())}};
}

nlohmann::json result_sidecar(const PreparedSweep& sweep, const Shard& shard,
                              const FinishedPoints& points, bool timing) {
  const Spec& spec = sweep.spec;
  nlohmann::json failed = nlohmann::json::array();
  nlohmann::json at_budget = nlohmann::json::array();
  for (const auto& [id, f] : points) {
    if (f.failed) {
      failed.push_back({{"id", id}, {"message", f.message}});
    } else if (f.at_budget) {
      at_budget.push_back({{"id", id}, {"message", f.message}});
    }
  }
  nlohmann::json listed = nlohmann::json::array();
  const std::vector<char> member = shard_members(sweep.points.size(), shard);
  for (const Point& p : sweep.points) {
    if (member[static_cast<std::size_t>(p.id)] != 0) {
      listed.push_back(p.to_json());
    }
  }
  nlohmann::json sidecar = {
      {"study", spec.study},
      {"name", spec.name},
      {"kind", spec.kind},
      {"description", spec.description},
      {"spec_file", spec.path},
      {"quick", spec.quick()},
      {"variant", variant_name(spec.variant)},
      {"spec", spec.source},
      {"columns", sweep.kind->column_names()},
      {"point_count", listed.size()},
      {"failed_point_count", failed.size()},
      {"failed_points", failed},
      {"budget_point_count", at_budget.size()},
      {"budget_points", at_budget},
      {"timing", timing},
      {"date", utc_now()},
      {"provenance", core::build_provenance()},
      {"points", listed},
  };
  if (!shard.whole()) {
    sidecar["shard"] = {{"index", shard.index}, {"count", shard.count}};
    sidecar["fingerprint"] = fingerprint(sweep);
  }
  return sidecar;
}

void write_result(const SweepFiles& files, const std::string& header, const FinishedPoints& points,
                  nlohmann::json sidecar) {
  std::string csv = header + "\n";
  for (const auto& [id, f] : points) {
    csv += f.rows;
  }
  sidecar["csv"] = files.csv.filename().string();
  // The CSV is renamed last, after its sidecar: it is never seen without it (a sidecar alone is
  // no result to any reader, and keep_finished reruns it).
  core::AtomicFile csv_file(files.csv);
  csv_file.stream() << csv;
  core::AtomicFile sidecar_file(files.sidecar);
  sidecar_file.stream() << sidecar.dump(1) << "\n";
  core::commit_with_sidecar(csv_file, sidecar_file);
}

}  // namespace slipwalk::sweeps
