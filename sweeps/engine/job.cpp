#include "sweeps/engine/job.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"
#include "core/provenance.hpp"
#include "inchworm/trace_file.hpp"
#include "scene/run_writer.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

fs::path sidecar_of(fs::path csv) { return csv.replace_extension(".json"); }

/// The sidecar of a finished job written by this build, or null (none, unreadable, another
/// build): what `keep_finished` compares against the job's inputs.
nlohmann::json finished_sidecar(const fs::path& csv) {
  const fs::path json = sidecar_of(csv);
  if (!fs::is_regular_file(csv) || !fs::is_regular_file(json)) {
    return nullptr;
  }
  nlohmann::json sidecar;
  try {
    sidecar = core::parse_json(core::read_json_text(json), json.string());
  } catch (const core::InputError&) {  // a sidecar we cannot trust: the job runs again
    return nullptr;
  }
  const nlohmann::json build = core::build_provenance();
  if (!sidecar.is_object() || !sidecar.contains("provenance") ||
      sidecar["provenance"].value("git_commit", "") != build.value("git_commit", "") ||
      sidecar["provenance"].value("slipwalk_version", "") != build.value("slipwalk_version", "")) {
    return nullptr;
  }
  return sidecar;
}

/// The CSV a study entry writes.
fs::path csv_of(const JobContext& context, const Study& study, const std::string& name) {
  return context.sweep.data_dir / study.id / (name + ".csv");
}

/// A job's summary with its identity set: `points` points, none failed, resumed or timed.
JobSummary summary_of(std::string study, std::string name, const char* kind, fs::path csv,
                      long long points) {
  JobSummary s;
  s.study = std::move(study);
  s.name = std::move(name);
  s.kind = kind;
  s.csv = std::move(csv);
  s.points = points;
  return s;
}

/// A summary for a job kept from an earlier run.
JobSummary kept(std::string study, std::string name, const char* kind, fs::path csv,
                long long points, long long failed) {
  JobSummary s = summary_of(std::move(study), std::move(name), kind, std::move(csv), points);
  s.failed = failed;
  s.resumed = points;
  return s;
}

/// The sidecar of a study entry's finished output when it was written for the same entry (its
/// kind and its [[trace]] / [[scene]] table); null otherwise.
nlohmann::json finished_entry(const JobContext& context, const Study& study,
                              const std::string& name, const char* sidecar_kind,
                              const nlohmann::json& source) {
  nlohmann::json side = finished_sidecar(csv_of(context, study, name));
  if (side.is_null() || side.value("kind", "") != sidecar_kind ||
      side.value("spec", nlohmann::json()) != source) {
    return nullptr;
  }
  return side;
}

JobSummary run_kind(const TraceRun& run, const JobContext& context) {
  const Study& study = *run.study;
  const TraceJob& job = *run.job;
  if (context.keep_finished &&
      !finished_entry(context, study, job.name, "inchworm_trace", job.source).is_null()) {
    return kept(study.id, job.name, "trace", csv_of(context, study, job.name), 1, 0);
  }
  return write_trace_job(study, job, context.sweep.data_dir);
}

JobSummary run_kind(const SceneRun& run, const JobContext& context) {
  const Study& study = *run.study;
  const SceneJob& job = *run.job;
  if (context.keep_finished) {
    const nlohmann::json side = finished_entry(context, study, job.name, "scene_run", job.source);
    if (!side.is_null() && side.value("quick", !context.quick) == context.quick &&
        side.value("scene", nlohmann::json()) == scene::to_json(scene_of(job, context.quick))) {
      return kept(study.id, job.name, "scene", csv_of(context, study, job.name), 1, 0);
    }
  }
  return write_scene_job(study, job, context.sweep.data_dir, context.quick);
}

