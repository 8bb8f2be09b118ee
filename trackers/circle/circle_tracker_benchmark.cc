// circle tracker per-frame time on one thread (issue 3; results/speed.md): full detection +
// analytic pose + refinement (with and without the refinement on the pixels), tracking mode
// (the region predicted from the frames before: one with no history, two of a smooth hand-held
// video; three of a steady glide, tracked on the pixels from the prediction), and two of their
// steps alone: the fit on the disks' pixels and the check of the printed design. circles_a with
// a 0.1 m equal-area footprint at 0.6 m, σ² = 0.02, the frames of the other tracker benchmarks;
// at 1 m under blur σ 2 and 8 (the whole disks' model); and full detection of markers (e) and
// (f) on the same poses (issue 22: their pose fitted on the pixels of the whole design). Run from
// the project root.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <functional>
#include <opencv2/core.hpp>

#include "bench/plan/trajectory.h"
#include "core/marker_scaling.h"
#include "core/marker_yaml.h"
#include "testing/benchmark_frames.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/circle/photometric_refinement.h"

namespace markerbench {
namespace {

// A marker of scenarios/markers/ at the paper's 0.1 m equal-area footprint.
MarkerSpec PaperMarker(const std::string& kind) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/" + kind + ".yaml");
  return ScaledMarker(marker, EqualAreaFactor(marker, 0.01));
}

void BM_CircleFullDetection(benchmark::State& state) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  CircleTracker tracker;
  TimeIndependentFrames(state, tracker, marker, frames);
}

// The same without the refinement on the pixels (`photometric: false`): the fast path.
void BM_CircleFullDetectionEdgesOnly(benchmark::State& state) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  CircleTrackerOptions options;
  options.photometric = false;
  CircleTracker tracker(options);
  TimeIndependentFrames(state, tracker, marker, frames);
}

// Heavy blur: at 1 m and blur σ = 8 px (the paper's blur sweep) both disks are modelled whole
// on their pixels (the exact blurred ellipse); with the same frames at σ = 2 (osculating
// disks) as the reference of the same run.
void BM_CircleFullDetectionBlurred(benchmark::State& state) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  BenchmarkFrameOptions options;
  options.distance_m = 1.0;
  options.blur_sigma_px = static_cast<double>(state.range(0));
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16, options);
  CircleTracker tracker;
  TimeIndependentFrames(state, tracker, marker, frames);
}

// Markers (e) and (f): full detection, the pose fitted on the design's pixels from both of
// the circle's tilts.
void BM_CircleDesignFullDetection(benchmark::State& state, const std::string& kind) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker(kind);
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  CircleTracker tracker;
  TimeIndependentFrames(state, tracker, marker, frames);
}

// Tracking mode: each of the 16 poses starts a video (videos[j][k]: frame j of pose k's), whose
// frames are tracked in order from a Reset(), untimed but the last; as in a video, the tracker
// predicts each frame from the ones before it (its pose, and its motion from two frames on).
void TimeLastFramesOfVideos(benchmark::State& state,
                            const MarkerSpec& marker,
                            const std::vector<std::vector<Image8>>& videos,
                            const CircleTrackerOptions& options = {}) {
  const Camera camera;
  CircleTracker tracker(options);
  size_t i = 0, ok = 0, in_region = 0, from_prediction = 0, on_pixels = 0;
  for (auto _ : state) {
    const size_t k = i++ % videos.front().size();
    state.PauseTiming();
    tracker.Reset();
    for (size_t j = 0; j + 1 < videos.size(); ++j) tracker.Track({&videos[j][k], &camera, &marker});
    state.ResumeTiming();
    ok += tracker.Track({&videos.back()[k], &camera, &marker}).status == TrackStatus::kOk;
    in_region += tracker.diagnostics().used_tracking_region;
    from_prediction += tracker.diagnostics().used_predicted_ellipses;
    on_pixels += tracker.diagnostics().tracked_on_pixels;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / static_cast<double>(i);
  state.counters["region_fraction"] = static_cast<double>(in_region) / static_cast<double>(i);
  // Found by the edge pass from the predicted ellipses (else by the search of the region).
  state.counters["predicted_fraction"] =
      static_cast<double>(from_prediction) / static_cast<double>(i);
  // Found by the fit on the pixels from the predicted pose, without the detector.
  state.counters["on_pixels_fraction"] = static_cast<double>(on_pixels) / static_cast<double>(i);
}

// Each frame followed by the next frame of a hand-held video with no history (the camera moved
// by 5 mm and turned by 1°, each in a random direction, new noise): the second timed from the
// first's pose, by a tracker of `options`.
void TimeNextHandheldFrames(benchmark::State& state, const CircleTrackerOptions& options) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  BenchmarkFrameOptions later;
  later.camera_move = RandomHandheldFrameMotion;
  later.video_frame = 1;
  TimeLastFramesOfVideos(
      state, marker, {BenchmarkFrames(marker, 16), BenchmarkFrames(marker, 16, later)}, options);
}

void BM_CircleTrackingMode(benchmark::State& state) { TimeNextHandheldFrames(state, {}); }

// The same without the refinement on the pixels (`photometric: false`): each frame's ellipses
// found by the detector's edge pass from the predicted ones, or by its search of the region
// around them where they moved too far (predicted_fraction).
void BM_CircleTrackingModeEdgesOnly(benchmark::State& state) {
  CircleTrackerOptions options;
  options.photometric = false;
  TimeNextHandheldFrames(state, options);
}

