// The refinement on the design's pixels (markers e and f) on rendered frames with known ground
// truth: from a perturbed start it recovers the pose and the blur; the clipping of noise at
// black and white, at the noise its residuals show, keeps its blur (and so its edges)
// unbiased; of the circle's two tilts it keeps the one the design shows; in the tracker it
// beats the edge points and the centre point on the same frames.
#include "trackers/circle/design_refinement.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "core/camera_yaml.h"
#include "core/marker_scaling.h"
#include "core/marker_yaml.h"
#include "core/pose_error.h"
#include "core/random.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
#include "testing/clipped_noise_testing.h"
#include "testing/paired_tracking.h"
#include "testing/sanitized_build.h"
#include "testing/square_tracker_testing.h"
#include "testing/tilt_choice.h"
#include "trackers/circle/circle_geometry.h"
#include "trackers/circle/circle_tracker.h"
#include "trackers/circle/conic.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

MarkerSpec Load(const std::string& kind) {
  return LoadMarkerYaml("scenarios/markers/" + kind + ".yaml");
}

TEST(DesignRefinement, RecoversThePoseAndTheBlurFromAPerturbedStart) {
  const Camera camera;
  Rng rng(3);
  for (const char* kind : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = Load(kind);
    for (double blur : {0.0, 2.0}) {
      SCOPED_TRACE(std::string(kind) + " blur " + std::to_string(blur));
      const Rigid3 truth = TiltedView(0.6, 30.0, 40.0);
      const RenderedFrame frame = RenderMarker(marker, truth, 0.005, blur, 7);
      const std::optional<PixelRefinement> refined = RefineDesign(
          frame.image, camera, marker, SlightlyPerturbed(truth, &rng), 1.0, std::sqrt(0.005));
      ASSERT_TRUE(refined);
      const Rigid3& pose = refined->fit.cam_from_marker;
      // Measured: 0.15-0.22 mm and 0.015-0.022° sharp (0.37-0.51 mm and 0.04-0.05° with the
      // pixel's area taken as a Gaussian), 1.0 mm and 0.10° at blur 2.
      EXPECT_LE(PositionError(pose, truth), blur == 0.0 ? 0.4e-3 : 1.5e-3);
      EXPECT_LE(RotationErrorDeg(pose, truth), blur == 0.0 ? 0.04 : 0.15);
      // The optics' σ (the model averages over the pixel): measured 0.02-0.048 px sharp, within
      // 0.007 px at blur 2.
      EXPECT_NEAR(refined->fit.sigma_px, blur, 0.08);
      EXPECT_GT(refined->pixels, 500);
    }
  }
}

// Through a wide lens (scenarios/cameras/wide_distorted.yaml), near the frame's side where a
// pixel spans about 2 of the pinhole's: the design is averaged over each pixel's footprint
// through the lens, so a sharp, nearly noise-free frame fits at a blur near 0 and near the true
// pose, from a start a typical edge fit away.
TEST(DesignRefinement, FitsASharpDesignThroughAWideLens) {
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  Rng rng(5);
  for (const char* kind : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = Load(kind);
    for (const double roll_deg : {30.0, 120.0}) {
      SCOPED_TRACE(std::string(kind) + " roll " + std::to_string(roll_deg));
      Rigid3 truth = TiltedView(0.45, 30.0, roll_deg);
      truth.translation.x() = 0.7 * truth.translation.z();
      FrameRequest request = SeededFrameRequest(marker, truth, 0.001, 0.0, 9, 3);
      request.scene.camera = camera;
      const RenderedFrame frame = RenderFrame(request);
      const std::optional<PixelRefinement> refined = RefineDesign(frame.image,
                                                                  camera,
                                                                  marker,
                                                                  SlightlyPerturbed(truth, &rng),
                                                                  std::sqrt(1.0 / 12.0),
                                                                  std::sqrt(0.001));
      ASSERT_TRUE(refined);
      // Measured: σ 0.020 px (the model's least) and 0.08-0.32 mm; with the pinhole's pixel
      // footprint, σ 0.21-0.26 px and 0.13-0.77 mm.
      EXPECT_LT(refined->fit.sigma_px, 0.1);
      EXPECT_LT(PositionError(refined->fit.cam_from_marker, truth), 0.45e-3);
    }
  }
}

