#pragma once
// The one way the project reads an input file whole (scene, spec, study, robot, frame and
// residual files): whatever the path names, the reader either returns its text or throws an
// InputError (exit 2) that names the path and says what is wrong — missing, a folder, unreadable,
// or longer than a limit — before any of it is parsed. The limit also bounds a path that never
// ends (/dev/zero, a pipe that keeps writing).
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>

namespace slipwalk::core {

/// The longest input file accepted. Our largest inputs are robot/frame JSON (a frame of 100,000
/// legs is about 25 MB); scene and spec files are a few kB.
inline constexpr std::size_t kInputMaxBytes = std::size_t{64} << 20;

/// All of `in` as text. `source` names it in errors ("<stdin>", a path); `what` says what it was
/// meant to be ("the scene file"). Throws InputError(source, ...) once the text passes
/// `max_bytes` or when the stream fails.
[[nodiscard]] std::string read_input_stream(std::istream& in, const std::string& source,
                                            std::string_view what,
                                            std::size_t max_bytes = kInputMaxBytes);

/// The text of the file at `path`: InputError(path, ...) when it does not exist, is a folder, a
/// named pipe or a socket,
/// cannot be opened or read (the system's reason is given), or is longer than `max_bytes`.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                                          std::size_t max_bytes = kInputMaxBytes);

}  // namespace slipwalk::core
