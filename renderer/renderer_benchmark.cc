// Renderer speed (issue goals: tag36h11 grey frame at 0.6 m with blur σ = 2 and noise
// ≤ 3 ms; colour circles_a frame ≤ 5 ms; memory flat over many frames). Run from the
// project root so the marker files are found. Figures go to results/speed.md.
#include <benchmark/benchmark.h>

#include "core/marker_yaml.h"
#include "core/random.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"

namespace markerbench {
namespace {

void RenderMarker(benchmark::State& state, const char* file, int channels) {
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
    request.scene.cam_from_marker = TiltedView(0.6, rng.Uniform(0, 40), rng.Uniform(0, 360));
    request.scene.cam_from_marker.translation -= request.scene.cam_from_marker.rotation * center;
    request.noise_seed = SeedFor(1, 0, frame++, SeedPurpose::kNoise);
    benchmark::DoNotOptimize(RenderFrame(request));
  }
}

void BM_RenderTag36h11Grey(benchmark::State& state) {
  RenderMarker(state, "scenarios/markers/apriltag.yaml", 1);
}
void BM_RenderCirclesAColour(benchmark::State& state) {
  RenderMarker(state, "scenarios/markers/circles_a.yaml", 3);
}
BENCHMARK(BM_RenderTag36h11Grey)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderCirclesAColour)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
