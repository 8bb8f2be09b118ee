#include "bench/plan/frame_plan.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "bench/plan/pose_sampler.h"
#include "core/number_text.h"
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

std::string GridText(const std::vector<SweepAxis>& axes, const std::vector<size_t>& indices) {
  std::string text;
  for (size_t a = 0; a < axes.size(); ++a) {
    text += (a == 0 ? "" : ";") + axes[a].parameter + "=" + NumberText(axes[a].values[indices[a]]);
  }
  return text;
}

std::vector<PlannedFrame> PlanFrames(const Scenario& s, int limit) {
  std::vector<PlannedFrame> frames;
  size_t combinations = 1;
  for (const SweepAxis& axis : s.grid_axes) combinations *= axis.values.size();
  const size_t values = s.sweep_values.size();
  for (size_t cell = 0; cell < combinations * values; ++cell) {
    PoseSamplerOptions poses = s.poses;
    Degradations degradations = s.render.degradations;
    // Mixed radix: the first axis fastest, then the grid's axes in order.
    const size_t value_index = cell % values;
    std::vector<size_t> indices;
    for (size_t rest = cell / values; indices.size() < s.grid_axes.size();) {
      const SweepAxis& axis = s.grid_axes[indices.size()];
      indices.push_back(rest % axis.values.size());
      rest /= axis.values.size();
      ApplySweepValue(axis.parameter, axis.values[indices.back()], &poses, &degradations);
    }
    ApplySweepValue(s.sweep_parameter, s.sweep_values[value_index], &poses, &degradations);
    const std::string grid = GridText(s.grid_axes, indices);
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
        f.sweep_value = s.sweep_values[value_index];
        f.grid = grid;
        f.example = trial == 0 && f.sweep_value == s.example_value && cell < values;
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
