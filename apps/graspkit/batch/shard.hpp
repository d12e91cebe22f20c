#pragma once
// Which share of the objects this process of graspkit batch takes: --shard K/N, else the task of a
// Slurm job array (SLURM_ARRAY_TASK_ID, _COUNT, _MIN), else all of them.

#include <string>

namespace graspkit::cli {

struct Shard {
  int index = 0;  // 0-based
  int count = 1;
};

inline constexpr long long kMaxShards = 1'000'000;

// --shard K/N (1-based K, N up to kMaxShards), else a Slurm job array's task, else the whole
// set. Throws graspkit::Error naming the flag or the Slurm variables when they are not a share.
Shard shardOf(const std::string& text);

}  // namespace graspkit::cli
