// A tracker run in a worker process, so that a crash or a hang on one frame is an `error` row
// and never the end of a sweep (architecture.md, "a tracker failure is a row"). The worker is
// forked from the calling thread and builds its own tracker; it is restarted on the next
// frame after it dies or is killed for exceeding the time limit. It sees the camera and the
// markers it was given at construction, which must outlive it unchanged: a fork shares them
// copy-on-write, so a request names a marker by its index and sends only the pixels.
#pragma once

#include <sys/types.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "trackers/tracker.h"

namespace markerbench {

struct IsolatedTrackerOptions {
  double timeout_s = 60.0;  // per frame; the worker is killed past it
};

class IsolatedTracker : public Tracker {
 public:
  using Factory = std::function<std::unique_ptr<Tracker>()>;

  // `make` builds the tracker, once here (for CanTrack and Parameters) and once in each
  // worker. `camera` and `markers` are what observations may point to.
  IsolatedTracker(Factory make,
                  const Camera* camera,
                  const std::vector<MarkerSpec>* markers,
                  IsolatedTrackerOptions options = {});
  ~IsolatedTracker() override;
  IsolatedTracker(const IsolatedTracker&) = delete;
  IsolatedTracker& operator=(const IsolatedTracker&) = delete;

  // Sets TrackResult::time_ms to the worker's own time for the call.
  TrackResult Track(const Observation& observation) override;
  bool CanTrack(const MarkerSpec& marker) const override { return local_->CanTrack(marker); }
  void Reset() override { reset_pending_ = true; }
  std::vector<std::pair<std::string, std::string>> Parameters() const override {
    return local_->Parameters();
  }

 private:
  void StartWorker();
  // Kills the worker and returns why it is gone: "exited with status N" or the signal's name.
  std::string StopWorker();
  TrackResult WorkerFailed(const std::string& why);

  Factory make_;
  std::unique_ptr<Tracker> local_;
  const Camera* camera_;
  const std::vector<MarkerSpec>* markers_;
  IsolatedTrackerOptions options_;
  bool reset_pending_ = true;
  pid_t pid_ = -1;
  int socket_ = -1;  // our end of the worker's socket pair
};

}  // namespace markerbench
