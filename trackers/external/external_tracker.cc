#include "trackers/external/external_tracker.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/config_error.h"
#include "core/number_text.h"
#include "trackers/external/external_protocol.h"
#include "trackers/process/socket_io.h"

namespace markerbench {
namespace {

// Longest reply line accepted (a reply holds a few poses and a message).
constexpr size_t kMaxReplyBytes = 1 << 20;

std::string CommandText(const std::vector<std::string>& command) {
  std::string text;
  for (const std::string& word : command) text += (text.empty() ? "" : " ") + word;
  return text;
}

// Writes `image` as a PNG at `path` (fast compression: the file lives for one frame).
bool WritePng(const Image8& image, const std::string& path) {
  const cv::Mat pixels(image.height,
                       image.width,
                       image.channels == 3 ? CV_8UC3 : CV_8UC1,
                       const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  if (image.channels == 3) cv::cvtColor(pixels, bgr, cv::COLOR_RGB2BGR);
  return cv::imwrite(path, image.channels == 3 ? bgr : pixels, {cv::IMWRITE_PNG_COMPRESSION, 1});
}

}  // namespace

ExternalTracker::ExternalTracker(ExternalTrackerOptions options) : options_(std::move(options)) {
  static std::atomic<int> instances{0};
  image_prefix_ = options_.image_dir + "/" + options_.name + "_" + std::to_string(getpid()) + "_" +
                  std::to_string(instances++) + "_";
  std::string error;
  if (!Start(&error)) {
    throw ConfigError("tracker '" + options_.name + "' (" + CommandText(options_.command) +
                      "): " + error + "; its standard error is in " + options_.stderr_path);
  }
}

bool ExternalTracker::Start(std::string* error) {
  ChildSpec spec;
  spec.argv = options_.command;
  spec.socket_fds = {STDIN_FILENO, STDOUT_FILENO};
  spec.stderr_path = options_.stderr_path;
  spec.working_dir = options_.working_dir;
  if (!child_.Start(spec, error)) return false;
  pending_.clear();
  const int64_t deadline = DeadlineAfter(options_.start_timeout_s);
  std::string ready;
  if (!SendAll(child_.socket(), HandshakeLine(options_.name), deadline, error) ||
      !ReceiveLine(child_.socket(), &pending_, &ready, kMaxReplyBytes, deadline, error)) {
    *error = "no handshake (" + *error + "); the program " + child_.Stop(true);
    return false;
  }
  try {
    CheckReadyLine(ready);
  } catch (const std::exception& e) {
    *error = std::string("handshake: ") + e.what();
    child_.Stop(true);
    return false;
  }
  reset_pending_ = true;
  return true;
}

bool ExternalTracker::CanTrack(const MarkerSpec& marker) const {
  return options_.markers.empty() ||
         std::find(options_.markers.begin(), options_.markers.end(), marker.name) !=
             options_.markers.end();
}

std::vector<std::pair<std::string, std::string>> ExternalTrackerParameters(
    const ExternalTrackerOptions& options) {
  return {{"exec", CommandText(options.command)},
          {"protocol", std::to_string(kExternalProtocol)},
          {"timeout_s", NumberText(options.timeout_s)}};
}

std::vector<std::pair<std::string, std::string>> ExternalTracker::Parameters() const {
  return ExternalTrackerParameters(options_);
}

TrackResult ExternalTracker::Fault(const std::string& why) {
  if (child_.running()) child_.Stop(true);
  return ErrorResult(why);
}

TrackResult ExternalTracker::Track(const Observation& observation) {
  if (std::optional<TrackResult> unusable = UnusableImage(observation)) return *unusable;
  if (!CanTrack(*observation.marker)) return CannotTrack(options_.name, *observation.marker);
  const auto marker_file = options_.marker_files.find(observation.marker->name);
  if (marker_file == options_.marker_files.end()) {
    return CannotTrack(options_.name, *observation.marker, "no marker file for it");
  }
  std::string error;
  if (!child_.running() && !Start(&error)) return Fault("cannot restart the program: " + error);
  ExternalRequest request;
  request.frame = observation.frame;
  request.image_path = image_prefix_ + std::to_string(observation.frame) + ".png";
  request.image = observation.image;
  request.camera = observation.camera;
  request.marker_path = marker_file->second;
  request.marker = observation.marker;
  request.reset = reset_pending_;
  if (!WritePng(*observation.image, request.image_path)) {
    return Fault("cannot write " + request.image_path);
  }
  const int64_t deadline = DeadlineAfter(options_.timeout_s);
  std::string line;
  const bool replied =
      SendAll(child_.socket(), RequestLine(request), deadline, &error) &&
      ReceiveLine(child_.socket(), &pending_, &line, kMaxReplyBytes, deadline, &error);
  std::remove(request.image_path.c_str());
  if (!replied) {
    if (error == kTimedOut) {
      return Fault("no reply within timeout_s " + NumberText(options_.timeout_s) +
                   " s; the program was stopped");
    }
    return Fault("the program " + child_.Stop(false) + " on this frame (" + error + ")");
  }
  reset_pending_ = false;
  try {
    return ParseReplyLine(line);
  } catch (const std::exception& e) {
    return Fault(std::string("malformed reply: ") + e.what());
  }
}

}  // namespace markerbench
