#pragma once
// The gaits of the scene format (scene.hpp), read from one table with an entry per gait
// (gaits.cpp): its name ([gait] kind), the robot it fits ([robot] name), its keys in [gait] and
// [robot], its reader (TOML → options, errors at file:line:col), its JSON and its walker. The
// scene reader, to_json and compose() iterate the table; nothing else names a gait.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "robots/robots.hpp"
#include "scene/leg_table.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

/// The robot and its gait: the options of one entry of the gait table (gaits.cpp checks at compile
/// time that the table lists exactly these types, in this order).
using Gait = std::variant<robots::TripodGait, robots::MetachronalGait, robots::UndulationGait,
                          robots::TrotGait, robots::DiskGait, LegTableGait>;

/// The gait's name in the format ([gait] kind), from its table entry.
[[nodiscard]] const char* gait_kind(const Gait& gait);

/// The walker of a gait (its entry's factory, robots/robots.hpp); throws the factory's
/// core::InputError.
[[nodiscard]] robots::Walker make_walker(const Gait& gait);

// ---- for the scene reader (scene.cpp) ---------------------------------------------------------

/// The [robot] names, each once, in table order.
[[nodiscard]] std::vector<std::string_view> robot_names();

/// The keys of [robot]: "name", then every key a gait reads from [robot].
[[nodiscard]] std::vector<std::string_view> robot_table_keys();

/// The keys of [gait]: "kind", "frequency", then every gait's own keys.
[[nodiscard]] std::vector<std::string_view> gait_table_keys();

/// Rejects the [robot] keys that only other robots than `name` have (at their file:line:col).
void forbid_other_robot_keys(const TableReader& robot, std::string_view name);

/// Reads [gait]: its kind among the gaits of `robot_name`, the keys of other gaits rejected, then
/// the chosen entry's reader (which may read [robot] keys too). `all` is the scene's schema.
[[nodiscard]] Gait read_gait(const TableReader& robot, const TableReader& gait,
                             std::string_view robot_name, const std::string& path,
                             const std::vector<TableSchema>& all);

/// {"kind", "frequency", then the gait's own parameters}.
[[nodiscard]] nlohmann::json gait_json(const Gait& gait);

}  // namespace slipwalk::scene
