// runetag-improved and runetag per-frame time on one thread (results/speed.md; issue 7's goal:
// <= 20 ms median, the original takes about 1 s). Run from the project root.
#include <benchmark/benchmark.h>

#include "testing/benchmark_frames.h"

namespace markerbench {
namespace {

void BM_RuneTag(benchmark::State& state) {
  TimeFactoryTracker(state, "scenarios/markers/runetag.yaml", "runetag-improved");
}
BENCHMARK(BM_RuneTag)->Unit(benchmark::kMillisecond);

void BM_RuneTagOriginalRules(benchmark::State& state) {
  TimeFactoryTracker(state, "scenarios/markers/runetag.yaml", "runetag");
}
BENCHMARK(BM_RuneTagOriginalRules)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace markerbench

BENCHMARK_MAIN();
