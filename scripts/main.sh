#!/usr/bin/env bash
# The main job from a clean clone: install dependencies, build (Release), run the paper's
# three sweeps (Fig. 6-8: noise, blur, distance; scenarios/paper/) with every available
# tracker, and write their report with plots and the reproduction table to results/paper/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/bench/markerbench sweep scenarios/paper/fig6_noise.yaml scenarios/paper/fig7_blur.yaml \
  scenarios/paper/fig8_distance.yaml --out results/paper --overwrite
./build/bench/markerbench report results/paper
echo "main: wrote results/paper (report.md, summary.csv, plots, manifest.json)"
