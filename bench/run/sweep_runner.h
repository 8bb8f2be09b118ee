// markerbench sweep: runs scenarios into DIR/<scenario name>/ (architecture.md, "Data flow").
// Each planned frame is rendered once and shared by every tracker that can track its marker;
// a thread pool does the work with one tracker instance per thread. Rows are appended to
// frames.csv in plan order as frames finish, one write() per frame, so a killed run keeps
// every finished frame and --resume continues to the same bytes as an uninterrupted run.
#pragma once

#include <string>
#include <vector>

#include "bench/plan/scenario.h"
#include "bench/plan/shard.h"

namespace markerbench {

constexpr int kMaxThreads = 1024;

struct SweepOptions {
  std::string out_dir;
  int threads = 0;         // 0: every hardware thread; at most kMaxThreads
  bool resume = false;     // continue a killed run of the same scenario
  bool overwrite = false;  // start again over an earlier run
  Shard shard;             // run only this shard of each scenario's plan (bench/plan/shard.h)
  // Once a scenario is complete, replace frames.csv and timing.csv by frames.csv.zst and
  // timing.csv.zst (every command reads both forms).
  bool compress = false;
  // Applied to every scenario (bench/plan/scenario.h); recorded in the manifest.
  ScenarioOverrides overrides;
};

// Loads and checks every scenario before writing anything (bad input: ConfigError), locks
// DIR (DIR/markerbench.lock: a second sweep into DIR is a ConfigError), then runs them one
// after another. Writes, per scenario, frames.csv, timing.csv, run.json (the scenario's
// fingerprint, the shard, and whether the run is complete) and examples/<marker>.png (trial 0
// at the example value), and updates DIR/manifest.json.
void RunSweeps(const std::vector<std::string>& scenario_paths, const SweepOptions& options);

}  // namespace markerbench
