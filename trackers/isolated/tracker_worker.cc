#include "trackers/isolated/tracker_worker.h"

#include <sys/prctl.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "trackers/isolated/worker_protocol.h"

namespace markerbench {

int ServeTrackerWorker(Tracker* tracker, const std::vector<MarkerSpec>& markers, int fd) {
  // A worker hung in a tracker dies with the thread that started it.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  std::string error;
  if (!SendMessage(fd, "", std::nullopt, &error)) return 0;
  for (std::string body;;) {
    if (!ReceiveMessage(fd, &body, std::nullopt, &error)) return 0;
    WorkerRequest request;
    try {
      request = DecodeRequest(body);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tracker worker: malformed request: %s\n", e.what());
      return 2;
    }
    const MarkerSpec* marker = nullptr;
    for (const MarkerSpec& m : markers) {
      if (m.name == request.marker_name) marker = &m;
    }
    if (marker == nullptr) {
      std::fprintf(stderr, "tracker worker: unknown marker '%s'\n", request.marker_name.c_str());
      return 2;
    }
    if (request.reset) tracker->Reset();
    WorkerReply reply;
    const auto start = std::chrono::steady_clock::now();
    reply.result = TrackCatchingExceptions(tracker, {&request.image, &request.camera, marker});
    reply.time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!SendMessage(fd, EncodeReply(reply), std::nullopt, &error)) return 0;
  }
}

}  // namespace markerbench
