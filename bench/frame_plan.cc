#include "bench/frame_plan.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "bench/pose_sampler.h"
#include "core/random.h"
#include "core/yaml_reader.h"

namespace markerbench {

ValueRange SweepRange(const std::string& parameter) {
  if (parameter == "distance_m") return {YamlMap::kMinLengthM, YamlMap::kMaxLengthM};
  if (parameter == "tilt_deg") return {0.0, 89.0};
  if (parameter == "noise_var") return {0.0, 10.0};
  if (parameter == "blur_sigma_px") return {0.0, 100.0};
  if (parameter == "motion_blur_px") return {0.0, 200.0};
  if (parameter == "gain") return {0.0, 100.0};
  if (parameter == "jpeg_quality") return {0.0, 100.0};
  throw std::invalid_argument("unknown sweep parameter " + parameter);
}

void ApplySweepValue(const std::string& parameter,
                     double value,
                     PoseSamplerOptions* poses,
                     Degradations* d) {
  const ValueRange range = SweepRange(parameter);
  if (!(value >= range.lo && value <= range.hi)) {
    std::ostringstream message;
    message << parameter << " values must be in [" << range.lo << ", " << range.hi << "]";
    throw std::invalid_argument(message.str());
  }
  if (parameter == "distance_m") {
    poses->distance_m = value;
  } else if (parameter == "tilt_deg") {
    poses->tilt_min_deg = poses->tilt_max_deg = value;
  } else if (parameter == "noise_var") {
    d->noise_var = value;
  } else if (parameter == "blur_sigma_px") {
    d->blur_sigma_px = value;
  } else if (parameter == "motion_blur_px") {
    d->motion_blur_px = value;
  } else if (parameter == "gain") {
    d->gain = value;
  } else {
    if (value != std::round(value)) throw std::invalid_argument("jpeg_quality must be whole");
    d->jpeg_quality = static_cast<int>(value);
  }
}

std::vector<PlannedFrame> PlanFrames(const Scenario& s, int limit) {
  std::vector<PlannedFrame> frames;
  for (size_t cell = 0; cell < s.sweep_values.size(); ++cell) {
    PoseSamplerOptions poses = s.poses;
    Degradations degradations = s.render.degradations;
    ApplySweepValue(s.sweep_parameter, s.sweep_values[cell], &poses, &degradations);
    for (int trial = 0; trial < s.trials; ++trial) {
      const Rigid3 cam_from_center = SamplePairedPose(
          poses, s.camera, s.markers, SeedFor(s.seed, cell, trial, SeedPurpose::kPose));
      for (size_t m = 0; m < s.markers.size(); ++m) {
        if (limit > 0 && static_cast<int>(frames.size()) >= limit) return frames;
        PlannedFrame f;
        f.index = static_cast<int>(frames.size());
        f.cell = static_cast<int>(cell);
        f.trial = trial;
        f.marker_index = static_cast<int>(m);
        f.sweep_value = s.sweep_values[cell];
        f.cam_from_marker = CamFromMarker(cam_from_center, s.markers[m]);
        f.degradations = degradations;
        f.channels = ChannelsFor(s.render.channels, s.markers[m]);
        // Common random numbers: every marker at a (cell, trial) gets the same noise stream.
        f.noise_seed = SeedFor(s.seed, cell, trial, SeedPurpose::kNoise);
        frames.push_back(f);
      }
    }
  }
  return frames;
}

FrameRequest RequestFor(const Scenario& s, const PlannedFrame& f) {
  FrameRequest request;
  request.scene.marker = &s.markers[static_cast<size_t>(f.marker_index)];
  request.scene.camera = s.camera;
  request.scene.cam_from_marker = f.cam_from_marker;
  request.scene.sheet_size_m = s.render.sheet_size_m;
  request.scene.backdrop = s.render.backdrop;
  request.degradations = f.degradations;
  request.channels = f.channels;
  request.noise_seed = f.noise_seed;
  return request;
}

}  // namespace markerbench
