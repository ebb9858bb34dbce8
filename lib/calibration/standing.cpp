// STUB: replaced by the standing-stage work.
#include "calibration/standing.hpp"

#include <stdexcept>

namespace slipwalk::calibration {
std::string_view model_label(MountingModel /*model*/) { throw std::logic_error("standing: not built yet"); }
int model_dof(MountingModel /*model*/, int /*legs*/) { throw std::logic_error("not built yet"); }
std::string_view solver_label(MountingSolver /*solver*/) { throw std::logic_error("not built yet"); }
void validate(const MountingOptions& /*options*/) { throw std::logic_error("not built yet"); }
MountingEstimate fit_mounting(const Geometry& /*g*/, const StandingPoses& /*p*/, const HangingCalibration& /*h*/, const MountingOptions& /*o*/, const MountingStart& /*s*/) { throw std::logic_error("not built yet"); }
Eigen::MatrixXd balance_residuals(const Geometry& /*g*/, const StandingPoses& /*p*/, const HangingCalibration& /*h*/, const MountingEstimate& /*e*/) { throw std::logic_error("not built yet"); }
Eigen::MatrixXd naive_residuals(const Geometry& /*g*/, const StandingPoses& /*p*/, const HangingRecord& /*air*/, double /*cycles*/) { throw std::logic_error("not built yet"); }
std::vector<ModelScore> score_models(const Geometry& /*g*/, const StandingPoses& /*p*/, const HangingCalibration& /*h*/, const MountingOptions& /*o*/, int /*folds*/, std::uint64_t /*seed*/) { throw std::logic_error("not built yet"); }
std::vector<MountingEstimate> multistart(const Geometry& /*g*/, const StandingPoses& /*p*/, const HangingCalibration& /*h*/, const MountingOptions& /*o*/, int /*starts*/, std::uint64_t /*seed*/, double /*a*/, double /*d*/) { throw std::logic_error("not built yet"); }
}  // namespace slipwalk::calibration