// A print's grey is rarely the one specified (and a camera's response moves it too): f's wedge
// printed at 0.4 where the design says 0.5. The wedge's level is fitted with the pose from a
// fit's second round on (design_refinement.cc), and the pose is as good as on the same frame
// printed as designed: measured 0.81-1.32 times its error on 12 frames (0.16-3.4 mm), the level
// 0.095-0.104 below the design's (within 0.006 of it printed as designed). Held at the design's
// 0.5, the fit moved the wedge's sides to match the brighter grey: 5.1 mm off on the first frame
// (0.46 as designed).
TEST(DesignRefinement, FitsTheGreyThePrintShows) {
  const Camera camera;
  const MarkerSpec marker = Load("circle_f");
  MarkerSpec grey_print = marker;
  grey_print.layers[1].color = Rgb::Constant(0.4);
  const MarkerSpec& printed = grey_print;
  Rng rng(5);
  for (int i = 0; i < 6; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const Rigid3 truth = RandomTiltedView(0.6, 10.0, 40.0, &rng);
    const Rigid3 start = SlightlyPerturbed(truth, &rng);
    std::vector<double> errors;
    for (const MarkerSpec* print : {&printed, &marker}) {
      const RenderedFrame frame = RenderMarker(*print, truth, 0.005, 1.0, 60 + i);
      const std::optional<PixelRefinement> refined =
          RefineDesign(frame.image, camera, marker, start, 1.0, std::sqrt(0.005));
      ASSERT_TRUE(refined);
      // The levels: offset, gain, and the grey's luma less the design's.
      ASSERT_EQ(refined->fit.levels.size(), 3);
      EXPECT_NEAR(refined->fit.levels[2], print == &printed ? -0.1 : 0.0, 0.01);
      errors.push_back(PositionError(refined->fit.cam_from_marker, truth));
    }
    EXPECT_LE(errors[0], 1.5 * errors[1] + 1e-4);
  }
}

// f at 1 m, blur σ = 3, noise variance 0.02 (the paper's blur sweep): the noise clipped at the
// black disk lifts its pixels, and at the white paper lowers them, most where the blurred
// edge is near either level, so an edge model without the clipping sees the edges sharper
// than they are (its σ measured 11 % low) and the wedge's sides moved. The clipping depends
// on the noise, which a global estimate on clipped white paper puts far too low (the
// detector's: 0.06 for these 0.14); from such a start the fit on the clipped pixels'
// likelihood finds it from its residuals, its noise within 5 % (0.135-0.141) and the σ right
// (1.2 % low).
TEST(DesignRefinement, ModelsTheNoiseClippedAtBlackAndWhite) {
  const Camera camera;
  const MarkerSpec marker = Load("circle_f");
  const double ratio = MeanBlurRatioUnderClippedNoise(
      marker, 3.0, [&](const Image8& image, const Rigid3& truth, double blur, double noise) {
        return RefineDesign(image, camera, marker, truth, blur, noise);
      });
  EXPECT_NEAR(ratio, 1.0, 0.03);
}

