// Whether an MPI launcher started this process: built with or without MPI, so that a build
// without it refuses a sweep under mpirun instead of running the whole sweep once per rank.
#include <cstdlib>

#include "sweeps/engine/mpi/mpi_run.hpp"

namespace slipwalk::sweeps::mpi {

bool launched() {
  // Open MPI's mpirun, PMIx launchers (Open MPI 4 and 5, Slurm's srun --mpi=pmix) and PMI-1/2
  // launchers (MPICH's Hydra, srun --mpi=pmi2).
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) {  // NOLINT(concurrency-mt-unsafe): read before threads
      return true;
    }
  }
  return false;
}

int launched_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    const char* value = std::getenv(name);  // NOLINT(concurrency-mt-unsafe): read before threads
    if (value != nullptr) {
      char* end = nullptr;
      const long rank = std::strtol(value, &end, 10);
      return end != value && *end == '\0' && rank >= 0 && rank < 1'000'000'000
                 ? static_cast<int>(rank)
                 : -1;
    }
  }
  return -1;
}

}  // namespace slipwalk::sweeps::mpi
