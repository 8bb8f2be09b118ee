// The messages between an IsolatedTracker and its worker process: one request (an
// Observation, with the marker named) and one reply (a TrackResult) per frame, each framed as
// a 4-byte length and a binary body. Doubles travel as their exact bytes, so a result is the
// same whether the tracker ran in the worker or in-process.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/camera.h"
#include "core/image.h"
#include "trackers/tracker.h"

namespace markerbench {

// The worker's end of its socket: a file descriptor of its own, so that anything a library
// prints on standard output cannot mix with the messages.
constexpr int kWorkerFd = 3;

struct WorkerRequest {
  bool reset = false;  // Reset() the tracker before this frame
  std::string marker_name;
  Camera camera;
  Image8 image;
};

struct WorkerReply {
  TrackResult result;
  double time_ms = 0.0;  // Track() alone, measured in the worker
};

std::string EncodeRequest(bool reset, const Observation& observation);
std::string EncodeReply(const WorkerReply& reply);
// Both throw std::runtime_error on a body that is short, long or out of range.
WorkerRequest DecodeRequest(const std::string& body);
WorkerReply DecodeReply(const std::string& body);

// Largest body either side accepts: an image at the camera pixel budget, in colour.
constexpr uint32_t kMaxMessageBytes = 256u * 1024 * 1024;

// Sends or receives one framed message, as trackers/process/socket_io.h sends and receives.
bool SendMessage(int fd,
                 const std::string& body,
                 std::optional<int64_t> deadline_ms,
                 std::string* error);
bool ReceiveMessage(int fd,
                    std::string* body,
                    std::optional<int64_t> deadline_ms,
                    std::string* error);

}  // namespace markerbench
