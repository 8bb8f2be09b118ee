// `markerbench tracker-worker SCENARIO --tracker-index I`: the worker process of a sweep's
// isolated tracker (trackers/isolated/isolated_tracker.h), started by the sweep itself.
#pragma once

#include <cstddef>
#include <string>

namespace markerbench {

// Serves the scenario's tracker `tracker_index` on kWorkerFd; returns the exit status.
int RunTrackerWorker(const std::string& scenario_path, size_t tracker_index);

}  // namespace markerbench
