// Frames for tracker benchmarks: 640x480, the marker at 0.6 m (tilt 0-40°, any roll),
// imnoise σ² = 0.02, rendered once before timing (issue 4's protocol; distance, blur and noise
// can be set); RGB for colour markers.
// And the timing loop the tracker benchmarks share, with a factory tracker on those frames.
#pragma once

#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <opencv2/core/utility.hpp>
#include <vector>

#include "core/marker_yaml.h"
#include "core/random.h"
#include "core/yaml_reader.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
#include "trackers/tracker.h"
#include "trackers/tracker_factory.h"

namespace markerbench {

// The view and degradations of the frames: issue 4's protocol by default.
struct BenchmarkFrameOptions {
  double distance_m = 0.6;
  double blur_sigma_px = 0.0;
  double noise_var = 0.02;
  // Each frame moved from the protocol's pose by camera_move(its index), the camera's move
  // (camera_after_from_before; none: the pose itself), with noise of its own for each
  // video_frame.
  std::function<Rigid3(int)> camera_move;
  uint64_t video_frame = 0;
};

// The seed of the benchmarks' frame i for `purpose` (their scenario's seed, 11), in video frame
// `video_frame`.
inline uint64_t BenchmarkSeed(int i, SeedPurpose purpose, uint64_t video_frame = 0) {
  return SeedFor(11, video_frame, static_cast<uint64_t>(i), purpose);
}

// The camera's move to the next frame of a hand-held video (scenarios/sequences/handheld.yaml:
// 0.15 m/s and 30°/s at 30 fps) with no history: moved by 5 mm and turned by 1°, each in a
// random direction drawn for frame i.
inline Rigid3 RandomHandheldFrameMotion(int i) {
  Rng rng(BenchmarkSeed(i, SeedPurpose::kMotion));
  constexpr double kStepM = 0.15 / 30.0, kTurnRad = (30.0 / 30.0) * M_PI / 180.0;
  const Eigen::Vector3d axis = GaussianVector(&rng);
  const Eigen::Vector3d direction = GaussianVector(&rng);
  return {Eigen::AngleAxisd(kTurnRad, axis.normalized()).toRotationMatrix(),
          kStepM * direction.normalized()};
}

inline std::vector<Image8> BenchmarkFrames(const MarkerSpec& marker,
                                           int count,
                                           const BenchmarkFrameOptions& options = {}) {
  std::vector<Image8> frames;
  const Eigen::Vector2d c = marker.InkBounds().center();
  for (int i = 0; i < count; ++i) {
    Rng rng(BenchmarkSeed(i, SeedPurpose::kPose));
    FrameRequest request;
    request.scene.marker = &marker;
    request.scene.cam_from_marker = RandomTiltedView(options.distance_m, 0.0, 40.0, &rng);
    request.scene.cam_from_marker.translation -=
        request.scene.cam_from_marker.rotation * Eigen::Vector3d(c.x(), c.y(), 0.0);
    if (options.camera_move) {
      request.scene.cam_from_marker = options.camera_move(i) * request.scene.cam_from_marker;
    }
    request.degradations.blur_sigma_px = options.blur_sigma_px;
    request.degradations.noise_var = options.noise_var;
    request.channels = marker.HasColor() ? 3 : 1;
    request.noise_seed = BenchmarkSeed(i, SeedPurpose::kNoise, options.video_frame);
    frames.push_back(RenderFrame(request).image);
  }
  return frames;
}

// One Track call per iteration over `frames` cycled in order, each after Reset() (frames
// are independent, as in the sweeps); reports the fraction with status ok.
inline void TimeIndependentFrames(benchmark::State& state,
                                  Tracker& tracker,
                                  const MarkerSpec& marker,
                                  const std::vector<Image8>& frames) {
  const Camera camera;
  size_t i = 0, ok = 0;
  for (auto _ : state) {
    tracker.Reset();
    ok +=
        tracker.Track({&frames[i++ % frames.size()], &camera, &marker}).status == TrackStatus::kOk;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / static_cast<double>(i);
}

// The factory's tracker `name` with `options_yaml`, timed on 16 frames of the marker file
// `marker_yaml` (a path from the project root) on one thread: OpenCV's own threads are off.
inline void TimeFactoryTracker(benchmark::State& state,
                               const char* marker_yaml,
                               const char* name,
                               const char* options_yaml = "{}") {
  cv::setNumThreads(1);
  const MarkerSpec marker = LoadMarkerYaml(marker_yaml);
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const YamlMap options(YAML::Load(options_yaml), "benchmark options", "");
  const std::unique_ptr<Tracker> tracker = MakeTracker(name, &options);
  TimeIndependentFrames(state, *tracker, marker, frames);
}

}  // namespace markerbench
