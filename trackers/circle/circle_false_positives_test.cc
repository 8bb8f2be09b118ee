// False positives of the circle tracker (issue 21): on the negative set (testing/
// negative_scenes.h, 560 frames of clutter and other marker systems) no circle marker a-f
// may be reported, in detection mode or in tracking mode after a frame that showed it (the
// set's frames of e and f do not count for those two). Under the sanitizers, every fourth frame
// (testing/sanitized_build.h). One frame that needs the design check's blocks of samples, and one
// under heavy blur that needs the feature dot's contrast to be the design's. And,
// when asked, the rate on fresh draws of the set.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "bench/metrics/intervals.h"
#include "core/marker_yaml.h"
#include "renderer/test_scenes.h"
#include "testing/negative_scenes.h"
#include "testing/sanitized_build.h"
#include "testing/square_tracker_testing.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/printed_appearance.h"

namespace markerbench {
namespace {

constexpr const char* kKinds[] = {
    "circles_a", "circles_b", "circles_c", "circle_d", "circle_e", "circle_f"};

// Whether frame `negative` is one of `kind`'s own (e and f are in the set as other markers).
bool ShowsKind(const NegativeFrame& negative, const std::string& kind) {
  return negative.label.find("(" + kind + ")") != std::string::npos;
}

TEST(CircleFalsePositives, NoMarkerOnTheNegativeSet) {
  std::vector<MarkerSpec> markers;
  std::vector<CircleTracker> tracking;  // each has just tracked its marker
  for (const char* kind : kKinds) {
    markers.push_back(LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml"));
    tracking.emplace_back();
    const TrackedFrame primed = RenderAndTrack(
        &tracking.back(), markers.back(), markers.back(), TiltedView(0.8, 20.0, 0.0), 0.01, 1);
    ASSERT_EQ(primed.result.status, TrackStatus::kOk) << kind;
  }
  const Camera camera = FrameRequest().scene.camera;
  int found = 0, tries = 0, frames = 0;
  for (int i = 0; i < kNegativeSetSize; i += SanitizedStride(4)) {
    ++frames;
    const NegativeFrame negative = RenderNegative(i);
    const Observation observation{&negative.frame.image, &camera, nullptr};
    for (size_t k = 0; k < markers.size(); ++k) {
      if (ShowsKind(negative, kKinds[k])) continue;
      Observation of_marker = observation;
      of_marker.marker = &markers[k];
      CircleTracker detection;
      CircleTracker after_the_marker = tracking[k];
      for (CircleTracker* tracker : {&detection, &after_the_marker}) {
        const TrackResult result = tracker->Track(of_marker);
        ++tries;
        found += result.status == TrackStatus::kOk;
        EXPECT_NE(result.status, TrackStatus::kOk)
            << kKinds[k] << " found in " << negative.label
            << (tracker == &detection ? "" : " in tracking mode");
      }
    }
  }
  EXPECT_EQ(found, 0) << "of " << tries << " tries";
  EXPECT_GT(tries, 2 * 6 * (frames - 30 / SanitizedStride(4)));
}

// Frame "dots 218" of the set: circle_f's closed-form pose (from the circle's edge points, before
// the fit on the pixels) puts its circle on a cluster of dots. The paper around it misfits alike
// over wide areas, which the blocks of the design check show and single pixel pairs do not
// (measured: 0.27 over blocks, above their 0.25; 0.22 over pairs, not significantly above 0.1); the
// tracker reports no marker. The tracker's fitted pose on grey squares ("squares 141", circle_d)
// needed the blocks until the fit took steps below 1 % of its cost unevaluated; since then no frame
// of this set or five fresh ones does at the fitted pose, and this one only at the closed form.
TEST(CircleFalsePositives, BlocksOfTheDesignCheckRejectAClusterOfDots) {
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/circle_f.yaml");
  const Camera camera = FrameRequest().scene.camera;
  const NegativeFrame negative = RenderNegative(218);
  ASSERT_EQ(negative.label, "dots 218");
  CircleTracker tracker;
  const TrackResult result = tracker.Track({&negative.frame.image, &camera, &marker});
  EXPECT_NE(result.status, TrackStatus::kOk);
  const CircleDiagnostics& d = tracker.diagnostics();
  ASSERT_TRUE(d.analytic_cam_from_marker);
  AppearanceOptions pairs_alone;
  pairs_alone.blocks_per_side = 0;
  EXPECT_TRUE(CheckPrintedAppearance(negative.frame.image,
                                     camera,
                                     marker,
                                     *d.analytic_cam_from_marker,
                                     d.image_blur_sigma_px,
                                     pairs_alone)
                  .ShowsMarker());
  EXPECT_FALSE(
      CheckPrintedAppearance(
          negative.frame.image, camera, marker, *d.analytic_cam_from_marker, d.image_blur_sigma_px)
          .ShowsMarker());
}

// Frame "squares 198" of fresh set 5 under the paper's heavier blur (σ 6 px, noise-free):
// circle_d's tracker took a blurred grey square for its disk, and the paper past the square's
// corner for its feature dot, at 0.62 of the dot's designed contrast, measured to 0.03 (within
// contrast_tolerance, so the search took it before feature_dot_tolerance; the design check's
// misfit, about 0.06, is below its 0.1).
TEST(CircleFalsePositives, AFeatureDotMustShowTheDesignsContrast) {
  NegativeSceneOptions scenes;
  scenes.blur_sigmas_px = kPaperBlurSigmasPx;
  const NegativeFrame negative = RenderNegative(198, 5, scenes);
  ASSERT_EQ(negative.label, "squares 198");
  const MarkerSpec marker = LoadMarkerYaml("scenarios/markers/circle_d.yaml");
  const Camera camera = FrameRequest().scene.camera;
  const Observation observation{&negative.frame.image, &camera, &marker};
  CircleTracker tracker;
  EXPECT_NE(tracker.Track(observation).status, TrackStatus::kOk);
  CircleTrackerOptions within_contrast_tolerance;
  BlurredDotOptions& dots = within_contrast_tolerance.detector.blurred_dots;
  dots.feature_dot_tolerance = dots.contrast_tolerance;
  CircleTracker lenient(within_contrast_tolerance);
  EXPECT_EQ(lenient.Track(observation).status, TrackStatus::kOk);
}

// The rate out of sample (results/circle_false_positives.md, written by
// scripts/false_positive_rate.sh): detection mode on fresh draws of the negative set, sets 1 to
// MARKERBENCH_FRESH_NEGATIVE_SETS (the committed set above is the one the tracker was checked
// on while it was built). Prints each find and a markdown table of the rate per marker with
// its 95 % Wilson interval, which must lie below 1 %. Skipped unless the variable is set: a
// measurement of minutes, not a check for every build. MARKERBENCH_NEGATIVE_BLUR=paper draws
// the blur from the heavier half of the paper's sweep (5-10 px) instead of the set's 0-4.
TEST(CircleFalsePositives, RateOnFreshDraws) {
  const char* sets_text = std::getenv("MARKERBENCH_FRESH_NEGATIVE_SETS");
  if (!sets_text) GTEST_SKIP() << "MARKERBENCH_FRESH_NEGATIVE_SETS=N measures on N fresh sets";
  const int sets = std::atoi(sets_text);
  ASSERT_GT(sets, 0) << sets_text;
  NegativeSceneOptions scenes;
  if (const char* blur = std::getenv("MARKERBENCH_NEGATIVE_BLUR")) {
    ASSERT_EQ(std::string(blur), "paper") << "MARKERBENCH_NEGATIVE_BLUR: 'paper' or unset";
    scenes.blur_sigmas_px = kPaperBlurSigmasPx;
  }
  const Camera camera = FrameRequest().scene.camera;
  std::vector<MarkerSpec> markers;
  for (const char* kind : kKinds) {
    markers.push_back(LoadMarkerYaml(std::string("scenarios/markers/") + kind + ".yaml"));
  }
  std::vector<int> found(markers.size(), 0), tries(markers.size(), 0);
  for (int set = 1; set <= sets; ++set) {
    for (int i = 0; i < kNegativeSetSize; ++i) {
      const NegativeFrame negative = RenderNegative(i, set, scenes);
      for (size_t k = 0; k < markers.size(); ++k) {
        if (ShowsKind(negative, kKinds[k])) continue;
        CircleTracker tracker;
        const TrackResult result = tracker.Track({&negative.frame.image, &camera, &markers[k]});
        ++tries[k];
        if (result.status != TrackStatus::kOk) continue;
        ++found[k];
        const CircleDiagnostics& d = tracker.diagnostics();
        std::printf("FIND %s in set %d, %s: blur %g px, noise sigma %.3f, design misfit %.3f\n",
                    kKinds[k],
                    set,
                    negative.label.c_str(),
                    negative.degradations.blur_sigma_px,
                    d.noise_sigma,
                    d.appearance_misfit);
      }
    }
  }
  std::printf("TABLE | marker | tries | found | rate | 95 %% interval |\n");
  std::printf("TABLE |---|---|---|---|---|\n");
  int all_found = 0, all_tries = 0;
  for (size_t k = 0; k <= markers.size(); ++k) {
    const bool all = k == markers.size();
    const int f = all ? all_found : found[k], n = all ? all_tries : tries[k];
    const Interval interval = WilsonInterval(f, n);
    std::printf("TABLE | %s | %d | %d | %.3f %% | %.3f-%.3f %% |\n",
                all ? "all" : kKinds[k],
                n,
                f,
                100.0 * f / n,
                100.0 * interval.lo,
                100.0 * interval.hi);
    if (!all) {
      all_found += f;
      all_tries += n;
    }
    EXPECT_LT(interval.hi, 0.01) << (all ? "all" : kKinds[k]);
  }
}

}  // namespace
}  // namespace markerbench
