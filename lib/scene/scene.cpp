// The scene reader: the whole file is checked before anything runs (scene.hpp has the format).
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "scene/effects.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

namespace {

using core::InputError;

/// Every table a scene may hold and the keys each may hold (toml_reader.hpp uses it to suggest).
const std::vector<TableSchema>& schema() {
  static const std::vector<TableSchema> tables = {
      {"robot", {"name", "legs", "radius", "stiffness", "mass", "leg"}},
      {"gait",
       {"kind", "frequency", "steer", "duty", "sweep", "dphi", "roll_amplitude", "yaw_amplitude",
        "stride", "swing_height", "height", "lift"}},
      {"run", {"duration", "dt", "steps"}},
      {"friction", {"law", "tol", "max_iterations", "w"}},
      {"filter", {"gamma"}},
      {"residual", {"file"}},
      {"noise", {"sigma", "sigma_theta", "seed"}},
      {"terrain", {"kind", "angle_deg", "heading_deg", "com_height", "tread", "riser"}},
  };
  return tables;
}

const TableSchema& schema_of(std::string_view name) {
  for (const TableSchema& t : schema()) {
    if (t.name == name) {
      return t;
    }
  }
  throw std::logic_error("scene: no schema for a table");
}

/// The top level holds tables only, each named in the schema; a key of a table written at the top
/// level is pointed to its table.
void check_top_level(const toml::table& doc, const std::string& path) {
  std::vector<std::string_view> names;
  for (const TableSchema& t : schema()) {
    names.push_back(t.name);
  }
  for (auto&& [k, v] : doc) {
    const std::string_view key = k.str();
    const bool known = std::find(names.begin(), names.end(), key) != names.end();
    if (known && v.is_table()) {
      continue;
    }
    std::string what;
    if (known) {
      what.append("expected a table [").append(key).append("], got ").append(type_name(v));
    } else if (v.is_table()) {
      what.append("unknown table [").append(key).append("]");
      if (const std::string_view guess = nearest(key, names); !guess.empty()) {
        what.append("; did you mean [").append(guess).append("]?");
      }
    } else {
      what.append("unknown key '").append(key).append("' at the top level");
      for (const TableSchema& t : schema()) {
        if (std::find(t.keys.begin(), t.keys.end(), key) != t.keys.end()) {
          what.append("; it belongs in [").append(t.name).append("]");
          break;
        }
      }
    }
    what.append(" (tables: ");
    for (std::size_t i = 0; i < names.size(); ++i) {
      what.append(i == 0 ? "" : ", ").append(names[i]);
    }
    what.append(")");
    throw InputError(origin_of(k.source(), path), what);
  }
}

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

/// The gaits each robot walks with; the first is listed first in messages.
std::vector<std::string_view> gaits_of(std::string_view robot) {
  if (robot == "bigant") {
    return {"tripod", "metachronal"};
  }
  if (robot == "multipod") {
    return {"undulation"};
  }
  if (robot == "quadruped") {
    return {"trot"};
  }
  if (robot == "legs") {
    return {"foot_path"};
  }
  return {"disk"};
}

/// The [gait] keys that belong to some gaits only (kind and frequency belong to all).
struct GaitKey {
  std::string_view key;
  std::vector<std::string_view> kinds;  ///< the gaits that have it
  std::string_view owner;               ///< for messages: "the tripod and trot gaits"
};

const std::vector<GaitKey>& gait_keys() {
  static const std::vector<GaitKey> keys = {
      {"steer", {"tripod"}, "the tripod gait"},
      {"duty", {"tripod", "trot"}, "the tripod and trot gaits"},
      {"sweep", {"tripod", "metachronal"}, "the tripod and metachronal gaits"},
      {"dphi", {"undulation"}, "the undulation gait"},
      {"roll_amplitude", {"undulation"}, "the undulation gait"},
      {"yaw_amplitude", {"undulation"}, "the undulation gait"},
      {"stride", {"trot", "foot_path"}, "the trot and foot_path gaits"},
      {"height", {"foot_path"}, "the foot_path gait"},
      {"lift", {"foot_path"}, "the foot_path gait"},
      {"swing_height", {"trot"}, "the trot gait"},
  };
  return keys;
}

/// Reads `key` into `value` if the table has it (a finite number); ranges are checked here for the
/// options every gait shares and by the robot factories for the rest (check_with_factory).
void read_number(const TableReader& table, std::string_view key, double& value) {
  if (const toml::node* n = table.find(key)) {
    value = table.number(*n, key);
  }
}

void read_frequency(const TableReader& gait, double& value) {
  read_number(gait, "frequency", value);
  if (const toml::node* n = gait.find("frequency")) {
    gait.check(value > 0.0, *n, "frequency", "must be > 0 Hz, got " + core::format_double(value));
  }
}

int read_legs(const TableReader& robot, int value, long long lo, long long hi, bool even) {
  if (const toml::node* n = robot.find("legs")) {
    const long long legs = robot.integer(*n, "legs");
    const bool ok = legs >= lo && legs <= hi && (!even || legs % 2 == 0);
    robot.check(ok, *n, "legs",
                (even ? "the multipod has 6, 8, 10 or 12 legs, got "
                      : "the disk robot has 3 to 1000 legs, got ") +
                    std::to_string(legs));
    return static_cast<int>(legs);
  }
  return value;
}

Gait read_gait(const TableReader& robot, const TableReader& gait, const std::string& robot_name,
               const std::string& path) {
  const std::string kind = gait.choice(gait.required("kind"), "kind", gaits_of(robot_name));
  std::string chosen = "kind = '";
  chosen.append(kind).append("'");
  for (const GaitKey& k : gait_keys()) {
    if (std::find(k.kinds.begin(), k.kinds.end(), kind) == k.kinds.end()) {
      gait.forbid(k.key, k.owner, chosen);
    }
  }
  if (kind == "foot_path") {
    return read_leg_table(robot, gait, path, schema());
  }
  if (kind == "tripod") {
    robots::TripodGait g;
    read_frequency(gait, g.frequency);
    read_number(gait, "steer", g.steer);
    if (const toml::node* n = gait.find("steer")) {
      gait.check(std::abs(g.steer) <= 1.0, *n, "steer",
                 "must be in [-1, 1], got " + core::format_double(g.steer));
    }
    read_number(gait, "duty", g.duty);
    read_number(gait, "sweep", g.sweep);
    return g;
  }
  if (kind == "metachronal") {
    robots::MetachronalGait g;
    read_frequency(gait, g.frequency);
    read_number(gait, "sweep", g.sweep);
    return g;
  }
  if (kind == "undulation") {
    robots::UndulationGait g;
    read_frequency(gait, g.frequency);
    read_number(gait, "dphi", g.dphi);
    read_number(gait, "roll_amplitude", g.roll_amplitude);
    read_number(gait, "yaw_amplitude", g.yaw_amplitude);
    g.legs = read_legs(robot, g.legs, 6, 12, true);
    read_number(robot, "stiffness", g.stiffness);
    return g;
  }
  if (kind == "trot") {
    robots::TrotGait g;
    read_frequency(gait, g.frequency);
    read_number(gait, "duty", g.duty);
    read_number(gait, "stride", g.stride);
    read_number(gait, "swing_height", g.swing_height);
    return g;
  }
  robots::DiskGait g;
  read_frequency(gait, g.frequency);
  g.legs = read_legs(robot, g.legs, 3, 1000, false);
  read_number(robot, "radius", g.radius);
  if (const toml::node* r = robot.find("radius")) {
    robot.check(g.radius > 0.0, *r, "radius",
                "must be > 0 m, got " + core::format_double(g.radius));
  }
  return g;
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
  scene.duration = run.number(duration, "duration");
  run.check(scene.duration > 0.0, duration, "duration",
            "must be > 0 s, got " + core::format_double(scene.duration));
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
    return;
  }
  scene.dt = run.number(*dt, "dt");
  run.check(scene.dt > 0.0, *dt, "dt", "must be > 0 s, got " + core::format_double(scene.dt));
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
}

