#pragma once
// The friction laws of the scene format (scene.hpp), read from one table with an entry per law
// (friction_laws.cpp): its name ([friction] law, and the kernel's name), its keys, its reader
// (TOML → FrictionEffect, errors at file:line:col), its JSON, the law policy of the trajectory
// kernel and what it sets on the walker's robot. The scene reader, to_json and compose() iterate
// the table; nothing else names a law.
#include <nlohmann/json.hpp>
#include <string_view>
#include <variant>
#include <vector>

#include "connection/trajectory.hpp"
#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

/// The law policies of connection::Effects a law entry can pick (compose.cpp visits them).
using LawPolicy = std::variant<connection::ViscousCoulombKernel, connection::CoulombKernel>;

/// One friction law of the format.
struct FrictionLawEntry {
  std::string_view name;               ///< [friction] law; the kernel's name starts with it
  connection::FrictionLaw law;         ///< FrictionEffect::law of a scene with this law
  bool anisotropic;                    ///< FrictionEffect::anisotropic of a scene with this law
  std::vector<std::string_view> keys;  ///< its [friction] keys besides law
  /// Reads its keys into `effect` (law and anisotropic already set); `legs`: the walker's.
  void (*read)(const TableReader& friction, int legs, FrictionEffect& effect);
  /// Adds its parameters to the JSON after "law".
  void (*to_json)(const FrictionEffect& effect, nlohmann::json& out);
  /// The trajectory kernel's law policy (connection/trajectory.hpp).
  LawPolicy (*policy)(const FrictionEffect& effect);
  /// Sets what the law changes on the walker's robot (at compose time), if anything.
  void (*fit_robot)(const FrictionEffect& effect, contact::Robot& robot);
};

/// The table, in the order of the names in messages.
[[nodiscard]] const std::vector<FrictionLawEntry>& friction_laws();

/// The entry of a scene's friction effect (by its law and anisotropic fields).
[[nodiscard]] const FrictionLawEntry& friction_law_of(const FrictionEffect& effect);

/// The entry named `name`; nullptr if the table has none.
[[nodiscard]] const FrictionLawEntry* find_friction_law(std::string_view name);

/// The keys of [friction]: "law", then every law's own keys.
[[nodiscard]] std::vector<std::string_view> friction_table_keys();

/// Reads [friction]: the law among the table's, the keys of other laws rejected, the chosen
/// entry's reader. `legs`: the walker's (a per-leg w is checked against it).
[[nodiscard]] FrictionEffect read_friction(const TableReader& friction, int legs);

/// {"law", then the law's own parameters}.
[[nodiscard]] nlohmann::json friction_json(const FrictionEffect& effect);

}  // namespace slipwalk::scene
