// `markerbench tracker-worker SCENARIO --tracker-index I --fingerprint F`: the worker process
// of a sweep's isolated tracker (trackers/isolated/isolated_tracker.h), started by the sweep
// itself.
#pragma once

#include <cstddef>
#include <string>

namespace markerbench {

// Serves the scenario's tracker `tracker_index` on kWorkerFd; returns the exit status (2 when
// the scenario's files no longer have the sweep's `fingerprint`: they changed during the run).
int RunTrackerWorker(const std::string& scenario_path,
                     size_t tracker_index,
                     const std::string& fingerprint);

}  // namespace markerbench
