#include "trackers/tracker.h"

#include <array>
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

TrackResult CannotTrack(const std::string& tracker,
                        const MarkerSpec& marker,
                        const std::string& why) {
  TrackResult result;
  result.status = TrackStatus::kError;
  result.message =
      tracker + " cannot track marker '" + marker.name + "'" + (why.empty() ? "" : ": " + why);
  return result;
}

std::optional<TrackStatus> TrackStatusFromString(const std::string& text) {
  for (const auto& [s, name] : kStatusNames) {
    if (text == name) return s;
  }
  return std::nullopt;
}

}  // namespace markerbench
