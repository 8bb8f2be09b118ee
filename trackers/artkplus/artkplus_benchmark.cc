// artkplus per-frame time on one thread (results/speed.md): Robust Planar Pose (the
// default) and the classic arGetTransMat search. Run from the project root.
#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include <opencv2/core/utility.hpp>

#include "core/marker_yaml.h"
#include "core/yaml_reader.h"
#include "trackers/benchmark_frames.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

void TrackFrames(benchmark::State& state, const char* options_yaml) {
  cv::setNumThreads(1);  // connectedComponentsWithStats would otherwise run in parallel
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/artkplus.yaml");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const YamlMap options(YAML::Load(options_yaml), "benchmark options", "");
  auto tracker = MakeTracker("artkplus", &options);
  TimeIndependentFrames(state, *tracker, marker, frames);
}

void BM_ArtkPlusRobustPlanarPose(benchmark::State& state) { TrackFrames(state, "pose: rpp"); }
void BM_ArtkPlusClassicPose(benchmark::State& state) { TrackFrames(state, "pose: classic"); }
BENCHMARK(BM_ArtkPlusRobustPlanarPose)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ArtkPlusClassicPose)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
