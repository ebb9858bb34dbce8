#include "sweeps/engine/study.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/toml_input.hpp"
#include "scene/friction_laws.hpp"
#include "scene/ranges.hpp"
#include "scene/run_writer.hpp"
#include "sweeps/engine/toml_util.hpp"

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

void check_plain_name(const std::string& name, const std::string& where) {
  const bool plain =
      !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain) {
    throw InputError(where, "name: '" + name + "' is not a plain file name");
  }
}

/// steps = duration / dt, which must be a whole number (the frames end at the duration).
long long whole_steps(double duration, double dt, const std::string& where,
                      const std::string& key) {
  const double ratio = duration / dt;
  const double n = std::round(ratio);
  if (!(n >= 1.0 && n <= static_cast<double>(scene::kMaxSteps)) ||
      std::abs(ratio - n) > 1e-9 * ratio) {
    std::string what = key;
    what.append(": duration / dt = ")
        .append(core::format_double(ratio))
        .append(" must be a whole number of steps from 1 to ")
        .append(std::to_string(scene::kMaxSteps));
    throw InputError(where, what);
  }
  return static_cast<long long>(n);
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
  check_plain_name(job.name, where["name"]);
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

SceneJob parse_scene_entry(const toml::table& t, const std::filesystem::path& dir,
                           const std::string& path) {
  SceneJob job;
  job.origin = origin_of(t.source(), path);
  job.source = nlohmann::json::object();
  std::map<std::string, std::string> where;  // key -> file:line:col
  std::map<std::string, const toml::node*> nodes;
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    static const std::array<const char*, 8> kKeys = {"name",  "file",     "law", "filter",
                                                     "gamma", "duration", "dt",  "quick_duration"};
    if (std::find_if(kKeys.begin(), kKeys.end(), [&](const char* c) { return key == c; }) ==
        kKeys.end()) {
      throw InputError(origin_of(k.source(), path),
                       "unknown key '" + key +
                           "' in [[scene]]; expected name, file, law, filter, gamma, duration, "
                           "dt, quick_duration");
    }
    where[key] = origin_of(v.source(), path);
    nodes[key] = &v;
    job.source[key] = toml_to_json(v);
  }
  if (!nodes.count("name") || !nodes.count("file")) {
    throw InputError(job.origin, "a [[scene]] needs name and file");
  }
  job.name = text(*nodes["name"], "name", path);
  check_plain_name(job.name, where["name"]);
  const std::filesystem::path file = dir / text(*nodes["file"], "file", path);
  if (!std::filesystem::is_regular_file(file)) {
    throw InputError(where["file"],
                     "file: " + file.string() +
                         (std::filesystem::is_directory(file) ? " is a folder, not a scene file"
                                                              : ": no such scene file"));
  }
  job.scene = scene::read_scene(file);  // errors name the scene file's line and column

  // Overrides: one scene file serves both friction laws, filter on and off, shorter runs.
  scene::Scene& sc = job.scene;
  if (nodes.count("law")) {
    const std::string law = text(*nodes["law"], "law", path);
    // The isotropic laws of the scene format's table: those an override may switch between.
    std::vector<std::string_view> names;
    for (const scene::FrictionLawEntry& entry : scene::friction_laws()) {
      if (!entry.anisotropic) {
        names.push_back(entry.name);
      }
    }
    const scene::FrictionLawEntry* entry = scene::find_friction_law(law);
    if (entry == nullptr || entry->anisotropic) {
      std::string message = "law: unknown law '";
      message.append(law).append("'; expected ");
      for (std::size_t i = 0; i < names.size(); ++i) {
        message.append(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ");
        message.append("\"").append(names[i]).append("\"");
      }
      throw InputError(where["law"], message);
    }
    // The scene's w stays (as if its file named this law), so the law must take it: an
    // anisotropic scene may switch to Coulomb with the same ellipses, not to isotropic viscous.
    if (sc.friction.w.cols() > 0 &&
        std::find(entry->keys.begin(), entry->keys.end(), "w") == entry->keys.end()) {
      throw InputError(where["law"], "law: the scene gives w (anisotropy), which the law '" + law +
                                         "' does not take");
    }
    sc.friction.law = entry->law;
    sc.friction.anisotropic = entry->anisotropic;
  }
  if (nodes.count("filter")) {
    const auto* on = nodes["filter"]->as_boolean();
    if (on == nullptr) {
      throw InputError(where["filter"], "filter: expected true or false");
    }
    if (!on->get()) {
      if (nodes.count("gamma")) {
        throw InputError(where["gamma"], "gamma: only used with the filter on");
      }
      sc.filter.reset();
    } else if (!sc.filter) {
      sc.filter = scene::FilterEffect{};
    }
  }
  // The overrides take the scene format's ranges (scene/ranges.hpp).
  const auto in_range = [&](const char* key, const core::Range& range) {
    const toml::node& node = *nodes[key];
    const auto parsed = node.value<double>();
    if (!parsed || !(node.is_integer() || node.is_floating_point())) {
      throw InputError(where[key], std::string(key) + ": expected a number");
    }
    const double value = *parsed;
    if (!range.contains(value)) {
      throw InputError(where[key], std::string(key) + ": must be in " + range.describe() +
                                       ", got " + core::format_double(value));
    }
    return value;
  };
  if (nodes.count("gamma")) {
    sc.filter = scene::FilterEffect{in_range("gamma", scene::ranges::kFilterGamma)};
  }
  if (nodes.count("duration")) {
    sc.duration = in_range("duration", scene::ranges::kDuration);
  }
  if (nodes.count("dt")) {
    sc.dt = in_range("dt", scene::ranges::kStep);
  }
  if (nodes.count("duration") || nodes.count("dt")) {
    const std::string key = nodes.count("dt") ? "dt" : "duration";
    sc.steps = whole_steps(sc.duration, sc.dt, where[key], key);
    // The CSV's size is bounded as in the scene file, now at the override.
    sc.run_origin = where[key];
    sc.run_key = key;
    scene::check_run_size(sc, scene::make_walker(sc.gait));
  }
  if (nodes.count("quick_duration")) {
    job.quick_duration = in_range("quick_duration", scene::ranges::kDuration);
    (void)whole_steps(*job.quick_duration, sc.dt, where["quick_duration"], "quick_duration");
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
  const std::string content = core::read_input_file(file, "a study file");
  const toml::table doc = core::parse_toml(content, path);
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
          throw InputError(origin_of(s.source(), path), "sweeps: " + spec.string() +
                                                            (std::filesystem::is_directory(spec)
                                                                 ? " is a folder, not a spec file"
                                                                 : ": no such spec file"));
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
    } else if (k == "scene") {
      const auto* a = v.as_array();
      if (a == nullptr || !a->is_array_of_tables()) {
        throw InputError(origin_of(v.source(), path), "scene: expected [[scene]] tables");
      }
      for (const auto& t : *a) {
        study.scenes.push_back(parse_scene_entry(*t.as_table(), dir, path));
      }
    } else {
      throw InputError(origin_of(k.source(), path), "unknown key '" + std::string(k.str()) +
                                                        "'; expected title, sweeps, trace, scene");
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

scene::Scene scene_of(const SceneJob& job, bool quick) {
  scene::Scene sc = job.scene;
  if (quick && job.quick_duration) {
    sc.duration = *job.quick_duration;
    sc.steps = whole_steps(sc.duration, sc.dt, job.origin, "quick_duration");
  }
  return sc;
}

}  // namespace slipwalk::sweeps
