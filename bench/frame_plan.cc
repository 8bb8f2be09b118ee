#include "bench/frame_plan.h"

#include <cmath>
#include <stdexcept>

#include "bench/pose_sampler.h"
#include "core/random.h"

namespace markerbench {

void ApplySweepValue(const std::string& parameter,
                     double value,
                     PoseSamplerOptions* poses,
                     Degradations* d) {
  if (parameter == "distance_m") {
    if (!(value > 0.0)) throw std::invalid_argument("distance_m values must be > 0");
    poses->distance_m = value;
  } else if (parameter == "tilt_deg") {
    if (!(value >= 0.0 && value <= 89.0)) {
      throw std::invalid_argument("tilt_deg values must be in [0, 89]");
    }
    poses->tilt_min_deg = poses->tilt_max_deg = value;
  } else if (parameter == "noise_var") {
    d->noise_var = value;
  } else if (parameter == "blur_sigma_px") {
    d->blur_sigma_px = value;
  } else if (parameter == "motion_blur_px") {
    d->motion_blur_px = value;
  } else if (parameter == "gain") {
    d->gain = value;
  } else if (parameter == "jpeg_quality") {
    if (value != std::round(value)) throw std::invalid_argument("jpeg_quality must be whole");
    d->jpeg_quality = static_cast<int>(value);
  } else {
    throw std::invalid_argument("unknown sweep parameter " + parameter);
  }
  std::string error;
  if (!d->IsValid(&error)) throw std::invalid_argument(error);
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
