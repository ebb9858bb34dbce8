// Fuzz target: a hanging-experiment CSV file (calibration::parse_hanging against a two-leg
// geometry, then the pairing checks of `slipwalk calibrate`). An accepted file gives finite
// records of the geometry's widths, a row per sample, and reads back the same after writing.
#include <sstream>
#include <string>
#include <vector>

#include "calibration/files.hpp"
#include "core/error.hpp"
#include "fuzz/fuzz_calibration_files.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome calibration_hanging(std::string_view bytes) {
  const calibration::Geometry g = fuzz_calibration_geometry();
  std::vector<calibration::HangingRecord> records;
  try {
    records = calibration::parse_hanging(bytes, "fuzz_hanging.csv", g);
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
  require(!records.empty(), "an accepted file holds a record");
  for (const calibration::HangingRecord& r : records) {
    require(r.samples() > 0 && r.phi.cols() == 2 && r.wrench.cols() == 12 &&
                r.wrench.rows() == r.samples(),
            "an accepted record has the geometry's widths");
    require(r.phi.allFinite() && r.wrench.allFinite(), "an accepted record is finite");
    require(static_cast<Eigen::Index>(r.rows.size()) == r.samples(), "a row per sample");
  }
  std::ostringstream out;
  calibration::write_hanging(out, records, g);
  const std::vector<calibration::HangingRecord> back =
      calibration::parse_hanging(out.str(), "written.csv", g);
  require(back.size() == records.size(), "the written file holds the same records");
  for (std::size_t i = 0; i < back.size(); ++i) {
    require(back[i].down == records[i].down && back[i].phi == records[i].phi &&
                back[i].wrench == records[i].wrench,
            "the written file reads back bit for bit");
  }
  try {
    calibration::check_hanging_pairs(records, 0.01, 3);
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
  return Outcome::kAccepted;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(calibration_hanging)
