// The gait table (gaits.hpp): one entry per gait. A new gait is one entry here and its options'
// type in scene::Gait (the static_assert below keeps the two in step).
#include "scene/gaits.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "core/csv.hpp"
#include "scene/ranges.hpp"

namespace slipwalk::scene {

namespace {

/// What a gait's reader reads: the file's [robot] and [gait] tables.
struct GaitTables {
  const TableReader& robot;
  const TableReader& gait;
  const std::string& path;              ///< the scene file (messages)
  const std::vector<TableSchema>& all;  ///< the scene's schema (nested tables' suggestions)
};

/// One gait of the format.
template <class Options>
struct GaitEntry {
  using Type = Options;
  std::string_view name;               ///< [gait] kind
  std::string_view robot;              ///< the [robot] name it fits
  std::string_view robot_owner;        ///< how messages name that robot; empty: "the <robot> robot"
  std::vector<std::string_view> keys;  ///< its [gait] keys besides kind and frequency
  std::vector<std::string_view> robot_keys;          ///< the [robot] keys it reads besides name
  Options (*read)(const GaitTables&);                ///< TOML → options, every error at its key
  void (*to_json)(const Options&, nlohmann::json&);  ///< its parameters after kind, frequency
  robots::Walker (*walker)(const Options&);          ///< the factory (checks the options)
};

/// Every number is read in its range (scene/ranges.hpp), at its key; the robot factories check
/// the options again (scene.cpp builds the walker once and reports a factory's error at its key).
void read_frequency(const TableReader& gait, double& value) {
  gait.read_in("frequency", ranges::kFrequency, value);
}

/// [robot] legs, an integer in [lo, hi] (even when `even`); `what` starts the range message.
int read_legs(const TableReader& robot, int value, long long lo, long long hi, bool even,
              const std::string& what) {
  if (const toml::node* n = robot.find("legs")) {
    const long long legs = robot.integer(*n, "legs");
    const bool ok = legs >= lo && legs <= hi && (!even || legs % 2 == 0);
    robot.check(ok, *n, "legs", what + std::to_string(legs));
    return static_cast<int>(legs);
  }
  return value;
}

/// [robot] linkage of BigANT (robots/robots.hpp: BigAntLinkage), "standard" when absent.
constexpr std::string_view kLinkageNames[] = {"standard", "stairs"};

void read_linkage(const TableReader& robot, robots::BigAntLinkage& value) {
  if (const toml::node* n = robot.find("linkage")) {
    const std::string name =
        robot.choice(*n, "linkage", {std::begin(kLinkageNames), std::end(kLinkageNames)});
    value = name == kLinkageNames[1] ? robots::BigAntLinkage::kStairs
                                     : robots::BigAntLinkage::kStandard;
  }
}

std::string_view linkage_name(robots::BigAntLinkage linkage) {
  return kLinkageNames[static_cast<std::size_t>(linkage)];
}

/// The table. Its order is the order of scene::Gait and of the names in messages.
const auto& table() {
  using nlohmann::json;
  using robots::DiskGait, robots::MetachronalGait, robots::TripodGait, robots::TrotGait,
      robots::UndulationGait;
  static const auto gaits = std::tuple{
      // BigANT's alternating tripod with steering (§3.5.1.4).
      GaitEntry<TripodGait>{
          .name = "tripod",
          .robot = "bigant",
          .robot_owner = {},
          .keys = {"steer", "duty", "sweep"},
          .robot_keys = {"linkage"},
          .read =
              [](const GaitTables& t) {
                TripodGait g;
                read_frequency(t.gait, g.frequency);
                t.gait.read_in("steer", ranges::kSteer, g.steer);
                t.gait.read_in("duty", ranges::kDuty, g.duty);
                t.gait.read_in("sweep", ranges::kSweep, g.sweep);
                read_linkage(t.robot, g.linkage);
                return g;
              },
          .to_json =
              [](const TripodGait& g, json& out) {
                out["steer"] = g.steer;
                out["duty"] = g.duty;
                out["sweep"] = g.sweep;
                out["linkage"] = std::string(linkage_name(g.linkage));
              },
          .walker = &robots::bigant_tripod,
      },
      // BigANT's metachronal slipping gait (§3.5.1.5).
      GaitEntry<MetachronalGait>{
          .name = "metachronal",
          .robot = "bigant",
          .robot_owner = {},
          .keys = {"sweep"},
          .robot_keys = {"linkage"},
          .read =
              [](const GaitTables& t) {
                MetachronalGait g;
                read_frequency(t.gait, g.frequency);
                t.gait.read_in("sweep", ranges::kSweep, g.sweep);
                read_linkage(t.robot, g.linkage);
                return g;
              },
          .to_json =
              [](const MetachronalGait& g, json& out) {
                out["sweep"] = g.sweep;
                out["linkage"] = std::string(linkage_name(g.linkage));
              },
          .walker = &robots::bigant_metachronal,
      },
      // The Multipod's undulation (§3.5.2.1).
      GaitEntry<UndulationGait>{
          .name = "undulation",
          .robot = "multipod",
          .robot_owner = {},
          .keys = {"dphi", "roll_amplitude", "yaw_amplitude"},
          .robot_keys = {"legs", "stiffness"},
          .read =
              [](const GaitTables& t) {
                UndulationGait g;
                read_frequency(t.gait, g.frequency);
                t.gait.read_in("dphi", ranges::kPhaseLag, g.dphi);
                t.gait.read_in("roll_amplitude", ranges::kRollAmplitude, g.roll_amplitude);
                t.gait.read_in("yaw_amplitude", ranges::kYawAmplitude, g.yaw_amplitude);
                g.legs = read_legs(t.robot, g.legs, 6, 12, true,
                                   "the multipod has 6, 8, 10 or 12 legs, got ");
                t.robot.read_in("stiffness", ranges::kStiffness, g.stiffness);
                return g;
              },
          .to_json =
              [](const UndulationGait& g, json& out) {
                out["legs"] = g.legs;
                out["dphi"] = g.dphi;
                out["roll_amplitude"] = g.roll_amplitude;
                out["yaw_amplitude"] = g.yaw_amplitude;
                out["stiffness"] = g.stiffness;
              },
          .walker = &robots::multipod,
      },
      // The quadruped's trot (§3.5.2.2).
      GaitEntry<TrotGait>{
          .name = "trot",
          .robot = "quadruped",
          .robot_owner = {},
          .keys = {"duty", "stride", "swing_height"},
          .robot_keys = {},
          .read =
              [](const GaitTables& t) {
                TrotGait g;
                read_frequency(t.gait, g.frequency);
                t.gait.read_in("duty", ranges::kDuty, g.duty);
                t.gait.read_in("stride", ranges::kTrotStride, g.stride);
                t.gait.read_in("swing_height", ranges::kTrotSwingHeight, g.swing_height);
                return g;
              },
          .to_json =
              [](const TrotGait& g, json& out) {
                out["duty"] = g.duty;
                out["stride"] = g.stride;
                out["swing_height"] = g.swing_height;
              },
          .walker = &robots::quadruped_trot,
      },
      // The N-leg disk robot of the scaling studies.
      GaitEntry<DiskGait>{
          .name = "disk",
          .robot = "disk",
          .robot_owner = {},
          .keys = {},
          .robot_keys = {"legs", "radius"},
          .read =
              [](const GaitTables& t) {
                DiskGait g;
                read_frequency(t.gait, g.frequency);
                g.legs = read_legs(t.robot, g.legs, 3, 1000, false,
                                   "the disk robot has 3 to 1000 legs, got ");
                t.robot.read_in("radius", ranges::kRadius, g.radius);
                return g;
              },
          .to_json =
              [](const DiskGait& g, json& out) {
                out["legs"] = g.legs;
                out["radius"] = g.radius;
              },
          .walker = &robots::disk_robot,
      },
      // A robot given as a leg table, walking the foot path of leg_table.hpp.
      GaitEntry<LegTableGait>{
          .name = "foot_path",
          .robot = "legs",
          .robot_owner = "a leg table (name = 'legs')",
          .keys = {"stride", "height", "lift"},
          .robot_keys = {"mass", "leg"},
          .read =
              [](const GaitTables& t) { return read_leg_table(t.robot, t.gait, t.path, t.all); },
          .to_json =
              [](const LegTableGait& g, json& out) {
                out["stride"] = g.stride;
                out["height"] = g.height;
                out["lift"] = g.lift;
                out["mass"] = g.mass;
                json legs = json::array();
                for (const LegSpec& leg : g.legs) {
                  legs.push_back({{"name", leg.name},
                                  {"hip", {leg.hip(0), leg.hip(1), leg.hip(2)}},
                                  {"K", leg.K},
                                  {"mu", leg.mu},
                                  {"phase", leg.phase}});
                }
                out["legs"] = legs;
              },
          .walker = &leg_table_walker,
      },
  };
  return gaits;
}

template <class Table>
struct OptionsOf;
template <class... Options>
struct OptionsOf<std::tuple<GaitEntry<Options>...>> {
  using type = std::variant<Options...>;
};
static_assert(
    std::is_same_v<OptionsOf<std::remove_cvref_t<decltype(table())>>::type, Gait>,
    "scene::Gait must list the options of the gait table's entries, in the table's order");

/// Calls f(entry) for every entry, in table order.
template <class F>
void for_each_gait(F&& f) {
  std::apply([&](const auto&... entry) { (f(entry), ...); }, table());
}

/// The entry of the gait `gait` holds.
template <class F>
decltype(auto) with_entry(const Gait& gait, F&& f) {
  return std::visit(
      [&](const auto& options) -> decltype(auto) {
        using Options = std::decay_t<decltype(options)>;
        return f(std::get<GaitEntry<Options>>(table()), options);
      },
      gait);
}

void add_once(std::vector<std::string_view>& list, std::string_view word) {
  if (!contains(list, word)) {
    list.push_back(word);
  }
}

}  // namespace

const char* gait_kind(const Gait& gait) {
  // The names are string literals, so their views end in '\0'.
  return with_entry(gait, [](const auto& entry, const auto&) { return entry.name.data(); });
}

robots::Walker make_walker(const Gait& gait) {
  return with_entry(gait,
                    [](const auto& entry, const auto& options) { return entry.walker(options); });
}

std::vector<std::string_view> robot_names() {
  std::vector<std::string_view> names;
  for_each_gait([&](const auto& entry) { add_once(names, entry.robot); });
  return names;
}

std::vector<std::string_view> robot_table_keys() {
  std::vector<std::string_view> keys = {"name"};
  for_each_gait([&](const auto& entry) {
    for (std::string_view k : entry.robot_keys) {
      add_once(keys, k);
    }
  });
  return keys;
}

std::vector<std::string_view> gait_table_keys() {
  std::vector<std::string_view> keys = {"kind", "frequency"};
  for_each_gait([&](const auto& entry) {
    for (std::string_view k : entry.keys) {
      add_once(keys, k);
    }
  });
  return keys;
}

void forbid_other_robot_keys(const TableReader& robot, std::string_view name) {
  std::string chosen = "name = '";
  chosen.append(name).append("'");
  const std::vector<std::string_view> keys = robot_table_keys();
  for (auto key = keys.begin() + 1; key != keys.end(); ++key) {
    std::vector<std::string_view> owners;
    std::string_view only_owner_phrase;
    for_each_gait([&](const auto& entry) {
      if (contains(entry.robot_keys, *key)) {
        add_once(owners, entry.robot);
        only_owner_phrase = entry.robot_owner;
      }
    });
    if (!contains(owners, name)) {
      robot.forbid(*key,
                   owners.size() == 1 && !only_owner_phrase.empty() ? std::string(only_owner_phrase)
                                                                    : owner_phrase(owners, "robot"),
                   chosen);
    }
  }
}

Gait read_gait(const TableReader& robot, const TableReader& gait, std::string_view robot_name,
               const std::string& path, const std::vector<TableSchema>& all) {
  std::vector<std::string_view> kinds;
  for_each_gait([&](const auto& entry) {
    if (entry.robot == robot_name) {
      kinds.push_back(entry.name);
    }
  });
  const std::string kind = gait.choice(gait.required("kind"), "kind", kinds);
  const std::string chosen = "kind = '" + kind + "'";
  const std::vector<std::string_view> keys = gait_table_keys();
  for (auto key = keys.begin() + 2; key != keys.end(); ++key) {
    std::vector<std::string_view> owners;
    for_each_gait([&](const auto& entry) {
      if (contains(entry.keys, *key)) {
        owners.push_back(entry.name);
      }
    });
    if (!contains(owners, kind)) {
      gait.forbid(*key, owner_phrase(owners, "gait"), chosen);
    }
  }
  const GaitTables tables{robot, gait, path, all};
  std::optional<Gait> out;
  for_each_gait([&](const auto& entry) {
    if (entry.name == kind) {
      out.emplace(entry.read(tables));
    }
  });
  if (!out) {
    throw std::logic_error("scene: a gait kind without a table entry");
  }
  return *out;
}

nlohmann::json gait_json(const Gait& gait) {
  return with_entry(gait, [](const auto& entry, const auto& options) {
    nlohmann::json out = {{"kind", std::string(entry.name)}, {"frequency", options.frequency}};
    entry.to_json(options, out);
    return out;
  });
}

}  // namespace slipwalk::scene
