#!/usr/bin/env bash
# The circle tracker's false-positive rate out of sample: detection mode, every marker a-f, on
# SETS (default 3) fresh draws of the negative set (testing/negative_scenes.h; the committed set
# is the one the tests check), with the set's blur (0-4 px) and again with the heavier half of the
# paper's blur sweep (5-10 px), into results/circle_false_positives.md. Needs a build with tests
# (scripts/build.sh); six sets take about 9 minutes on one core.
set -euo pipefail
cd "$(dirname "$0")/.."
sets="${1:-3}"
log="$(mktemp)"
heavy_log="$(mktemp)"
trap 'rm -f "$log" "$heavy_log"' EXIT
test=./build/trackers/trackers_circle_false_positives_test
MARKERBENCH_FRESH_NEGATIVE_SETS="$sets" "$test" \
  --gtest_filter=CircleFalsePositives.RateOnFreshDraws > "$log"
# The test asks for a rate below 1 % (its 95 % interval); under heavy blur that is measured, not
# assumed.
if MARKERBENCH_FRESH_NEGATIVE_SETS="$sets" MARKERBENCH_NEGATIVE_BLUR=paper "$test" \
  --gtest_filter=CircleFalsePositives.RateOnFreshDraws > "$heavy_log"; then
  heavy_verdict="below 1 % for every marker (the test's bound on the 95 % interval holds)."
else
  heavy_verdict="**not** below 1 % for every marker (the test's bound on the 95 % interval fails)."
fi
grep -q '^TABLE | all' "$heavy_log" || { echo "no rate under heavy blur: see $heavy_log" >&2; exit 1; }
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
  echo "## Under the paper's heavier blur"
  echo
  echo "The same frames with the blur drawn from 5, 6, 7, 8, 9 and 10 px instead (the heavier half"
  echo "of the paper's blur sweep, beyond the committed set's reach; \`NegativeSceneOptions\`,"
  echo "\`MARKERBENCH_NEGATIVE_BLUR=paper\`). The rate is"
  echo "$heavy_verdict"
  echo
  sed -n 's/^TABLE //p' "$heavy_log"
  echo
  echo "## Each find"
  echo
  echo "The marker, the frame, its blur, the image's noise σ as the tracker estimated it (0-1)"
  echo "and the design's misfit at the pose found (printed_appearance.h: a fraction of the"
  echo "contrast, over pixel pairs or blocks of them; the check rejects only a misfit above 0.1,"
  echo "over blocks 0.25, by more than 4 standard errors). With the set's blur:"
  echo
  sed -n 's/^FIND /- /p' "$log"
  echo
  echo "Under the paper's heavier blur:"
  echo
  sed -n 's/^FIND /- /p' "$heavy_log"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
