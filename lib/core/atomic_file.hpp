#pragma once
// Outputs are written to a temporary name beside the target and renamed when complete, so a
// reader never sees a partial file and a failed run leaves nothing behind (DESIGN.md).
#include <filesystem>
#include <fstream>
#include <string>

namespace slipwalk::core {

class AtomicFile {
 public:
  /// Opens `<path>.tmp.<pid>` for writing; throws InputError if the folder is not writable.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary file unless commit() was called.
  ~AtomicFile();

  std::ofstream& stream() { return out_; }
  /// Flushes, closes and renames onto the target. Throws ComputationError on I/O failure.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `text` to `target` atomically.
void write_file_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace slipwalk::core
