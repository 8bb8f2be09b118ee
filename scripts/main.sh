#!/usr/bin/env bash
# The main job from a clean clone: install dependencies, build (Release), and render the
# example scenario (every marker kind under paired poses) plus print-ready marker sheets into
# out/. The paper's sweeps and their report replace this when the sweep harness lands.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/bench/markerbench render scenarios/examples/all_markers.yaml --out out/examples
./build/bench/markerbench markers --out out/marker_sheets
echo "main: wrote out/examples (frames + groundtruth.csv) and out/marker_sheets"
