#pragma once
// A trace (inchworm/trace.hpp) written to a file whole or not at all: a temporary file renamed
// when complete, so an interrupted or failed trace leaves no partial CSV behind.
#include <filesystem>

#include "inchworm/params.hpp"
#include "inchworm/trace.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {

/// Writes write_trace(params, method, options) to `path` (creating its folder). Throws
/// core::InputError(path) when the file cannot be opened, core::ComputationError when the trace
/// stops early or the write fails (no file is left then).
void write_trace_file(const Params& params, Method method, const TraceOptions& options,
                      const std::filesystem::path& path);

}  // namespace slipwalk::inchworm
