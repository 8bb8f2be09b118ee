// runetag per-frame time on one thread (results/speed.md; issue 7's goal: <= 20 ms median,
// the original takes about 1 s). Run from the project root.
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
  cv::setNumThreads(1);  // OpenCV would otherwise parallelise the threshold and contours
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/runetag.yaml");
  const std::vector<Image8> frames = BenchmarkFrames(marker, 16);
  const YamlMap options(YAML::Load(options_yaml), "benchmark options", "");
  auto tracker = MakeTracker("runetag", &options);
  TimeIndependentFrames(state, *tracker, marker, frames);
}

void BM_RuneTag(benchmark::State& state) { TrackFrames(state, "{}"); }
BENCHMARK(BM_RuneTag)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
