#include "sweeps/study.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "sweeps/runner.hpp"
#include "sweeps/toml_util.hpp"

namespace slipwalk::sweeps {

namespace {

using core::InputError;

double number(const toml::node& node, const std::string& key, const std::string& path) {
  const auto v = node.value<double>();
  if (!v || !(node.is_integer() || node.is_floating_point()) || !std::isfinite(*v)) {
    throw InputError(origin_of(node.source(), path), key + ": expected a finite number");
  }
  return *v;
}

std::string text(const toml::node& node, const std::string& key, const std::string& path) {
  const auto* s = node.as_string();
  if (s == nullptr) {
    throw InputError(origin_of(node.source(), path), key + ": expected a string");
  }
  return s->get();
}

TraceJob parse_trace(const toml::table& t, const std::string& path) {
  TraceJob job;
  job.origin = origin_of(t.source(), path);
  job.source = nlohmann::json::object();
  std::map<std::string, std::string> where;  // key -> file:line:col
  bool has_force = false;
  bool has_mu = false;
  bool has_alpha = false;
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    where[key] = origin_of(v.source(), path);
    job.source[key] = toml_to_json(v);
    if (key == "name") {
      job.name = text(v, key, path);
    } else if (key == "F") {
      job.params.F = number(v, key, path);
      has_force = true;
    } else if (key == "mu") {
      job.params.mu = number(v, key, path);
      has_mu = true;
    } else if (key == "mu_s") {
      job.params.mu_s = number(v, key, path);
    } else if (key == "m") {
      job.params.m = number(v, key, path);
    } else if (key == "M") {
      job.params.M = number(v, key, path);
    } else if (key == "L_min") {
      job.params.L_min = number(v, key, path);
    } else if (key == "L_max") {
      job.params.L_max = number(v, key, path);
    } else if (key == "g") {
      job.params.g = number(v, key, path);
    } else if (key == "cycles") {
      const auto* i = v.as_integer();
      if (i == nullptr || i->get() < 1 || i->get() > 10000) {
        throw InputError(where[key], "cycles: expected an integer from 1 to 10000");
      }
      job.options.cycles = static_cast<int>(i->get());
    } else if (key == "dt") {
      job.options.sample_dt = number(v, key, path);
      if (!(job.options.sample_dt > 0.0)) {
        throw InputError(where[key], "dt: must be positive");
      }
    } else if (key == "rtol") {
      job.options.rtol = number(v, key, path);
      if (!(job.options.rtol > 0.0 && job.options.rtol < 1.0)) {
        throw InputError(where[key], "rtol: must be in (0, 1)");
      }
    } else if (key == "model") {
      const std::string name = text(v, key, path);
      if (name == "instant") {
        job.params.model = inchworm::SwapModel::kInstant;
      } else if (name == "dm") {
        job.params.model = inchworm::SwapModel::kMass;
      } else {
        throw InputError(where[key],
                         "model: unknown model '" + name + "'; expected \"instant\" or \"dm\"");
      }
    } else if (key == "alpha") {
      job.params.alpha = number(v, key, path);
      has_alpha = true;
    } else if (key == "method") {
      const std::string name = text(v, key, path);
      const auto m = inchworm::parse_method(name);
      if (!m) {
        throw InputError(where[key], "method: unknown method '" + name + "'; expected " +
                                         inchworm::method_names());
      }
      job.method = *m;
    } else {
      throw InputError(origin_of(k.source(), path),
                       "unknown key '" + key +
                           "' in [[trace]]; expected name, F, mu, mu_s, m, M, L_min, L_max, g, "
                           "model, alpha, cycles, dt, method, rtol");
    }
  }
  if (job.name.empty() || !has_force || !has_mu) {
    throw InputError(job.origin, "a [[trace]] needs name, F and mu");
  }
  const bool plain =
      job.name.front() != '.' && std::all_of(job.name.begin(), job.name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain) {
    throw InputError(where["name"], "name: '" + job.name + "' is not a plain file name");
  }
  if (has_alpha && job.params.model != inchworm::SwapModel::kMass) {
    throw InputError(where["alpha"],
                     "alpha: only used with model = \"dm\" (the instant swap has no swap force)");
  }
  try {
    inchworm::validate(job.params);
  } catch (const InputError& e) {
    const std::string_view mapped = inchworm::param_key_of_option(e.where());
    const std::string key = mapped.empty() ? "F" : std::string(mapped);
    const std::string what = e.what();
    throw InputError(where.count(key) ? where[key] : job.origin,
                     key + ": " + what.substr(std::min(what.size(), e.where().size() + 2)));
  }
  return job;
}

}  // namespace

Study load_study(const std::filesystem::path& dir) {
  Study study;
  study.dir = dir;
  study.id = dir.filename().string();
  if (study.id.empty()) {
    study.id = dir.parent_path().filename().string();
  }
  const std::filesystem::path file = dir / "study.toml";
  const std::string path = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw InputError(path, "cannot read the study file");
  }
  std::ostringstream content;
  content << in.rdbuf();
  toml::table doc;
  try {
    doc = toml::parse(content.str(), path);
  } catch (const toml::parse_error& e) {
    throw InputError(origin_of(e.source(), path), std::string(e.description()));
  }
  for (auto&& [k, v] : doc) {
    if (k == "title") {
      study.title = text(v, "title", path);
    } else if (k == "sweeps") {
      const auto* a = v.as_array();
      if (a == nullptr) {
        throw InputError(origin_of(v.source(), path), "sweeps: expected a list of spec files");
      }
      for (const auto& s : *a) {
        const std::filesystem::path spec = dir / text(s, "sweeps", path);
        if (!std::filesystem::is_regular_file(spec)) {
          throw InputError(origin_of(s.source(), path), "sweeps: no spec file " + spec.string());
        }
        study.sweeps.push_back(spec);
      }
    } else if (k == "trace") {
      const auto* a = v.as_array();
      if (a == nullptr || !a->is_array_of_tables()) {
        throw InputError(origin_of(v.source(), path), "trace: expected [[trace]] tables");
      }
      for (const auto& t : *a) {
        study.traces.push_back(parse_trace(*t.as_table(), path));
      }
    } else {
      throw InputError(origin_of(k.source(), path),
                       "unknown key '" + std::string(k.str()) + "'; expected title, sweeps, trace");
    }
  }
  return study;
}

std::vector<std::filesystem::path> find_studies(const std::filesystem::path& studies_dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(studies_dir, ec)) {
    if (entry.is_directory() && std::filesystem::is_regular_file(entry.path() / "study.toml")) {
      out.push_back(entry.path());
    }
  }
  if (ec) {
    throw InputError(studies_dir.string(), "cannot list the studies: " + ec.message());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::filesystem::path write_trace_job(const Study& study, const TraceJob& job,
                                      const std::filesystem::path& data_dir) {
  const auto start = std::chrono::steady_clock::now();
  std::filesystem::path csv = data_dir / study.id / (job.name + ".csv");
  {
    core::AtomicFile file(csv);
    inchworm::write_trace(job.params, job.method, job.options, file.stream());
    file.commit();
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  std::filesystem::path json = csv;
  json.replace_extension(".json");
  core::write_file_atomically(json, sidecar.dump(1) + "\n");
  return csv;
}

}  // namespace slipwalk::sweeps
