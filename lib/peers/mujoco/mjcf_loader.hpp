#pragma once
// Compiling an MJCF text held in memory (MuJoCo 2.2.2: mj_loadXML from a virtual file system).
// Loads are serialized: MuJoCo 2.2's XML loader keeps global state.
#include <string>

struct mjModel_;

namespace slipwalk::peers::mujoco {

/// The compiled model (free with mj_deleteModel). Throws core::ComputationError with MuJoCo's
/// message if it does not compile.
[[nodiscard]] mjModel_* load_mjcf(const std::string& xml, const char* file_name);

}  // namespace slipwalk::peers::mujoco
