#include "bench/run/sweep_trackers.h"

#include <unistd.h>

#include <filesystem>

#include "bench/plan/marker_files.h"
#include "trackers/external/external_tracker.h"
#include "trackers/isolated/isolated_tracker.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

bool HasExternalTrackers(const Scenario& scenario) {
  for (const TrackerEntry& t : scenario.trackers) {
    if (!t.exec.empty()) return true;
  }
  return false;
}

}  // namespace

SweepTrackerContext::SweepTrackerContext(const Scenario& scenario,
                                         const std::string& fingerprint,
                                         const std::string& run_dir)
    : scenario_(scenario), fingerprint_(fingerprint), run_dir_(fs::absolute(run_dir).string()) {
  if (!HasExternalTrackers(scenario)) return;
  marker_files_ = WriteScaledMarkerFiles(scenario, run_dir_ + "/markers");
  const fs::path tmpfs = "/dev/shm";
  const fs::path base = access(tmpfs.c_str(), W_OK) == 0 ? tmpfs : fs::temp_directory_path();
  image_dir_ = (base / ("markerbench-" + std::to_string(getpid()) + "-" + scenario.name)).string();
  for (size_t t = 0; t < scenario.trackers.size(); ++t) {
    if (!scenario.trackers[t].exec.empty()) MakeTracker(t);  // the handshake, then stopped
  }
  // Last: a constructor that throws leaves nothing to remove.
  fs::create_directories(image_dir_);
}

SweepTrackerContext::~SweepTrackerContext() {
  std::error_code ignored;
  if (!image_dir_.empty()) fs::remove_all(image_dir_, ignored);
}

std::unique_ptr<Tracker> SweepTrackerContext::MakeTracker(size_t index) const {
  const TrackerEntry& entry = scenario_.trackers.at(index);
  if (!entry.exec.empty()) {
    ExternalTrackerOptions options;
    options.name = entry.name;
    options.command = entry.exec;
    for (const size_t m : entry.markers) options.markers.push_back(scenario_.markers[m].name);
    options.timeout_s = entry.timeout_s;
    options.working_dir = entry.working_dir;
    options.stderr_path = run_dir_ + "/" + entry.name + ".stderr.log";
    options.image_dir = image_dir_;
    options.marker_files = marker_files_;
    return std::make_unique<ExternalTracker>(options);
  }
  std::unique_ptr<Tracker> local = MakeScenarioTracker(scenario_, entry);
  if (!entry.isolated) return local;
  IsolationOptions options;
  // The worker is this program's own build, also after a build during the sweep replaced its
  // file (by the file's path, a rebuilt program's worker, or none: its path then named nothing).
  options.worker_argv = {kThisProgram,
                         "tracker-worker",
                         scenario_.path,
                         "--tracker-index",
                         std::to_string(index),
                         "--fingerprint",
                         fingerprint_};
  for (const std::string& argument : scenario_.overrides.Arguments()) {
    options.worker_argv.push_back(argument);
  }
  options.timeout_s = entry.timeout_s;
  return std::make_unique<IsolatedTracker>(std::move(local), options);
}

}  // namespace markerbench
