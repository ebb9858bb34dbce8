#include "inchworm/trace_file.hpp"

#include "core/atomic_file.hpp"

namespace slipwalk::inchworm {

void write_trace_file(const Params& params, Method method, const TraceOptions& options,
                      const std::filesystem::path& path) {
  core::AtomicFile file(path);
  write_trace(params, method, options, file.stream());
  file.commit();
}

}  // namespace slipwalk::inchworm
