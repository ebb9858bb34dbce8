#pragma once
// The frame format of DESIGN.md (`slipwalk model`), read and written here so that the command
// line, the studies and the tests share one parser:
//   in:  {"q": [[x,y,z],...], "qdot": [[x,y,z],...], "K": [...], "Mg": 1.0, "mu": [...],
//         "w": [[wx,wy],...], "theta": 0.0}      (K, mu, w, theta, Mg optional: 1, 1, 0, 0, 1)
//   out: {"alpha","beta","z","contact":[bool..],"Fz":[..],"v_body":[vx,vy,wz],
//         "Fxy":[[fx,fy]..],"A":[[..]..] | null, "support":{..}, "friction":{..}}
// Errors are core::InputError whose `where` is "<source>:<line>:<col>": of the syntax error for
// malformed JSON (read by core::parse_json, which also refuses deep nesting, long texts and
// duplicate keys), of the value for a bad value, whose message then starts with its name and
// states the allowed range ("K[1]: must be in [0.001, 1000000000] N/m, got -2"; the ranges are
// contact::limits), of the key for an unknown key, and of the document for a missing key.
// The output is finite or not written: frame_to_json throws core::ComputationError (exit 1)
// instead. A written result says how far to trust it: "support"."status" ("balanced", "line",
// "point": a balance; "unsupported", "iteration_limit": none), "friction"."converged" (false:
// the solver stopped short of its tolerance, or no balance exists) and "friction"."unique"
// (false: a continuum of body velocities balances; the least-norm one is written).
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "contact/robot.hpp"

namespace slipwalk::contact {

/// A robot and one frame of it, read together from one JSON object.
struct FrameInput {
  explicit FrameInput(Robot r) : robot(std::move(r)), frame(robot) {}
  Robot robot;
  Frame frame;
};

/// Parses the frame format; validates sizes, finiteness and ranges (validate(), check_frame()).
[[nodiscard]] FrameInput parse_frame_json(std::string_view text, const std::string& source);

/// Parses a robot alone: {"K": [...] | n legs given by "legs", "mu", "w", "Mg"} (for CSV batches).
[[nodiscard]] Robot parse_robot_json(std::string_view text, const std::string& source);

/// The outputs of a frame; A only if `with_connection` (the viscous-Coulomb law). Throws
/// core::ComputationError when an output is not finite.
[[nodiscard]] nlohmann::json frame_to_json(const Robot& robot, const Frame& frame,
                                           bool with_connection);

}  // namespace slipwalk::contact
