// Protocol 1 of external trackers (README, "Benchmark your own tracker", the specification):
// the lines markerbench sends and the replies it accepts.
#pragma once

#include <string>

#include "trackers/tracker.h"

namespace markerbench {

constexpr int kExternalProtocol = 1;

// {"protocol": 1, "tracker": NAME}
std::string HandshakeLine(const std::string& tracker_name);
// Throws std::runtime_error unless `line` is {"protocol": 1, "ready": true}.
void CheckReadyLine(const std::string& line);

struct ExternalRequest {
  int64_t frame = 0;
  std::string image_path;  // absolute
  const Image8* image = nullptr;
  const Camera* camera = nullptr;
  std::string marker_path;  // absolute
  const MarkerSpec* marker = nullptr;
  bool reset = true;
};
std::string RequestLine(const ExternalRequest& request);

// A reply as a result (poses as hypotheses, best first; its time_ms when given). Throws
// std::runtime_error saying what is wrong: not JSON, an unknown status, `ok` without a pose,
// a pose with a non-finite number or a rotation R with ||R^T R - I|| > 1e-6 or det R < 0.
TrackResult ParseReplyLine(const std::string& line);

}  // namespace markerbench
