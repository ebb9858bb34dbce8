// The scene reader: the whole file is checked before anything runs (scene.hpp has the format).
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/toml_input.hpp"
#include "scene/effects.hpp"
#include "scene/friction_laws.hpp"
#include "scene/ranges.hpp"
#include "scene/run_writer.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

namespace {

using core::InputError;

/// Every table a scene may hold and the keys each may hold (toml_reader.hpp uses it to suggest);
/// the keys of [robot], [gait] and [friction] are those of the gait and law tables.
const std::vector<TableSchema>& schema() {
  static const std::vector<TableSchema> tables = {
      {"robot", robot_table_keys()},
      {"gait", gait_table_keys()},
      {"run", {"duration", "dt", "steps"}},
      {"friction", friction_table_keys()},
      {"filter", {"gamma"}},
      {"residual", {"file"}},
      {"noise", {"sigma", "sigma_theta", "seed"}},
      {"terrain", {"kind", "angle_deg", "heading_deg", "com_height", "tread", "riser"}},
  };
  return tables;
}

const TableSchema& schema_of(std::string_view name) { return schema_table(schema(), name); }

/// The table `name`, or nullptr when the file has none.
const toml::table* table_of(const toml::table& doc, std::string_view name) {
  const toml::node* node = doc.get(name);
  return node == nullptr ? nullptr : node->as_table();
}

const toml::table& required_table(const toml::table& doc, std::string_view name,
                                  const std::string& path) {
  const toml::table* t = table_of(doc, name);
  if (t == nullptr) {
    std::string what = "missing required table [";
    what.append(name).append("]");
    throw InputError(origin_of(doc.source(), path), what);
  }
  return *t;
}

/// The robot factories check their options (robots/check.hpp); an InputError of theirs names the
/// option as "<factory>.<option>", which is re-raised at that key in the file.
void check_with_factory(const Gait& g, const TableReader& robot, const TableReader& gait) {
  try {
    (void)make_walker(g);
  } catch (const InputError& e) {
    const std::string& where = e.where();
    const std::string option = where.substr(where.rfind('.') + 1);
    std::string what = e.what();
    if (what.rfind(where + ": ", 0) == 0) {
      what.erase(0, where.size() + 2);
    }
    for (const TableReader* table : {&gait, &robot}) {
      if (const toml::node* n = table->find(option)) {
        table->check(false, *n, option, what);
      }
    }
    throw InputError(gait.origin(), e.what());
  }
}

void read_run(const TableReader& run, Scene& scene) {
  const toml::node& duration = run.required("duration");
  scene.duration = run.number_in(duration, "duration", ranges::kDuration);
  const toml::node* dt = run.find("dt");
  const toml::node* steps = run.find("steps");
  if (dt != nullptr && steps != nullptr) {
    run.check(false, *steps, "steps", "give dt or steps, not both");
  }
  if (dt == nullptr && steps == nullptr) {
    throw InputError(run.origin(), "missing required key 'dt' (or 'steps') in [run]");
  }
  if (steps != nullptr) {
    scene.steps = run.integer(*steps, "steps");
    run.check(
        scene.steps >= 1 && scene.steps <= kMaxSteps, *steps, "steps",
        "must be from 1 to " + std::to_string(kMaxSteps) + ", got " + std::to_string(scene.steps));
    scene.dt = scene.duration / static_cast<double>(scene.steps);
    scene.run_origin = run.origin(*steps);
    scene.run_key = "run.steps";
    return;
  }
  scene.dt = run.number_in(*dt, "dt", ranges::kStep);
  // The frames are t_n = n·dt, n = 0 … steps, and the last one is the duration: the duration
  // must be a whole number of steps (to rounding).
  const double ratio = scene.duration / scene.dt;
  run.check(ratio <= static_cast<double>(kMaxSteps), *dt, "dt",
            "duration / dt = " + core::format_double(ratio) + " steps; at most " +
                std::to_string(kMaxSteps));
  const double whole = std::round(ratio);
  run.check(whole >= 1.0 && std::abs(ratio - whole) <= 1e-9 * whole, *dt, "dt",
            "the duration must be a whole number of steps, got duration / dt = " +
                core::format_double(ratio));
  scene.steps = static_cast<long long>(whole);
  scene.run_origin = run.origin(*dt);
  scene.run_key = "run.dt";
}

/// [terrain] (§5.2): kind = "flat" | "slope" | "stairs" and that kind's parameters only.
terrain::Terrain read_terrain(const TableReader& t) {
  const std::string kind = t.choice(t.required("kind"), "kind", {"flat", "slope", "stairs"});
  const std::string chosen = "kind = '" + kind + "'";
  if (kind != "slope") {
    t.forbid("angle_deg", "the slope", chosen);
    t.forbid("com_height", "the slope", chosen);
  }
  if (kind != "stairs") {
    t.forbid("tread", "the stairs", chosen);
    t.forbid("riser", "the stairs", chosen);
  }
  if (kind == "flat") {
    t.forbid("heading_deg", "the slope and the stairs", chosen);
    return terrain::Flat{};
  }
  constexpr double kDeg = std::numbers::pi / 180.0;
  double heading_deg = 0.0;
  t.read_in("heading_deg", ranges::kHeading, heading_deg);
  if (kind == "slope") {
    terrain::Slope slope;
    slope.angle = t.number_in(t.required("angle_deg"), "angle_deg", ranges::kSlopeAngle) * kDeg;
    slope.heading = heading_deg * kDeg;
    t.read_in("com_height", ranges::kLengthOrZero, slope.com_height);
    return slope;
  }
  terrain::Stairs stairs;
  stairs.heading = heading_deg * kDeg;
  stairs.tread = t.number_in(t.required("tread"), "tread", ranges::kLength);
  stairs.riser = t.number_in(t.required("riser"), "riser", ranges::kLengthOrZero);
  return stairs;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& path) {
  const toml::table doc = core::parse_toml(text, path);
  check_top_level(doc, path, schema());
  const std::vector<TableSchema>& all = schema();
  Scene scene;
  scene.path = path;

  // [robot]: which walker; its legs and radius where it has them.
  const TableReader robot(required_table(doc, "robot", path), schema_of("robot"), path, all);
  scene.robot = robot.choice(robot.required("name"), "name", robot_names());
  forbid_other_robot_keys(robot, scene.robot);

  // [gait]: the gait of that robot and its parameters.
  const TableReader gait(required_table(doc, "gait", path), schema_of("gait"), path, all);
  scene.gait_origin = gait.origin();
  scene.gait = read_gait(robot, gait, scene.robot, path, all);
  check_with_factory(scene.gait, robot, gait);

  // [run] and the effects.
  read_run(TableReader(required_table(doc, "run", path), schema_of("run"), path, all), scene);
  const robots::Walker walker = make_walker(scene.gait);
  const int legs = walker.legs();
  scene.friction = read_friction(
      TableReader(required_table(doc, "friction", path), schema_of("friction"), path, all), legs);
  if (const toml::table* t = table_of(doc, "filter")) {
    const TableReader filter(*t, schema_of("filter"), path, all);
    FilterEffect effect;
    filter.read_in("gamma", ranges::kFilterGamma, effect.gamma);
    scene.filter = effect;
  }
  if (const toml::table* t = table_of(doc, "residual")) {
    scene.residual = read_residual(TableReader(*t, schema_of("residual"), path, all), path, legs);
  }
  if (const toml::table* t = table_of(doc, "noise")) {
    scene.noise = read_noise(TableReader(*t, schema_of("noise"), path, all));
  }
  if (const toml::table* t = table_of(doc, "terrain")) {
    scene.terrain = read_terrain(TableReader(*t, schema_of("terrain"), path, all));
  }
  // The CSV's size, known now: refused here, at dt or steps, before anything runs.
  check_run_size(scene, walker);
  return scene;
}

Scene read_scene(const std::filesystem::path& path) {
  return parse_scene(core::read_input_file(path, "a scene file"), path.string());
}

nlohmann::json to_json(const Scene& scene) {
  nlohmann::json out = {
      {"file", scene.path},
      {"robot", scene.robot},
      {"gait", gait_json(scene.gait)},
      {"run", {{"duration", scene.duration}, {"dt", scene.dt}, {"steps", scene.steps}}},
      {"friction", friction_json(scene.friction)},
  };
  if (scene.filter) {
    out["filter"] = {{"gamma", scene.filter->gamma}};
  }
  if (scene.residual) {
    out["residual"] = {{"file", scene.residual->file}};
  }
  if (scene.noise) {
    out["noise"] = {{"sigma", scene.noise->sigma},
                    {"sigma_theta", scene.noise->sigma_theta},
                    {"seed", scene.noise->seed}};
  }
  constexpr double kDeg = 180.0 / std::numbers::pi;
  if (const auto* slope = std::get_if<terrain::Slope>(&scene.terrain)) {
    out["terrain"] = {{"kind", "slope"},
                      {"angle_deg", slope->angle * kDeg},
                      {"heading_deg", slope->heading * kDeg},
                      {"com_height", slope->com_height}};
  } else if (const auto* stairs = std::get_if<terrain::Stairs>(&scene.terrain)) {
    out["terrain"] = {{"kind", "stairs"},
                      {"tread", stairs->tread},
                      {"riser", stairs->riser},
                      {"heading_deg", stairs->heading * kDeg}};
  }
  return out;
}

}  // namespace slipwalk::scene
