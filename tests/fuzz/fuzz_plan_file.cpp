// Fuzz target: a plan file (planning::parse_plan_file, then its provenance JSON). Named as a file
// in the shipped plans' folder, so that a [goal] waypoints file = "..." resolves beside them.
#include <string>

#include "core/error.hpp"
#include "fuzz/fuzz_target.hpp"
#include "planning/plan_file.hpp"

namespace slipwalk::fuzz {

Outcome plan_file(std::string_view bytes) {
  try {
    const planning::PlanFile p =
        planning::parse_plan_file(bytes, source_path("studies/ch5_planning/plans/fuzz.toml"));
    require(
        p.options.steps >= 0 && p.options.execute >= 1 && p.options.execute <= p.options.substeps,
        "an accepted plan executes 1 to T_s substeps per step");
    require(static_cast<int>(p.start.phi.size()) == p.robot.legs(),
            "an accepted plan starts every leg");
    (void)planning::to_json(p).dump();
    return Outcome::kAccepted;
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(plan_file)