void read_friction(const TableReader& friction, Scene& scene, int legs) {
  const std::string law =
      friction.choice(friction.required("law"), "law", {"viscous", "anisotropic", "coulomb"});
  const std::string chosen = "law = '" + law + "'";
  if (law != "anisotropic") {
    friction.forbid("w", "the anisotropic law", chosen);
  }
  if (law != "coulomb") {
    scene.friction.law = connection::FrictionLaw::kViscousCoulomb;
    friction.forbid("tol", "the coulomb law", chosen);
    friction.forbid("max_iterations", "the coulomb law", chosen);
    if (law == "anisotropic") {
      scene.friction.anisotropic = true;
      scene.friction.w = read_anisotropy(friction, friction.required("w"), legs);
    }
    return;
  }
  scene.friction.law = connection::FrictionLaw::kCoulomb;
  if (const toml::node* n = friction.find("tol")) {
    const double tol = friction.number(*n, "tol");
    friction.check(tol > 0.0, *n, "tol", "must be > 0, got " + core::format_double(tol));
    scene.friction.coulomb.tol = tol;
  }
  if (const toml::node* n = friction.find("max_iterations")) {
    const long long m = friction.integer(*n, "max_iterations");
    friction.check(m >= 1 && m <= 1'000'000, *n, "max_iterations",
                   "must be from 1 to 1000000, got " + std::to_string(m));
    scene.friction.coulomb.max_iterations = static_cast<int>(m);
  }
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
  read_number(t, "heading_deg", heading_deg);
  if (kind == "slope") {
    terrain::Slope slope;
    const toml::node& angle = t.required("angle_deg");
    const double deg = t.number(angle, "angle_deg");
    t.check(deg >= 0.0 && deg < 90.0, angle, "angle_deg",
            "must be in [0, 90) degrees, got " + core::format_double(deg));
    slope.angle = deg * kDeg;
    slope.heading = heading_deg * kDeg;
    read_number(t, "com_height", slope.com_height);
    if (const toml::node* n = t.find("com_height")) {
      t.check(slope.com_height >= 0.0, *n, "com_height",
              "must be >= 0 m, got " + core::format_double(slope.com_height));
    }
    return slope;
  }
  terrain::Stairs stairs;
  stairs.heading = heading_deg * kDeg;
  const toml::node& tread = t.required("tread");
  stairs.tread = t.number(tread, "tread");
  t.check(stairs.tread > 0.0, tread, "tread",
          "must be > 0 m, got " + core::format_double(stairs.tread));
  const toml::node& riser = t.required("riser");
  stairs.riser = t.number(riser, "riser");
  t.check(stairs.riser >= 0.0, riser, "riser",
          "must be >= 0 m, got " + core::format_double(stairs.riser));
  return stairs;
}

}  // namespace

