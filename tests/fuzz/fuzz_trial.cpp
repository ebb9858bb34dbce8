// Fuzz target: a motion-trial file (residual::parse_trials, then the template's prediction along
// each trial: a prediction per interior sample, or a refusal naming the sample's row).
#include <string>

#include "core/error.hpp"
#include "fuzz/fuzz_target.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"

namespace slipwalk::fuzz {

Outcome trial(std::string_view bytes) {
  std::vector<residual::MotionTrial> trials;
  try {
    trials = residual::parse_trials(bytes, "fuzz_trial.csv");
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
  require(!trials.empty(), "an accepted file holds a trial");
  for (const residual::MotionTrial& t : trials) {
    require(t.samples() >= residual::kMinTrialSamples, "an accepted trial has enough samples");
    require(t.t.allFinite() && t.pose.allFinite() && t.joints.allFinite(),
            "an accepted trial is finite");
    try {
      const residual::TemplatePrediction p =
          residual::predict(residual::multipod_template(t.legs()), t);
      require(p.v_true.rows() == t.samples() - 2, "a prediction per interior sample");
    } catch (const core::InputError&) {
      return Outcome::kRejected;  // joints that jump make feet faster than the model takes
    } catch (const core::ComputationError&) {
      // A template with no finite support for the file's joints says so: exit 1, not a crash.
    }
  }
  return Outcome::kAccepted;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(trial)
