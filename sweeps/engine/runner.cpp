#include "sweeps/engine/runner.hpp"

#include <gsl/gsl_errno.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/provenance.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {

namespace {

using Clock = std::chrono::steady_clock;

std::string join(const std::vector<std::string>& columns) {
  std::string out;
  for (const auto& c : columns) {
    out += (out.empty() ? "" : ",") + c;
  }
  return out;
}

/// FNV-1a over the kind, the columns and every point: a checkpoint is only resumed by the spec
/// (after quick overrides) that wrote it.
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

/// The columns that hold timings, from the kind's column table: written as 0 when timing is off.
std::vector<bool> timing_columns(const std::vector<ColumnInfo>& columns) {
  std::vector<bool> out(columns.size(), false);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    out[i] = columns[i].timing;
  }
  return out;
}

/// Held while a point of a timed kind runs: process-wide, so timed points of concurrent sweeps
/// take turns too.
std::mutex& timed_points_mutex() {
  static std::mutex m;
  return m;
}

/// A timed kind's point holds the process-wide lock while it runs; any other runs freely.
PointResult run_point(const PointKind& kind, const Point& point) {
  if (kind.timed == Timed::kYes) {
    const std::lock_guard lock(timed_points_mutex());
    return kind.run(point);
  }
  return kind.run(point);
}

