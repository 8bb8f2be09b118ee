#!/usr/bin/env bash
# The CI accuracy gate (README, "Use markerbench as a regression gate"): sweeps the suite in
# scenarios/ci/ and checks the run against results/reference/ (exit 1 on a regression).
# Extra arguments go to `markerbench check`: --bless accepts the run as the new reference.
# Needs a build (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out=build/ci-gate
./build/bench/markerbench sweep scenarios/ci/*.yaml --out "$out" --overwrite
./build/bench/markerbench check "$out" --reference results/reference \
  --markdown "$out/check.md" --junit "$out/check.xml" "$@"