// f's circle alone is seen the same from either of its two tilts (§4.7); the design is not.
// Fits started on each tilt end in a minimum each, and the design's pixels keep the true one.
TEST(DesignRefinement, KeepsTheTiltTheDesignShows) {
  const Camera camera;
  const MarkerSpec marker = Load("circle_f");
  Rng rng(9);
  for (int i = 0; i < 6; ++i) {
    const double tilt = rng.Uniform(15.0, 40.0), roll = rng.Uniform(0.0, 360.0);
    SCOPED_TRACE("tilt " + std::to_string(tilt) + " roll " + std::to_string(roll));
    const Rigid3 truth = TiltedView(0.6, tilt, roll);
    const RenderedFrame frame = RenderMarker(marker, truth, 0.02, 1.0, 40 + i);
    std::vector<PixelRefinement> fits;
    for (const double start_tilt : {-tilt, tilt}) {
      const std::optional<PixelRefinement> refined = RefineDesign(
          frame.image, camera, marker, TiltedView(0.6, start_tilt, roll), 1.0, std::sqrt(0.02));
      ASSERT_TRUE(refined);
      fits.push_back(*refined);
    }
    // Measured: 420-760 mm from the other tilt, 0.5-3.9 mm from the true one.
    EXPECT_GT(PositionError(fits[0].fit.cam_from_marker, truth), 0.1);
    EXPECT_LT(PositionError(fits[1].fit.cam_from_marker, truth), 0.01);
    const std::vector<double> log_ratios = DesignLogRatios(frame.image, camera, marker, fits);
    EXPECT_EQ(log_ratios[1], 0.0);
    EXPECT_GT(log_ratios[0], 100.0);
    // From both starts in either order, the true tilt's fit, whether a later start is given up
    // after its first round where it is far behind (the default) or at all behind (0), or never
    // (infinity: then the other tilt's fit follows, far less likely).
    const double never = std::numeric_limits<double>::infinity();
    for (const double max_log_ratio : {100.0, 0.0, never}) {
      DesignRefinementOptions options;
      options.max_first_round_log_ratio = max_log_ratio;
      for (const bool true_first : {false, true}) {
        const Rigid3 other_tilt = TiltedView(0.6, -tilt, roll);
        const std::vector<Rigid3> starts = true_first ? std::vector<Rigid3>{truth, other_tilt}
                                                      : std::vector<Rigid3>{other_tilt, truth};
        const std::vector<RankedFit<PixelRefinement>> ranked = RefineDesignFromStarts(
            frame.image, camera, marker, starts, 1.0, std::sqrt(0.02), options);
        ASSERT_FALSE(ranked.empty());
        EXPECT_EQ(ranked[0].result.fit.cam_from_marker.translation,
                  fits[1].fit.cam_from_marker.translation);
        EXPECT_EQ(ranked[0].log_ratio, 0.0);
        if (max_log_ratio == never) {
          ASSERT_EQ(ranked.size(), 2u);
          EXPECT_GT(PositionError(ranked[1].result.fit.cam_from_marker, truth), 0.1);
          EXPECT_GT(ranked[1].log_ratio, 100.0);
        }
      }
    }
  }
}

// Without noise the true tilt's fit leaves about 0.6 levels (8-bit rounding and the model's
// error), the other tilt's 80-90: it takes a gain near 3 and a σ near 1 px, so that the ink
// falls far below black and the paper far above white, where the clipped likelihood takes a
// pixel as certain. Judged at the mean of the two fits' noise (0.17), that made the clipped
// pixels cheaper than the true fit's and the other tilt won on 28 of the paper's 100 noise-free
// frames of e (3 of 100 of f); judged at the least noise any fit leaves, never. Measured on
// these 12 frames of e at the paper's ink area: the mean chose the other tilt on 8 (on two, both
// starts end at the true tilt).
TEST(DesignRefinement, KeepsTheTrueTiltWithoutNoise) {
  const Camera camera;
  const MarkerSpec raw = Load("circle_e");
  const MarkerSpec marker = ScaledMarker(raw, EqualAreaFactor(raw, 0.01));
  Rng rng(21);
  for (int i = 0; i < 12; ++i) {
    const Rigid3 truth = RandomTiltedView(0.6, 0.0, 40.0, &rng);
    const RenderedFrame frame = RenderMarker(marker, truth, 0.0, 0.0, 1);
    std::vector<PixelRefinement> fits;
    for (const Rigid3& start : {OtherTilt(truth), truth}) {
      const std::optional<PixelRefinement> refined =
          RefineDesign(frame.image, camera, marker, start, std::sqrt(1.0 / 12.0), 0.0);
      ASSERT_TRUE(refined);
      fits.push_back(*refined);
    }
    ASSERT_LT(PositionError(fits[1].fit.cam_from_marker, truth), 1e-3) << "frame " << i;
    // (Near a frontal view both starts end at the true tilt.)
    const std::vector<double> log_ratios = DesignLogRatios(frame.image, camera, marker, fits);
    const size_t best = std::min_element(log_ratios.begin(), log_ratios.end()) - log_ratios.begin();
    EXPECT_LT(PositionError(fits[best].fit.cam_from_marker, truth), 1e-3) << "frame " << i;
  }
}

