// STUB: replaced by the synthetic-robot work.
#include "calibration/synthetic.hpp"

#include <stdexcept>

namespace slipwalk::calibration {
void validate(const SynthOptions& /*options*/) { throw std::logic_error("synthetic: not built yet"); }
Eigen::Vector3d SyntheticTruth::leg_com(int /*leg*/, double /*phi*/) const { throw std::logic_error("not built yet"); }
Frame SyntheticTruth::transducer_frame(int /*leg*/) const { throw std::logic_error("not built yet"); }
Eigen::Vector3d SyntheticTruth::displacement(int /*leg*/) const { throw std::logic_error("not built yet"); }
double SyntheticTruth::chassis_weight() const { throw std::logic_error("not built yet"); }
double SyntheticTruth::com_torque_bias() const { throw std::logic_error("not built yet"); }
SyntheticTruth synthetic_truth(const SynthOptions& /*options*/) { throw std::logic_error("not built yet"); }
std::vector<HangingRecord> synthetic_hanging(const SyntheticTruth& /*truth*/, const SynthOptions& /*options*/) { throw std::logic_error("not built yet"); }
StandingPoses synthetic_poses(const SyntheticTruth& /*truth*/, const SynthOptions& /*options*/) { throw std::logic_error("not built yet"); }
Wrench true_reading(const SyntheticTruth& /*truth*/, int /*leg*/, double /*phi*/, const Eigen::Vector3d& /*down*/, const Eigen::Vector3d& /*foot_force*/) { throw std::logic_error("not built yet"); }
}  // namespace slipwalk::calibration
