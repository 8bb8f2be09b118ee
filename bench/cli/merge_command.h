// markerbench merge: the N shards of a sweep (sweep --shard I/N, each in its own --out
// folder, possibly on other machines) back into one run folder, whose frames.csv is
// byte-identical to a single-machine sweep of the scenario, so `report` and `check` read it
// as any run. Streams: memory grows with the number of shards, not with the rows.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace markerbench {

struct MergeOptions {
  std::vector<std::string> shard_dirs;  // the shards' --out folders, in any order
  std::string out_dir;
  bool compress = false;   // write frames.csv.zst and timing.csv.zst
  bool overwrite = false;  // replace a scenario folder an earlier merge wrote in out_dir
};

// Merges every scenario found in the shard folders. Checks first, writes nothing on failure:
// every shard of a scenario must come from one plan (the same fingerprint of the scenario's
// files and the same N), be present once and be complete; otherwise ConfigError naming the
// shards missing, given twice, incomplete or of another scenario. Writes
// OUT/<scenario>/{frames.csv, timing.csv, run.json, examples/} and OUT/manifest.json; logs
// warnings (shards built from different commits) to `log`.
void MergeShards(const MergeOptions& options, std::ostream& log);

}  // namespace markerbench
