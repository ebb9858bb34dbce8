// The calibration in the thesis' order (§4.3): the hanging records fix each transducer's offset,
// its leg's weight and centre of mass (§4.3.1); with those, the standing poses fix the mounting
// (§4.3.2), either in the model the caller names or in the model of Table 4.2 with the smallest
// BIC (§4.4.2: "We selected (1) full model ... which yielded the smallest BIC").
#include "calibration/calibrate.hpp"

#include <algorithm>
#include <string>

#include "core/clock.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {

namespace {

void validate_options(const CalibrationOptions& options, Eigen::Index poses) {
  validate(options.hanging);
  validate(options.mounting);
  if (options.select_model && (options.folds < 2 || options.folds > poses)) {
    throw core::InputError("folds", "must lie in [2, " + std::to_string(poses) +
                                        "] (the number of poses), got " +
                                        std::to_string(options.folds));
  }
}

}  // namespace

Calibration calibrate(const Geometry& geometry, const std::vector<HangingRecord>& hanging,
                      const StandingPoses& poses, const CalibrationOptions& options) {
  validate(geometry);
  validate_options(options, poses.poses());

  Calibration result;
  result.geometry = geometry;
  // CPU time of this thread: the stages run on it alone, and on a shared machine wall time is
  // mostly waiting for a core.
  const double hanging_start = core::thread_cpu_seconds();
  result.hanging = calibrate_hanging(geometry, hanging, options.hanging);
  result.seconds_hanging = core::thread_cpu_seconds() - hanging_start;

  const double standing_start = core::thread_cpu_seconds();
  MountingOptions mounting = options.mounting;
  if (options.select_model) {
    result.models =
        score_models(geometry, poses, result.hanging, mounting, options.folds, options.seed);
    const auto best =
        std::min_element(result.models.begin(), result.models.end(),
                         [](const ModelScore& a, const ModelScore& b) { return a.bic < b.bic; });
    mounting.model = best->model;
  }
  result.mounting = fit_mounting(geometry, poses, result.hanging, mounting);
  result.seconds_standing = core::thread_cpu_seconds() - standing_start;
  return result;
}

Wrench ground_contact_wrench(const Calibration& calibration, int leg, double phi,
                             const Wrench& reading, const Eigen::Matrix3d& attitude) {
  const auto k = static_cast<std::size_t>(leg);
  const LegEstimate& estimate = calibration.hanging.legs.at(k);
  const Frame& nominal = calibration.geometry.transducer.at(k);
  // The transducer in C (model.hpp): R_k = R_N,k R̃_k, origin p_N,k + u_k.
  const Frame in_c{nominal.R * calibration.mounting.rotation.at(k),
                   nominal.p + calibration.mounting.displacement.at(k)};
  // Eq. 4.3: what the leg applies to the chassis, less the leg's own gravity wrench at its centre
  // of mass, leaves the ground contact wrench (about C, C's axes).
  const Wrench applied = transform_wrench(in_c, reading - estimate.offset);
  const Eigen::Vector3d down = attitude.transpose() * Eigen::Vector3d(0.0, 0.0, -1.0);
  const Wrench gravity = force_at(estimate.weight * down, in_c * estimate.com(phi));
  const Wrench contact_c = applied - gravity;
  Wrench contact_w;
  contact_w.head<3>() = attitude * contact_c.head<3>();
  contact_w.tail<3>() = attitude * contact_c.tail<3>();
  return contact_w;
}

}  // namespace slipwalk::calibration
