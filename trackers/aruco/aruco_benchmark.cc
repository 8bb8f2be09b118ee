// aruco per-frame time on one thread (results/speed.md). Run from the project root.
#include <benchmark/benchmark.h>

#include "testing/benchmark_frames.h"

namespace markerbench {
namespace {

void BM_Aruco(benchmark::State& state) {
  TimeFactoryTracker(state, "scenarios/markers/aruco.yaml", "aruco");
}
BENCHMARK(BM_Aruco)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
