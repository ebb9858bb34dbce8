// Fuzz target: the spring-support search (contact::spring_support, §3.3) on a frame decoded from
// the bytes (fuzz_frames.hpp), by both routes: the default (Newton, then Alg. 1) and Alg. 1 alone.
#include "contact/spring_support.hpp"
#include "fuzz/fuzz_checks.hpp"
#include "fuzz/fuzz_frames.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome spring_support(std::string_view bytes) {
  const std::optional<contact::FrameInput> input = decode_frame(bytes);
  if (!input) {
    return Outcome::kRejected;
  }
  for (const bool newton : {true, false}) {
    contact::Frame frame = input->frame;
    contact::SupportOptions options;
    options.newton = newton;
    contact::spring_support(input->robot, frame, options);
    check_support(frame);
  }
  return Outcome::kAccepted;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(spring_support)
