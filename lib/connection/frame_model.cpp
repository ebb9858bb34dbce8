#include "connection/frame_model.hpp"

#include <sstream>
#include <utility>

#include "contact/frame_batch.hpp"
#include "contact/frame_json.hpp"
#include "core/csv.hpp"

namespace slipwalk::connection {

std::string evaluate_frame_json(std::string_view text, const std::string& source, FrictionLaw law) {
  contact::FrameInput input = contact::parse_frame_json(text, source);
  evaluate(input.robot, input.frame, law);
  const auto json =
      contact::frame_to_json(input.robot, input.frame, law == FrictionLaw::kViscousCoulomb);
  return json.dump(1) + "\n";
}

std::string evaluate_frame_batch(const contact::Robot& robot, std::string csv,
                                 const std::string& source, FrictionLaw law) {
  contact::FrameBatchReader reader(std::move(csv), source, robot.legs());
  std::ostringstream text;
  core::CsvWriter out(text, contact::batch_output_columns(robot.legs()));
  contact::Frame frame(robot);
  while (reader.next(frame)) {
    evaluate(robot, frame, law);
    contact::write_batch_row(out, reader.frame_number(), frame);
  }
  return text.str();
}

}  // namespace slipwalk::connection
