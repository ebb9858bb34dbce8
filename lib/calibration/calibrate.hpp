#pragma once
// The whole calibration of thesis ch. 4 in order: §4.3.1 on the hanging records, then §4.3.2 on
// the standing poses (one model, or Table 4.2's selection by the smallest BIC), and the calibrated
// ground contact wrench of eq. 4.3 for new readings.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "calibration/hanging.hpp"
#include "calibration/model.hpp"
#include "calibration/standing.hpp"

namespace slipwalk::calibration {

/// The calibration's mounting defaults: the joint solve on SO(3), and the errors-in-variables
/// correction with σ_f² estimated from the forces' residuals (standing.hpp). Both go beyond the
/// thesis: its plain least squares leaves the displacements biased by the force noise — on the
/// synthetic robot (twenty seeds) their errors are 2.5 of their standard errors RMS, against 1.0
/// with the correction (tests/calibration/test_calibrate.cpp).
[[nodiscard]] inline MountingOptions default_mounting() {
  MountingOptions m;
  m.solver = MountingSolver::ceres_so3;
  m.force_noise_variance = -1.0;
  return m;
}

struct CalibrationOptions {
  HangingOptions hanging;
  MountingOptions mounting = default_mounting();  ///< mounting.model: used without selection
  bool select_model = true;  ///< Table 4.2: fit all four models, keep the smallest BIC
  int folds = 5;             ///< cross-validation folds of the selection (2..P)
  std::uint64_t seed = 1;    ///< the folds' shuffle
};

struct Calibration {
  Geometry geometry;
  HangingCalibration hanging;
  MountingEstimate mounting;       ///< the selected (or requested) model
  std::vector<ModelScore> models;  ///< Table 4.2 (empty without selection)
  double seconds_hanging = 0.0;    ///< CPU time of §4.3.1, s
  double seconds_standing = 0.0;   ///< of §4.3.2 and the selection, s
};

/// Validates everything (InputError naming the place), then calibrates.
[[nodiscard]] Calibration calibrate(const Geometry& geometry,
                                    const std::vector<HangingRecord>& hanging,
                                    const StandingPoses& poses,
                                    const CalibrationOptions& options = {});

/// Eq. 4.3 with the calibration: leg k's ground contact wrench about C in W, from its reading at
/// shaft angle φ with the body's attitude R^W_C: [R^W_C]·(transform(ŵ) − leg gravity wrench).
[[nodiscard]] Wrench ground_contact_wrench(const Calibration& calibration, int leg, double phi,
                                           const Wrench& reading, const Eigen::Matrix3d& attitude);

}  // namespace slipwalk::calibration
