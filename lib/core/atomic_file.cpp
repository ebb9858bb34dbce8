#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>

#include "core/error.hpp"

namespace slipwalk::core {

namespace {

// Linux's NAME_MAX and PATH_MAX; the temporary's suffix ".tmp.<pid>" needs room in the name.
constexpr std::size_t kNameMax = 255;
constexpr std::size_t kPathMax = 4096;
constexpr std::size_t kTempSuffixMax = 15;  // ".tmp." and a pid of up to 10 digits

std::ostream* g_notes = nullptr;

// The temporaries a signal handler must unlink. A slot is free (0), being filled or emptied (1)
// or holds a path (2); the handler reads only lock-free atomics and plain chars and calls only
// unlink, sigaction and raise, which are async-signal-safe. More open files than slots are
// simply not cleaned up on a signal (the next run reports them as stale).
constexpr int kSlots = 64;
struct Slot {
  std::atomic<int> state{0};
  std::array<char, kPathMax> path{};
};
std::array<Slot, kSlots> g_slots;
static_assert(std::atomic<int>::is_always_lock_free);

int register_temporary(const std::filesystem::path& temp) {
  const std::string& s = temp.native();
  if (s.size() >= kPathMax) {
    return -1;
  }
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = g_slots[static_cast<std::size_t>(i)];
    int expected = 0;
    if (slot.state.compare_exchange_strong(expected, 1)) {
      std::memcpy(slot.path.data(), s.c_str(), s.size() + 1);
      slot.state.store(2, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temporary(int i) {
  if (i >= 0) {
    Slot& slot = g_slots[static_cast<std::size_t>(i)];
    slot.state.store(1);
    slot.state.store(0, std::memory_order_release);
  }
}

// The farewell of set_signal_farewell(): state 0 none, 1 being written, 2 set.
std::atomic<int> g_farewell_state{0};
std::array<char, 2048> g_farewell{};
std::size_t g_farewell_size = 0;
int g_farewell_code = 1;

std::atomic<bool> g_handling{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void unlink_temporaries_and_reraise(int sig) {
  // A second signal (the launcher's SIGTERM after its SIGINT, or one on another thread) while the
  // first is handled: the first finishes the job, and says its farewell once.
  if (g_handling.exchange(true)) {
    return;
  }
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == 2) {
      ::unlink(slot.path.data());
    }
  }
  if (g_farewell_state.load(std::memory_order_acquire) == 2) {
    const ssize_t written = ::write(2, g_farewell.data(), g_farewell_size);
    (void)written;  // nothing more can be done about a failed write here
    ::_exit(g_farewell_code);
  }
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;  // NOLINT(cppcoreguidelines-pro-type-union-access)
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);
}

std::string quoted(const std::filesystem::path& p) {
  std::string text(1, '\'');
  text.append(p.native()).push_back('\'');
  return text;
}

std::string errno_text(int err) { return err != 0 ? std::string(": ") + std::strerror(err) : ""; }

bool all_digits(std::string_view s) {
  if (s.empty() || s.size() > 10) {
    return false;
  }
  for (const char c : s) {
    if (c < '0' || c > '9') {
      return false;
    }
  }
  return true;
}

}  // namespace

void check_output_path(const std::filesystem::path& target, const std::string& option,
                       std::span<const std::filesystem::path> inputs, bool create_parents) {
  namespace fs = std::filesystem;
  const std::string& text = target.native();
  if (text.empty()) {
    throw InputError(option, "expected a file name, got an empty string");
  }
  std::error_code ec;
  const fs::path name = target.filename();
  if (text.back() == '/' || name == "." || name == ".." || fs::is_directory(target, ec)) {
    throw InputError(option, quoted(target) + " is a folder; expected a file name");
  }
  if (name.native().size() + kTempSuffixMax > kNameMax) {
    throw InputError(option, "file name too long (" + std::to_string(name.native().size()) +
                                 " characters; at most " +
                                 std::to_string(kNameMax - kTempSuffixMax) + ")");
  }
  if (text.size() + kTempSuffixMax >= kPathMax) {
    throw InputError(option, "path too long (" + std::to_string(text.size()) +
                                 " characters; at most " +
                                 std::to_string(kPathMax - kTempSuffixMax - 1) + ")");
  }
  const fs::file_status st = fs::status(target, ec);
  const bool exists = fs::exists(st);
  // A device or pipe is written in place: its folder need not be writable.
  if (!exists || fs::is_regular_file(st)) {
    fs::path parent = target.parent_path();
    if (parent.empty()) {
      parent = ".";
    }
    while (create_parents && !fs::exists(parent, ec) && parent.has_relative_path() &&
           parent != parent.parent_path()) {
      parent = parent.parent_path();
      if (parent.empty()) {
        parent = ".";
      }
    }
    if (!fs::exists(parent, ec)) {
      throw InputError(option, "the folder " + quoted(parent) + " does not exist");
    }
    if (!fs::is_directory(parent, ec)) {
      throw InputError(option, quoted(parent) + " is not a folder");
    }
    if (::access(parent.c_str(), W_OK | X_OK) != 0) {
      throw InputError(option,
                       "the folder " + quoted(parent) + " is not writable" + errno_text(errno));
    }
  }
  if (exists) {
    for (const fs::path& input : inputs) {
      if (!input.empty() && input != "-" && fs::equivalent(target, input, ec)) {
        throw InputError(option, quoted(target) + " is the input file " + quoted(input) +
                                     "; refusing to overwrite it");
      }
    }
  }
}

void check_output_dir(const std::filesystem::path& dir, const std::string& option) {
  if (dir.empty()) {
    throw InputError(option, "expected a folder, got an empty string");
  }
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw InputError(option, quoted(dir) + " exists and is not a folder");
  }
  if (dir.native().size() + 2 * kNameMax >= kPathMax) {
    throw InputError(option,
                     "path too long (" + std::to_string(dir.native().size()) + " characters)");
  }
  for (const auto& part : dir) {
    if (part.native().size() > kNameMax) {
      throw InputError(option, "folder name too long (" + std::to_string(part.native().size()) +
                                   " characters; at most " + std::to_string(kNameMax) + ")");
    }
  }
}

void set_note_stream(std::ostream* notes) { g_notes = notes; }

void set_signal_farewell(const std::string& message, int exit_code) {
  g_farewell_state.store(1);
  const std::string line = message.empty() ? std::string() : message + "\n";
  g_farewell_size = std::min(line.size(), g_farewell.size());
  std::memcpy(g_farewell.data(), line.data(), g_farewell_size);
  g_farewell_code = exit_code;
  g_farewell_state.store(message.empty() ? 0 : 2, std::memory_order_release);
}

void install_signal_cleanup() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = unlink_temporaries_and_reraise;  // NOLINT(*-pro-type-union-access)
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
    return true;
  }();
  (void)installed;
}

