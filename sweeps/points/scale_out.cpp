// Scaling out (studies/scaling_out, the performance page's "Scaling out"): what a sweep gains
// from more workers, and how many ranks one MPI coordinator can feed.
//
// `scale_out` runs a CPU-bound workload sweep as child processes of the `slipwalk` binary in four
// ways — one thread, R threads, R MPI ranks of one thread, R shards side by side then merged —
// in rounds whose order rotates, so that a slow spell of the shared machine falls on every mode
// alike; parallel efficiency is T_serial / (R · T_mode) within a round. Each mode's CSV is
// compared byte for byte with a reference serial run (all run with --no-timing).
//
// `coordinator_throughput` runs a sweep of `noop` points (a point that does nothing) over MPI
// ranks with rank 0 only coordinating (--coordinator-jobs 0) and reads from the sidecar how many
// points rank 0 handed out and collected per second of its own CPU time: the rate it could keep
// up if it were the bottleneck, and so how many ranks it can feed for points of a given cost.
//
// Without MPI in the build the MPI rows say so (exit_code −1, NaN times); the rest still runs.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/json_input.hpp"
#include "core/range.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"
#include "sweeps/points/subprocess.hpp"

namespace slipwalk::sweeps::points {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// The longest one command of the benchmark may run before it counts as failed.
constexpr double kCommandLimitS = 900.0;

// ---- noop -----------------------------------------------------------------------------------

struct NoopRow {
  long long id = 0;
  double i = 0.0;
  static std::vector<Column<NoopRow>> columns() {
    return {value("id", &NoopRow::id), value("i", &NoopRow::i)};
  }
};

/// A noop point's label `i`, 0 … 10^7 (what a spec of many points puts on an axis).
double noop_label(const Point& p) {
  return Reader(p, "noop", {"i"}).number("i", 0.0, core::closed(0.0, 1e7));
}

// ---- running the binary ---------------------------------------------------------------------

/// A scratch folder for one point's child runs, removed with it.
class Scratch {
 public:
  explicit Scratch(long long id)
      : path_(fs::temp_directory_path() /
              ("slipwalk-scale-out-" + std::to_string(::getpid()) + "-" + std::to_string(id))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// mpirun's arguments for `ranks` ranks on one machine, whatever its core count and user.
std::vector<std::string> launcher(int ranks) {
  std::vector<std::string> argv = {
      SLIPWALK_MPIEXEC, "--oversubscribe", "--bind-to", "none", "-np", std::to_string(ranks)};
  if (::geteuid() == 0) {
    argv.emplace_back("--allow-run-as-root");  // containers and CI run as root
  }
  return argv;
}

/// The last lines of a child's stderr, for a row's message.
std::string tail_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr std::size_t kTail = 300;
  text = text.size() > kTail ? text.substr(text.size() - kTail) : text;
  for (char& c : text) {
    c = (c == '\n' || c == ',') ? ' ' : c;
  }
  return text;
}

struct Outcome {
  int exit_code = 0;
  double process_wall_s = 0.0;
  std::string message;
};

/// Runs the commands side by side and waits for all of them.
Outcome run_together(const std::vector<std::vector<std::string>>& commands, const fs::path& dir) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<pid_t> pids;
  for (std::size_t k = 0; k < commands.size(); ++k) {
    pids.push_back(start_child(commands[k], dir / ("out" + std::to_string(k)),
                               dir / ("err" + std::to_string(k))));
  }
  Outcome o;
  for (std::size_t k = 0; k < pids.size(); ++k) {
    const int code = wait_child(pids[k], kCommandLimitS);
    if (code != 0 && o.exit_code == 0) {
      o.exit_code = code;
      o.message = tail_of(dir / ("err" + std::to_string(k)));
    }
  }
  o.process_wall_s = seconds_since(start);
  return o;
}

nlohmann::json read_sidecar(const fs::path& json) {
  return core::parse_json(core::read_json_text(json), json.string());
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- scale_out ------------------------------------------------------------------------------

const std::vector<std::string_view> kModes = {"serial", "threads", "mpi", "shards"};

struct ScaleRow {
  long long id = 0;
  std::string workload;
  std::string mode;
  long long workers = 1;
  long long repeat = 0;
  long long points = 0;
  double wall_s = kNaN;
  double process_wall_s = kNaN;
  long long same_bytes = 0;
  long long exit_code = 0;
  std::string message;
  static std::vector<Column<ScaleRow>> columns() {
    return {value("id", &ScaleRow::id),
            value("workload", &ScaleRow::workload),
            value("mode", &ScaleRow::mode),
            value("workers", &ScaleRow::workers),
            value("repeat", &ScaleRow::repeat),
            value("points", &ScaleRow::points),
            timing("wall_s", &ScaleRow::wall_s),
            timing("process_wall_s", &ScaleRow::process_wall_s),
            value("same_bytes", &ScaleRow::same_bytes),
            value("exit_code", &ScaleRow::exit_code),
            value("message", &ScaleRow::message)};
  }
};

struct ScaleInputs {
  fs::path workload;
  std::string workload_name;
  int ranks = 2;
  long long repeats = 5;
};

ScaleInputs read_scale(const Point& p) {
  const Reader r(p, "scale_out", {"workload", "ranks", "repeats"});
  ScaleInputs in;
  const auto file = r.text("workload");
  if (!file) {
    r.fail("workload", "required (a sweep spec, relative to this spec)");
  }
  in.workload_name = *file;
  in.workload = fs::path(p.source).parent_path() / *file;
  std::error_code ec;
  if (!fs::is_regular_file(in.workload, ec)) {
    r.fail("workload", "no such file: " + in.workload.string());
  }
  in.ranks = static_cast<int>(r.integer("ranks", 2, 2, 16));
  in.repeats = r.integer("repeats", 5, 1, 50);
  return in;
}

/// One mode's run of the workload into `data`; its CSV is `<data>/<study>/<name>.csv`.
ScaleRow run_mode(const ScaleInputs& in, std::string_view mode, const fs::path& binary,
                  const fs::path& data, const fs::path& logs) {
  ScaleRow row;
  row.mode = std::string(mode);
  row.workers = mode == "serial" ? 1 : in.ranks;
  const std::vector<std::string> sweep = {binary.string(), "sweep",  in.workload.string(),
                                          "--no-timing",   "--data", data.string()};
  const auto with = [](std::vector<std::string> a, std::initializer_list<std::string> more) {
    a.insert(a.end(), more);
    return a;
  };
  Outcome o;
  if (mode == "serial") {
    o = run_together({with(sweep, {"--jobs", "1"})}, logs);
  } else if (mode == "threads") {
    o = run_together({with(sweep, {"--jobs", std::to_string(in.ranks)})}, logs);
  } else if (mode == "mpi") {
    if (!mpi::available()) {
      row.exit_code = -1;
      row.message = "this build has no MPI";
      return row;
    }
    std::vector<std::string> argv = launcher(in.ranks);
    argv.insert(argv.end(), sweep.begin(), sweep.end());
    o = run_together({with(argv, {"--jobs", "1"})}, logs);
  } else {
    std::vector<std::vector<std::string>> shards;
    for (int k = 1; k <= in.ranks; ++k) {
      shards.push_back(with(
          sweep, {"--jobs", "1", "--shard", std::to_string(k) + "/" + std::to_string(in.ranks)}));
    }
    o = run_together(shards, logs);
    if (o.exit_code == 0) {
      const Outcome merged = run_together(
          {{binary.string(), "sweep", "merge", in.workload.string(), "--data", data.string()}},
          logs);
      o.exit_code = merged.exit_code;
      o.message = merged.message;
      o.process_wall_s += merged.process_wall_s;
    }
  }
  row.exit_code = o.exit_code;
  row.message = o.message;
  row.process_wall_s = o.process_wall_s;
  return row;
}

Rows<ScaleRow> run_scale(const Point& p) {
  const ScaleInputs in = read_scale(p);
  const Scratch scratch(p.id);
  const fs::path binary = slipwalk_binary();
  const PreparedSweep workload = points::prepare(load_spec(in.workload));
  const auto csv_in = [&](const fs::path& data) { return sweep_files(workload.spec, data).csv; };
  Rows<ScaleRow> out;
  // The reference: a serial run that also warms the file cache and the binary's pages.
  const ScaleRow reference =
      run_mode(in, "serial", binary, scratch.path() / "reference", scratch.path());
  if (reference.exit_code != 0) {
    out.failed = true;
    out.message = "the reference run failed: " + reference.message;
    return out;
  }
  const std::string expected = read_bytes(csv_in(scratch.path() / "reference"));
  for (long long round = 0; round < in.repeats; ++round) {
    for (std::size_t m = 0; m < kModes.size(); ++m) {
      const std::string_view mode = kModes[(m + static_cast<std::size_t>(round)) % kModes.size()];
      const fs::path data = scratch.path() / (std::string(mode) + "-" + std::to_string(round));
      ScaleRow row = run_mode(in, mode, binary, data, scratch.path());
      row.id = p.id;
      row.workload = in.workload_name;
      row.repeat = round;
      row.points = static_cast<long long>(workload.points.size());
      if (row.exit_code == 0) {
        const nlohmann::json side = read_sidecar(sweep_files(workload.spec, data).sidecar);
        row.wall_s = side.value("wall_s", kNaN);
        row.same_bytes = read_bytes(csv_in(data)) == expected ? 1 : 0;
      } else if (row.exit_code != -1 || mpi::available()) {
        out.failed = true;
        out.message = mode == "mpi" ? "the MPI run failed" : "a run failed";
      }
      std::error_code ec;
      fs::remove_all(data, ec);
      out.rows.push_back(std::move(row));
    }
  }
  return out;
}

// ---- coordinator_throughput -------------------------------------------------------------------

struct CoordinatorRow {
  long long id = 0;
  long long points = 0;
  long long ranks = 0;
  long long jobs = 0;
  long long repeat = 0;
  double wall_s = kNaN;
  double coordinator_cpu_s = kNaN;
  long long messages = 0;
  long long remote_points = 0;
  double points_per_s = kNaN;
  double points_per_cpu_s = kNaN;
  double points_per_message = kNaN;
  long long exit_code = 0;
  std::string message;
  static std::vector<Column<CoordinatorRow>> columns() {
    using R = CoordinatorRow;
    return {value("id", &R::id),
            value("points", &R::points),
            value("ranks", &R::ranks),
            value("jobs", &R::jobs),
            value("repeat", &R::repeat),
            timing("wall_s", &R::wall_s),
            timing("coordinator_cpu_s", &R::coordinator_cpu_s),
            value("messages", &R::messages),
            value("remote_points", &R::remote_points),
            timing("points_per_s", &R::points_per_s, "1/s"),
            timing("points_per_cpu_s", &R::points_per_cpu_s, "1/s"),
            value("points_per_message", &R::points_per_message),
            value("exit_code", &R::exit_code),
            value("message", &R::message)};
  }
};

struct CoordinatorInputs {
  long long points = 200000;
  int ranks = 3;
  int jobs = 1;
  long long repeats = 3;
};

CoordinatorInputs read_coordinator(const Point& p) {
  const Reader r(p, "coordinator_throughput", {"points", "ranks", "jobs", "repeats"});
  CoordinatorInputs in;
  in.points = r.integer("points", in.points, 1000, 2'000'000);
  in.ranks = static_cast<int>(r.integer("ranks", in.ranks, 2, 16));
  in.jobs = static_cast<int>(r.integer("jobs", in.jobs, 1, 16));
  in.repeats = r.integer("repeats", in.repeats, 1, 20);
  return in;
}

Rows<CoordinatorRow> run_coordinator(const Point& p) {
  const CoordinatorInputs in = read_coordinator(p);
  Rows<CoordinatorRow> out;
  const auto row_of = [&](long long repeat) {
    CoordinatorRow row;
    row.id = p.id;
    row.points = in.points;
    row.ranks = in.ranks;
    row.jobs = in.jobs;
    row.repeat = repeat;
    return row;
  };
  if (!mpi::available()) {
    for (long long k = 0; k < in.repeats; ++k) {
      CoordinatorRow row = row_of(k);
      row.exit_code = -1;
      row.message = "this build has no MPI";
      out.rows.push_back(row);
    }
    out.failed = true;
    out.message = "this build has no MPI";
    return out;
  }
  const Scratch scratch(p.id);
  const fs::path spec = scratch.path() / "noop.toml";
  {
    std::ofstream file(spec);
    file << "study = \"noop\"\nname = \"noop\"\nkind = \"noop\"\n"
         << "description = \"points that do nothing: the engine's own cost\"\n"
         << "[axes]\ni = { linspace = [0, " << in.points - 1 << "], n = " << in.points << " }\n";
  }
  for (long long k = 0; k < in.repeats; ++k) {
    CoordinatorRow row = row_of(k);
    const fs::path data = scratch.path() / ("data-" + std::to_string(k));
    std::vector<std::string> argv = launcher(in.ranks);
    for (const std::string& a :
         {slipwalk_binary().string(), std::string("sweep"), spec.string(), std::string("--jobs"),
          std::to_string(in.jobs), std::string("--coordinator-jobs"), std::string("0"),
          std::string("--no-timing"), std::string("--data"), data.string()}) {
      argv.push_back(a);
    }
    const Outcome o = run_together({argv}, scratch.path());
    row.exit_code = o.exit_code;
    row.message = o.message;
    if (o.exit_code == 0) {
      const nlohmann::json side = read_sidecar(data / "noop" / "noop.json");
      const nlohmann::json c = side.value("coordinator", nlohmann::json::object());
      row.wall_s = side.value("wall_s", kNaN);
      row.coordinator_cpu_s = c.value("cpu_s", kNaN);
      row.messages = c.value("messages", 0LL);
      row.remote_points = c.value("remote_points", 0LL);
      row.points_per_s = static_cast<double>(in.points) / row.wall_s;
      row.points_per_cpu_s = static_cast<double>(row.remote_points) / row.coordinator_cpu_s;
      row.points_per_message =
          static_cast<double>(row.remote_points) / static_cast<double>(std::max(1LL, row.messages));
    } else {
      out.failed = true;
      out.message = "the MPI run failed";
    }
    std::error_code ec;
    fs::remove_all(data, ec);
    out.rows.push_back(row);
  }
  return out;
}

}  // namespace

std::vector<PointKind> scale_out_kinds() {
  std::vector<PointKind> kinds;
  kinds.push_back(make_point_kind<NoopRow>(
      "noop", "a point that does nothing (one row with its id and i): the engine's own cost",
      Timed::kNo, [](const Point& p) { (void)noop_label(p); },
      [](const Point& p) {
        Rows<NoopRow> out;
        out.rows.push_back({p.id, noop_label(p)});
        return out;
      }));
  kinds.push_back(make_point_kind<ScaleRow>(
      "scale_out",
      "a workload sweep run on 1 thread, R threads, R MPI ranks and R shards (child processes), "
      "in rotated rounds: wall times and whether each CSV equals the serial one",
      Timed::kYes, [](const Point& p) { (void)read_scale(p); }, run_scale));
  kinds.push_back(make_point_kind<CoordinatorRow>(
      "coordinator_throughput",
      "a no-op sweep over MPI ranks with rank 0 only coordinating: the points it hands out and "
      "collects per second of wall time and of its own CPU time",
      Timed::kYes, [](const Point& p) { (void)read_coordinator(p); }, run_coordinator));
  return kinds;
}

}  // namespace slipwalk::sweeps::points
