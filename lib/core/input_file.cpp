#include "core/input_file.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.hpp"

namespace slipwalk::core {

std::string read_input_stream(std::istream& in, const std::string& source, std::string_view what,
                              std::size_t max_bytes) {
  std::string text;
  std::array<char, 65536> chunk{};
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      throw InputError(source, std::string(what) + " is longer than the limit of " +
                                   std::to_string(max_bytes) + " bytes");
    }
  }
  if (in.bad()) {
    throw InputError(source, "cannot read " + std::string(what));
  }
  return text;
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::size_t max_bytes) {
  const std::string source = path.string();
  if (source.empty()) {
    throw InputError("<empty path>", "no file named for " + std::string(what));
  }
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    throw InputError(source, "no such file (expected " + std::string(what) + ")");
  }
  if (status.type() == std::filesystem::file_type::directory) {
    throw InputError(source, "is a folder, not " + std::string(what));
  }
  // Opening a named pipe waits for a writer that may never come; a socket cannot be opened.
  if (status.type() == std::filesystem::file_type::fifo ||
      status.type() == std::filesystem::file_type::socket) {
    throw InputError(
        source, std::string("is a ") +
                    (status.type() == std::filesystem::file_type::fifo ? "named pipe" : "socket") +
                    ", not " + std::string(what));
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    std::string why = err != 0 ? std::string(std::strerror(err)) : std::string("cannot open");
    if (ec) {
      why = ec.message();
    }
    throw InputError(source, "cannot read " + std::string(what) + ": " + why);
  }
  return read_input_stream(in, source, what, max_bytes);
}

}  // namespace slipwalk::core
