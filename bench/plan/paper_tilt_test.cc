// The circle tracker on the paper's blur and distance sweeps (scenarios/paper/fig7_blur.yaml:
// 1 m, noise variance 0.02; fig8_distance.yaml: 0.5-3.5 m, the same noise), their own frames
// (PlanFrames), against the best choice any tracker can make with the same pixels: the likelier
// of two fits on them, started from the true pose and from its mirror (testing/tilt_choice.h).
// Under heavy blur, or far away, a near-frontal marker looks nearly the same from its mirrored
// tilt, and that fit is itself wrong (beyond a tenth of the distance, the sweeps' success) on a
// share of the frames that the local bound's `success_at_bound` does not count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "bench/metrics/metrics.h"
#include "bench/plan/frame_plan.h"
#include "bench/plan/scenario.h"
#include "testing/sanitized_build.h"
#include "testing/tilt_choice.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/pixel_area_blur.h"

namespace markerbench {
namespace {

// The counts per sweep value of `kind`'s frames of the paper's `scenario_file` at values in
// [min_value, max_value] (with `found_only`, those the tracker finds); the fits from the truth
// start at each frame's blur and noise.
std::map<double, TiltChoiceCounts> CountPaperFrames(const std::string& scenario_file,
                                                    MarkerKind kind,
                                                    double min_value,
                                                    double max_value,
                                                    bool found_only = false) {
  ScenarioOverrides circle_only;
  circle_only.trackers = {"circle"};
  const Scenario scenario = LoadScenario(scenario_file, circle_only);
  const auto marker = std::find_if(scenario.markers.begin(),
                                   scenario.markers.end(),
                                   [&](const MarkerSpec& m) { return m.kind == kind; });
  if (marker == scenario.markers.end()) return {};
  const int marker_index = static_cast<int>(marker - scenario.markers.begin());
  const bool design = kind == MarkerKind::kCircleE || kind == MarkerKind::kCircleF;
  CircleTracker tracker;
  std::map<double, TiltChoiceCounts> cells;
  for (const PlannedFrame& planned : PlanFrames(scenario)) {
    if (planned.marker_index != marker_index || planned.sweep_value < min_value ||
        planned.sweep_value > max_value) {
      continue;
    }
    const RenderedFrame frame = RenderFrame(RequestFor(scenario, planned));
    // The edges' σ the fits start from: the blur with the pixel's area.
    const double edge_sigma_px = EdgeSigmaOfBlur(planned.degradations.blur_sigma_px);
    const double noise_sigma = std::sqrt(planned.degradations.noise_var);
    const FitFromTruthAndMirror from_truth =
        design ? DesignFitFromTruthAndMirror(scenario.camera, *marker, edge_sigma_px, noise_sigma)
               : PixelFitFromTruthAndMirror(scenario.camera, *marker, edge_sigma_px, noise_sigma);
    CountTiltChoice(frame.image,
                    scenario.camera,
                    *marker,
                    planned.cam_from_marker,
                    DistanceToMarker(planned.cam_from_marker, *marker),
                    tracker,
                    from_truth,
                    &cells[planned.sweep_value],
                    found_only);
  }
  return cells;
}

// In each cell the likelier fit is wrong on more than `max_wrong` of the 100 frames (so a
// success above 1 - max_wrong/100 is out of these frames' reach), and the tracker is not wrong
// more often (McNemar, each cell at 0.05 over `tests`, the cells of the test).
void ExpectAtTheLikelierFitsChoice(const std::map<double, TiltChoiceCounts>& cells,
                                   int max_wrong,
                                   size_t tests) {
  for (const auto& [value, counts] : cells) {
    SCOPED_TRACE("sweep value " + std::to_string(value));
    EXPECT_GT(counts.from_truth_wrong, max_wrong);
    EXPECT_GT(counts.OursWrongMoreOftenP(), 0.05 / tests)
        << counts.only_ours_wrong << " frames wrong only ours, " << counts.only_from_truth_wrong
        << " only from the truth";
  }
}

// circles_a at σ 7-10: the likelier fit is wrong on 5, 7, 8 and 9 of each σ's 100 frames, the
// tracker on 6, 6, 11 and 11, and on 6 frames where that fit is right, against 1 the other way
// (measured). Issue 21's 97 % is out of reach.
TEST(PaperBlurSweep, CirclesAChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "400 frames under heavy blur: the optimised build's";
  const std::map<double, TiltChoiceCounts> cells =
      CountPaperFrames("scenarios/paper/fig7_blur.yaml", MarkerKind::kCirclesA, 7.0, 10.0);
  ASSERT_EQ(cells.size(), 4u);
  ExpectAtTheLikelierFitsChoice(cells, 3, cells.size());
}

// circle_d at σ 5 and 6, where its dots are found by their blurred images
// (blurred_dot_search.h): the likelier fit is wrong on 28 and 21 of 100 frames, the tracker on
// 29 and 26 (only ours 1 and 6, only that fit's 0 and 1; measured). From σ 7 on the tracker
// loses frames that fit gets right, where it finds no marker (README).
TEST(PaperBlurSweep, CircleDChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "200 frames under heavy blur: the optimised build's";
  const std::map<double, TiltChoiceCounts> cells =
      CountPaperFrames("scenarios/paper/fig7_blur.yaml", MarkerKind::kCircleD, 5.0, 6.0);
  ASSERT_EQ(cells.size(), 2u);
  ExpectAtTheLikelierFitsChoice(cells, 3, cells.size());
}

// circle_d at σ 7, the one cell of the blur sweep where a circle marker succeeds on more than
// half of the frames with a median error above 1.5x its bound (1.51x, 54 % success,
// results/paper/summary.csv): on the 76 frames the tracker finds, the likelier fit is wrong on
// 22, the very frames the tracker is wrong on (measured: no discordant frame). Those are the
// mirror's frames, which the local bound does not count.
TEST(PaperBlurSweep, CircleDFoundAtSigma7ChoosesTheTiltAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "100 frames under heavy blur: the optimised build's";
  const std::map<double, TiltChoiceCounts> cells = CountPaperFrames(
      "scenarios/paper/fig7_blur.yaml", MarkerKind::kCircleD, 7.0, 7.0, /*found_only=*/true);
  ASSERT_EQ(cells.size(), 1u);
  const TiltChoiceCounts& counts = cells.begin()->second;
  EXPECT_GT(counts.frames, 50);
  // That fit wrong on more than a fifth of the frames found, where the bound's
  // `success_at_bound` puts 14 % of the cell's frames beyond a tenth of the distance.
  ExpectAtTheLikelierFitsChoice(cells, counts.frames / 5, 1);
}

// The markers of one circle, d, e and f, at 2.5 m and 3.5 m, where issue 21 asks for 90 % and
// 75 %: with one circle the tilt rests on the dot or the design inside it, a few pixels across,
// and the likelier fit is wrong on 15, 12 and 25 of the 100 frames at 2.5 m and 41, 38 and 47
// at 3.5 m, beyond both goals; the tracker on 18, 13 and 27, and 46, 37 and 49 (measured: d at
// 3.5 m on 6 frames where that fit is right, against 1 the other way).
TEST(PaperDistanceSweep, OneCircleMarkersChooseTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "600 frames, the designs' fits: the optimised build's";
  constexpr size_t kCells = 6;
  for (const MarkerKind kind : {MarkerKind::kCircleD, MarkerKind::kCircleE, MarkerKind::kCircleF}) {
    SCOPED_TRACE(ToString(kind));
    const std::map<double, TiltChoiceCounts> at_2_5 =
        CountPaperFrames("scenarios/paper/fig8_distance.yaml", kind, 2.5, 2.5);
    ASSERT_EQ(at_2_5.size(), 1u);
    ExpectAtTheLikelierFitsChoice(at_2_5, 10, kCells);
    const std::map<double, TiltChoiceCounts> at_3_5 =
        CountPaperFrames("scenarios/paper/fig8_distance.yaml", kind, 3.5, 3.5);
    ASSERT_EQ(at_3_5.size(), 1u);
    ExpectAtTheLikelierFitsChoice(at_3_5, 25, kCells);
  }
}

}  // namespace
}  // namespace markerbench