std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  std::vector<fs::path> removed;
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".tmp.";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !all_digits(std::string_view(name).substr(prefix.size())) ||
        !it->is_regular_file(ec)) {
      continue;
    }
    const long pid = std::stol(name.substr(prefix.size()));
    // Only a process that is gone: a live one (or a reused pid) keeps its file.
    if (pid <= 0 || pid > 0x7fffffffL || pid == ::getpid() ||
        ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) {
      continue;
    }
    std::error_code rm;
    if (fs::remove(it->path(), rm)) {
      removed.push_back(it->path());
      if (g_notes != nullptr) {
        *g_notes << "slipwalk: note: removed " << quoted(it->path()) << ", left by process " << pid
                 << " that was killed while writing\n";
      }
    }
  }
  return removed;
}

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temp_(target_.string() + ".tmp." + std::to_string(::getpid())) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(target_, ec);
  if (fs::is_directory(st)) {
    throw InputError(target_.string(), "is a folder; expected a file name");
  }
  in_place_ = fs::exists(st) && !fs::is_regular_file(st);
  if (in_place_) {
    out_.open(target_, std::ios::out | std::ios::trunc);
    if (!out_) {
      throw InputError(target_.string(), "cannot open for writing" + errno_text(errno));
    }
    out_.precision(17);
    return;
  }
  // Missing folders are created, and remembered so that a failure removes them again.
  for (fs::path p = target_.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created_dirs_.insert(created_dirs_.begin(), p);
    if (p == p.parent_path()) {
      break;
    }
  }
  for (const fs::path& p : created_dirs_) {
    fs::create_directory(p, ec);
  }
  remove_stale_temporaries(target_);
  slot_ = register_temporary(temp_);
  out_.open(temp_, std::ios::out | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    unregister_temporary(slot_);
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
      fs::remove(*it, ec);
    }
    throw InputError(target_.string(), "cannot open for writing" + errno_text(err));
  }
  out_.precision(17);
}

AtomicFile::~AtomicFile() {
  if (committed_) {
    return;
  }
  out_.close();
  std::error_code ec;
  if (!in_place_) {
    std::filesystem::remove(temp_, ec);
  }
  unregister_temporary(slot_);
  // Only folders left empty go (remove() refuses a non-empty one).
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    std::filesystem::remove(*it, ec);
  }
}

void AtomicFile::check() const {
  if (!out_) {
    throw ComputationError(target_.string() + ": write failed" + errno_text(errno));
  }
}

void AtomicFile::finish() {
  if (finished_) {
    return;
  }
  errno = 0;
  out_.flush();
  bool ok = static_cast<bool>(out_);
  int err = ok ? 0 : errno;
  out_.close();
  if (ok && out_.fail()) {
    ok = false;
    err = errno;
  }
  if (ok && !in_place_) {
    // The data reach the disk before the rename makes them visible under the target's name.
    const int fd = ::open(temp_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
      ok = false;
      err = errno;
    }
    if (fd >= 0) {
      ::close(fd);
    }
  }
  if (!ok) {
    throw ComputationError(target_.string() + ": write failed" + errno_text(err));
  }
  finished_ = true;
}

void AtomicFile::commit() {
  finish();
  if (!in_place_) {
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) {
      throw ComputationError(target_.string() + ": cannot rename temporary file: " + ec.message());
    }
    unregister_temporary(slot_);
  }
  committed_ = true;
}

void commit_with_sidecar(AtomicFile& result, AtomicFile& sidecar) {
  result.finish();
  sidecar.finish();
  std::error_code ec;
  if (std::filesystem::is_regular_file(result.target(), ec)) {
    std::filesystem::remove(result.target(), ec);
    if (ec) {
      throw ComputationError(result.target().string() +
                             ": cannot replace the earlier result: " + ec.message());
    }
  }
  sidecar.commit();
  result.commit();
}

void write_file_atomically(const std::filesystem::path& target, const std::string& text) {
  AtomicFile file(target);
  file.stream() << text;
  file.commit();
}

}  // namespace slipwalk::core
