#include "trackers/tracker.h"

#include <algorithm>
#include <array>
#include <exception>
#include <utility>

namespace markerbench {
namespace {

constexpr std::array<std::pair<TrackStatus, const char*>, 5> kStatusNames = {{
    {TrackStatus::kOk, "ok"},
    {TrackStatus::kNotDetected, "not_detected"},
    {TrackStatus::kWrongId, "wrong_id"},
    {TrackStatus::kPoseFailed, "pose_failed"},
    {TrackStatus::kError, "error"},
}};

}  // namespace

const char* ToString(TrackStatus status) {
  for (const auto& [s, name] : kStatusNames) {
    if (s == status) return name;
  }
  return "error";
}

TrackResult ErrorResult(const std::string& message) {
  TrackResult result;
  result.status = TrackStatus::kError;
  result.message = message;
  return result;
}

TrackResult CannotTrack(const std::string& tracker,
                        const MarkerSpec& marker,
                        const std::string& why) {
  return ErrorResult(tracker + " cannot track marker '" + marker.name + "'" +
                     (why.empty() ? "" : ": " + why));
}

std::optional<TrackResult> UnusableImage(const Observation& observation) {
  const Image8* image = observation.image;
  if (!image || !observation.camera || !observation.marker) {
    return ErrorResult("observation without an image, camera or marker");
  }
  const std::string size = std::to_string(image->width) + "x" + std::to_string(image->height) +
                           "x" + std::to_string(image->channels);
  const bool shape_ok =
      image->width > 0 && image->height > 0 && (image->channels == 1 || image->channels == 3);
  if (!shape_ok || image->pixels.size() != static_cast<size_t>(image->width) *
                                               static_cast<size_t>(image->height) *
                                               static_cast<size_t>(image->channels)) {
    return ErrorResult("malformed image " + size + " with " + std::to_string(image->pixels.size()) +
                       " bytes");
  }
  if (std::min(image->width, image->height) < kMinImageSide) {
    TrackResult result;
    result.status = TrackStatus::kNotDetected;
    result.message =
        "image " + size + " is under " + std::to_string(kMinImageSide) + " px on a side";
    return result;
  }
  return std::nullopt;
}

TrackResult TrackCatchingExceptions(Tracker* tracker, const Observation& observation) {
  try {
    return tracker->Track(observation);
  } catch (const std::exception& e) {
    return ErrorResult(std::string("exception: ") + e.what());
  } catch (...) {
    return ErrorResult("exception of unknown type");
  }
}

std::optional<TrackStatus> TrackStatusFromString(const std::string& text) {
  for (const auto& [s, name] : kStatusNames) {
    if (text == name) return s;
  }
  return std::nullopt;
}

}  // namespace markerbench
