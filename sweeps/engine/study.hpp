#pragma once
// A study (studies/<id>/study.toml, sweeps/README.md): a title, time-series traces of the
// inchworm, scene runs (trajectories of walking robots) and sweep specs in the same folder.
// Their runs are the jobs of job.hpp; the pipeline of reproduce.hpp runs them all.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "inchworm/params.hpp"
#include "inchworm/trace.hpp"
#include "inchworm/vss.hpp"
#include "scene/scene.hpp"
#include "sweeps/engine/spec.hpp"

namespace slipwalk::sweeps {

struct TraceJob {
  std::string name;  ///< output stem: <data>/<study>/<name>.csv
  inchworm::Params params;
  inchworm::Method method = inchworm::Method::kAnalytic;
  inchworm::TraceOptions options;
  std::string origin;     ///< file:line:col of its [[trace]] table
  nlohmann::json source;  ///< the table as JSON (sidecar)
};

/// A [[scene]] entry: a scene file (relative to the study folder) run into <name>.csv, with
/// optional overrides of its friction law, filter, duration and dt (one scene file serves
/// several runs: both laws, filter on and off).
struct SceneJob {
  std::string name;                      ///< output stem: <data>/<study>/<name>.csv
  scene::Scene scene;                    ///< the file with the overrides applied
  std::optional<double> quick_duration;  ///< s, the duration under reproduce --quick
  std::string origin;                    ///< file:line:col of its [[scene]] table
  nlohmann::json source;                 ///< the table as JSON (sidecar)
};

struct Study {
  std::string id;  ///< the folder name, also the data folder of its traces
  std::filesystem::path dir;
  std::string title;
  std::vector<TraceJob> traces;
  std::vector<SceneJob> scenes;
  std::vector<std::filesystem::path> sweeps;  ///< spec files, in the order listed
};

/// Reads <dir>/study.toml. Throws core::InputError (file:line:col) for a malformed file, an
/// unknown key, invalid trace parameters or a sweep spec file that does not exist.
[[nodiscard]] Study load_study(const std::filesystem::path& dir);

/// The study folders under `studies_dir` (those holding a study.toml), sorted by name.
[[nodiscard]] std::vector<std::filesystem::path> find_studies(
    const std::filesystem::path& studies_dir);

/// The scene a [[scene]] entry runs: its scene, under `quick` with its quick_duration (when
/// given).
[[nodiscard]] scene::Scene scene_of(const SceneJob& job, bool quick);

}  // namespace slipwalk::sweeps
