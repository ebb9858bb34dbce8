#pragma once
// The Multipod trials of thesis §5.3.2 as the residual kinds (residual.cpp) share them: a
// process-wide cache of recorded trials and of the template's prediction along each, and the
// seeded draws of training subsets.
//
// The cache. A trial is fixed by its key (every parameter that changes what MuJoCo records: Δφ,
// f, cycles, the asymmetry's seed and scale, settle, timestep, sample rate, legs). The first
// request for a key computes the trial; a request for the same key, from any thread, while it is
// being computed waits for that computation, and every later request gets the same object: one
// process records each trial once, whether the trials sweep, the transfer sweeps or all of them
// in one `slipwalk reproduce` ask for it, and whichever sweep's thread comes first. A trial that
// fails (MuJoCo blows up, the template refuses it) stays failed for its key: every point that
// needs it fails with the same message (core::ComputationError). Entries are never evicted: a
// full study's trials (≈ 130 of up to 3 400 samples) take a few tens of MB.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "residual/template.hpp"
#include "residual/trial.hpp"

namespace slipwalk::sweeps::points {

/// What fixes a Multipod trial (the shared parameters of the residual kinds).
struct MultipodTrialKey {
  double dphi_pi = 1.0;        ///< Δφ / π, in [0, 2]; quantized to 1e-12 (trial_key)
  double frequency = 0.3;      ///< f, Hz
  double cycles = 8.0;         ///< gait cycles recorded
  std::uint64_t seed = 1;      ///< the asymmetry draw's seed
  double asymmetry = 1.0;      ///< scale of the drawn asymmetries (0: the symmetric robot)
  double settle = 0.5;         ///< s, standing in the t = 0 pose before recording
  double timestep = 0.001;     ///< s, MuJoCo's step
  double sample_rate = 125.0;  ///< Hz, the motion capture's
  int legs = 8;                ///< 2 · modules

  auto operator<=>(const MultipodTrialKey&) const = default;
};

/// Δφ/π rounded to 12 decimals, so that a Δφ of a spec's linspace axis (0.2 + 5 · 0.064 =
/// 0.52000000000000002) and the same Δφ written in a list ("0.52") name one trial.
[[nodiscard]] double quantize_dphi_pi(double dphi_pi);

/// "Δφ = 0.65π, f = 0.3 Hz, asymmetry 1 (seed 1)": the trial's label in messages.
[[nodiscard]] std::string trial_label(const MultipodTrialKey& key);

/// The trial of `key` (its dphi_pi quantized), recorded once per process. Throws
/// core::ComputationError when the trial could not be recorded (or without MuJoCo).
[[nodiscard]] std::shared_ptr<const residual::MotionTrial> cached_trial(MultipodTrialKey key);

/// The template's prediction along the trial of `key` (residual::predict against
/// residual::multipod_template(legs)), computed once per process. Throws core::ComputationError
/// when the trial failed or the template refuses it.
[[nodiscard]] std::shared_ptr<const residual::TemplatePrediction> cached_prediction(
    MultipodTrialKey key);

/// Where trials come from: by default MuJoCo's Multipod (peers/mujoco/multipod_peer.hpp) with the
/// asymmetries peers::mujoco::draw_asymmetry(legs, seed, asymmetry) and the §5.3.2 gait. The
/// tests put in a synthetic source (trials made from the template plus a known B) to check the
/// kinds' plumbing against known truth. A source may throw; the key's entry then holds the error.
using TrialSource = std::function<residual::MotionTrial(const MultipodTrialKey&)>;

/// Replaces the trial source (an empty function: the default) and empties the cache; returns the
/// previous source. For tests: call it only while no point runs.
TrialSource set_trial_source(TrialSource source);

/// Empties the cache (trials and predictions). For tests: only while no point runs.
void clear_trial_cache();

/// The 26 phase offsets of §5.3.2, Δφ/π = linspace(0.2, 1.8, 26) (sweeps::linspace, so they are
/// the values of a spec's `{ linspace = [0.2, 1.8], n = 26 }` axis), quantized.
[[nodiscard]] std::vector<double> thesis_dphi_grid();

/// Draw `draws` subsets of `k` distinct indices from {0, …, pool − 1} (each sorted ascending),
/// deterministically from `seed`: a partial Fisher–Yates shuffle on std::mt19937_64 (whose output
/// the standard fixes), reduced to a range by rejection (not std::uniform_int_distribution, whose
/// algorithm is the library's), so every platform draws the same subsets. Draw d is the same
/// whatever `draws` is. Requires 1 ≤ k ≤ pool.
[[nodiscard]] std::vector<std::vector<int>> draw_subsets(std::uint64_t seed, int k, int pool,
                                                         int draws);

}  // namespace slipwalk::sweeps::points
