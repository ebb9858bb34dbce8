#pragma once
// Outputs are written to a temporary name beside the target and renamed when complete, so a
// reader never sees a partial file and a failed run leaves nothing behind (DESIGN.md). Every
// output of the binary goes through AtomicFile, which
//  - is preceded by check_output_path(), run before any work, so that a destination that cannot
//    be written is bad input (exit 2) naming the option, not a library message after the work;
//  - removes its temporary, and the folders it created, on any failure, and on SIGINT/SIGTERM
//    once install_signal_cleanup() has run (the handler unlinks the registered temporaries and
//    re-raises, so the exit status still says which signal ended the process);
//  - removes stale `<target>.tmp.<pid>` files of processes that no longer run (a SIGKILL leaves
//    them), with a one-line note to the stream set by set_note_stream().
// A target that exists and is not a regular file (/dev/null, /dev/full, a pipe) is written in
// place: it cannot be half-written in the sense a file can, and renaming onto it would replace
// the device node.
#include <filesystem>
#include <fstream>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace slipwalk::core {

/// Refuses an output destination before any work, throwing InputError(option, ...): an empty
/// name, a directory (or a name ending in '/'), a missing parent folder or one that is not a
/// folder, a file name too long for the file system (with room for the temporary's suffix), or
/// the same file as one of `inputs` (std::filesystem::equivalent). With `create_parents` a
/// missing parent is allowed (it is created when the file is opened).
void check_output_path(const std::filesystem::path& target, const std::string& option,
                       std::span<const std::filesystem::path> inputs = {},
                       bool create_parents = false);

/// Refuses an output folder before any work: empty, or an existing path that is not a folder.
void check_output_dir(const std::filesystem::path& dir, const std::string& option);

/// Where notes about removed stale temporaries go (nullptr: removed silently; the default).
void set_note_stream(std::ostream* notes);

/// Installs SIGINT and SIGTERM handlers that unlink every open AtomicFile's temporary and then
/// re-raise the signal with its default action. Idempotent.
void install_signal_cleanup();

/// Once set, a SIGINT or SIGTERM handled by install_signal_cleanup()'s handler writes `message`
/// (and a newline) to stderr after the temporaries are gone and ends the process with
/// `exit_code` instead of re-raising: how a process that is told to stop by its launcher (an MPI
/// runtime ending a job whose rank died) says what it kept. An empty message unsets it.
void set_signal_farewell(const std::string& message, int exit_code);

/// Removes `<target>.tmp.<pid>` files beside `target` whose process no longer runs; returns them.
std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path& target);

class AtomicFile {
 public:
  /// Opens `<path>.tmp.<pid>` for writing (creating missing parent folders); throws InputError if
  /// it cannot be opened.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary file (and the folders the constructor created) unless committed.
  ~AtomicFile();

  std::ofstream& stream() { return out_; }
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// Throws ComputationError if a write has failed so far (call it in long write loops, so that a
  /// full disk stops the run rather than the end of it).
  void check() const;
  /// Flushes, closes and syncs the temporary; throws ComputationError on any I/O failure. After
  /// finish() only the rename is left, so that several files can be finished first and renamed
  /// together.
  void finish();
  /// finish() if not yet done, then renames onto the target. Throws ComputationError on failure.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::vector<std::filesystem::path> created_dirs_;  // deepest last
  std::ofstream out_;
  int slot_ = -1;          // the signal handler's registry slot of temp_, -1 if none
  bool in_place_ = false;  // target is a device or pipe: written directly
  bool finished_ = false;
  bool committed_ = false;
};

/// Commits a result file and its sidecar so that a reader never sees the result without its own
/// sidecar: both are finished first, then an earlier result at the target is removed, the sidecar
/// renamed, and the result renamed last. A process killed in between leaves at most a sidecar
/// without its result, which every reader takes as no result (the next run replaces it).
void commit_with_sidecar(AtomicFile& result, AtomicFile& sidecar);

/// Writes `text` to `target` atomically.
void write_file_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace slipwalk::core
