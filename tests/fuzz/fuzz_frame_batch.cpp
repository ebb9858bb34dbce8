// Fuzz target: `slipwalk model --robot` on a CSV batch (contact::FrameBatchReader through
// connection::evaluate_frame_batch). The first line of the input picks the robot: its length is
// the leg count (1 … 64, a uniform robot), an odd length picks Coulomb friction over
// viscous-Coulomb; the rest is the CSV.
#include <algorithm>
#include <string>

#include "connection/frame_model.hpp"
#include "contact/robot.hpp"
#include "core/error.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome frame_batch(std::string_view bytes) {
  const std::size_t eol = std::min(bytes.find('\n'), bytes.size());
  const auto legs = static_cast<int>(std::clamp<std::size_t>(eol, 1, 64));
  const auto law =
      eol % 2 == 1 ? connection::FrictionLaw::kCoulomb : connection::FrictionLaw::kViscousCoulomb;
  const std::string csv(bytes.substr(std::min(eol + 1, bytes.size())));
  try {
    (void)connection::evaluate_frame_batch(contact::uniform_robot(legs, 10.0), csv, "fuzz.csv",
                                           law);
    return Outcome::kAccepted;
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(frame_batch)
