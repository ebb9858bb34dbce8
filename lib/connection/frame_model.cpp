#include "connection/frame_model.hpp"

#include <array>
#include <span>
#include <sstream>
#include <utility>
#include <vector>

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
  // The rows are independent frames (no warm start from row to row): four per call of the
  // batched model, written in their order.
  constexpr std::size_t kGroup = 4;
  std::vector<contact::Frame> frames(kGroup, contact::Frame(robot));
  std::array<long long, kGroup> numbers{};
  contact::BatchScratch scratch(robot.legs());
  for (bool more = true; more;) {
    std::size_t count = 0;
    while (count < kGroup && (more = reader.next(frames[count]))) {
      numbers[count++] = reader.frame_number();
    }
    const std::span<contact::Frame> group(frames.data(), count);
    evaluate_batch(robot, group, law, scratch);
    for (std::size_t i = 0; i < count; ++i) {
      contact::write_batch_row(out, numbers[i], frames[i]);
    }
  }
  return text.str();
}

}  // namespace slipwalk::connection
