#pragma once
// `slipwalk model` as library calls: frames in the frame format of DESIGN.md (one JSON object, or
// a CSV batch of frames for a robot) evaluated by connection::evaluate (a batch: evaluate_batch)
// under one friction law,
// the outputs as text. The parsers and writers are contact/frame_json.hpp and
// contact/frame_batch.hpp; their errors (core::InputError naming file, line and column) pass
// through.
#include <string>
#include <string_view>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"

namespace slipwalk::connection {

/// One frame: parse `text` (named `source` in errors), evaluate, and the output JSON (with A only
/// under the viscous-Coulomb law), dumped with indent 1 and a final newline.
[[nodiscard]] std::string evaluate_frame_json(std::string_view text, const std::string& source,
                                              FrictionLaw law);

/// A CSV batch of frames of `robot`: every row evaluated, four rows per call of evaluate_batch
/// (the rows are independent frames: the same outputs as evaluate row by row, to rounding), the
/// output CSV (contact::batch_output_columns). Nothing is returned when a row is bad (the error
/// names it).
[[nodiscard]] std::string evaluate_frame_batch(const contact::Robot& robot, std::string csv,
                                               const std::string& source, FrictionLaw law);

}  // namespace slipwalk::connection
