#pragma once
// Helpers for the command-line tests: run the slipwalk binary with captured stdout, stderr and
// exit code, and a scratch folder removed at the end of each test.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace slipwalk::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Single-quotes an argument for /bin/sh.
inline std::string shell_quote(const std::string& arg) {
  std::string out = "'";
  for (char c : arg) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

/// A fresh folder under the system temp folder, removed by the destructor.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "slipwalk_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("mkdtemp failed");
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

/// Runs a shell command line (its arguments already quoted), stdin from /dev/null, capturing
/// stdout and stderr.
inline CommandResult run_command_line(const std::string& line) {
  const ScratchDir capture;
  std::string command = line;
  command.append(" >").append(shell_quote((capture / "out").string()));
  command.append(" 2>").append(shell_quote((capture / "err").string()));
  command.append(" </dev/null");
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(capture / "out");
  r.err = read_text(capture / "err");
  return r;
}

/// Runs SLIPWALK_BINARY with `args` (each quoted), capturing stdout and stderr.
inline CommandResult run_slipwalk(const std::vector<std::string>& args) {
  std::string command = shell_quote(SLIPWALK_BINARY);
  for (const auto& a : args) {
    command += ' ';
    command += shell_quote(a);
  }
  return run_command_line(command);
}

/// Files in a folder (recursively), relative paths, sorted; empty if it does not exist.
inline std::vector<std::string> files_under(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) {
    return out;
  }
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) {
      out.push_back(std::filesystem::relative(e.path(), dir).string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace slipwalk::testing
