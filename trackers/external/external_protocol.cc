#include "trackers/external/external_protocol.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace markerbench {
namespace {

using nlohmann::json;

// Tolerance on ||R^T R - I|| (Frobenius) for a reply's rotation.
constexpr double kRotationTolerance = 1e-6;

std::vector<double> FiniteNumbers(const json& value, size_t count, const std::string& what) {
  if (!value.is_array() || value.size() != count) {
    throw std::runtime_error(what + " must be a list of " + std::to_string(count) + " numbers");
  }
  std::vector<double> numbers;
  for (const json& v : value) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      throw std::runtime_error(what + " holds " + v.dump() + ", not a finite number");
    }
    numbers.push_back(v.get<double>());
  }
  return numbers;
}

Rigid3 ParsePose(const json& pose, size_t index) {
  const std::string where = "poses[" + std::to_string(index) + "]";
  if (!pose.is_object() || !pose.contains("R") || !pose.contains("t")) {
    throw std::runtime_error(where + " must be {\"R\": [9 numbers], \"t\": [3 numbers]}");
  }
  const std::vector<double> r = FiniteNumbers(pose["R"], 9, where + ".R");
  const std::vector<double> t = FiniteNumbers(pose["t"], 3, where + ".t");
  Rigid3 result;
  for (int k = 0; k < 9; ++k) result.rotation(k / 3, k % 3) = r[static_cast<size_t>(k)];
  for (int k = 0; k < 3; ++k) result.translation[k] = t[static_cast<size_t>(k)];
  if (!IsRotation(result.rotation, kRotationTolerance)) {
    throw std::runtime_error(where + ".R is not a rotation (||R^T R - I|| > 1e-6 or det R < 0)");
  }
  return result;
}

}  // namespace

std::string HandshakeLine(const std::string& tracker_name) {
  return json{{"protocol", kExternalProtocol}, {"tracker", tracker_name}}.dump() + "\n";
}

void CheckReadyLine(const std::string& line) {
  const json ready = json::parse(line, nullptr, false);
  if (!ready.is_object() || ready.value("protocol", json()) != kExternalProtocol ||
      ready.value("ready", json()) != true) {
    throw std::runtime_error("expected {\"protocol\": 1, \"ready\": true}, got '" +
                             line.substr(0, 200) + "'");
  }
}

std::string RequestLine(const ExternalRequest& request) {
  const Camera& c = *request.camera;
  json line = {{"frame", request.frame},
               {"image", request.image_path},
               {"width", request.image->width},
               {"height", request.image->height},
               {"channels", request.image->channels},
               {"camera",
                {{"fx", c.fx},
                 {"fy", c.fy},
                 {"cx", c.cx},
                 {"cy", c.cy},
                 {"dist", std::vector<double>(c.distortion.begin(), c.distortion.end())}}},
               {"marker", request.marker_path},
               {"marker_kind", ToString(request.marker->kind)},
               {"reset", request.reset}};
  return line.dump() + "\n";
}

TrackResult ParseReplyLine(const std::string& line) {
  const json reply = json::parse(line, nullptr, false);
  if (reply.is_discarded() || !reply.is_object()) {
    throw std::runtime_error("not a JSON object: '" + line.substr(0, 200) + "'");
  }
  TrackResult result;
  const json status = reply.value("status", json());
  const std::optional<TrackStatus> parsed =
      status.is_string() ? TrackStatusFromString(status.get<std::string>()) : std::nullopt;
  if (!parsed) {
    throw std::runtime_error("status " + status.dump() +
                             " is not one of ok, not_detected, wrong_id, pose_failed, error");
  }
  result.status = *parsed;
  if (reply.contains("poses")) {
    const json& poses = reply["poses"];
    if (!poses.is_array()) throw std::runtime_error("poses must be a list");
    for (size_t i = 0; i < poses.size(); ++i) result.hypotheses.push_back(ParsePose(poses[i], i));
  }
  if (result.status == TrackStatus::kOk && result.hypotheses.empty()) {
    throw std::runtime_error("status ok without a pose");
  }
  if (result.status != TrackStatus::kOk) result.hypotheses.clear();
  if (reply.contains("message")) {
    if (!reply["message"].is_string()) throw std::runtime_error("message must be a string");
    result.message = reply["message"].get<std::string>();
  }
  if (reply.contains("time_ms")) {
    const json& time = reply["time_ms"];
    if (!time.is_number() || !std::isfinite(time.get<double>()) || time.get<double>() < 0.0) {
      throw std::runtime_error("time_ms " + time.dump() + " is not a time");
    }
    result.time_ms = time.get<double>();
  }
  return result;
}

}  // namespace markerbench
