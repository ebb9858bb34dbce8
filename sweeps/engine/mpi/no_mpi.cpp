// The MPI entry points of a build without MPI (CMake found none): a sweep under an MPI launcher,
// or one that asks for MPI, is refused with a message that says how to get it.
#include "core/error.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"

namespace slipwalk::sweeps::mpi {

namespace {
[[noreturn]] void unavailable() {
  throw core::InputError("MPI",
                         "this slipwalk was built without MPI support; install Debian's "
                         "openmpi-bin and libopenmpi-dev (make deps) and rebuild, or run "
                         "the sweep as shards (--shard k/n, then `slipwalk sweep merge`)");
}
}  // namespace

bool available() { return false; }

Session::Session() { unavailable(); }
Session::~Session() = default;
void Session::barrier() const {}

RunSummary run_sweep(const Session& /*session*/, const Setup& /*setup*/,
                     const Options& /*options*/) {
  unavailable();
}

}  // namespace slipwalk::sweeps::mpi
