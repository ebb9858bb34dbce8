#include "core/atomic_file.hpp"

#include <unistd.h>

#include "core/error.hpp"

namespace slipwalk::core {

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temp_(target_.string() + ".tmp." + std::to_string(::getpid())) {
  if (target_.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(target_.parent_path(), ec);
  }
  out_.open(temp_, std::ios::out | std::ios::trunc);
  if (!out_) {
    throw InputError(target_.string(), "cannot open for writing");
  }
  out_.precision(17);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok) {
    throw ComputationError(target_.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    throw ComputationError(target_.string() + ": cannot rename temporary file: " + ec.message());
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& target, const std::string& text) {
  AtomicFile file(target);
  file.stream() << text;
  file.commit();
}

}  // namespace slipwalk::core
