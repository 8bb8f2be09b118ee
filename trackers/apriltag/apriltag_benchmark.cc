// apriltag / apriltag-ippe per-frame time on one thread (results/speed.md). Run from the
// project root.
#include <benchmark/benchmark.h>

#include "core/marker_yaml.h"
#include "trackers/benchmark_frames.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

void TrackFrames(benchmark::State& state, const char* name) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const Camera camera;
  auto tracker = MakeTracker(name, nullptr);
  size_t i = 0, ok = 0;
  for (auto _ : state) {
    const TrackResult r = tracker->Track({&frames[i++ % frames.size()], &camera, &marker});
    ok += r.status == TrackStatus::kOk;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / static_cast<double>(i);
}

void BM_AprilTag(benchmark::State& state) { TrackFrames(state, "apriltag"); }
void BM_AprilTagIppe(benchmark::State& state) { TrackFrames(state, "apriltag-ippe"); }
BENCHMARK(BM_AprilTag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AprilTagIppe)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
