// artkplus per-frame time on one thread (results/speed.md): Robust Planar Pose (the
// default) and the classic arGetTransMat search. Run from the project root.
#include <benchmark/benchmark.h>

#include "testing/benchmark_frames.h"

namespace markerbench {
namespace {

constexpr char kMarker[] = "scenarios/markers/artkplus.yaml";

void BM_ArtkPlusRobustPlanarPose(benchmark::State& state) {
  TimeFactoryTracker(state, kMarker, "artkplus", "pose: rpp");
}
void BM_ArtkPlusClassicPose(benchmark::State& state) {
  TimeFactoryTracker(state, kMarker, "artkplus", "pose: classic");
}
BENCHMARK(BM_ArtkPlusRobustPlanarPose)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ArtkPlusClassicPose)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
