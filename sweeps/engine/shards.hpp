#pragma once
// Shards for clusters that schedule job arrays: `slipwalk sweep SPEC --shard k/n` runs the k-th
// of n deterministic shards (checkpoint.hpp: Shard) into `<name>.shard-k-of-n.csv` and its
// sidecar, and `slipwalk sweep merge SPEC` combines the n shards into exactly the CSV a single
// run writes (rows by id; the bytes are the same apart from the timing columns) and a sidecar
// that lists every shard's provenance. Each shard checkpoints and resumes on its own.
#include <filesystem>
#include <optional>

#include "sweeps/engine/runner.hpp"

namespace slipwalk::sweeps {

struct MergeOptions {
  std::filesystem::path data_dir = "data";  ///< where the shards are and the result goes
  std::optional<long long> shards;  ///< the shard count n; none: the one count found on disk
  bool keep_shards = false;         ///< keep the shard files after a successful merge
};

struct MergeSummary {
  std::filesystem::path csv;
  std::filesystem::path sidecar;
  long long points = 0;
  long long failed = 0;
  long long at_budget = 0;
  long long shards = 0;
};

/// Merges the shards of `sweep` found under `options.data_dir`. Throws core::InputError, having
/// written nothing, when a shard is missing or unfinished (the message names it and how to finish
/// it), was written for another spec or by another build, or is malformed (file:line).
MergeSummary merge_shards(const PreparedSweep& sweep, const MergeOptions& options);

}  // namespace slipwalk::sweeps