// Near fronto-parallel and far, or blurred, f's design tells its two tilts apart only weakly: at
// 1.5 m (the circle 40 px across) and 3-8° of tilt, the best fit at the mirrored pose differs from
// the true pose's image by about one noise σ in all (0.7-1.6 σ on noise-free renders), and so at 1
// m under blur σ = 2 px and 5-15° of tilt (the wedge's sides blurred over a quarter of the circle's
// radius). The least cost between fits started at the true pose and at its mirror (no search: the
// best a likelihood can do with the right basins) is then wrong on several frames, and the tracker,
// which finds its starts itself, about as often (McNemar's test). Measured, of 60: at 1.5 m 12
// wrong from the truth, 14 ours (3 only ours, 1 only from the truth); at 1 m and blur 2, 5 and 8
// (4 and 1); with the wedge's grey held at the design's (blurred_design.h), 11 and 13, 7 and 8. Of
// 30 earlier: at 1.5 m 2 from the truth, 3 ours; at 1 m and blur 2, 3 and 4; with the pixel's area
// taken as a Gaussian, 4 and 4, and 3 and 3; before the clipped likelihood, seeds 14-18 at 1.5 m:
// 6, 11, 12, 4, 9 from the truth, ours the same or one more; seeds 15-17 at blur 2: 4, 3, 7 from
// the truth, ours 3, 2, 6. No choice by likelihood reaches 95 % success on such poses with this
// design (results/paper: the tracker misses 8 and 6 of the sweep's 100 frames of f at 1.5 m and at
// blur 2, most on the other tilt). Not under the sanitizers (testing/sanitized_build.h).
TEST(DesignRefinement, ChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "counts over 60 frames: the optimised build's";
  const MarkerSpec marker = Load("circle_f");
  const Camera camera;
  CircleTracker tracker;
  struct Case {
    double distance_m, min_tilt_deg, max_tilt_deg, blur;
    uint64_t pose_seed;
  };
  for (const Case& c : {Case{1.5, 3.0, 8.0, 0.0, 13}, Case{1.0, 5.0, 15.0, 2.0, 14}}) {
    SCOPED_TRACE("distance " + std::to_string(c.distance_m) + " blur " + std::to_string(c.blur));
    TiltedFrames views;
    views.distance_m = c.distance_m;
    views.min_tilt_deg = c.min_tilt_deg;
    views.max_tilt_deg = c.max_tilt_deg;
    views.blur_sigma_px = c.blur;
    views.pose_seed = c.pose_seed;
    views.first_noise_seed = 200;
    views.frames = 60;
    const TiltChoiceCounts counts =
        CountTiltChoices(marker,
                         tracker,
                         views,
                         DesignFitFromTruthAndMirror(
                             camera, marker, std::max(c.blur, 0.3), std::sqrt(views.noise_var)));
    // The premise: even the likelier of the two fits keeps the mirror on some frames.
    EXPECT_GE(counts.from_truth_wrong, 2);
    // Two tests, so each at 0.05/2 (Bonferroni), as the far-away test below.
    EXPECT_GT(counts.OursWrongMoreOftenP(), 0.05 / 2)
        << counts.only_ours_wrong << " frames wrong only ours, " << counts.only_from_truth_wrong
        << " only from the truth";
  }
}

