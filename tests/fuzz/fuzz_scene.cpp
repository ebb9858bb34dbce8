// Fuzz target: a scene file (scene::parse_scene, then its provenance JSON). Named as a file in
// the shipped scenes' folder, so that a [residual] file = "..." reaches the residual reader.
#include <string>

#include "core/error.hpp"
#include "fuzz/fuzz_target.hpp"
#include "scene/scene.hpp"

namespace slipwalk::fuzz {

Outcome scene(std::string_view bytes) {
  try {
    const scene::Scene s =
        scene::parse_scene(bytes, source_path("studies/scene_effects/scenes/fuzz.toml"));
    require(s.dt > 0.0 && s.steps >= 1 && s.steps <= scene::kMaxSteps,
            "an accepted scene runs a bounded positive number of steps");
    (void)scene::to_json(s).dump();
    return Outcome::kAccepted;
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(scene)
