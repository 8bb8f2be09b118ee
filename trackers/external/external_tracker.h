// A tracker that is another program (README, "Benchmark your own tracker"): protocol 1,
// JSON Lines on the child's standard input and output, one request and one reply per frame,
// each frame's image in a PNG file. The child starts with the tracker and again after any
// fault; a fault (an exit, a crash, a malformed reply, a pose that is not a rotation, no
// reply within timeout_s) is that frame's `error` row.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "trackers/process/child_process.h"
#include "trackers/tracker.h"

namespace markerbench {

struct ExternalTrackerOptions {
  std::string name;                  // the scenario's name for it, sent in the handshake
  std::vector<std::string> command;  // the program and its arguments
  std::vector<std::string> markers;  // names of the markers it tracks; empty: every marker
  double timeout_s = 10.0;           // per frame
  double start_timeout_s = 30.0;     // for a start and its handshake
  std::string working_dir;           // where it runs; empty: this process's folder
  std::string stderr_path;           // the child's standard error is appended here
  std::string image_dir;             // each frame's PNG is written here, removed after
  // The marker file each request names (an absolute path), by marker name.
  std::map<std::string, std::string> marker_files;
};

// Its parameters for the run manifest: the command, the protocol and the timeout.
std::vector<std::pair<std::string, std::string>> ExternalTrackerParameters(
    const ExternalTrackerOptions& options);

class ExternalTracker : public Tracker {
 public:
  // Starts the child and completes the handshake; throws ConfigError naming the command
  // when it cannot.
  explicit ExternalTracker(ExternalTrackerOptions options);

  TrackResult Track(const Observation& observation) override;
  bool CanTrack(const MarkerSpec& marker) const override;
  void Reset() override { reset_pending_ = true; }
  std::vector<std::pair<std::string, std::string>> Parameters() const override;

 private:
  bool Start(std::string* error);
  TrackResult Fault(const std::string& why);

  ExternalTrackerOptions options_;
  ChildProcess child_;
  std::string pending_;  // bytes received after the last reply line
  std::string image_prefix_;
  bool reset_pending_ = true;
};

}  // namespace markerbench