const char* gait_kind(const Gait& gait) {
  constexpr const char* kNames[] = {"tripod", "metachronal", "undulation",
                                    "trot",   "disk",        "foot_path"};
  return kNames[gait.index()];
}

Scene parse_scene(std::string_view text, const std::string& path) {
  toml::table doc;
  try {
    doc = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(origin_of(e.source(), path), std::string(e.description()));
  }
  check_top_level(doc, path);
  const std::vector<TableSchema>& all = schema();
  Scene scene;
  scene.path = path;

  // [robot]: which walker; its legs and radius where it has them.
  const TableReader robot(required_table(doc, "robot", path), schema_of("robot"), path, all);
  scene.robot = robot.choice(robot.required("name"), "name",
                             {"bigant", "multipod", "quadruped", "disk", "legs"});
  std::string chosen = "name = '";
  chosen.append(scene.robot).append("'");
  if (scene.robot != "multipod" && scene.robot != "disk") {
    robot.forbid("legs", "the multipod and disk robots", chosen);
  }
  if (scene.robot != "disk") {
    robot.forbid("radius", "the disk robot", chosen);
  }
  if (scene.robot != "multipod") {
    robot.forbid("stiffness", "the multipod robot", chosen);
  }
  if (scene.robot != "legs") {
    robot.forbid("mass", "a leg table (name = 'legs')", chosen);
    robot.forbid("leg", "a leg table (name = 'legs')", chosen);
  }

  // [gait]: the gait of that robot and its parameters.
  const TableReader gait(required_table(doc, "gait", path), schema_of("gait"), path, all);
  scene.gait_origin = gait.origin();
  scene.gait = read_gait(robot, gait, scene.robot, path);
  check_with_factory(scene.gait, robot, gait);

  // [run] and the effects.
  read_run(TableReader(required_table(doc, "run", path), schema_of("run"), path, all), scene);
  const int legs = make_walker(scene.gait).legs();
  read_friction(
      TableReader(required_table(doc, "friction", path), schema_of("friction"), path, all), scene,
      legs);
  if (const toml::table* t = table_of(doc, "filter")) {
    const TableReader filter(*t, schema_of("filter"), path, all);
    FilterEffect effect;
    if (const toml::node* n = filter.find("gamma")) {
      effect.gamma = filter.number(*n, "gamma");
      filter.check(effect.gamma >= 0.0 && effect.gamma < 1.0, *n, "gamma",
                   "must be in [0, 1), got " + core::format_double(effect.gamma));
    }
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
  return scene;
}

Scene read_scene(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path.string(), "cannot read the scene file");
  }
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return parse_scene(text, path.string());
}

