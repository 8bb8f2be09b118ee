#!/usr/bin/env bash
# How far a sweep depends on the CPU it runs on: the scenarios swept twice on this machine, as
# the CPU is and with glibc's AVX2, FMA and AVX-512 variants masked (GLIBC_TUNABLES), and per
# scenario the rows of frames.csv that differ. glibc picks the code of its maths functions (exp,
# sin, atan2, ...) by the CPU, and the variants can differ in the last bit; a frame whose result
# turns on such bits moves (README, "Across machines"). Arguments after `--` go
# to both sweeps (e.g. --trackers circle). Needs a build (scripts/build.sh).
# Usage: scripts/cpu_dispatch_check.sh OUT_DIR SCENARIO.yaml... [-- SWEEP_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: scripts/cpu_dispatch_check.sh OUT_DIR SCENARIO.yaml... [-- SWEEP_ARGS...]" >&2
  exit 2
fi
out="$1"
shift
scenarios=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  scenarios+=("$1")
  shift
done
if [ "${1:-}" = "--" ]; then shift; fi
masked="glibc.cpu.hwcaps=-AVX512F,-AVX512DQ,-AVX2,-FMA,-FMA4"
./build/bench/markerbench sweep "${scenarios[@]}" --out "$out/as_is" --overwrite "$@"
GLIBC_TUNABLES="$masked" ./build/bench/markerbench sweep "${scenarios[@]}" \
  --out "$out/masked" --overwrite "$@"
for frames in "$out"/as_is/*/frames.csv; do
  name="$(basename "$(dirname "$frames")")"
  if [ ! -f "$out/masked/$name/frames.csv" ]; then
    echo "cpu_dispatch_check: $out/masked/$name/frames.csv: missing (the masked sweep failed?)" >&2
    exit 2
  fi
  rows=$(($(wc -l < "$frames") - 1))
  differ="$(diff "$frames" "$out/masked/$name/frames.csv" | grep -c '^>' || true)"
  echo "$name: $differ of $rows rows differ with glibc's AVX2, FMA and AVX-512 variants masked"
done
