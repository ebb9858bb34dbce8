// The synthetic robots and default calibrations of the calibration kinds, computed once per key
// per process (calibration.hpp states the contract): a map from key to a shared_future, filled by
// the first thread that asks; the others wait on the future.
#include <cstddef>
#include <exception>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "sweeps/engine/once_cache.hpp"
#include "sweeps/points/calibration.hpp"

namespace slipwalk::sweeps::points {

namespace {

std::string robot_label(const SynthKey& key) {
  return "synthetic BigANT (seed " + std::to_string(key.seed) + ", noise scale " +
         core::format_double(key.noise_scale) + ", " + std::to_string(key.poses) + " poses, " +
         std::to_string(key.samples_per_cycle) + " samples per cycle × " +
         std::to_string(key.cycles) + " cycles, translation errors σ " +
         core::format_double(key.mounting_translation) + " m, rotation errors σ " +
         core::format_double(key.mounting_rotation) + " rad)";
}

struct Cache {
  engine::OnceCache<SynthKey, SyntheticRobot> robots;
  engine::OnceCache<SynthKey, calibration::Calibration> calibrations;
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

calibration::SynthOptions SynthKey::options() const {
  calibration::SynthOptions o;
  o.seed = seed;
  o.noise_scale = noise_scale;
  o.poses = poses;
  o.samples_per_cycle = samples_per_cycle;
  o.mounting_translation = mounting_translation;
  o.mounting_rotation = mounting_rotation;
  o.cycles = cycles;
  return o;
}

SyntheticRobot make_synthetic_robot(const SynthKey& key) {
  SyntheticRobot robot;
  robot.options = key.options();
  robot.truth = calibration::synthetic_truth(robot.options);
  robot.hanging = calibration::synthetic_hanging(robot.truth, robot.options);
  robot.poses = calibration::synthetic_poses(robot.truth, robot.options);
  return robot;
}

calibration::CalibrationOptions default_calibration_options(std::uint64_t seed) {
  calibration::CalibrationOptions o;
  o.select_model = false;
  o.mounting.model = calibration::MountingModel::full;
  o.mounting.solver = calibration::MountingSolver::ceres_so3;
  o.mounting.target = calibration::BalanceTarget::chassis;
  o.seed = seed;
  return o;
}

std::shared_ptr<const SyntheticRobot> cached_robot(const SynthKey& key) {
  return cache().robots.get(
      key, [&] { return make_synthetic_robot(key); }, robot_label);
}

std::shared_ptr<const calibration::Calibration> cached_calibration(const SynthKey& key) {
  return cache().calibrations.get(
      key,
      [&] {
        const std::shared_ptr<const SyntheticRobot> robot = cached_robot(key);
        return calibration::calibrate(robot->truth.geometry, robot->hanging, robot->poses,
                                      default_calibration_options(key.seed));
      },
      robot_label);
}

std::size_t calibration_cache_computations() {
  return cache().robots.computations() + cache().calibrations.computations();
}

void clear_calibration_cache() {
  cache().robots.clear();
  cache().calibrations.clear();
}

}  // namespace slipwalk::sweeps::points
