// How `sweep --shard I/N` splits a scenario's plan among N machines. A shard takes the
// (cell, trial) pose groups g = cell × trials + trial with g mod N = I, every marker of each.
// Interleaved, not in blocks: a frame's cost varies with the sweep value (blur, distance,
// noise change the detectors' work by 10× and more) and with the marker, so blocks of the
// plan would give one shard the slow cells; interleaving gives each shard the same share of
// every cell and every marker, and keeps a pose group's common random numbers in one shard.
#pragma once

#include <string>

#include "bench/frame_plan.h"

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
