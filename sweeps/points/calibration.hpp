#pragma once
// The in-situ F/T calibration of thesis ch. 4 on the synthetic BigANT (calibration/synthetic.hpp)
// as the calibration kinds (calibration.cpp) share it: a process-wide cache of synthetic robots —
// truth, hanging records, standing poses — and of their default calibration.
//
// The cache. A synthetic robot is fixed by its key (the synthetic options a spec can set: seed,
// noise scale, poses, samples per cycle, cycles; every other option at SynthOptions' default).
// The first request for a key computes the robot (or its calibration); a request for the same key,
// from any thread, while it is being computed waits for that computation, and every later request
// gets the same object: one `slipwalk reproduce` computes each synthetic robot and its calibration
// once, whichever of ch4_calibration's sweeps asks first. A computation that fails stays failed for
// its key: every point that needs it fails with the same message. Entries are never evicted: a
// default robot (4 × 9,000 hanging samples × 42 numbers) takes ≈ 12 MB, and a study caches a few
// dozen (seeds.toml's 20 seeds); calib_accuracy's grid of 150 robots goes around the cache.
//
// The default calibration: calibration::calibrate with the full model (no selection: Table 4.2's
// selection is calib_models' own), the joint Ceres solver on SO(3), the chassis balance target,
// the hanging stage's defaults (exact model, RTS smoother, 4 harmonics). Ceres rather than the
// thesis' alternating solver because the latter crawls along the nearly free gauge direction
// (standing.hpp): on 60 poses it used all 1000 sweeps (7 s) and stopped short of the minimum
// (RSS 3e-4 on noiseless data) where Ceres converged in 9 iterations (0.05 s, RSS 1e-8).
// calib_starts compares the two.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/model.hpp"
#include "calibration/synthetic.hpp"

namespace slipwalk::sweeps::points {

/// What fixes a synthetic robot (the shared parameters of the calibration kinds).
struct SynthKey {
  std::uint64_t seed = 1;
  double noise_scale = 1.0;
  int poses = 543;
  int samples_per_cycle = 900;
  int cycles = 10;
  double mounting_translation = 0.003;  ///< m, σ per axis of the transducers' translation errors
  double mounting_rotation = 0.035;     ///< rad, σ per axis of the transducers' rotation errors

  bool operator==(const SynthKey&) const = default;
  /// Lexicographic over the fields (the cache's order).
  friend bool operator<(const SynthKey& a, const SynthKey& b) {
    return std::tie(a.seed, a.noise_scale, a.poses, a.samples_per_cycle, a.cycles,
                    a.mounting_translation, a.mounting_rotation) <
           std::tie(b.seed, b.noise_scale, b.poses, b.samples_per_cycle, b.cycles,
                    b.mounting_translation, b.mounting_rotation);
  }
  /// SynthOptions at their defaults but for the key's fields.
  [[nodiscard]] calibration::SynthOptions options() const;
};

/// A synthetic robot: its truth and both experiments' data.
struct SyntheticRobot {
  calibration::SynthOptions options;
  calibration::SyntheticTruth truth;
  std::vector<calibration::HangingRecord> hanging;  ///< +x, −x, +z, −z
  calibration::StandingPoses poses;
};

/// Computes the robot of `key` (no cache): calibration::synthetic_truth, _hanging, _poses.
[[nodiscard]] SyntheticRobot make_synthetic_robot(const SynthKey& key);

/// The options of the default calibration (see the head of this file), the folds seeded by `seed`.
[[nodiscard]] calibration::CalibrationOptions default_calibration_options(std::uint64_t seed);

/// The robot of `key`, computed once per process. Throws core::ComputationError when it could not
/// be made (an InputError of the generator becomes one, naming the key); std::logic_error as is.
[[nodiscard]] std::shared_ptr<const SyntheticRobot> cached_robot(const SynthKey& key);

/// The default calibration of the robot of `key`, computed once per process; throws as
/// cached_robot.
[[nodiscard]] std::shared_ptr<const calibration::Calibration> cached_calibration(
    const SynthKey& key);

/// How many robots and calibrations the cache has started computing since the last clear (each
/// key counts once per kind of entry, whether it succeeded or not): for the tests.
[[nodiscard]] std::size_t calibration_cache_computations();

/// Empties the cache and its count. For tests: only while no point runs.
void clear_calibration_cache();

}  // namespace slipwalk::sweeps::points
