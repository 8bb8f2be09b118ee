#!/usr/bin/env bash
# The sequence runs (issue 22): an orbit under three noise levels, an approach, and a
# hand-held shake with motion blur, with and without a rolling shutter, and the circle markers
# receding, tracked and each frame alone (scenarios/sequences/),
# swept and reported into results/sequences/ (report.md, sequence_summary.csv, sequences.csv per
# scenario, plots); the README's "Tracking over time" table is generated from it
# (scripts/readme_figures.py).
# Assumes a build (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
./build/bench/markerbench sweep scenarios/sequences/orbit.yaml scenarios/sequences/approach.yaml \
  scenarios/sequences/handheld.yaml scenarios/sequences/handheld_rolling_shutter.yaml \
  scenarios/sequences/recede.yaml scenarios/sequences/recede_each_frame.yaml \
  --out results/sequences --overwrite
./build/bench/markerbench report results/sequences
echo "sequences: wrote results/sequences"
