#!/usr/bin/env bash
# The circle tracker's false-positive rate out of sample: detection mode, every marker a-f, on
# SETS (default 3) fresh draws of the negative set (testing/negative_scenes.h; the committed set
# is the one the tests check), into results/circle_false_positives.md. Needs a build with tests
# (scripts/build.sh); about 30 s per set on one core.
set -euo pipefail
cd "$(dirname "$0")/.."
sets="${1:-3}"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
MARKERBENCH_FRESH_NEGATIVE_SETS="$sets" ./build/trackers/trackers_circle_false_positives_test \
  --gtest_filter=CircleFalsePositives.RateOnFreshDraws > "$log"
out=results/circle_false_positives.md
{
  echo "# The circle tracker's false positives out of sample"
  echo
  echo "Written by \`bash scripts/false_positive_rate.sh $sets\`. Detection mode (a fresh tracker"
  echo "per frame), every circle marker a-f, on $sets fresh draws of the negative set of 560"
  echo "frames (\`RenderNegative(index, set)\`, sets 1-$sets: clutter, other marker systems, noise"
  echo "σ² up to 0.3, blur up to 4 px; each marker's own frames left out). The committed set"
  echo "(set 0), on which the tests ask for no find at all, is the one the tracker was checked on"
  echo "while it was built; these sets were not. Intervals: 95 % Wilson."
  echo
  sed -n 's/^TABLE //p' "$log"
  echo
  echo "Each find: the marker, the frame, the image's noise σ as the tracker estimated it (0-1)"
  echo "and the design's misfit at the pose found (printed_appearance.h: a fraction of the"
  echo "contrast, over pixel pairs or blocks of them; the check rejects only a misfit above 0.1,"
  echo "over blocks 0.25, by more than 4 standard errors)."
  echo
  sed -n 's/^FIND /- /p' "$log"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
