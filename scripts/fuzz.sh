#!/usr/bin/env bash
# Usage: scripts/fuzz.sh [SECONDS] [TREE]
# Builds the libFuzzer targets, replays the inputs earlier fuzzing found
# (*/fuzz_regressions/<target>/), then runs both targets side by side for SECONDS (default 60)
# from their committed seed corpus. A crash, a leak, an escaped exception or an input that
# takes over TIMEOUT seconds fails; the input is saved in TREE/findings/. New corpus entries
# stay in TREE/corpus/. TREE is a build tree configured with MARKERBENCH_FUZZ and
# MARKERBENCH_ASAN (scripts/test.sh passes its sanitizer tree, which built the targets beside
# the tests); without it, build-fuzz/ is configured here: clang, AddressSanitizer (with
# LeakSanitizer) and UBSan with every check.
# TIMEOUT is 3 s: the heaviest input known (runetag-improved on a 256x256 texture of 5000
# dots, 0.1 s in Release) took 0.56 s under the sanitizers on one machine and 1.8 s on another
# as libFuzzer printed it, the time of its two runs of a replayed input (the second looks for
# leaks; about 1 s a run there since its RANSAC scans bands of rows), so 1 s failed CI on it;
# 3 s still fails the ArUco texture that took 3.5 s before its fix.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
tree="${2:-build-fuzz}"
timeout=3
if [ $# -lt 2 ]; then
  cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER=clang++ -DMARKERBENCH_FUZZ=ON -DMARKERBENCH_ASAN=ON \
    -DMARKERBENCH_UBSAN=ON -DMARKERBENCH_TESTS=OFF -DMARKERBENCH_BENCHMARKS=OFF
else
  # A tree fuzzes only with the targets and AddressSanitizer (a fuzzer without it misses
  # every overflow that does not crash).
  for option in MARKERBENCH_FUZZ MARKERBENCH_ASAN; do
    if ! grep -qx "$option:BOOL=ON" "$tree/CMakeCache.txt" 2> /dev/null; then
      echo "fuzz.sh: $tree/CMakeCache.txt: $option is not ON (configure the tree with" \
        "-D$option=ON, or leave TREE out for build-fuzz/)" >&2
      exit 2
    fi
  done
fi
cmake --build "$tree" --parallel "$(nproc)" --target loaders_fuzz track_fuzz
mkdir -p "$tree/findings"
# The regressions are replayed first, one target after the other (alone on the machine: the
# heaviest, runetag_few_inliers, takes a third of the timeout a run in the sanitizer tree, and
# libFuzzer runs a replayed input twice, the second time to look for leaks, so the time it
# prints is both: 1.6-2.2 s); then the targets fuzz side by side (one process each, so on two
# cores at once), each into its own log, printed when both end.
targets=(bench/fuzz_corpus/loaders_fuzz trackers/fuzz_corpus/track_fuzz)
binary_of() { echo "$tree/$(dirname "$(dirname "$1")")/$(basename "$1")"; }
for seeds in "${targets[@]}"; do
  regressions="$(dirname "$(dirname "$seeds")")/fuzz_regressions/$(basename "$seeds")"
  if [ -d "$regressions" ]; then
    echo "== replaying $regressions"
    "$(binary_of "$seeds")" -timeout="$timeout" -rss_limit_mb=4096 "$regressions"/*
  fi
done
pids=()
trap 'kill "${pids[@]}" 2> /dev/null || true' EXIT  # a failing script stops the fuzzers
for seeds in "${targets[@]}"; do
  name="$(basename "$seeds")"
  mkdir -p "$tree/corpus/$name"
  echo "== fuzzing $name for ${seconds} s (log: $tree/$name.log)"
  "$(binary_of "$seeds")" "$tree/corpus/$name" "$seeds" \
    -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=4096 -print_final_stats=1 \
    -print_funcs=0 -artifact_prefix="$tree/findings/$name-" > "$tree/$name.log" 2>&1 &
  pids+=("$!")
done
failed=0
for i in "${!targets[@]}"; do
  name="$(basename "${targets[$i]}")"
  status=0
  wait "${pids[$i]}" || status=$?
  echo "== $name (exit status $status)"
  cat "$tree/$name.log"
  [ "$status" -eq 0 ] || failed=1
done
exit "$failed"