std::string format_rows(const PointResult& r, const std::vector<bool>& timing_column, bool timing) {
  std::string out;
  const std::size_t columns = timing_column.size();
  for (const Cells& row : r.rows) {
    if (row.size() != columns) {
      throw std::logic_error("point kind returned " + std::to_string(row.size()) + " cells for " +
                             std::to_string(columns) + " columns");
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      out += i ? "," : "";
      out += timing_column[i] && !timing ? std::string("0") : format_cell(row[i]);
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

struct Finished {
  std::string rows;  ///< CSV text, one line per row
  bool failed = false;
  std::string message;
};

/// The largest checkpoint --resume reads: a sweep's CSV of kMaxPoints points of a few hundred
/// bytes each.
constexpr std::size_t kMaxCheckpointBytes = std::size_t{16} << 30;

/// The checkpoint: the header, `#spec,<fingerprint>`, then per finished point its rows and a
/// `#done,<id>,<failed>,<message>` line. A point counts only once its #done line is complete, so
/// a run killed in the middle of a write loses at most the point being written.
std::map<long long, Finished> read_partial(const std::filesystem::path& path,
                                           const std::string& header, const std::string& print,
                                           long long n_points) {
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
  std::map<long long, Finished> done;
  std::string rows;
  for (std::size_t i = 2; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.rfind("#done,", 0) != 0) {
      rows += line + '\n';
      continue;
    }
    long long id = -1;
    int failed = 0;
    int consumed = 0;
    if (std::sscanf(line.c_str(), "#done,%lld,%d,%n", &id, &failed, &consumed) >= 2 &&
        consumed > 0 && id >= 0 && id < n_points) {
      // Every row of the point must carry its id.
      const std::string prefix = std::to_string(id) + ",";
      bool ok = true;
      for (std::size_t p = 0; p < rows.size(); p = rows.find('\n', p) + 1) {
        ok = ok && rows.compare(p, prefix.size(), prefix) == 0;
      }
      if (ok) {
        done[id] = Finished{rows, failed != 0, line.substr(static_cast<std::size_t>(consumed))};
      }
    }
    rows.clear();
  }
  return done;
}

void write_partial_start(const std::filesystem::path& path, const std::string& header,
                         const std::string& print, const std::map<long long, Finished>& done) {
  core::AtomicFile file(path);
  file.stream() << header << "\n#spec," << print << "\n";
  for (const auto& [id, f] : done) {
    file.stream() << f.rows << "#done," << id << "," << (f.failed ? 1 : 0) << "," << f.message
                  << "\n";
  }
  file.commit();
}

}  // namespace

std::filesystem::path csv_path(const Spec& spec, const std::filesystem::path& data) {
  return data / spec.study / (spec.name + ".csv");
}

std::filesystem::path partial_path(const Spec& spec, const std::filesystem::path& data) {
  return data / spec.study / (spec.name + ".partial.csv");
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

PreparedSweep prepare(Spec spec, std::span<const PointKind> kinds) {
  PreparedSweep s;
  s.kind = find_point_kind(kinds, spec.kind);
  if (s.kind == nullptr) {
    throw core::InputError(spec.kind_origin,
                           "unknown kind '" + spec.kind + "'; expected " + point_kind_names(kinds));
  }
  s.points = expand(spec);
  for (const Point& p : s.points) {
    s.kind->check(p);
  }
  // The variant not run is checked as well: a bad value is bad input whether or not --quick
  // overrides it, and a bad [quick] value is found by a full run too.
  for (const Point& p : expand_other(spec)) {
    try {
      s.kind->check(p);
    } catch (const core::InputError& e) {
      std::string what = e.what();
      what.erase(0, std::min(what.size(), e.where().size() + 2));
      what.append(spec.quick ? " (in the spec without --quick)" : " (in the spec under --quick)");
      throw core::InputError(e.where(), what);
    }
  }
  s.spec = std::move(spec);
  return s;
}

RunSummary run(const PreparedSweep& sweep, const RunOptions& options) {
  const auto start = Clock::now();
  gsl_set_error_handler_off();  // a GSL failure is a failed point, never an abort()
  const Spec& spec = sweep.spec;
  const PointKind& fn = *sweep.kind;
  const auto n_points = static_cast<long long>(sweep.points.size());
  const std::string header = join(fn.column_names());
  const std::string print = fingerprint(sweep);
  const std::vector<bool> timing_column = timing_columns(fn.columns);
  const std::string label = "[" + spec.study + "/" + spec.name + "] ";

  RunSummary summary;
  summary.csv = csv_path(spec, options.data_dir);
  summary.sidecar = summary.csv;
  summary.sidecar.replace_extension(".json");
  summary.partial = partial_path(spec, options.data_dir);
  summary.points = n_points;

  // The checkpoint: resumed, or discarded.
  std::map<long long, Finished> done;
  if (std::filesystem::exists(summary.partial)) {
    if (options.resume) {
      done = read_partial(summary.partial, header, print, n_points);
    }
  }
  summary.resumed = static_cast<long long>(done.size());
  // A run that fails before it finishes a point leaves nothing behind: no empty checkpoint, and
  // not the study folder it created.
  const std::filesystem::path folder = summary.partial.parent_path();
  std::error_code exists_ec;
  const bool folder_existed = folder.empty() || std::filesystem::exists(folder, exists_ec);
  const auto discard_if_nothing_done = [&] {
    if (done.empty()) {
      std::error_code ec;
      std::filesystem::remove(summary.partial, ec);
      if (!folder_existed) {
        std::filesystem::remove(folder, ec);  // only if empty
      }
    }
  };
  write_partial_start(summary.partial, header, print, done);

  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    if (done.find(sweep.points[i].id) == done.end()) {
      pending.push_back(i);
    }
  }
  if (options.max_points >= 0 && static_cast<long long>(pending.size()) > options.max_points) {
    pending.resize(static_cast<std::size_t>(options.max_points));
  }

  unsigned jobs = options.jobs != 0 ? options.jobs : std::thread::hardware_concurrency();
  jobs = std::clamp<unsigned>(jobs, 1U,
                              static_cast<unsigned>(std::max<std::size_t>(1, pending.size())));
  summary.jobs = jobs;

  if (!pending.empty()) {
    std::ofstream partial(summary.partial, std::ios::out | std::ios::app | std::ios::binary);
    if (!partial) {
      throw core::InputError(summary.partial.string(), "cannot open for appending");
    }
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;  // guards partial, done, error, the counters and the progress stream
    std::string error;
    long long computed = 0;
    auto last_progress = start;
    const auto worker = [&] {
      while (!stop) {
        const std::size_t k = next++;
        if (k >= pending.size()) {
          return;
        }
        const Point& point = sweep.points[pending[k]];
        Finished f;
        try {
          const PointResult r = run_point(fn, point);
          f.rows = format_rows(r, timing_column, options.timing);
          f.failed = r.failed;
          f.message = one_line(r.message);
        } catch (const std::exception& e) {
          const std::lock_guard lock(mutex);
          if (error.empty()) {
            error = "point " + std::to_string(point.id) + ": " + e.what();
          }
          stop = true;
          return;
        }
        const std::lock_guard lock(mutex);
        partial << f.rows << "#done," << point.id << "," << (f.failed ? 1 : 0) << "," << f.message
                << "\n";
        partial.flush();
        done[point.id] = std::move(f);
        ++computed;
        const auto now = Clock::now();
        if (options.progress != nullptr &&
            std::chrono::duration<double>(now - last_progress).count() >=
                options.progress_interval_s) {
          last_progress = now;
          const double elapsed = std::chrono::duration<double>(now - start).count();
          const auto remaining =
              static_cast<double>(pending.size()) - static_cast<double>(computed);
          *options.progress << label << done.size() << "/" << n_points << " points, "
                            << seconds_text(elapsed) << ", ETA "
                            << seconds_text(elapsed / static_cast<double>(computed) * remaining)
                            << std::endl;
        }
      }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < jobs; ++t) {
      threads.emplace_back(worker);
    }
    worker();
    for (auto& t : threads) {
      t.join();
    }
    summary.computed = computed;
    if (!partial) {
      discard_if_nothing_done();
      throw core::ComputationError(summary.partial.string() + ": write failed");
    }
    if (!error.empty()) {
      discard_if_nothing_done();
      throw core::ComputationError(
          label + error +
          (done.empty() ? std::string()
                        : " (finished points are kept in " + summary.partial.string() + ")"));
    }
  }

  summary.wall_s = seconds_since(start);
  nlohmann::json failed = nlohmann::json::array();
  for (const auto& [id, f] : done) {
    if (f.failed) {
      ++summary.failed;
      failed.push_back({{"id", id}, {"message", f.message}});
    }
  }
  if (static_cast<long long>(done.size()) < n_points) {
    if (options.progress != nullptr) {
      *options.progress << label << "stopped after " << done.size() << "/" << n_points
                        << " points; the rest follow with --resume" << std::endl;
    }
    return summary;
  }

  // Complete: the sorted CSV and the sidecar, then the checkpoint goes.
  std::string csv = header + "\n";
  for (const auto& [id, f] : done) {
    csv += f.rows;
  }
  nlohmann::json points = nlohmann::json::array();
  for (const Point& p : sweep.points) {
    points.push_back(p.to_json());
  }
  nlohmann::json sidecar = {
      {"study", spec.study},
      {"name", spec.name},
      {"kind", spec.kind},
      {"description", spec.description},
      {"spec_file", spec.path},
      {"quick", spec.quick},
      {"spec", spec.source},
      {"columns", fn.column_names()},
      {"csv", summary.csv.filename().string()},
      {"point_count", n_points},
      {"failed_point_count", summary.failed},
      {"failed_points", failed},
      {"resumed_point_count", summary.resumed},
      {"threads", jobs},
      {"wall_s", summary.wall_s},
      {"timing", options.timing},
      {"date", utc_now()},
      {"provenance", core::build_provenance()},
      {"points", points},
  };
  // The CSV is renamed last, after its sidecar: it is never seen without it (a sidecar alone is
  // no result to any reader, and keep_finished reruns it).
  core::AtomicFile csv_file(summary.csv);
  csv_file.stream() << csv;
  core::AtomicFile sidecar_file(summary.sidecar);
  sidecar_file.stream() << sidecar.dump(1) << "\n";
  core::commit_with_sidecar(csv_file, sidecar_file);
  std::error_code ec;
  std::filesystem::remove(summary.partial, ec);
  summary.complete = true;
  return summary;
}

}  // namespace slipwalk::sweeps
