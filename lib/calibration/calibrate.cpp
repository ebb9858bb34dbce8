// STUB: written after the stages land.
#include "calibration/calibrate.hpp"

#include <stdexcept>

namespace slipwalk::calibration {
Calibration calibrate(const Geometry& /*g*/, const std::vector<HangingRecord>& /*h*/, const StandingPoses& /*p*/, const CalibrationOptions& /*o*/) { throw std::logic_error("calibrate: not built yet"); }
Wrench ground_contact_wrench(const Calibration& /*c*/, int /*leg*/, double /*phi*/, const Wrench& /*r*/, const Eigen::Matrix3d& /*a*/) { throw std::logic_error("not built yet"); }
}  // namespace slipwalk::calibration
