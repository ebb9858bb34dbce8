#pragma once
// The fuzz targets of tests/fuzz (one fuzz_<name>.cpp each). A target takes arbitrary bytes and
// keeps the command line's contract for them: the input is accepted, or refused with
// core::InputError (the target returns kRejected); any other exception escapes, and a crash, a
// sanitizer report or a hang is a failure of the run. A target also checks what an accepted input
// must give (e.g. no non-finite answer reported as converged) and throws TargetViolation if not.
//
// One source, two drivers: in the SLIPWALK_FUZZ build (clang, libFuzzer) SLIPWALK_FUZZ_ENTRY
// makes the target the program's LLVMFuzzerTestOneInput; in the normal build the targets are
// plain functions that tests/fuzz/test_fuzz_replay.cpp runs over the corpora, the regressions
// and seeded mutations of them.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace slipwalk::fuzz {

enum class Outcome { kRejected, kAccepted };

/// A broken promise about an accepted input (never InputError, so it is never taken for one).
class TargetViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Throws TargetViolation("<what>") unless ok.
inline void require(bool ok, const std::string& what) {
  if (!ok) {
    throw TargetViolation(what);
  }
}

/// A path in the source tree (SLIPWALK_SOURCE_DIR): targets name their inputs as files in the
/// studies' folders, so that relative references (a scene's residual file, a spec's robot)
/// resolve to the shipped files.
[[nodiscard]] inline std::string source_path(std::string_view relative) {
  return (std::filesystem::path(SLIPWALK_SOURCE_DIR) / relative).string();
}

Outcome scene(std::string_view bytes);           ///< scene::parse_scene, to_json
Outcome spec(std::string_view bytes);            ///< sweeps::parse_spec, points::prepare
Outcome frame_json(std::string_view bytes);      ///< `slipwalk model`: a JSON frame, both laws
Outcome frame_batch(std::string_view bytes);     ///< `slipwalk model --robot`: a CSV batch
Outcome residual(std::string_view bytes);        ///< scene::parse_residual (a B file)
Outcome spring_support(std::string_view bytes);  ///< contact::spring_support on a decoded frame
Outcome coulomb(std::string_view bytes);         ///< friction::solve_coulomb on a decoded frame
Outcome plan_file(std::string_view bytes);       ///< planning::parse_plan_file, to_json
Outcome trial(std::string_view bytes);           ///< residual::parse_trials, predict
Outcome calibration_hanging(std::string_view bytes);  ///< calibration::parse_hanging, pairing
Outcome calibration_poses(std::string_view bytes);    ///< calibration::parse_poses

}  // namespace slipwalk::fuzz

#ifdef SLIPWALK_LIBFUZZER
#define SLIPWALK_FUZZ_ENTRY(target)                                                            \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {          \
    (void)slipwalk::fuzz::target(std::string_view(reinterpret_cast<const char*>(data), size)); \
    return 0;                                                                                  \
  }
#else
#define SLIPWALK_FUZZ_ENTRY(target)
#endif
