// STUB: replaced by the files-and-command-line work.
#include "calibration/files.hpp"

#include <stdexcept>

namespace slipwalk::calibration {
std::vector<HangingRecord> read_hanging(const std::filesystem::path& /*p*/, const Geometry& /*g*/) { throw std::logic_error("files: not built yet"); }
void write_hanging(std::ostream& /*o*/, const std::vector<HangingRecord>& /*r*/, const Geometry& /*g*/) { throw std::logic_error("not built yet"); }
StandingPoses read_poses(const std::filesystem::path& /*p*/, const Geometry& /*g*/) { throw std::logic_error("not built yet"); }
void write_poses(std::ostream& /*o*/, const StandingPoses& /*p*/, const Geometry& /*g*/) { throw std::logic_error("not built yet"); }
Geometry read_geometry(const std::filesystem::path& /*p*/) { throw std::logic_error("not built yet"); }
void write_geometry(std::ostream& /*o*/, const Geometry& /*g*/) { throw std::logic_error("not built yet"); }
nlohmann::json calibration_json(const Calibration& /*c*/) { throw std::logic_error("not built yet"); }
nlohmann::json truth_json(const SyntheticTruth& /*t*/, const SynthOptions& /*o*/) { throw std::logic_error("not built yet"); }
}  // namespace slipwalk::calibration
