#!/usr/bin/env bash
# The sequence runs (issue 22): an orbit under three noise levels, an approach, and a
# hand-held shake with motion blur, with and without a rolling shutter, and the circle markers
# receding, tracked and each frame alone (scenarios/sequences/),
# swept and reported into results/sequences/ (report.md, sequence_summary.csv, sequences.csv per
# scenario, plots; recede_pairs.csv: the receding frames beyond 2.5 m, tracked against each frame
# alone, pair by pair); the README's "Tracking over time" table is generated from it
# (scripts/readme_figures.py).
# Assumes a build (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
./build/bench/markerbench sweep scenarios/sequences/orbit.yaml scenarios/sequences/approach.yaml \
  scenarios/sequences/handheld.yaml scenarios/sequences/handheld_rolling_shutter.yaml \
  scenarios/sequences/recede.yaml scenarios/sequences/recede_each_frame.yaml \
  --out results/sequences --overwrite
./build/bench/markerbench report results/sequences
/usr/bin/python3 scripts/paired_runs.py results/sequences recede recede_each_frame \
  --min-distance 2.5 --out results/sequences/recede_pairs.csv
echo "sequences: wrote results/sequences"
