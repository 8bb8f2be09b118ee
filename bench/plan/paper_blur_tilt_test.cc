// The circle tracker on the paper's blur sweep (scenarios/paper/fig7_blur.yaml: circles_a at
// 1 m, noise variance 0.02) at blur σ 7-10 px, its own frames (PlanFrames), against the best
// choice any tracker can make with the same pixels: the likelier of two fits on them, started
// from the true pose and from its mirror (testing/tilt_choice.h). Issue 21 asks for success
// ≥ 97 % there. Under that blur a near-frontal marker looks nearly the same from its mirrored
// tilt, and the likelier fit is itself wrong (beyond a tenth of the distance) on 5, 7, 9 and 9
// of each σ's 100 frames (measured): from these pixels 97 % is out of reach. The tracker is
// wrong on 6, 6, 10 and 10, and on 3 frames where that fit is right, against 1 the other way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "bench/plan/frame_plan.h"
#include "bench/plan/scenario.h"
#include "testing/sanitized_build.h"
#include "testing/tilt_choice.h"
#include "trackers/circle/circle_geometry.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/circle/photometric_refinement.h"

namespace markerbench {
namespace {

TEST(PaperBlurSweep, CircleTrackerChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "400 frames under heavy blur: the optimised build's";
  ScenarioOverrides circle_only;
  circle_only.trackers = {"circle"};
  const Scenario scenario = LoadScenario("scenarios/paper/fig7_blur.yaml", circle_only);
  const auto marker =
      std::find_if(scenario.markers.begin(), scenario.markers.end(), [](const MarkerSpec& m) {
        return m.kind == MarkerKind::kCirclesA;
      });
  ASSERT_NE(marker, scenario.markers.end());
  const int marker_index = static_cast<int>(marker - scenario.markers.begin());
  CircleTracker tracker;
  std::map<double, TiltChoiceCounts> cells;  // per blur σ
  for (const PlannedFrame& planned : PlanFrames(scenario)) {
    if (planned.marker_index != marker_index || planned.sweep_value < 7.0) continue;
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
        [&](const Image8& image, const Rigid3& truth) {
          const std::optional<PhotometricResult> fit =
              RefinePhotometricFromStarts(image,
                                          scenario.camera,
                                          *marker,
                                          {truth, OtherTilt(truth)},
                                          edge_sigma_px,
                                          noise_sigma);
          return fit ? std::optional<Rigid3>(fit->fit.cam_from_marker) : std::nullopt;
        },
        &cells[planned.sweep_value]);
  }
  ASSERT_EQ(cells.size(), 4u);
  for (const auto& [blur, counts] : cells) {
    SCOPED_TRACE("blur σ " + std::to_string(blur));
    // The premise: the likelier fit is wrong on more than 3 of the 100 frames.
    EXPECT_GT(counts.from_truth_wrong, 3);
    EXPECT_GT(counts.OursWrongMoreOftenP(), 0.05 / cells.size())
        << counts.only_ours_wrong << " frames wrong only ours, " << counts.only_from_truth_wrong
        << " only from the truth";
  }
}

}  // namespace
}  // namespace markerbench
