// apriltag / apriltag-ippe per-frame time on one thread (results/speed.md). Run from the
// project root.
#include <benchmark/benchmark.h>

#include "testing/benchmark_frames.h"

namespace markerbench {
namespace {

constexpr char kMarker[] = "scenarios/markers/apriltag.yaml";

void BM_AprilTag(benchmark::State& state) { TimeFactoryTracker(state, kMarker, "apriltag"); }
void BM_AprilTagIppe(benchmark::State& state) {
  TimeFactoryTracker(state, kMarker, "apriltag-ippe");
}
BENCHMARK(BM_AprilTag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AprilTagIppe)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