// The same at the far end of the paper's distance sweep (equal ink area, noise variance 0.02, tilts
// of 0-40°), where the paper cells below find 54-77 % of frames, their median errors 1.5-2.8× the
// median bound: the fits from the truth and its mirror keep the mirror about as often as ours.
// Measured of 100 frames, wrong from the truth and its mirror, then wrong only ours and only from
// the truth: e at 3 m 29, 1 and 2; e at 3.5 m 37, 9 and 2 (p 0.033); f at 3 m 45, 2 and 0; f at
// 3.5 m 51, 1 and 2. Four tests, so each at 0.05/4 (Bonferroni).
// (There the fits keep the start's noise, the detector's 2.5× low estimate, as too few pixels are
// mid-range to measure it. Fitted at the noise their censored likelihood finds, a probe not kept: 2
// and 0 here, but on the paper's frames of d, e and f no cell moved by a sign test, success at
// 3.5 m d 53 → 54 %, e 64 → 61 %.) Not under the sanitizers (testing/sanitized_build.h).
TEST(DesignRefinement, FarAwayChoosesTheTiltAsOftenAsFromTheTruePoseAndItsMirror) {
  if (kSanitizedBuild) GTEST_SKIP() << "counts over 400 frames: the optimised build's";
  const Camera camera;
  CircleTracker tracker;
  struct Case {
    const char* kind;
    double distance_m;
  };
  const std::vector<Case> cases = {
      {"circle_e", 3.0}, {"circle_e", 3.5}, {"circle_f", 3.0}, {"circle_f", 3.5}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.kind) + " distance " + std::to_string(c.distance_m));
    const MarkerSpec loaded = Load(c.kind);
    const MarkerSpec marker = ScaledMarker(loaded, EqualAreaFactor(loaded, 0.01));
    TiltedFrames views;
    views.distance_m = c.distance_m;
    views.frames = 100;
    views.pose_seed = 32;
    views.first_noise_seed = 500;
    const TiltChoiceCounts counts = CountTiltChoices(
        marker,
        tracker,
        views,
        DesignFitFromTruthAndMirror(camera, marker, 0.3, std::sqrt(views.noise_var)));
    // The premise: the likelier of the two fits is often the mirror.
    EXPECT_GE(counts.from_truth_wrong, views.frames / 10);
    EXPECT_GT(counts.OursWrongMoreOftenP(), 0.05 / cases.size())
        << counts.only_ours_wrong << " frames wrong only ours, " << counts.only_from_truth_wrong
        << " only from the truth";
  }
}

// A frame of the paper's noise sweep (seed 6): `kind` at the sweep's equal ink area, seen
// from `truth` with the noise of its sweep `cell` and `trial`, tracked by `tracker`.
TrackResult TrackPaperNoiseFrame(const std::string& kind,
                                 const Rigid3& truth,
                                 double noise_var,
                                 int cell,
                                 int trial,
                                 CircleTracker* tracker) {
  const MarkerSpec loaded = Load(kind);
  const MarkerSpec marker = ScaledMarker(loaded, EqualAreaFactor(loaded, 0.01));
  FrameRequest request = MarkerFrameRequest(marker, truth, noise_var, 0.0, 1);
  request.noise_seed = SeedFor(6, cell, trial, SeedPurpose::kNoise);
  const RenderedFrame frame = RenderFrame(request);
  return tracker->Track({&frame.image, &request.scene.camera, &marker});
}

// The image of a plane is the same from the pose with r1, r2 and t negated, which puts the
// marker behind the camera, and a fit on pixels can end there. A frame of the paper's noise
// sweep (e, σ² = 0.25, trial 54 of a 300-trial run with seed 6): the design's fit went there
// and the tracker returned "the pose puts the marker behind the camera" where the edge fit
// alone finds the marker. A fit behind the camera is no fit; the other start's fit stands
// (measured: 3.8 mm off).
TEST(DesignRefinement, NeverEndsBehindTheCamera) {
  Rigid3 truth;
  truth.rotation << -0.8258926052745595, 0.37458499494685926, -0.42141130278323324,
      0.36464911771573155, 0.9249192974959791, 0.10749564674294076, 0.43003770241914724,
      -0.06488740001114188, -0.9004760961945936;
  truth.translation << 0.03304914374629794, 0.027977091003279518, 0.5984354906559527;
  CircleTracker tracker;
  const TrackResult result = TrackPaperNoiseFrame("circle_e", truth, 0.25, 0, 54, &tracker);
  ASSERT_EQ(result.status, TrackStatus::kOk) << result.message;
  EXPECT_LT(PositionError(result.hypotheses.front(), truth), 0.01);
}

