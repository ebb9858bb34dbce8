#pragma once
// What every evaluated frame must satisfy, whatever the input: a support state reported as a
// balance is finite, and a friction solve reported as converged has a finite answer.
#include <string>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

inline void check_support(const contact::Frame& frame) {
  using Status = contact::SupportSummary::Status;
  const Status s = frame.support.status;
  if (s == Status::kBalanced || s == Status::kLine || s == Status::kPoint) {
    const bool finite = std::isfinite(frame.alpha) && std::isfinite(frame.beta) &&
                        std::isfinite(frame.z) && frame.Fz.allFinite();
    require(finite, std::string("support reported '") + contact::status_name(s) +
                        "' with a non-finite state");
  }
}

inline void check_friction(const contact::Frame& frame) {
  if (frame.friction.converged) {
    require(frame.v_body.allFinite() && frame.Fxy.allFinite(),
            "friction reported converged with a non-finite v_body or Fxy");
  }
}

}  // namespace slipwalk::fuzz
