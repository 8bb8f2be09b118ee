// aruco per-frame time on one thread (results/speed.md). Run from the project root.
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include "core/marker_yaml.h"
#include "trackers/benchmark_frames.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

void BM_Aruco(benchmark::State& state) {
  cv::setNumThreads(1);  // OpenCV would otherwise parallelise detectMarkers
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/aruco.yaml");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const Camera camera;
  auto tracker = MakeTracker("aruco", nullptr);
  size_t i = 0, ok = 0;
  for (auto _ : state) {
    const TrackResult r = tracker->Track({&frames[i++ % frames.size()], &camera, &marker});
    ok += r.status == TrackStatus::kOk;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / static_cast<double>(i);
}
BENCHMARK(BM_Aruco)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
