// The circle tracker on the paper's blur sweep (scenarios/paper/fig7_blur.yaml: 1 m, noise
// variance 0.02), its own frames (PlanFrames), against the best choice any tracker can make
// with the same pixels: the likelier of two fits on them, started from the true pose and from
// its mirror (testing/tilt_choice.h). Under heavy blur a near-frontal marker looks nearly the
// same from its mirrored tilt, and that fit is itself wrong (beyond a tenth of the distance) on
// a share of the frames that the local bound's `success_at_bound` does not count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "bench/plan/frame_plan.h"
#include "bench/plan/scenario.h"
#include "testing/sanitized_build.h"
#include "testing/tilt_choice.h"
#include "trackers/circle/circle_tracker.h"

namespace markerbench {
namespace {

// The counts per blur σ of `kind`'s frames at blur σ in [min_blur_px, max_blur_px].
std::map<double, TiltChoiceCounts> CountPaperBlurFrames(MarkerKind kind,
                                                        double min_blur_px,
                                                        double max_blur_px) {
  ScenarioOverrides circle_only;
  circle_only.trackers = {"circle"};
  const Scenario scenario = LoadScenario("scenarios/paper/fig7_blur.yaml", circle_only);
  const auto marker = std::find_if(scenario.markers.begin(),
                                   scenario.markers.end(),
                                   [&](const MarkerSpec& m) { return m.kind == kind; });
  if (marker == scenario.markers.end()) return {};
  const int marker_index = static_cast<int>(marker - scenario.markers.begin());
  CircleTracker tracker;
  std::map<double, TiltChoiceCounts> cells;
  for (const PlannedFrame& planned : PlanFrames(scenario)) {
    if (planned.marker_index != marker_index || planned.sweep_value < min_blur_px ||
        planned.sweep_value > max_blur_px) {
      continue;
    }
    const RenderedFrame frame = RenderFrame(RequestFor(scenario, planned));
    // The edges' σ the fits start from: the blur with the pixel's area.
    const double edge_sigma_px = std::hypot(planned.sweep_value, std::sqrt(1.0 / 12.0));
    const double noise_sigma = std::sqrt(planned.degradations.noise_var);
    CountTiltChoice(
        frame.image,
        scenario.camera,
        *marker,
        planned.cam_from_marker,
        scenario.poses.distance_m,
        tracker,
        PixelFitFromTruthAndMirror(scenario.camera, *marker, edge_sigma_px, noise_sigma),
        &cells[planned.sweep_value]);
  }
  return cells;
}

// In each cell the likelier fit is wrong on more than 3 of the 100 frames (so issue 21's
// success of 97 % is out of these frames' reach), and the tracker is not wrong more often.
void ExpectAtTheLikelierFitsChoice(const std::map<double, TiltChoiceCounts>& cells) {
  for (const auto& [blur, counts] : cells) {
    SCOPED_TRACE("blur σ " + std::to_string(blur));
    EXPECT_GT(counts.from_truth_wrong, 3);
    EXPECT_GT(counts.OursWrongMoreOftenP(), 0.05 / cells.size())
        << counts.only_ours_wrong << " frames wrong only ours, " << counts.only_from_truth_wrong
        << " only from the truth";
  }
}

// circles_a at σ 7-10: the likelier fit is wrong on 5, 7, 9 and 9 of each σ's 100 frames, the
// tracker on 6, 6, 10 and 10, and on 3 frames where that fit is right, against 1 the other way
// (measured).
TEST(PaperBlurSweep, CirclesAChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "400 frames under heavy blur: the optimised build's";
  const std::map<double, TiltChoiceCounts> cells =
      CountPaperBlurFrames(MarkerKind::kCirclesA, 7.0, 10.0);
  ASSERT_EQ(cells.size(), 4u);
  ExpectAtTheLikelierFitsChoice(cells);
}

// circle_d at σ 5 and 6, where its dots are found by their blurred images
// (blurred_dot_search.h): the likelier fit is wrong on 27 and 21 of 100 frames, the tracker on
// 29 and 23 (only ours 2 and 3, only that fit's 0 and 1; measured). From σ 7 on the tracker
// loses frames that fit gets right (the centre dot's test: README).
TEST(PaperBlurSweep, CircleDChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "200 frames under heavy blur: the optimised build's";
  const std::map<double, TiltChoiceCounts> cells =
      CountPaperBlurFrames(MarkerKind::kCircleD, 5.0, 6.0);
  ASSERT_EQ(cells.size(), 2u);
  ExpectAtTheLikelierFitsChoice(cells);
}

}  // namespace
}  // namespace markerbench
