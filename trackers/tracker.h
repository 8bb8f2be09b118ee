// The tracker interface (architecture.md): an Observation in, a TrackResult out. Trackers
// never see ground truth and never link the renderer; a failure on a frame is data (a
// TrackStatus), not an exception. Adapters hide third-party types behind this header.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/marker_spec.h"
#include "core/rigid3.h"

namespace markerbench {

// Written as ok, not_detected, wrong_id, pose_failed, error in every CSV file.
enum class TrackStatus { kOk, kNotDetected, kWrongId, kPoseFailed, kError };

const char* ToString(TrackStatus status);
std::optional<TrackStatus> TrackStatusFromString(const std::string& text);

struct Observation {
  const Image8* image = nullptr;
  const Camera* camera = nullptr;
  const MarkerSpec* marker = nullptr;
  int64_t frame = 0;  // the frame's index in its run, for trackers that name it to others
};

struct TrackResult {
  TrackStatus status = TrackStatus::kNotDetected;
  // cam_from_marker hypotheses in our marker frame, best first (planar ambiguity: often 2).
  std::vector<Rigid3> hypotheses;
  // Detected MarkerSpec::keypoints in pixels, same order; empty when not measured.
  std::vector<Eigen::Vector2d> keypoints_px;
  std::string message;  // why it failed, for error rows
  // Time spent in Track() where it ran, set by trackers that run in another process; the
  // harness times in-process trackers itself.
  std::optional<double> time_ms;
};

// The `error` result of a tracker handed a marker it cannot track: "<tracker> cannot track
// marker '<name>'", then ": <why>" when given.
TrackResult CannotTrack(const std::string& tracker,
                        const MarkerSpec& marker,
                        const std::string& why = "");

// Images under this many pixels on a side hold no readable marker (and libapriltag crashes
// on images 4 px tall or less).
constexpr int kMinImageSide = 8;

// An `error` result with `message`: what a tracker, a worker or a command reports for a frame
// it could not process.
TrackResult ErrorResult(const std::string& message);

// What a tracker returns, before looking at it, for an image it must not read: `error` for a
// malformed observation (a null pointer, a side <= 0, channels other than 1 or 3, a pixel
// count that is not width * height * channels), `not_detected` for a side under
// kMinImageSide. nullopt for a usable image. Every Track() starts with it.
std::optional<TrackResult> UnusableImage(const Observation& observation);

class Tracker;

// tracker->Track(observation), with anything it throws as an `error` result whose message is
// "exception: <what>" (or "exception of unknown type").
TrackResult TrackCatchingExceptions(Tracker* tracker, const Observation& observation);

class Tracker {
 public:
  virtual ~Tracker() = default;
  // One frame. Must not throw for bad images: report a status instead.
  virtual TrackResult Track(const Observation& observation) = 0;
  // Whether this tracker (with its options) can track `marker`; Track returns kError for
  // markers it cannot, and the harness pairs trackers only with the markers they can.
  virtual bool CanTrack(const MarkerSpec& marker) const = 0;
  // Forgets any state carried between frames (tracking mode).
  virtual void Reset() {}
  // Every parameter in effect, as (name, value) text, for the run manifest.
  virtual std::vector<std::pair<std::string, std::string>> Parameters() const = 0;
};

}  // namespace markerbench
