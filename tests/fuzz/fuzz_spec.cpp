// Fuzz target: a sweep spec (sweeps::parse_spec, then points::prepare: expanded and every point
// checked by its kind), plain and with its [quick] overrides. Named as a file in the legged
// study's folder, so that a point's robot = "..." reaches the shipped robot files.
#include <string>

#include "core/error.hpp"
#include "fuzz/fuzz_target.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::fuzz {

namespace {

Outcome prepared(std::string_view bytes, bool quick) {
  try {
    const sweeps::PreparedSweep p = sweeps::points::prepare(
        sweeps::parse_spec(bytes, source_path("studies/ch3_legged/fuzz.toml"), quick));
    require(!p.points.empty(), "an accepted spec has at least one point");
    return Outcome::kAccepted;
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
}

}  // namespace

Outcome spec(std::string_view bytes) {
  const Outcome plain = prepared(bytes, false);
  const Outcome quick = prepared(bytes, true);
  return plain == Outcome::kAccepted || quick == Outcome::kAccepted ? Outcome::kAccepted
                                                                    : Outcome::kRejected;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(spec)
