// Renderer speed (issue goals: tag36h11 grey frame at 0.6 m with blur σ = 2 and noise
// ≤ 3 ms; colour circles_a frame ≤ 5 ms; memory flat over many frames) and the cost of the
// frames' Cramér-Rao bound beside it. Run from the
// project root so the marker files are found. Figures go to results/speed.md.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <Eigen/Geometry>

#include "core/marker_yaml.h"
#include "core/random.h"
#include "renderer/pose_crlb.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

// A hand-held camera's motion as in scenarios/sequences/handheld_rolling_shutter.yaml: 1/60 s
// exposure, 20 ms rolling-shutter readout, 0.15 m/s sideways and 30°/s about the camera's y
// axis, the truth at mid-exposure of the middle row.
void MakeMoving(FrameRequest* request) {
  const double exposure_s = 1.0 / 60.0, readout_s = 0.02;
  MoveAtConstantRates(request,
                      Eigen::Vector3d(0.15, 0.0, 0.0),
                      Eigen::Vector3d(0.0, 30.0 * 3.14159265358979323846 / 180.0, 0.0),
                      exposure_s,
                      readout_s,
                      0.5 * (exposure_s + readout_s));
}

// Calls work(request) on a fresh paired-protocol frame of `file` per iteration (seen by a
// moving camera when `moving`).
template <typename Work>
void EachFrame(
    benchmark::State& state, const char* file, int channels, Work work, bool moving = false) {
  const MarkerSpec marker = LoadMarkerYaml(file);
  FrameRequest request;
  request.scene.marker = &marker;
  request.channels = channels;
  request.degradations.blur_sigma_px = 2.0;
  request.degradations.noise_var = 0.02;
  const Eigen::Vector3d center(marker.InkBounds().center().x(), marker.InkBounds().center().y(), 0);
  uint64_t frame = 0;
  for (auto _ : state) {
    // A fresh pose and noise seed every frame: tilt 0..40°, any roll, as in the paper sweeps.
    Rng rng(SeedFor(1, 0, frame, SeedPurpose::kPose));
    request.scene.cam_from_marker = RandomTiltedView(0.6, 0.0, 40.0, &rng);
    request.scene.cam_from_marker.translation -= request.scene.cam_from_marker.rotation * center;
    request.noise_seed = SeedFor(1, 0, frame++, SeedPurpose::kNoise);
    if (moving) MakeMoving(&request);
    work(request);
  }
}

void RenderMarker(benchmark::State& state, const char* file, int channels, bool moving = false) {
  EachFrame(
      state,
      file,
      channels,
      [](const FrameRequest& request) { benchmark::DoNotOptimize(RenderFrame(request)); },
      moving);
}

void BM_RenderTag36h11Grey(benchmark::State& state) {
  RenderMarker(state, "scenarios/markers/apriltag.yaml", 1);
}
void BM_RenderCirclesAColour(benchmark::State& state) {
  RenderMarker(state, "scenarios/markers/circles_a.yaml", 3);
}

// The Cramér-Rao bound of the same frames (computed once per frame in sweeps): its cost
// against the render's is what it adds to a sweep.
void BoundOfMarker(benchmark::State& state, const char* file, int channels, bool moving = false) {
  EachFrame(
      state,
      file,
      channels,
      [](const FrameRequest& request) { benchmark::DoNotOptimize(PoseCrlb(request)); },
      moving);
}
void BM_CrlbTag36h11Grey(benchmark::State& state) {
  BoundOfMarker(state, "scenarios/markers/apriltag.yaml", 1);
}
void BM_CrlbCirclesAColour(benchmark::State& state) {
  BoundOfMarker(state, "scenarios/markers/circles_a.yaml", 3);
}
void BM_CrlbRuneTagGrey(benchmark::State& state) {
  BoundOfMarker(state, "scenarios/markers/runetag.yaml", 1);
}
// A moving camera (MakeMoving): the render integrates the exposure row band by row band, the
// bound samples the exposure every 0.25 px of motion.
void BM_RenderCirclesAMovingGrey(benchmark::State& state) {
  RenderMarker(state, "scenarios/markers/circles_a.yaml", 1, true);
}
void BM_CrlbCirclesAMovingGrey(benchmark::State& state) {
  BoundOfMarker(state, "scenarios/markers/circles_a.yaml", 1, true);
}
BENCHMARK(BM_RenderCirclesAMovingGrey)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CrlbCirclesAMovingGrey)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CrlbTag36h11Grey)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CrlbCirclesAColour)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CrlbRuneTagGrey)->Unit(benchmark::kMillisecond);

// Stages of the grey tag frame, to see where the time goes.
void BM_StageRasterizeTag(benchmark::State& state) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  Scene scene;
  scene.marker = &marker;
  scene.cam_from_marker = TiltedView(0.6, 30.0, 20.0);
  for (auto _ : state) benchmark::DoNotOptimize(Rasterize(scene, 1));
}
void BM_StageBlurSigma2(benchmark::State& state) {
  ImageF image(640, 480, 1);
  for (auto _ : state) {
    benchmark::DoNotOptimize(GaussianBlur(2.0, PixelRect{250, 170, 390, 310}, &image));
  }
}
void BM_StageNoiseAndQuantizeGrey(benchmark::State& state) {
  ImageF image(640, 480, 1);
  uint64_t seed = 0;
  for (auto _ : state) benchmark::DoNotOptimize(AddNoiseAndQuantize(0.02, 1.0, ++seed, &image));
}
BENCHMARK(BM_StageRasterizeTag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageBlurSigma2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StageNoiseAndQuantizeGrey)->Unit(benchmark::kMillisecond);
// Peak resident memory must not grow with the number of frames rendered.
void BM_MemoryOver10000Frames(benchmark::State& state) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  FrameRequest request;
  request.scene.marker = &marker;
  request.degradations.blur_sigma_px = 2.0;
  request.degradations.noise_var = 0.02;
  auto peak_kb = [] {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss);
  };
  for (auto _ : state) {
    double after_warmup = 0.0;
    for (int frame = 0; frame < 10000; ++frame) {
      if (frame == 100) after_warmup = peak_kb();
      Rng rng(SeedFor(2, 0, frame, SeedPurpose::kPose));
      request.scene.cam_from_marker = RandomTiltedView(0.6, 0.0, 40.0, &rng);
      request.noise_seed = SeedFor(2, 0, frame, SeedPurpose::kNoise);
      benchmark::DoNotOptimize(RenderFrame(request));
    }
    state.counters["peak_rss_growth_kb"] = peak_kb() - after_warmup;
    state.counters["peak_rss_kb"] = peak_kb();
  }
}

BENCHMARK(BM_RenderTag36h11Grey)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderCirclesAColour)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MemoryOver10000Frames)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
