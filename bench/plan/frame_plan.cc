#include "bench/plan/frame_plan.h"

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "bench/plan/pose_sampler.h"
#include "bench/plan/trajectory.h"
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
  if (parameter == "gamma") return {0.1, 10.0};
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
  } else if (parameter == "gamma") {
    d->gamma = value;
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

namespace {

// What a sequence's frames share: the trajectory and the trial's draw of it.
struct SequenceMotion {
  TrajectoryOptions options;
  TrialTrajectory trial;
  Camera camera;
};

// Appends the frames of one (cell, trial): a sequence per marker when the scenario has a
// trajectory, else one frame per marker; false once `limit` frames are planned.
bool PlanTrial(const Scenario& s,
               size_t cell,
               int trial,
               const PoseSamplerOptions& poses,
               PlannedFrame common,
               int limit,
               std::vector<PlannedFrame>* frames) {
  const uint64_t pose_seed = SeedFor(s.seed, cell, trial, SeedPurpose::kPose);
  // Common random numbers: every marker at a (cell, trial) gets the same noise stream.
  const uint64_t noise_seed = SeedFor(s.seed, cell, trial, SeedPurpose::kNoise);
  std::shared_ptr<const SequenceMotion> motion;
  Rigid3 cam_from_center;
  if (s.trajectory) {
    motion = std::make_shared<SequenceMotion>(
        SequenceMotion{*s.trajectory,
                       SampleTrialTrajectory(*s.trajectory,
                                             poses,
                                             s.camera,
                                             s.markers,
                                             pose_seed,
                                             SeedFor(s.seed, cell, trial, SeedPurpose::kMotion)),
                       s.camera});
  } else {
    cam_from_center = SamplePairedPose(poses, s.camera, s.markers, pose_seed);
  }
  const int frames_per_marker = s.trajectory ? s.trajectory->Frames() : 1;
  for (size_t m = 0; m < s.markers.size(); ++m) {
    for (int k = 0; k < frames_per_marker; ++k) {
      if (limit > 0 && static_cast<int>(frames->size()) >= limit) return false;
      PlannedFrame f = common;
      f.index = static_cast<int>(frames->size());
      f.trial = trial;
      f.marker_index = static_cast<int>(m);
      f.example = f.example && k == 0;
      f.channels = ChannelsFor(s.render.channels, s.markers[m]);
      f.noise_seed = noise_seed;
      if (motion) {
        const MarkerSpec& marker = s.markers[m];
        const TrajectoryOptions& o = motion->options;
        f.sequence_frame = k;
        f.occluded = o.Occluded(k);
        f.cam_from_marker =
            CamFromMarker(TrajectoryPose(o, motion->trial, motion->camera, o.TruthTime(k)), marker);
        // Each frame its own noise, the same for every marker at this (cell, trial, frame).
        f.noise_seed = SeedFor(noise_seed, static_cast<uint64_t>(k), 0, SeedPurpose::kNoise);
        if (o.exposure_s > 0.0 || o.readout_s > 0.0) {
          const Rigid3 center_from_marker = CamFromMarker(Rigid3(), marker);
          f.cam_from_marker_at = [motion, k, center_from_marker](double t) {
            const TrajectoryOptions& o = motion->options;
            return TrajectoryPose(o, motion->trial, motion->camera, o.FrameTime(k) + t) *
                   center_from_marker;
          };
        }
      } else {
        f.cam_from_marker = CamFromMarker(cam_from_center, s.markers[m]);
      }
      frames->push_back(std::move(f));
    }
  }
  return true;
}

}  // namespace

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
    PlannedFrame common;
    common.cell = static_cast<int>(cell);
    common.sweep_value = s.sweep_values[value_index];
    common.grid = grid;
    common.degradations = degradations;
    for (int trial = 0; trial < s.trials; ++trial) {
      common.example = trial == 0 && common.sweep_value == s.example_value && cell < values;
      if (!PlanTrial(s, cell, trial, poses, common, limit, &frames)) return frames;
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
  request.scene.marker_hidden = f.occluded;
  request.cam_from_marker_at = f.cam_from_marker_at;
  if (s.trajectory) {
    request.exposure_s = s.trajectory->exposure_s;
    request.readout_s = s.trajectory->readout_s;
  }
  return request;
}

}  // namespace markerbench
