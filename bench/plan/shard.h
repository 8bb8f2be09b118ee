// How `sweep --shard I/N` splits a scenario's plan among N machines. A shard takes the
// (cell, trial) pose groups g = cell × trials + trial with g mod N = I, every marker of each.
// Interleaved, not in blocks: a tracker's time changes with the sweep value (artkplus takes
// 2.1 ms a frame at blur σ ≤ 2 and 7.6 ms from σ 3 on), so blocks of the plan would give the
// shards of slow values more work, while interleaving gives every shard the same share of
// each value; a whole job waits for its slowest shard (results/speed.md, "Shards").
#pragma once

#include <string>

#include "bench/plan/frame_plan.h"

namespace markerbench {

struct Shard {
  int index = 0;  // 0 .. count-1
  int count = 1;
};

// "I/N" with 0 <= I < N; throws ConfigError naming `option` otherwise.
Shard ParseShard(const std::string& text, const std::string& option = "--shard");

// Whether `frame` of a scenario with `trials` trials per value belongs to `shard`.
bool InShard(const PlannedFrame& frame, int trials, const Shard& shard);

}  // namespace markerbench
