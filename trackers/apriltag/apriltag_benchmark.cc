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
  auto tracker = MakeTracker(name, nullptr);
  TimeIndependentFrames(state, *tracker, marker, frames);
}

void BM_AprilTag(benchmark::State& state) { TrackFrames(state, "apriltag"); }
void BM_AprilTagIppe(benchmark::State& state) { TrackFrames(state, "apriltag-ippe"); }
BENCHMARK(BM_AprilTag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AprilTagIppe)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
