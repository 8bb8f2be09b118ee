#include "bench/tracker_worker_command.h"

#include <cstdio>
#include <filesystem>

#include "trackers/isolated/isolated_tracker.h"
#include "trackers/isolated/tracker_worker.h"
#include "trackers/isolated/worker_protocol.h"

namespace markerbench {

int RunTrackerWorker(const std::string& scenario_path, size_t tracker_index) {
  const Scenario scenario = LoadScenario(scenario_path);
  if (tracker_index >= scenario.trackers.size()) {
    std::fprintf(
        stderr, "tracker-worker: %s has no tracker %zu\n", scenario_path.c_str(), tracker_index);
    return 2;
  }
  const std::unique_ptr<Tracker> tracker =
      MakeScenarioTracker(scenario, scenario.trackers[tracker_index]);
  return ServeTrackerWorker(tracker.get(), scenario.markers, kWorkerFd);
}

std::unique_ptr<Tracker> MakeSweepTracker(const Scenario& scenario, size_t index) {
  const TrackerEntry& entry = scenario.trackers.at(index);
  std::unique_ptr<Tracker> local = MakeScenarioTracker(scenario, entry);
  if (!entry.isolated) return local;
  IsolationOptions options;
  options.worker_argv = {std::filesystem::read_symlink("/proc/self/exe").string(),
                         "tracker-worker",
                         scenario.path,
                         "--tracker-index",
                         std::to_string(index)};
  options.timeout_s = entry.timeout_s;
  return std::make_unique<IsolatedTracker>(std::move(local), options);
}

}  // namespace markerbench
