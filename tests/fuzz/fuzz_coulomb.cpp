// Fuzz target: classical Coulomb friction (friction::solve_coulomb, §3.4) on a frame decoded from
// the bytes (fuzz_frames.hpp) after its spring support, with the fast path and without.
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "fuzz/fuzz_checks.hpp"
#include "fuzz/fuzz_frames.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome coulomb(std::string_view bytes) {
  const std::optional<contact::FrameInput> input = decode_frame(bytes);
  if (!input) {
    return Outcome::kRejected;
  }
  contact::Frame supported = input->frame;
  contact::spring_support(input->robot, supported);
  for (const bool fast_path : {true, false}) {
    contact::Frame frame = supported;
    friction::CoulombOptions options;
    options.fast_path = fast_path;
    friction::solve_coulomb(input->robot, frame, options);
    check_friction(frame);
    if (frame.friction.converged) {
      require(frame.friction.certificate <= options.tol,
              "Coulomb friction reported converged with a certificate above its tolerance");
    }
  }
  return Outcome::kAccepted;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(coulomb)