nlohmann::json to_json(const Scene& scene) {
  nlohmann::json gait = {{"kind", gait_kind(scene.gait)}};
  std::visit(
      [&](const auto& g) {
        using G = std::decay_t<decltype(g)>;
        gait["frequency"] = g.frequency;
        if constexpr (std::is_same_v<G, robots::TripodGait>) {
          gait["steer"] = g.steer;
          gait["duty"] = g.duty;
          gait["sweep"] = g.sweep;
        } else if constexpr (std::is_same_v<G, robots::MetachronalGait>) {
          gait["sweep"] = g.sweep;
        } else if constexpr (std::is_same_v<G, robots::UndulationGait>) {
          gait["legs"] = g.legs;
          gait["dphi"] = g.dphi;
          gait["roll_amplitude"] = g.roll_amplitude;
          gait["yaw_amplitude"] = g.yaw_amplitude;
          gait["stiffness"] = g.stiffness;
        } else if constexpr (std::is_same_v<G, robots::TrotGait>) {
          gait["duty"] = g.duty;
          gait["stride"] = g.stride;
          gait["swing_height"] = g.swing_height;
        } else if constexpr (std::is_same_v<G, robots::DiskGait>) {
          gait["legs"] = g.legs;
          gait["radius"] = g.radius;
        } else if constexpr (std::is_same_v<G, LegTableGait>) {
          gait["stride"] = g.stride;
          gait["height"] = g.height;
          gait["lift"] = g.lift;
          gait["mass"] = g.mass;
          nlohmann::json legs = nlohmann::json::array();
          for (const LegSpec& leg : g.legs) {
            legs.push_back({{"name", leg.name},
                            {"hip", {leg.hip(0), leg.hip(1), leg.hip(2)}},
                            {"K", leg.K},
                            {"mu", leg.mu},
                            {"phase", leg.phase}});
          }
          gait["legs"] = legs;
        }
      },
      scene.gait);
  const bool coulomb = scene.friction.law == connection::FrictionLaw::kCoulomb;
  nlohmann::json friction = {{"law", coulomb                      ? "coulomb"
                                     : scene.friction.anisotropic ? "anisotropic"
                                                                  : "viscous"}};
  if (scene.friction.anisotropic) {
    nlohmann::json w = nlohmann::json::array();
    for (Eigen::Index k = 0; k < scene.friction.w.cols(); ++k) {
      w.push_back({scene.friction.w(0, k), scene.friction.w(1, k)});
    }
    friction["w"] = w;
  }
  if (scene.friction.law == connection::FrictionLaw::kCoulomb) {
    friction["tol"] = scene.friction.coulomb.tol;
    friction["max_iterations"] = scene.friction.coulomb.max_iterations;
  }
  nlohmann::json out = {
      {"file", scene.path},
      {"robot", scene.robot},
      {"gait", gait},
      {"run", {{"duration", scene.duration}, {"dt", scene.dt}, {"steps", scene.steps}}},
      {"friction", friction},
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
