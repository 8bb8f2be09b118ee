// A tracker that runs in a worker process, so that a crash or a hang inside it (third-party C
// code such as libapriltag) is an `error` row and the sweep goes on. The worker is a program
// started with posix_spawn (never a fork of this multithreaded process: a child of fork may
// need a lock that another thread held) that serves ServeTrackerWorker on file descriptor
// kWorkerFd; it is started when the tracker is made, and again after a crash or a timeout.
// Results are bit-identical to running the tracker in-process.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackers/process/child_process.h"
#include "trackers/tracker.h"

namespace markerbench {

// The path that starts this very program: the kernel's link to the running process's own file, so
// a worker started by it is the same build even where the file has since been rebuilt or removed.
inline constexpr char kThisProgram[] = "/proc/self/exe";

struct IsolationOptions {
  // The worker program and its arguments; argv[0] is the path run.
  std::vector<std::string> worker_argv;
  // A frame without a reply by then is an `error` row, and the worker is stopped.
  double timeout_s = 60.0;
  // For the worker's start: its first reply says it is ready.
  double start_timeout_s = 60.0;
};

// The parameters an isolated tracker adds to its tracker's (Tracker::Parameters).
std::vector<std::pair<std::string, std::string>> IsolationParameters(double timeout_s);

class IsolatedTracker : public Tracker {
 public:
  // `local` is the same tracker in-process: it answers CanTrack and Parameters. Throws
  // std::runtime_error when the worker fails to start twice in a row.
  IsolatedTracker(std::unique_ptr<Tracker> local, IsolationOptions options);
  IsolatedTracker(const IsolatedTracker&) = delete;
  IsolatedTracker& operator=(const IsolatedTracker&) = delete;

  TrackResult Track(const Observation& observation) override;
  bool CanTrack(const MarkerSpec& marker) const override { return local_->CanTrack(marker); }
  void Reset() override { reset_pending_ = true; }
  std::vector<std::pair<std::string, std::string>> Parameters() const override;

 private:
  // Starts the worker and waits for its ready message; false with `*error` set otherwise.
  bool Start(std::string* error);

  std::unique_ptr<Tracker> local_;
  IsolationOptions options_;
  ChildProcess worker_;
  bool reset_pending_ = true;
};

}  // namespace markerbench
