#pragma once
// A hostile-input campaign against the `slipwalk` binary itself (DESIGN.md: Command line): six
// classes of inputs a hostile user would try, each generated from a seed, each case run as a
// subprocess in a fresh temporary folder and judged against the command-line contract:
//
//   exit 0  the requested output is there, complete, every number in it finite;
//   exit 1  the computation could not finish, with a `slipwalk: error:` message;
//   exit 2  bad input, the message names the option or the file (with line where a file's value
//           is at fault), and is short (never the input re-serialised);
//   never   a death by a signal we did not send (a crash), a run past its wall-time limit or one
//           writing without bound (a hang), a zero exit on a full device, a changed input file,
//           or files left beyond what the contract allows (the outputs on success, a sweep's
//           checkpoint after SIGINT/SIGTERM, a temporary after SIGKILL that the next run removes).
//
// One table (classes()) holds the classes: id, title, generator. The generators build cases from
// a few blocks (a template input, a field or option, a hostile value), so a class is sampled,
// not listed; case `i` of a class with seed `s` is the same on every machine, which makes every
// failure replayable. The point kind `hostile_inputs` (one point = class, seed, first, count) and
// tests/sweeps/test_hostile_inputs.cpp run the same cases.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace slipwalk::sweeps::hostile {

/// A file the case writes into its folder before the run.
struct InputFile {
  std::string name;    ///< relative to the case folder
  std::string text;    ///< its bytes
  std::string recipe;  ///< a shell line that writes it, for long files (replays); "" = printf
};

/// One invocation of the binary, in the case folder as its working directory.
struct Invocation {
  std::vector<std::string> args;  ///< after the binary's name
  std::string stdin_file;         ///< relative name, or "" for /dev/null
  std::string stdout_to;          ///< "" to capture, or a device path (/dev/full)
  int signal = 0;                 ///< sent after signal_after_s (0: none)
  double signal_after_s = 0.0;
};

/// What the twin run of a case (its second invocation) must show.
enum class Twin {
  kNone,
  kCleanAfterKill,  ///< the same command after a SIGKILL: exit 0, the stale temporary gone
  kResume,          ///< a sweep resumed after a signal: exit 0, every point exactly once
  kSameOutput,      ///< the same data written another way (CRLF): exit 0 and the same output
};

/// How an exit-0 output is read for non-finite numbers.
enum class Output { kNone, kJson, kText, kCsv };

struct Case {
  std::string title;  ///< what was generated, in a few words
  std::vector<InputFile> files;
  std::vector<std::string> folders;  ///< made before the run (inputs that are folders)
  std::vector<std::string> fifos;    ///< named pipes (inputs that never deliver)
  std::vector<std::pair<std::string, std::string>> symlinks;  ///< (link, target)
  Invocation run;
  std::set<int> exits = {0, 1, 2};  ///< the exit codes the contract allows for this input
  std::string place;                ///< an exit-2 message must contain it ("" = any)
  bool place_line = false;          ///< ... followed by ":<line>"
  /// Other places an exit-2 message may name instead (an option bound to the one set by a
  /// relation, such as M > m or F > μ_s m g, may be the one named).
  std::vector<std::string> also;
  std::vector<std::string> outputs;  ///< what exit 0 must leave (relative paths)
  std::string output;                ///< the output judged for non-finite numbers ("" = stdout)
  Output output_kind = Output::kNone;
  std::vector<std::string> after_signal;  ///< name prefixes allowed to stay after our signal
  Twin twin = Twin::kNone;
  Invocation second;            ///< the twin run
  std::string twin_output;      ///< kSameOutput: the twin's output file ("" = stdout)
  long long resume_points = 0;  ///< kResume: rows the finished CSV must hold
  double limit_s = 10.0;        ///< wall-time limit of each invocation
};

/// One class of the table.
struct HostileClass {
  std::string id;
  std::string title;  ///< as the report names it
  std::string what;   ///< what its generator varies
  Case (*generate)(std::uint64_t seed, long long index);
};

/// The six classes, in the order of the report.
[[nodiscard]] const std::vector<HostileClass>& classes();
[[nodiscard]] const HostileClass* find_class(const std::string& id);

/// The faults a case can show; a clean case has none.
struct Verdict {
  bool crash = false;          ///< died of a signal we did not send, or exit >= 128 of its own
  bool hang = false;           ///< past its limit, or writing without bound
  bool wrong_exit = false;     ///< an exit code the contract does not allow here
  bool no_place = false;       ///< exit 1/2 without a message, or exit 2 not naming the place
  bool false_success = false;  ///< exit 0 with a non-finite or missing output, or on /dev/full
  bool clobbered = false;      ///< an input file changed
  bool leftovers = false;      ///< files left that the contract does not allow
  double wall_s = 0.0;         ///< the longest invocation
  std::string detail;          ///< what was wrong, one line

  [[nodiscard]] bool clean() const {
    return !(crash || hang || wrong_exit || no_place || false_success || clobbered || leftovers);
  }
};

/// Runs `c` with the binary at `binary` in a fresh folder under `scratch` (removed after).
[[nodiscard]] Verdict run_case(const std::filesystem::path& binary, const Case& c,
                               const std::filesystem::path& scratch);

/// A shell line that recreates the case's folder and runs it (`slipwalk` for the binary).
[[nodiscard]] std::string replay_line(const Case& c);

/// The totals of a run of cases of one class.
struct Tally {
  long long tried = 0;
  long long ok = 0;
  long long crashes = 0;
  long long hangs = 0;
  long long wrong_exit = 0;
  long long no_place = 0;
  long long false_success = 0;
  long long clobbered = 0;
  long long leftovers = 0;
  double max_wall_s = 0.0;
  std::string first_failure;  ///< "case N (title): detail | replay line" of the first bad case
  void add(long long index, const Case& c, const Verdict& v);
};

}  // namespace slipwalk::sweeps::hostile
