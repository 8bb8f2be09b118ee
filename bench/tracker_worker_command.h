// `markerbench tracker-worker SCENARIO --tracker-index I`: the worker process of a sweep's
// isolated tracker (trackers/isolated/isolated_tracker.h), started by the sweep itself.
#pragma once

#include <memory>
#include <string>

#include "bench/scenario.h"

namespace markerbench {

// Serves the scenario's tracker `tracker_index` on kWorkerFd; returns the exit status.
int RunTrackerWorker(const std::string& scenario_path, size_t tracker_index);

// The tracker a sweep runs for `scenario.trackers[index]`: in a worker process of this
// program when the entry is isolated, else in-process.
std::unique_ptr<Tracker> MakeSweepTracker(const Scenario& scenario, size_t index);

}  // namespace markerbench
