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
#include "sweeps/points/calibration.hpp"

namespace slipwalk::sweeps::points {

namespace {

std::string robot_label(const SynthKey& key) {
  return "synthetic BigANT (seed " + std::to_string(key.seed) + ", noise scale " +
         core::format_double(key.noise_scale) + ", " + std::to_string(key.poses) + " poses, " +
         std::to_string(key.samples_per_cycle) + " samples per cycle × " +
         std::to_string(key.cycles) + " cycles)";
}

/// Values computed once per key; a failed computation stores its error (a logic_error as it is,
/// anything else as a ComputationError naming the robot).
template <class Value>
class OnceCache {
 public:
  using Pointer = std::shared_ptr<const Value>;

  template <class Make>
  Pointer get(const SynthKey& key, Make&& make) {
    std::promise<Pointer> promise;
    std::shared_future<Pointer> future;
    bool mine = false;
    {
      const std::lock_guard lock(mutex_);
      const auto it = entries_.find(key);
      if (it != entries_.end()) {
        future = it->second;
      } else {
        future = promise.get_future().share();
        entries_.emplace(key, future);
        ++computations_;
        mine = true;
      }
    }
    if (mine) {
      try {
        promise.set_value(std::make_shared<const Value>(make()));
      } catch (const std::logic_error&) {
        promise.set_exception(std::current_exception());  // a bug (or a stage not built): as is
      } catch (const std::exception& e) {
        const std::string what = e.what();
        const std::string label = robot_label(key);
        promise.set_exception(std::make_exception_ptr(core::ComputationError(
            what.find(label) == std::string::npos ? label + ": " + what : what)));
      }
    }
    return future.get();
  }

  [[nodiscard]] std::size_t computations() {
    const std::lock_guard lock(mutex_);
    return computations_;
  }

  void clear() {
    const std::lock_guard lock(mutex_);
    entries_.clear();
    computations_ = 0;
  }

 private:
  std::mutex mutex_;
  std::map<SynthKey, std::shared_future<Pointer>> entries_;
  std::size_t computations_ = 0;
};

struct Cache {
  OnceCache<SyntheticRobot> robots;
  OnceCache<calibration::Calibration> calibrations;
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
  return cache().robots.get(key, [&] { return make_synthetic_robot(key); });
}

std::shared_ptr<const calibration::Calibration> cached_calibration(const SynthKey& key) {
  return cache().calibrations.get(key, [&] {
    const std::shared_ptr<const SyntheticRobot> robot = cached_robot(key);
    return calibration::calibrate(robot->truth.geometry, robot->hanging, robot->poses,
                                  default_calibration_options(key.seed));
  });
}

std::size_t calibration_cache_computations() {
  return cache().robots.computations() + cache().calibrations.computations();
}

void clear_calibration_cache() {
  cache().robots.clear();
  cache().calibrations.clear();
}

}  // namespace slipwalk::sweeps::points
