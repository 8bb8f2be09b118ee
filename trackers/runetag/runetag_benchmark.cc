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
  const Camera camera;
  const YamlMap options(YAML::Load(options_yaml), "benchmark options", "");
  auto tracker = MakeTracker("runetag", &options);
  size_t i = 0, ok = 0;
  for (auto _ : state) {
    const TrackResult r = tracker->Track({&frames[i++ % frames.size()], &camera, &marker});
    ok += r.status == TrackStatus::kOk;
  }
  state.counters["ok_fraction"] = static_cast<double>(ok) / static_cast<double>(i);
}

void BM_RuneTag(benchmark::State& state) { TrackFrames(state, "{}"); }
BENCHMARK(BM_RuneTag)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