JobSummary run_kind(const SweepRun& run, const JobContext& context) {
  const PreparedSweep& sweep = *run.sweep;
  if (context.keep_finished) {
    const fs::path csv = csv_path(sweep.spec, context.sweep.data_dir);
    const nlohmann::json side = finished_sidecar(csv);
    nlohmann::json points = nlohmann::json::array();
    for (const Point& p : sweep.points) {
      points.push_back(p.to_json());
    }
    if (!side.is_null() && side.value("kind", "") == sweep.spec.kind &&
        side.value("quick", !sweep.spec.quick()) == sweep.spec.quick() &&
        side.value("variant", std::string()) == variant_name(sweep.spec.variant) &&
        side.value("columns", nlohmann::json()) == nlohmann::json(sweep.kind->column_names()) &&
        side.value("points", nlohmann::json()) == points) {
      JobSummary k =
          kept(sweep.spec.study, sweep.spec.name, "sweep", csv,
               static_cast<long long>(sweep.points.size()), side.value("failed_point_count", 0LL));
      k.point_kind = sweep.spec.kind;
      k.at_budget = side.value("budget_point_count", 0LL);
      return k;
    }
  }
  const auto start = Clock::now();
  const RunSummary s = sweeps::run(sweep, context.sweep);
  JobSummary done = summary_of(sweep.spec.study, sweep.spec.name, "sweep", s.csv, s.points);
  done.failed = s.failed;
  done.resumed = s.resumed;
  done.seconds = seconds_since(start);
  done.point_kind = sweep.spec.kind;
  done.at_budget = s.at_budget;
  return done;
}

}  // namespace

std::string JobSummary::line() const {
  std::string out = "  " + kind + " " + name;
  if (kind == "sweep") {
    out += ": " + std::to_string(points) + " points (" + std::to_string(failed) + " failed, ";
    if (at_budget > 0) {
      out += std::to_string(at_budget) + " at their budget, ";
    }
    out += std::to_string(resumed) + " resumed)";
  }
  return out + " -> " + csv.string() + " (" + seconds_text(seconds) + ")";
}

JobSummary run_job(const Job& job, const JobContext& context) {
  return std::visit([&](const auto& kind) { return run_kind(kind, context); }, job);
}

JobSummary write_trace_job(const Study& study, const TraceJob& job, const fs::path& data_dir) {
  const auto start = Clock::now();
  const fs::path csv = data_dir / study.id / (job.name + ".csv");
  inchworm::write_trace_file(job.params, job.method, job.options, csv);
  const double wall_s = seconds_since(start);
  const inchworm::Params& p = job.params;
  const nlohmann::json sidecar = {
      {"study", study.id},
      {"name", job.name},
      {"kind", "inchworm_trace"},
      {"spec_file", (study.dir / "study.toml").string()},
      {"spec", job.source},
      {"params",
       {{"m", p.m},
        {"M", p.M},
        {"L_min", p.L_min},
        {"L_max", p.L_max},
        {"g", p.g},
        {"mu", p.mu},
        {"mu_s", p.static_mu()},
        {"F", p.F},
        {"model", p.model == inchworm::SwapModel::kMass ? "dm" : "instant"},
        {"alpha", p.model == inchworm::SwapModel::kMass ? nlohmann::json(p.alpha)
                                                        : nlohmann::json(nullptr)}}},
      {"method", inchworm::method_name(job.method)},
      {"cycles", job.options.cycles},
      {"dt", job.options.sample_dt},
      {"rtol", job.options.rtol},
      {"csv", csv.filename().string()},
      {"threads", 1},
      {"wall_s", wall_s},
      {"date", utc_now()},
      {"provenance", core::build_provenance()},
  };
  core::write_file_atomically(sidecar_of(csv), sidecar.dump(1) + "\n");
  JobSummary done = summary_of(study.id, job.name, "trace", csv, 1);
  done.seconds = seconds_since(start);
  return done;
}

JobSummary write_scene_job(const Study& study, const SceneJob& job, const fs::path& data_dir,
                           bool quick) {
  const auto start = Clock::now();
  const scene::Scene sc = scene_of(job, quick);
  const scene::Simulator sim = scene::compose(sc);
  const fs::path csv = data_dir / study.id / (job.name + ".csv");
  const nlohmann::json extra = {
      {"study", study.id},   {"name", job.name},
      {"kind", "scene_run"}, {"spec_file", (study.dir / "study.toml").string()},
      {"spec", job.source},  {"quick", quick},
      {"date", utc_now()},
  };
  const scene::RunResult result = scene::write_run(sc, sim, csv, extra, nullptr);
  JobSummary summary = summary_of(study.id, job.name, "scene", csv, 1);
  const connection::TrajectorySummary& s = result.summary;
  if (!s.message.empty()) {
    summary.warning = study.id + "/" + job.name + ": " + std::to_string(s.unsupported) +
                      " unsupported and " + std::to_string(s.not_converged) +
                      " unconverged frames; first at " + s.message;
  }
  summary.seconds = seconds_since(start);
  return summary;
}

}  // namespace slipwalk::sweeps