// Under heavy noise the edge points alone scatter by nearly max_edge_rms_px, and a pose that
// fits the design leaves them a little more. A frame of the paper's noise sweep (f, σ² = 0.3,
// trial 87, cell 11): the edge fit's residual 1.80 px, the design fit's 2.13 px, which a limit
// at max_edge_rms_px threw away, returning the edge fit's pose on the circle's other tilt,
// 295 mm off. The design fit is kept within half a pixel of the edge fit's residual
// (measured: 7.4 mm off).
TEST(DesignRefinement, StandsWhereNoiseAloneMovesTheEdgesPastTheLimit) {
  Rigid3 truth;
  truth.rotation << -0.28916230788533087, -0.9347450194966205, -0.20648706551426288,
      -0.9566172341902511, 0.27413402811735216, 0.09866104539456665, -0.035617789777344686,
      0.2260581410929877, -0.9734624234642852;
  truth.translation << -0.026068199943199245, -0.01492101535060161, 0.5992477052543701;
  CircleTracker tracker;
  const TrackResult result = TrackPaperNoiseFrame("circle_f", truth, 0.3, 11, 87, &tracker);
  ASSERT_EQ(result.status, TrackStatus::kOk) << result.message;
  EXPECT_TRUE(tracker.diagnostics().photometric_used);
  EXPECT_GT(tracker.diagnostics().edge_rms_px, CircleTrackerOptions().max_edge_rms_px);
  EXPECT_LT(PositionError(result.hypotheses.front(), truth), 0.02);
}

// OtherTilt, the start of the circle's other tilt: its own inverse; from a centre on the
// optical axis the tilt about the same axis the other way, seen as an ellipse of the same
// shape with its centre mirrored through the principal point (0.8-2.3 px apart here, which
// the fit then closes).
TEST(OtherTilt, IsItsOwnInverseAndMirrorsTheEllipse) {
  const Camera camera;
  for (const double tilt : {10.0, 25.0, 40.0}) {
    for (const double roll : {0.0, 70.0}) {
      const Rigid3 pose = TiltedView(0.8, tilt, roll);
      const Rigid3 other = OtherTilt(pose);
      const Rigid3 back = OtherTilt(other);
      EXPECT_LT((back.rotation - pose.rotation).norm(), 1e-12);
      EXPECT_LT((back.translation - pose.translation).norm(), 1e-12);
      EXPECT_LT((other.rotation - TiltedView(0.8, -tilt, roll).rotation).norm(), 1e-12);
      const auto ellipse = [&](const Rigid3& cam_from_plane) {
        return EllipseFromConic(ImageOfCircle<double>(
            camera.K() * RayFromPlane(cam_from_plane), Eigen::Vector2d::Zero(), 0.05));
      };
      const Ellipse seen = ellipse(pose), from_other = ellipse(other);
      EXPECT_NEAR(from_other.semi_major, seen.semi_major, 1e-9);
      EXPECT_NEAR(from_other.semi_minor, seen.semi_minor, 1e-9);
      const Eigen::Vector2d principal(camera.cx, camera.cy);
      EXPECT_LT((from_other.center + seen.center - 2.0 * principal).norm(), 1e-6);
      EXPECT_GT((from_other.center - seen.center).norm(), 0.5);
    }
  }
}

