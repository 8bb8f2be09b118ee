// How a sweep makes its trackers: in-process, in an isolated worker process, or as an
// external program (README, "Scenario" and "Benchmark your own tracker").
#pragma once

#include <map>
#include <memory>
#include <string>

#include "bench/plan/scenario.h"

namespace markerbench {

// What a scenario's external trackers need during a run. Removes its image folder when
// destroyed.
class SweepTrackerContext {
 public:
  // For a run into `run_dir` (DIR/<scenario>): writes each marker's file as the trackers see
  // it (run_dir/markers/<name>.yaml, with the scenario's equal-area `scale`), makes a
  // temporary image folder (on tmpfs where there is one) and starts each external tracker
  // once to check its handshake: a ConfigError before any frame. Nothing for scenarios
  // without external trackers.
  // `fingerprint` (bench/plan/scenario.h) is checked again by isolated trackers' workers, which
  // load the scenario themselves.
  SweepTrackerContext(const Scenario& scenario,
                      const std::string& fingerprint,
                      const std::string& run_dir);
  ~SweepTrackerContext();
  SweepTrackerContext(const SweepTrackerContext&) = delete;
  SweepTrackerContext& operator=(const SweepTrackerContext&) = delete;

  // The tracker for `scenario.trackers[index]`.
  std::unique_ptr<Tracker> MakeTracker(size_t index) const;

 private:
  const Scenario& scenario_;
  std::string fingerprint_;
  std::string run_dir_;
  std::string image_dir_;
  std::map<std::string, std::string> marker_files_;
};

}  // namespace markerbench
