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
  auto tracker = MakeTracker("aruco", nullptr);
  TimeIndependentFrames(state, *tracker, marker, frames);
}
BENCHMARK(BM_Aruco)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
