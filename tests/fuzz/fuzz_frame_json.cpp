// Fuzz target: `slipwalk model` on one JSON frame (contact::parse_frame_json, then
// connection::evaluate under both friction laws and the output JSON).
#include "connection/local_connection.hpp"
#include "contact/frame_json.hpp"
#include "core/error.hpp"
#include "fuzz/fuzz_checks.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome frame_json(std::string_view bytes) {
  try {
    const contact::FrameInput input = contact::parse_frame_json(bytes, "fuzz.json");
    for (const auto law :
         {connection::FrictionLaw::kViscousCoulomb, connection::FrictionLaw::kCoulomb}) {
      contact::Frame frame = input.frame;
      connection::evaluate(input.robot, frame, law);
      check_support(frame);
      check_friction(frame);
      (void)contact::frame_to_json(input.robot, frame,
                                   law == connection::FrictionLaw::kViscousCoulomb)
          .dump();
    }
    return Outcome::kAccepted;
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(frame_json)
