// `markerbench tracker-worker SCENARIO --tracker-index I --fingerprint F [--set KEY=VALUE]...
// [--trackers a,b]`: the worker process of a sweep's isolated tracker
// (trackers/isolated/isolated_tracker.h), started by the sweep itself with the sweep's
// overrides, so that index I names the same tracker of the same scenario.
#pragma once

#include <cstddef>
#include <string>

#include "bench/plan/scenario.h"

namespace markerbench {

// Serves the scenario's tracker `tracker_index` on kWorkerFd; returns the exit status (2 when
// the scenario's files no longer have the sweep's `fingerprint`: they changed during the run).
int RunTrackerWorker(const std::string& scenario_path,
                     const ScenarioOverrides& overrides,
                     size_t tracker_index,
                     const std::string& fingerprint);

}  // namespace markerbench
