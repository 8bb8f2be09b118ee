#include "bench/cli/tracker_worker_command.h"

#include <cstdio>
#include <memory>

#include "bench/plan/scenario.h"
#include "trackers/isolated/tracker_worker.h"
#include "trackers/isolated/worker_protocol.h"

namespace markerbench {

int RunTrackerWorker(const std::string& scenario_path,
                     const ScenarioOverrides& overrides,
                     size_t tracker_index,
                     const std::string& fingerprint) {
  const Scenario scenario = LoadScenario(scenario_path, overrides);
  if (Fingerprint(InputHashes(scenario)) != fingerprint) {
    std::fprintf(stderr,
                 "tracker-worker: %s or its files changed since the sweep started; not serving\n",
                 scenario_path.c_str());
    return 2;
  }
  if (tracker_index >= scenario.trackers.size()) {
    std::fprintf(
        stderr, "tracker-worker: %s has no tracker %zu\n", scenario_path.c_str(), tracker_index);
    return 2;
  }
  const std::unique_ptr<Tracker> tracker =
      MakeScenarioTracker(scenario, scenario.trackers[tracker_index]);
  return ServeTrackerWorker(tracker.get(), scenario.markers, kWorkerFd);
}

}  // namespace markerbench
