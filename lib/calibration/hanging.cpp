// STUB: replaced by the hanging-stage work.
#include "calibration/hanging.hpp"

#include <stdexcept>

namespace slipwalk::calibration {
void validate(const HangingOptions& /*options*/) { throw std::logic_error("hanging: not built yet"); }
HangingCalibration calibrate_hanging(const Geometry& /*geometry*/, const std::vector<HangingRecord>& /*records*/, const HangingOptions& /*options*/) { throw std::logic_error("not built yet"); }
Eigen::MatrixXd predict_hanging(const Geometry& /*geometry*/, const HangingCalibration& /*calibration*/, const HangingRecord& /*record*/) { throw std::logic_error("not built yet"); }
Eigen::Matrix3Xd smooth_com(const Eigen::Matrix3Xd& /*torque*/, const Eigen::Vector3d& /*force*/, double /*q*/, double /*r*/, const Eigen::Vector3d& /*prior*/, double /*prior_variance*/) { throw std::logic_error("not built yet"); }
}  // namespace slipwalk::calibration
