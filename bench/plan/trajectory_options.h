// `trajectory:` of a sequence scenario (issue 22): the camera's path (bench/plan/trajectory.h
// draws and evaluates it), the video's frame rate and length, its still start, the exposure,
// the rolling shutter's readout and the frames where the marker is hidden.
#pragma once

#include <vector>

namespace markerbench {

enum class TrajectoryKind { kOrbit, kApproach, kHandheld };

// Frames first..last (inclusive, counted from 0 in each sequence) where the marker is
// hidden.
struct FrameRange {
  int first = 0;
  int last = 0;
};

struct TrajectoryOptions {
  TrajectoryKind kind = TrajectoryKind::kOrbit;
  double fps = 30.0;
  double duration_s = 5.0;
  double static_s = 0.0;
  double exposure_s = 0.0;
  double readout_s = 0.0;         // rolling shutter: the last row starts this much after the first
  double degrees_per_s = 30.0;    // orbit
  double to_m = 0.5;              // approach: from poses.distance_m to this
  double linear_speed_m_s = 0.1;  // handheld, RMS
  double angular_speed_deg_s = 20.0;
  std::vector<FrameRange> occlusions;

  int Frames() const;
  bool Occluded(int frame) const;
  // The start of frame k's first row's exposure; the time of its ground truth (the middle
  // row at mid-exposure); the end of its last row's exposure.
  double FrameTime(int frame) const;
  double TruthTime(int frame) const { return FrameTime(frame) + 0.5 * (exposure_s + readout_s); }
  double FrameEnd(int frame) const { return FrameTime(frame) + exposure_s + readout_s; }
};

const char* TrajectoryKindName(TrajectoryKind kind);

}  // namespace markerbench