// 24 frames of f at 1 m and σ² = 0.02 tracked with and without the pixels: the camera-centre
// error drops on most frames (measured: 21 of 24) and so does its median (measured: 4.4 mm
// against 9.1 mm).
TEST(DesignRefinement, BeatsTheEdgesAndTheCentrePointOnTheSameFrames) {
  CircleTrackerOptions edges_only;
  edges_only.photometric = false;
  CircleTracker with_pixels, without_pixels(edges_only);
  const PairedErrors errors =
      TrackPaired(Load("circle_f"), with_pixels, without_pixels, 1.0, 0.02, 24, 11, 100);
  const double on = UpperMedian(errors.first), off = UpperMedian(errors.second);
  EXPECT_LE(on, 0.7 * off) << on << " vs " << off;
  EXPECT_GE(errors.first_better, 17);  // a sign test: P(>= 17 of 24 | no difference) = 0.032
}

}  // namespace
// Where the pixels hardly tell the circle's two tilts apart (at the far end of the paper's
// distance sweep), the tracker returns the other tilt's fit on them as a second hypothesis, and it
// is the truth on most frames whose first is wrong (measured: f 23 of 29, with two hypotheses on 59
// of 60 frames; a 15 of 20, on 43); near (0.6 m) the pixels rule the other out, and no frame has
// one. f's fit is on its design's pixels (design_refinement.h), a's on its disks'
// (photometric_refinement.h). Not under the sanitizers (testing/sanitized_build.h).
TEST(DesignRefinement, TheTrackerOffersTheOtherTiltWhereThePixelsHardlyTellThemApart) {
  if (kSanitizedBuild) GTEST_SKIP() << "counts over 160 frames: the optimised build's";
  const Camera camera;
  for (const char* kind : {"circle_f", "circles_a"}) {
    SCOPED_TRACE(kind);
    const MarkerSpec loaded = Load(kind);
    const MarkerSpec marker = ScaledMarker(loaded, EqualAreaFactor(loaded, 0.01));
    CircleTrackerOptions options;
    CircleTracker tracker(options);
    struct Case {
      double distance_m;
      int frames;
    };
    for (const Case& c : {Case{3.5, 60}, Case{0.6, 20}}) {
      SCOPED_TRACE("distance " + std::to_string(c.distance_m));
      const double wrong_m = 0.1 * c.distance_m;
      Rng rng(32);
      int first_wrong = 0, second_right_where_first_wrong = 0, with_second = 0;
      for (int i = 0; i < c.frames; ++i) {
        const Rigid3 truth = RandomTiltedView(c.distance_m, 0.0, 40.0, &rng);
        const RenderedFrame frame = RenderMarker(marker, truth, 0.02, 0.0, 500 + i);
        tracker.Reset();
        const TrackResult result = tracker.Track({&frame.image, &camera, &marker});
        ASSERT_EQ(result.status, TrackStatus::kOk) << "frame " << i << ": " << result.message;
        const std::optional<double> log_ratio = tracker.diagnostics().second_tilt_log_ratio;
        ASSERT_LE(result.hypotheses.size(), 2u);
        if (result.hypotheses.size() == 2) {
          ++with_second;
          ASSERT_TRUE(log_ratio) << "frame " << i;
          EXPECT_LE(*log_ratio, options.max_second_hypothesis_log_ratio) << "frame " << i;
          // The other tilt: its plane's normal apart from the first's.
          EXPECT_LT(result.hypotheses[1].rotation.col(2).dot(result.hypotheses[0].rotation.col(2)),
                    std::cos(options.min_branch_angle_rad))
              << "frame " << i;
        } else if (log_ratio) {
          EXPECT_GT(*log_ratio, options.max_second_hypothesis_log_ratio) << "frame " << i;
        }
        if (!(PositionError(result.hypotheses[0], truth) <= wrong_m)) {
          ++first_wrong;
          second_right_where_first_wrong += result.hypotheses.size() == 2 &&
                                            PositionError(result.hypotheses[1], truth) <= wrong_m;
        }
      }
      if (c.distance_m > 1.0) {
        EXPECT_GE(first_wrong, c.frames / 5);  // the premise
        EXPECT_GE(with_second, first_wrong);
        EXPECT_GE(2 * second_right_where_first_wrong, first_wrong);
      } else {
        EXPECT_EQ(with_second, 0);
        EXPECT_EQ(first_wrong, 0);
      }
    }
  }
}

}  // namespace markerbench