// The camera's move `frames` video frames (30 fps) into the smooth shake of
// scenarios/sequences/handheld.yaml (bench/plan/trajectory.h: RMS 0.15 m/s and 30°/s, a hand's
// 0.2-1.5 Hz), a shake drawn for each pose.
std::function<Rigid3(int)> HandheldShakeMove(int frames) {
  return [frames](int i) {
    Rng rng(BenchmarkSeed(i, SeedPurpose::kMotion));
    const Shake shake = Shake::Draw(0.15, 30.0, &rng);
    return shake.MotionAt(frames / 30.0).Inverse() * shake.MotionAt(0.0);
  };
}

// The first `frames` frames of a video of circles_a (new noise in each) whose camera moves from
// the first frame to frame j by move_to(j) (a move for each pose), timed on the last: predicted
// from the frames before it, as in a video.
void TimeLastFramesOfMotion(benchmark::State& state,
                            int frames,
                            const std::function<std::function<Rigid3(int)>(int)>& move_to) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  std::vector<std::vector<Image8>> videos;
  for (int j = 0; j < frames; ++j) {
    BenchmarkFrameOptions options;
    options.camera_move = move_to(j);
    options.video_frame = static_cast<uint64_t>(j);
    videos.push_back(BenchmarkFrames(marker, 16, options));
  }
  TimeLastFramesOfVideos(state, marker, videos);
}

// Three frames of that smooth hand-held video: the third timed, predicted from the motion
// between the first two (`predict_motion`).
void BM_CircleTrackingModeHandheld(benchmark::State& state) {
  TimeLastFramesOfMotion(state, 3, HandheldShakeMove);
}

// The camera's move over `frames` frames of a steady glide: each frame the same move as
// RandomHandheldFrameMotion's for the pose (5 mm and 1°), a constant velocity.
std::function<Rigid3(int)> SteadyGlideMove(int frames) {
  return [frames](int i) {
    const Rigid3 step = RandomHandheldFrameMotion(i);
    Rigid3 move;
    for (int k = 0; k < frames; ++k) move = step * move;
    return move;
  };
}

// Four frames of a steady glide: the fourth timed, predicted from the motion of the second and
// third, where the third's image lay where its prediction put it, so tracked on the pixels from
// the prediction, without the detector (as on a smooth video).
void BM_CircleTrackingModeSteady(benchmark::State& state) {
  TimeLastFramesOfMotion(state, 4, SteadyGlideMove);
}

// What `tracker` finds on each frame it finds the marker in (untimed): the frame, the pose, and
// the blur and noise it measured.
struct Found {
  const Image8* frame;
  Rigid3 cam_from_marker;
  double blur_sigma_px, noise_sigma;
};
std::vector<Found> FoundOnFrames(CircleTracker& tracker,
                                 const MarkerSpec& marker,
                                 const Camera& camera,
                                 const std::vector<Image8>& frames) {
  std::vector<Found> found;
  for (const Image8& frame : frames) {
    tracker.Reset();
    if (tracker.Track({&frame, &camera, &marker}).status != TrackStatus::kOk) continue;
    const CircleDiagnostics& d = tracker.diagnostics();
    found.push_back({&frame, *d.refined_cam_from_marker, d.image_blur_sigma_px, d.noise_sigma});
  }
  return found;
}

// The fit on the disks' pixels (photometric_refinement.h), alone: from the pose the edge points
// give (the tracker with `photometric: false`, untimed) at the blur and noise it measured, as
// full detection runs it; more than half of that benchmark's time.
void BM_CirclePixelFit(benchmark::State& state) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const Camera camera;
  CircleTrackerOptions options;
  options.photometric = false;
  CircleTracker tracker(options);
  const std::vector<Found> starts = FoundOnFrames(tracker, marker, camera, frames);
  if (starts.empty()) {
    state.SkipWithError("the edge points gave no pose on any frame");
    return;
  }
  size_t i = 0, fitted = 0, iterations = 0, pixels = 0;
  for (auto _ : state) {
    const Found& start = starts[i++ % starts.size()];
    const std::optional<PixelRefinement> fit = RefinePhotometric(*start.frame,
                                                                 camera,
                                                                 marker,
                                                                 start.cam_from_marker,
                                                                 start.blur_sigma_px,
                                                                 start.noise_sigma);
    if (!fit) continue;
    ++fitted;
    iterations += fit->fit.iterations;
    pixels += fit->pixels;
  }
  state.counters["fitted_fraction"] = static_cast<double>(fitted) / state.iterations();
  state.counters["steps"] = static_cast<double>(iterations) / std::max<size_t>(fitted, 1);
  state.counters["pixels"] = static_cast<double>(pixels) / std::max<size_t>(fitted, 1);
}

// The check of the printed design at the found pose (printed_appearance.h), alone: part of
// every timing above.
void BM_CircleAppearanceCheck(benchmark::State& state) {
  cv::setNumThreads(1);
  const MarkerSpec marker = PaperMarker("circles_a");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const Camera camera;
  CircleTracker tracker;
  const std::vector<Found> found = FoundOnFrames(tracker, marker, camera, frames);
  if (found.empty()) {
    state.SkipWithError("the tracker found no frame");
    return;
  }
  size_t i = 0;
  for (auto _ : state) {
    const Found& k = found[i++ % found.size()];
    benchmark::DoNotOptimize(
        CheckPrintedAppearance(*k.frame, camera, marker, k.cam_from_marker, k.blur_sigma_px));
  }
}

BENCHMARK(BM_CircleFullDetection)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleFullDetectionEdgesOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleFullDetectionBlurred)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CircleDesignFullDetection, circle_e, std::string("circle_e"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CircleDesignFullDetection, circle_f, std::string("circle_f"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleTrackingMode)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleTrackingModeEdgesOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleTrackingModeHandheld)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleTrackingModeSteady)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CirclePixelFit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CircleAppearanceCheck)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
