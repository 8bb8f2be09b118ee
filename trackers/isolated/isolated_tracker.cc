#include "trackers/isolated/isolated_tracker.h"

#include <stdexcept>

#include "core/number_text.h"
#include "trackers/isolated/worker_protocol.h"
#include "trackers/process/socket_io.h"

namespace markerbench {

IsolatedTracker::IsolatedTracker(std::unique_ptr<Tracker> local, IsolationOptions options)
    : local_(std::move(local)), options_(std::move(options)) {
  // A worker killed while it starts (by the OOM killer, a scheduler, a user) is started once
  // more, as after a crash on a frame; one that fails twice cannot start.
  std::string error;
  if (!Start(&error) && !Start(&error)) {
    throw std::runtime_error("cannot start the worker process " + options_.worker_argv.at(0) +
                             " (tried twice): " + error);
  }
}

std::vector<std::pair<std::string, std::string>> IsolationParameters(double timeout_s) {
  return {{"isolated", "true"}, {"timeout_s", NumberText(timeout_s)}};
}

std::vector<std::pair<std::string, std::string>> IsolatedTracker::Parameters() const {
  std::vector<std::pair<std::string, std::string>> parameters = local_->Parameters();
  for (auto& parameter : IsolationParameters(options_.timeout_s)) parameters.push_back(parameter);
  return parameters;
}

bool IsolatedTracker::Start(std::string* error) {
  ChildSpec spec;
  spec.argv = options_.worker_argv;
  spec.socket_fds = {kWorkerFd};
  if (!worker_.Start(spec, error)) return false;
  std::string ready;
  if (!ReceiveMessage(worker_.socket(), &ready, DeadlineAfter(options_.start_timeout_s), error)) {
    *error = "no ready message (" + *error + "); the worker " + worker_.Stop(true);
    return false;
  }
  reset_pending_ = true;
  return true;
}

TrackResult IsolatedTracker::Track(const Observation& observation) {
  if (std::optional<TrackResult> unusable = UnusableImage(observation)) return *unusable;
  std::string error;
  if (!worker_.running() && !Start(&error)) {
    return ErrorResult("cannot restart the worker process: " + error);
  }
  const int64_t deadline = DeadlineAfter(options_.timeout_s);
  std::string reply;
  if (!SendMessage(
          worker_.socket(), EncodeRequest(reset_pending_, observation), deadline, &error) ||
      !ReceiveMessage(worker_.socket(), &reply, deadline, &error)) {
    const bool timed_out = error == kTimedOut;
    const std::string end = worker_.Stop(timed_out);
    return ErrorResult(timed_out ? "no result within timeout_s " + NumberText(options_.timeout_s) +
                                       " s; the worker was stopped"
                                 : "the worker " + end + " on this frame");
  }
  reset_pending_ = false;
  try {
    WorkerReply decoded = DecodeReply(reply);
    decoded.result.time_ms = decoded.time_ms;
    return decoded.result;
  } catch (const std::exception& e) {
    worker_.Stop(true);
    return ErrorResult(std::string("malformed reply from the worker: ") + e.what());
  }
}

}  // namespace markerbench
