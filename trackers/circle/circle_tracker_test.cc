// The circle tracker on rendered frames with known ground truth (issues 3, 22): round trips
// for markers a-f over distance, tilt and roll; no marker; a half-visible marker; frames and
// signs; tracking mode; gamma-encoded frames; options.
#include "trackers/circle/circle_tracker.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/binomial_tail.h"
#include "core/camera_yaml.h"
#include "core/gamma_curve.h"
#include "core/marker_scaling.h"
#include "core/marker_yaml.h"
#include "core/pose_error.h"
#include "core/random.h"
#include "core/test_files.h"
#include "core/yaml_reader.h"
#include "renderer/pose_crlb.h"
#include "renderer/render_frame.h"
#include "renderer/test_scenes.h"
#include "testing/sanitized_build.h"
#include "testing/square_tracker_testing.h"
#include "trackers/circle/circle_detector.h"
#include "trackers/circle/conic.h"
#include "trackers/circle/conic_fit.h"
#include "trackers/tracker_factory.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

// Clean frames (σ² = 0.001): camera-centre error as a fraction of the distance, and
// rotation error. Bounds are the measured envelope over the grid below, with margin.
// - Tilted views (30-60°) up to 1 m: measured <= 0.6 % and 0.35°.
constexpr double kTiltedPositionFraction = 0.01;
constexpr double kTiltedRotationDeg = 1.0;
// - Fronto-parallel views: the tilt is weakly observable (circle-method.md §7; its eccentricity
//   is second order), so 0.002 px of edge bias costs degrees. Measured <= 5.0 % and 2.9° at 1 m
//   for a-e (MarkerCase holds each marker's bound).
// - The far end of each marker's range (below): measured <= 8 % and 4.6°; 10 % is the
//   harness's success criterion.
constexpr double kFarPositionFraction = 0.10;
constexpr double kFarRotationDeg = 6.0;
constexpr double kLowNoiseVar = 0.001;

// Renders `marker` (RGB when it has colour) and tracks it.
TrackedFrame RenderAndTrack(CircleTracker* tracker,
                            const MarkerSpec& marker,
                            const Rigid3& cam_from_marker,
                            double noise_var,
                            uint64_t seed) {
  return markerbench::RenderAndTrack(tracker, marker, marker, cam_from_marker, noise_var, seed);
}

MarkerSpec Load(const std::string& kind) {
  return LoadMarkerYaml("scenarios/markers/" + kind + ".yaml");
}

// How far apart two ellipses lie: the larger of their centres' distance and their semi-axes'
// differences (px).
double EllipseDistancePx(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Ellipse ea = EllipseFromConic(a), eb = EllipseFromConic(b);
  return std::max({(ea.center - eb.center).norm(),
                   std::abs(ea.semi_major - eb.semi_major),
                   std::abs(ea.semi_minor - eb.semi_minor)});
}

// The same printed marker drawn in another in-plane frame: every layer, circle and keypoint
// moved by marker_from_paper (rotation about z by angle_rad, then translation).
MarkerSpec InAnotherFrame(const MarkerSpec& marker,
                          double angle_rad,
                          const Eigen::Vector2d& shift) {
  const Eigen::Rotation2Dd rotation(angle_rad);
  auto move = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d { return rotation * p + shift; };
  MarkerSpec moved = marker;
  for (Disk& disk : moved.circles) disk.center = move(disk.center);
  for (Eigen::Vector2d& k : moved.keypoints) k = move(k);
  for (PaintedShape& layer : moved.layers) {
    if (auto* disk = std::get_if<DiskShape>(&layer.shape)) {
      disk->center = move(disk->center);
    } else if (auto* crescent = std::get_if<CrescentShape>(&layer.shape)) {
      crescent->outer.center = move(crescent->outer.center);
      crescent->inner.center = move(crescent->inner.center);
    } else if (auto* sector = std::get_if<SectorShape>(&layer.shape)) {
      *sector = SectorShape(move(sector->center()),
                            sector->radius(),
                            sector->start_rad() + angle_rad,
                            sector->end_rad() + angle_rad);
    } else {
      ADD_FAILURE() << "circle markers are drawn with disks, crescents and sectors";
    }
  }
  return moved;
}

// What each marker's tests expect of it.
struct MarkerCase {
  const char* kind;
  // How far it is tracked in the round trips, and the largest tilt there: c and d are
  // identified by dots of 6-8 mm, lost beyond about 3 px across; b's fronto-parallel view at
  // 3 m measured 10.5 %, just over the success criterion, so its far end is 2 m (4.7 %).
  double far_m;
  double far_max_tilt_deg;
  // Fronto-parallel views at 1 m. f has no centre dot: its centre comes from the wedge's
  // sides, and there a single circle's tilt rests on its centre alone (measured <= 8.4 %
  // and 4.8°).
  double frontal_position_fraction;
  double frontal_rotation_deg;
  // The design is symmetric about the line through m0 at this angle (the marker file's
  // frame): the m0-m1 axis for a-d, the mouth's bisector for e, the wedge's for f.
  double symmetry_axis_deg;
};

class CircleTrackerTest : public ::testing::TestWithParam<MarkerCase> {};

// Under the sanitizers, every third pose (testing/sanitized_build.h).
TEST_P(CircleTrackerTest, RoundTripsOverDistanceTiltAndRoll) {
  const MarkerCase range = GetParam();
  const MarkerSpec marker = Load(range.kind);
  CircleTracker tracker;
  int frames = 0;
  for (double distance : {0.3, 1.0, range.far_m}) {
    for (double tilt : {0.0, 30.0, 60.0}) {
      const bool far = distance > 1.0;
      if (far && tilt > range.far_max_tilt_deg) continue;
      for (double roll : {10.0, 130.0, 250.0}) {
        if (frames++ % SanitizedStride(3) != 0) continue;
        SCOPED_TRACE("d=" + std::to_string(distance) + " tilt=" + std::to_string(tilt) +
                     " roll=" + std::to_string(roll));
        tracker.Reset();
        const Rigid3 truth = TiltedView(distance, tilt, roll);
        const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, kLowNoiseVar, frames);
        ASSERT_EQ(t.result.status, TrackStatus::kOk) << t.result.message;
        // Far away a near-frontal view may get the circle's other tilt second (the pixels
        // hardly tell the two apart: max_second_hypothesis_log_ratio).
        ASSERT_GE(t.result.hypotheses.size(), 1u);
        ASSERT_LE(t.result.hypotheses.size(), far ? 2u : 1u);
        const Rigid3& estimate = t.result.hypotheses.front();
        const double position_fraction = far           ? kFarPositionFraction
                                         : tilt == 0.0 ? range.frontal_position_fraction
                                                       : kTiltedPositionFraction;
        const double rotation_deg = far           ? kFarRotationDeg
                                    : tilt == 0.0 ? range.frontal_rotation_deg
                                                  : kTiltedRotationDeg;
        EXPECT_LE(PositionError(estimate, truth), position_fraction * distance);
        EXPECT_LE(RotationErrorDeg(estimate, truth), rotation_deg);
        // Sign rules (errata 1-2): the camera is on the printed side, the marker in front.
        EXPECT_GT(CameraCenterInMarker(estimate).z(), 0.0);
        EXPECT_GT(estimate.translation.z(), 0.0);
        ASSERT_EQ(t.result.keypoints_px.size(), marker.keypoints.size());
      }
    }
  }
}

TEST_P(CircleTrackerTest, NoDetectionWithoutTheMarker) {
  const MarkerSpec marker = Load(GetParam().kind);
  MarkerSpec blank = marker;
  blank.layers.clear();  // the paper alone
  CircleTracker tracker;
  for (double noise_var : {0.0, 0.02, 0.3}) {
    for (uint64_t seed : {1u, 2u, 3u}) {
      tracker.Reset();
      const TrackedFrame t = markerbench::RenderAndTrack(
          &tracker, blank, marker, TiltedView(0.6, 20.0, 0.0), noise_var, seed);
      EXPECT_EQ(t.result.status, TrackStatus::kNotDetected) << noise_var << " " << seed;
      EXPECT_TRUE(t.result.hypotheses.empty());
    }
  }
}

// Half the marker outside the image: a clean failure, never a pose from the visible part.
TEST_P(CircleTrackerTest, HalfVisibleMarkerFailsCleanly) {
  const MarkerSpec marker = Load(GetParam().kind);
  CircleTracker tracker;
  for (double roll : {0.0, 90.0, 180.0, 270.0}) {
    Rigid3 truth = TiltedView(0.5, 20.0, roll);
    // Slide the marker so that the image border cuts through its first circle's centre.
    truth.translation.x() += truth.translation.z() * 319.5 / 600.0;
    const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, kLowNoiseVar, 7);
    EXPECT_NE(t.result.status, TrackStatus::kOk) << roll;
    EXPECT_TRUE(t.result.hypotheses.empty());
  }
}

// Poses are reported in the marker file's frame, wherever its disks sit (the loader accepts
// markers a-d anywhere in the plane; here every layer is rotated by 0.7 rad and moved).
TEST_P(CircleTrackerTest, HonoursTheMarkerFrameOfTheFile) {
  const MarkerSpec marker = InAnotherFrame(Load(GetParam().kind), 0.7, {0.03, -0.02});
  CircleTracker tracker;
  for (double tilt : {10.0, 45.0}) {
    const Eigen::Vector2d c = marker.circles[0].center;
    Rigid3 truth = TiltedView(0.7, tilt, 40.0);
    truth.translation -= truth.rotation * Eigen::Vector3d(c.x(), c.y(), 0.0);
    const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, kLowNoiseVar, 9);
    ASSERT_EQ(t.result.status, TrackStatus::kOk) << t.result.message;
    EXPECT_LE(PositionError(t.result.hypotheses.front(), truth), kTiltedPositionFraction * 0.7);
    EXPECT_LE(RotationErrorDeg(t.result.hypotheses.front(), truth), kTiltedRotationDeg);
    for (size_t k = 0; k < marker.keypoints.size(); ++k) {
      EXPECT_LE((t.result.keypoints_px[k] - t.frame.truth.keypoints_px[k]).norm(), 1.0) << k;
    }
  }
}

// The same through a marker file whose disks are off the origin and whose m0 -> m1 runs
// along +y.
TEST(CircleTracker, HonoursAMarkerFileOffTheOrigin) {
  const MarkerSpec marker = LoadMarkerYaml(
      WriteTestFile("circles_a_moved.yaml",
                    "kind: circles_a\n"
                    "disks:\n"
                    "  - {center: [0.02, 0.01], radius: 0.03, color: [1.0, 0.0, 0.0]}\n"
                    "  - {center: [0.02, 0.09], radius: 0.03, color: [0.0, 0.0, 1.0]}\n"));
  CircleTracker tracker;
  const Rigid3 truth = TiltedView(0.6, 35.0, 15.0);
  const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, kLowNoiseVar, 11);
  ASSERT_EQ(t.result.status, TrackStatus::kOk) << t.result.message;
  EXPECT_LE(PositionError(t.result.hypotheses.front(), truth), kTiltedPositionFraction * 0.6);
  EXPECT_LE(RotationErrorDeg(t.result.hypotheses.front(), truth), kTiltedRotationDeg);
  EXPECT_GT(CameraCenterInMarker(t.result.hypotheses.front()).z(), 0.0);
}

// Unrelated frames fed as one sequence: tracking mode may not carry the previous pose into a
// frame it does not predict, so every frame gets the result of a tracker reset before it
// (status, message and pose, exactly). Centred markers at random distances and angles are
// the hard case: the predicted ellipses overlap the new ones, but at another size or place.
// Under the sanitizers, every third frame (testing/sanitized_build.h).
TEST_P(CircleTrackerTest, UnrelatedFramesInSequenceGiveTheDetectionResults) {
  const MarkerSpec marker = Load(GetParam().kind);
  CircleTracker sequence, detection;
  const Camera camera = FrameRequest().scene.camera;  // RenderAndTrack's
  Rng rng(41);
  int tracked = 0;
  for (int frame = 0; frame < 30; ++frame) {
    // g++'s order (test_scenes.h)
    const double roll_deg = rng.Uniform(0.0, 360.0), tilt_deg = rng.Uniform(0.0, 60.0);
    Rigid3 truth = TiltedView(rng.Uniform(0.3, 2.0), tilt_deg, roll_deg);
    truth.translation.x() += rng.Uniform(-0.1, 0.1) * truth.translation.z();
    truth.translation.y() += rng.Uniform(-0.1, 0.1) * truth.translation.z();
    if (frame % SanitizedStride(3) != 0) continue;
    SCOPED_TRACE("frame " + std::to_string(frame));
    const TrackedFrame in_sequence = RenderAndTrack(&sequence, marker, truth, 0.01, 100 + frame);
    detection.Reset();
    const TrackResult alone = detection.Track({&in_sequence.frame.image, &camera, &marker});
    ASSERT_EQ(in_sequence.result.status, alone.status);
    EXPECT_EQ(in_sequence.result.message, alone.message);
    ASSERT_EQ(in_sequence.result.hypotheses.size(), alone.hypotheses.size());
    if (alone.status != TrackStatus::kOk) continue;
    ++tracked;
    EXPECT_EQ(in_sequence.result.hypotheses.front().rotation, alone.hypotheses.front().rotation);
    EXPECT_EQ(in_sequence.result.hypotheses.front().translation,
              alone.hypotheses.front().translation);
  }
  EXPECT_GE(tracked, 15 / SanitizedStride(3));  // most frames are within the marker's range
}

// A mirrored print (every x negated: for a, red and blue swap sides as seen from the front)
// of a marker symmetric about a line at angle β through m0 is the same print turned by
// π - 2β about its normal: the frames are the same, so no tracker can reject it, and the pose
// returned is the turned one. Every marker of Fig. 3 is so symmetric (a-d about m0-m1, e
// about its mouth's bisector, f about its wedge's), so none has a handedness to check.
TEST_P(CircleTrackerTest, AMirroredPrintIsTheSamePrintTurned) {
  const MarkerSpec marker = Load(GetParam().kind);
  MarkerSpec mirrored = marker;
  for (PaintedShape& layer : mirrored.layers) {
    if (auto* disk = std::get_if<DiskShape>(&layer.shape)) {
      disk->center.x() = -disk->center.x();
    } else if (auto* crescent = std::get_if<CrescentShape>(&layer.shape)) {
      crescent->outer.center.x() = -crescent->outer.center.x();
      crescent->inner.center.x() = -crescent->inner.center.x();
    } else {
      const SectorShape& sector = std::get<SectorShape>(layer.shape);
      layer.shape = SectorShape(Eigen::Vector2d(-sector.center().x(), sector.center().y()),
                                sector.radius(),
                                M_PI - sector.end_rad(),
                                M_PI - sector.start_rad());
    }
  }
  const Rigid3 pose = TiltedView(0.6, 35.0, 20.0);
  Rigid3 turned = pose;
  const double axis_rad = GetParam().symmetry_axis_deg * M_PI / 180.0;
  turned.rotation =
      pose.rotation * Eigen::AngleAxisd(M_PI - 2.0 * axis_rad, Eigen::Vector3d::UnitZ());
  CircleTracker tracker;
  const TrackedFrame of_mirrored = RenderAndTrack(&tracker, mirrored, marker, pose, 0.0, 3);
  tracker.Reset();
  const TrackedFrame of_turned = RenderAndTrack(&tracker, marker, marker, turned, 0.0, 3);
  int largest_difference = 0;
  for (size_t i = 0; i < of_mirrored.frame.image.pixels.size(); ++i) {
    largest_difference =
        std::max(largest_difference,
                 std::abs(of_mirrored.frame.image.pixels[i] - of_turned.frame.image.pixels[i]));
  }
  EXPECT_LE(largest_difference, 1);
  ASSERT_EQ(of_mirrored.result.status, TrackStatus::kOk) << of_mirrored.result.message;
  EXPECT_LE(PositionError(of_mirrored.result.hypotheses.front(), turned),
            kTiltedPositionFraction * 0.6);
  EXPECT_LE(RotationErrorDeg(of_mirrored.result.hypotheses.front(), turned), kTiltedRotationDeg);
}

INSTANTIATE_TEST_SUITE_P(MarkersAtoF,
                         CircleTrackerTest,
                         ::testing::Values(MarkerCase{"circles_a", 3.0, 60.0, 0.06, 3.5, 0.0},
                                           MarkerCase{"circles_b", 2.0, 60.0, 0.06, 3.5, 0.0},
                                           MarkerCase{"circles_c", 2.0, 30.0, 0.06, 3.5, 0.0},
                                           MarkerCase{"circle_d", 1.5, 30.0, 0.06, 3.5, 0.0},
                                           MarkerCase{"circle_e", 1.5, 60.0, 0.06, 3.5, -45.0},
                                           MarkerCase{"circle_f", 1.5, 60.0, 0.10, 6.0, 30.0}),
                         [](const ::testing::TestParamInfo<MarkerCase>& info) {
                           return std::string(info.param.kind);
                         });

// Every stage is exposed, and the analytic pose is already close (§5).
TEST(CircleTracker, ReportsEveryStage) {
  const MarkerSpec marker = Load("circles_a");
  CircleTracker tracker;
  const Rigid3 truth = TiltedView(0.6, 35.0, 20.0);
  const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, 0.02, 3);
  ASSERT_EQ(t.result.status, TrackStatus::kOk);
  const CircleDiagnostics& d = tracker.diagnostics();
  ASSERT_EQ(d.conics_px.size(), 2u);
  ASSERT_EQ(d.edges.size(), 2u);
  EXPECT_GT(d.edges[0].size(), 40u);
  ASSERT_TRUE(d.analytic_cam_from_marker && d.refined_cam_from_marker);
  // l_inf = r3 in normalized coordinates (§0, eq. 11).
  EXPECT_LE((d.l_inf_norm - truth.rotation.col(2)).norm(), 0.05);
  EXPECT_LE(RotationErrorDeg(*d.analytic_cam_from_marker, truth), 3.0);
  EXPECT_GE(d.iterations, 1);
  EXPECT_LE(d.edge_rms_px, 0.5);
  EXPECT_GT(d.noise_sigma, 0.05);
}

// The edge points of disks only start the fit on the pixels (a-d): a second edge pass runs
// only where the first found the edges more blurred than it started from (the smoothing + 1
// px; its rays reach 2.5 of that σ + 3 px each way). Without blur one pass; where the pose
// rests on the edge points (photometric: false) and for e, whose design is fitted, two; under
// blur σ 6 two. Each conic is its edge points' direct fit there, and where the pose rests on
// them, their fit refined on the PND distance (the two 0.001-0.02 px apart in centre or axes
// on these frames, the same fit within 1e-12 px). The pose within three times the Cramér-Rao
// bound's RMS for the frame (one frame each; measured 0.5-2.1).
TEST(CircleTracker, TakesASecondEdgePassWhereTheEdgesAreBlurrierThanAssumed) {
  const Camera camera = FrameRequest().scene.camera;
  CircleTrackerOptions on_edges;
  on_edges.photometric = false;
  struct Case {
    const char* kind;
    const CircleTrackerOptions options;
    double blur_sigma_px;
    int passes;
  };
  for (const Case& c : {Case{"circles_a", {}, 0.0, 1},
                        Case{"circles_a", on_edges, 0.0, 2},
                        Case{"circle_e", {}, 0.0, 2},
                        Case{"circles_a", {}, 6.0, 2}}) {
    SCOPED_TRACE(std::string(c.kind) + " passes " + std::to_string(c.passes));
    const MarkerSpec marker = Load(c.kind);
    const Rigid3 truth = TiltedView(c.blur_sigma_px > 0.0 ? 1.0 : 0.6, 35.0, 20.0);
    const RenderedFrame frame = RenderMarker(marker, truth, 0.02, c.blur_sigma_px, 7);
    CircleTracker tracker(c.options);
    const TrackResult result = tracker.Track({&frame.image, &camera, &marker});
    ASSERT_EQ(result.status, TrackStatus::kOk) << result.message;
    const PoseBound bound = PoseCrlb(
        SeededFrameRequest(marker, truth, 0.02, c.blur_sigma_px, 7, marker.HasColor() ? 3 : 1));
    EXPECT_LE(PositionError(result.hypotheses.front(), truth), 3.0 * bound.position_rms_m);
    const std::vector<int>& passes = tracker.diagnostics().edge_passes;
    ASSERT_FALSE(passes.empty());
    for (const int run : passes) EXPECT_EQ(run, c.passes);
    const bool pixels_follow = c.options.photometric && c.kind != std::string("circle_e");
    const std::vector<Eigen::Matrix3d>& conics = tracker.diagnostics().conics_px;
    ASSERT_EQ(conics.size(), passes.size());
    for (size_t i = 0; i < conics.size(); ++i) {
      ConicFitOptions direct = CircleDetectorOptions().fit;
      direct.refine_pnd = false;
      const std::vector<Eigen::Vector2d>& points = tracker.diagnostics().edges[i];
      const std::optional<ConicFit> expected =
          FitEllipse(points, pixels_follow ? direct : CircleDetectorOptions().fit);
      const std::optional<ConicFit> other =
          FitEllipse(points, pixels_follow ? CircleDetectorOptions().fit : direct);
      ASSERT_TRUE(expected && other);
      EXPECT_LT(EllipseDistancePx(conics[i], expected->conic), 1e-6);
      EXPECT_GT(EllipseDistancePx(conics[i], other->conic), 1e-4);
    }
  }
}

// refine: false returns the analytic pose itself, with neither refinement after it.
TEST(CircleTracker, WithoutRefinementTheAnalyticPoseIsReturned) {
  const MarkerSpec marker = Load("circles_a");
  CircleTrackerOptions options;
  options.refine = false;
  CircleTracker tracker(options);
  const TrackedFrame t = RenderAndTrack(&tracker, marker, TiltedView(0.6, 35.0, 20.0), 0.02, 3);
  ASSERT_EQ(t.result.status, TrackStatus::kOk) << t.result.message;
  const CircleDiagnostics& d = tracker.diagnostics();
  EXPECT_FALSE(d.photometric_used);
  EXPECT_EQ(t.result.hypotheses.front().translation, d.analytic_cam_from_marker->translation);
  EXPECT_EQ(t.result.hypotheses.front().rotation, d.analytic_cam_from_marker->rotation);
}

// Tracking mode: after one frame the next is searched around the prediction; Reset forgets.
TEST(CircleTracker, TracksFromThePreviousPoseAndResets) {
  const MarkerSpec marker = Load("circles_a");
  CircleTracker tracker;
  for (int frame = 0; frame < 5; ++frame) {
    Rigid3 truth = TiltedView(0.6, 20.0 + 2.0 * frame, 30.0 + 3.0 * frame);
    truth.translation.x() += 0.004 * frame;  // about 4 px per frame
    const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, 0.02, 20 + frame);
    ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame;
    EXPECT_EQ(tracker.diagnostics().used_tracking_region, frame > 0) << frame;
    EXPECT_LE(PositionError(t.result.hypotheses.front(), truth), kTiltedPositionFraction * 0.6);
  }
  // Lost: the next frame has no marker; then a frame far from the old pose is found again.
  tracker.Reset();
  const TrackedFrame t = RenderAndTrack(&tracker, marker, TiltedView(0.9, 10.0, 200.0), 0.02, 30);
  EXPECT_EQ(t.result.status, TrackStatus::kOk);
  EXPECT_FALSE(tracker.diagnostics().used_tracking_region);
}

// A camera moving steadily by 12 px a frame, beyond the reach of an edge pass from the last
// pose's ellipses (8 px a frame stays within it; 14 px exceeds max_prediction_error, and
// tracking from the last pose falls back to full detection). Where the last pose came from the
// fit on the pixels, each frame after the first is that fit again: from the prediction moved onto
// the edges by their shifts (AlignByEdgeShifts) where the last prediction was off by 12 px, and
// straight from the prediction once it held (from the fourth frame, the third's image having
// lain where the last motion predicted it). On the edge points alone, tracking mode predicts each
// frame by the last frame-to-frame motion and finds the marker from there from the third frame
// on, in one edge pass; from the previous pose alone (predict_motion: false) each frame needs
// the search of the region.
TEST(CircleTracker, PredictsTheNextPoseByTheLastMotion) {
  const MarkerSpec marker = Load("circles_a");
  const double step_m = 0.012;
  for (const auto& [predict_motion, photometric] :
       {std::pair{true, true}, {true, false}, {false, true}}) {
    SCOPED_TRACE(std::string(predict_motion ? "predict_motion" : "previous pose") +
                 (photometric ? ", on the pixels" : ", edge points"));
    CircleTrackerOptions options;
    options.predict_motion = predict_motion;
    options.photometric = photometric;
    CircleTracker tracker(options);
    for (int frame = 0; frame < 5; ++frame) {
      Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
      truth.translation.x() += step_m * (frame - 2);
      const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, 0.02, 50 + frame);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame;
      EXPECT_EQ(tracker.diagnostics().used_tracking_region, frame > 0) << frame;
      const bool on_pixels = photometric && frame > 0;
      EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, on_pixels) << frame;
      EXPECT_EQ(tracker.diagnostics().aligned_by_edge_shifts,
                on_pixels && !(predict_motion && frame > 2))
          << frame;
      EXPECT_EQ(tracker.diagnostics().used_predicted_ellipses,
                predict_motion && frame > 1 && !on_pixels)
          << frame;
      EXPECT_LE(PositionError(t.result.hypotheses.front(), truth), kTiltedPositionFraction * 0.6);
    }
  }
}

// With the alignment by edge shifts off (edge_shift_alignment: false), the same video's frames
// whose prediction is pixels off take the detector: the second the search of the region (the
// last pose, 12 mm off), the third the predicted ellipses; from the fourth, once the last frame
// lay where the motion predicted it, the fit on the pixels runs from the prediction itself.
TEST(CircleTracker, TheAlignmentByEdgeShiftsCanBeTurnedOff) {
  const MarkerSpec marker = Load("circles_a");
  CircleTrackerOptions options;
  options.edge_shift.enabled = false;
  CircleTracker tracker(options);
  for (int frame = 0; frame < 5; ++frame) {
    Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
    truth.translation.x() += 0.012 * (frame - 2);
    const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, 0.02, 50 + frame);
    ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame;
    EXPECT_FALSE(tracker.diagnostics().aligned_by_edge_shifts) << frame;
    EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, frame > 2) << frame;
    EXPECT_EQ(tracker.diagnostics().used_predicted_ellipses, frame == 2) << frame;
    EXPECT_LE(PositionError(t.result.hypotheses.front(), truth), kTiltedPositionFraction * 0.6);
  }
}

// A smooth video (the camera moving 2 mm and turning 0.5° a frame): once a frame's pose came from
// the fit on the pixels, the next is that fit again, without the detector, from the predicted
// pose moved onto the edges (the second and third frames: the last prediction was off by more
// than kMaxLastPredictionErrorPx, or there was none; not d, whose single circle's edges leave
// its other tilt open: it takes the search there) or from the prediction itself (once the last
// frame's image lay where the motion predicted it), and it gives the pose a detection of
// the same frame gives, to a small part of the pose's standard error (the two fits stop at a cost
// within 1e-5 of their least; measured: at most 0.14 of the bound's RMS).
TEST(CircleTracker, TracksOnThePixelsFromThePrediction) {
  for (const char* kind : {"circles_a", "circle_d"}) {
    SCOPED_TRACE(kind);
    const MarkerSpec marker = Load(kind);
    const bool single_circle = marker.circles.size() == 1;
    const Camera camera = FrameRequest().scene.camera;  // RenderAndTrack's
    CircleTracker tracker, detection;
    for (int frame = 0; frame < 6; ++frame) {
      Rigid3 truth = TiltedView(0.6, 25.0 + 0.5 * frame, 40.0 + 0.5 * frame);
      truth.translation.x() += 0.002 * frame;
      const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, 0.02, 70 + frame);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame << t.result.message;
      EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, frame > (single_circle ? 2 : 0)) << frame;
      EXPECT_EQ(tracker.diagnostics().aligned_by_edge_shifts,
                !single_circle && (frame == 1 || frame == 2))
          << frame;
      EXPECT_EQ(tracker.diagnostics().used_tracking_region, frame > 0) << frame;
      detection.Reset();
      const TrackResult alone = detection.Track({&t.frame.image, &camera, &marker});
      ASSERT_EQ(alone.status, TrackStatus::kOk) << frame;
      const PoseBound bound = PoseCrlb(
          SeededFrameRequest(marker, truth, 0.02, 0.0, 70 + frame, marker.HasColor() ? 3 : 1));
      EXPECT_LE(PositionError(t.result.hypotheses.front(), alone.hypotheses.front()),
                0.3 * bound.position_rms_m)
          << frame;
      EXPECT_LE(RotationErrorDeg(t.result.hypotheses.front(), alone.hypotheses.front()),
                0.3 * bound.rotation_rms_deg)
          << frame;
    }
  }
}

// A tracked frame's check of the printed design starts at the lattice the last frame's decided on,
// and decides on the one a detection of the frame does: the coarse one without noise, the fine one
// where the noise leaves the coarse one undecided.
TEST(CircleTracker, TheTrackedDesignCheckStartsWhereTheLastDecided) {
  const MarkerSpec marker = Load("circles_a");
  const Camera camera = FrameRequest().scene.camera;  // RenderAndTrack's
  const AppearanceOptions appearance;
  for (const double noise_var : {0.0, 0.1}) {
    SCOPED_TRACE(noise_var);
    CircleTracker tracker, detection;
    for (int frame = 0; frame < 4; ++frame) {
      Rigid3 truth = TiltedView(0.6, 25.0 + 0.5 * frame, 40.0 + 0.5 * frame);
      truth.translation.x() += 0.002 * frame;
      const TrackedFrame t = RenderAndTrack(&tracker, marker, truth, noise_var, 90 + frame);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame << t.result.message;
      EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, frame > 0) << frame;
      EXPECT_EQ(tracker.diagnostics().appearance_grid,
                noise_var == 0.0 ? appearance.coarse_grid : appearance.grid)
          << frame;
      ASSERT_EQ(detection.Track({&t.frame.image, &camera, &marker}).status, TrackStatus::kOk);
      EXPECT_EQ(tracker.diagnostics().appearance_grid, detection.diagnostics().appearance_grid)
          << frame;
      detection.Reset();
    }
  }
}

// Tracking on the pixels gives way where its checks fail, and the frame gets the search around
// the prediction or full detection: on a frame without the marker the fit takes the gains to 0
// (not detected, as a detection of the frame says), a frame far noisier than the last shows that
// noise in the fit's residuals, and a marker crossing the frame's edge has edges the fit cannot
// see.
TEST(CircleTracker, TrackingOnThePixelsGivesWayWhereItsChecksFail) {
  const MarkerSpec marker = Load("circles_a");
  const Camera camera = FrameRequest().scene.camera;  // RenderAndTrack's
  const Rigid3 truth = TiltedView(0.6, 25.0, 40.0);
  CircleTracker tracker, detection;
  // Found by full detection, then tracked on the pixels: from its pose moved onto the edges, then,
  // that frame having lain where it was predicted (kMaxLastPredictionErrorPx), from the
  // prediction itself.
  const auto found_and_tracked = [&](uint64_t seed) {
    for (int frame = 0; frame < 3; ++frame) {
      ASSERT_EQ(RenderAndTrack(&tracker, marker, truth, 0.02, seed + frame).result.status,
                TrackStatus::kOk);
      EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, frame > 0) << frame;
      EXPECT_EQ(tracker.diagnostics().aligned_by_edge_shifts, frame == 1) << frame;
    }
  };
  found_and_tracked(80);
  // No marker: the blank paper.
  MarkerSpec blank = marker;
  blank.layers.clear();
  const TrackedFrame empty = markerbench::RenderAndTrack(&tracker, blank, marker, truth, 0.02, 83);
  const TrackResult alone = detection.Track({&empty.frame.image, &camera, &marker});
  EXPECT_EQ(empty.result.status, alone.status);
  EXPECT_EQ(empty.result.message, alone.message);
  EXPECT_FALSE(tracker.diagnostics().tracked_on_pixels);
  // Found again; then 4x the noise.
  found_and_tracked(84);
  const TrackedFrame noisier = RenderAndTrack(&tracker, marker, truth, 0.32, 87);
  ASSERT_EQ(noisier.result.status, TrackStatus::kOk) << noisier.result.message;
  EXPECT_FALSE(tracker.diagnostics().tracked_on_pixels);
  EXPECT_TRUE(tracker.diagnostics().used_tracking_region);
  // The marker moving 4 mm a frame until a disk crosses the frame's left edge: tracked on the
  // pixels while the disks are within the frame, not once one crosses.
  const auto disks_within_frame = [&](const Rigid3& cam_from_marker) {
    for (const Disk& disk : marker.circles) {
      for (int k = 0; k < 64; ++k) {
        const double angle = 2.0 * M_PI * k / 64;
        const Eigen::Vector2d px = camera.ImgFromCam(
            cam_from_marker * Eigen::Vector3d(disk.center.x() + disk.radius_m * std::cos(angle),
                                              disk.center.y() + disk.radius_m * std::sin(angle),
                                              0.0));
        if (!(px.x() >= 0.0 && px.x() <= camera.width && px.y() >= 0.0 && px.y() <= camera.height))
          return false;
      }
    }
    return true;
  };
  Rigid3 moving = truth;
  int tracked_within = 0;
  bool crossed = false;
  for (int frame = 0; frame < 100 && !crossed; ++frame) {
    moving.translation.x() -= 0.004;
    crossed = !disks_within_frame(moving);
    RenderAndTrack(&tracker, marker, moving, 0.02, 90 + frame);
    if (crossed) {
      EXPECT_FALSE(tracker.diagnostics().tracked_on_pixels) << frame;
    } else {
      tracked_within += tracker.diagnostics().tracked_on_pixels;
    }
  }
  EXPECT_TRUE(crossed);
  EXPECT_GT(tracked_within, 10);
}

// Near the camera's axis the circle's two tilts give nearly the same image (§4.7), and one frame
// does not settle which is seen: tracking on the pixels, which fits one, gives way to the search,
// which fits both, until the frames' evidence for one exceeds max_second_hypothesis_log_ratio.
// circles_a at 1 m, 3° of tilt, sharp, static: the first frame's fits on the two tilts lie 2 ln Λ
// 0.6 apart, its first on the wrong tilt; from the second frame on, both fits end on one, on the
// right tilt. The first of those slid from the tilt the evidence favoured, which stands against it
// (-0.6); the next works that off (kMergedFitLogRatio: 0.4), and the third, a merged fit on the
// tilt favoured, rules the other out. The search runs until then, the straight fit after. (Without
// the condition on the evidence, the straight fit ran from the third frame; before the merged
// fits worked a slide's evidence off, it stood at -0.6 and the search ran on every frame.)
TEST(CircleTracker, TrackingOnThePixelsWaitsForTheTiltToSettle) {
  const MarkerSpec marker = Load("circles_a");
  const Camera camera = FrameRequest().scene.camera;
  CircleTracker tracker;
  const Rigid3 truth = TiltedView(1.0, 3.0, 40.0);
  const Eigen::Vector3d normal = truth.rotation.col(2), other = OtherTilt(truth).rotation.col(2);
  for (int frame = 0; frame < 8; ++frame) {
    const RenderedFrame rendered = RenderMarker(marker, truth, 0.02, 0.0, 5 + frame);
    const TrackResult result = tracker.Track({&rendered.image, &camera, &marker});
    ASSERT_EQ(result.status, TrackStatus::kOk) << frame << result.message;
    EXPECT_EQ(tracker.diagnostics().tracked_on_pixels, frame >= 4) << frame;
    EXPECT_EQ(tracker.diagnostics().used_tracking_region, frame > 0) << frame;
    const Eigen::Vector3d found = result.hypotheses.front().rotation.col(2);
    if (frame > 0) {
      EXPECT_GT(found.dot(normal), found.dot(other)) << frame;
    }
  }
}

// A camera receding from `from_m` to 3.5 m in `frames` frames, `videos` videos tilted tilt_deg (a
// uniform draw) at any roll, σ² 0.02: beyond 2.5 m, the frames and those where the first hypothesis
// lies on the circle's wrong tilt (or none is found) in tracking mode, in a detection of each frame
// alone, and in tracking mode without the evidence carried (max_carried_tilt_log_ratio 0).
struct WrongTilts {
  int far = 0;
  int tracked = 0;
  int alone = 0;
  int uncarried = 0;
  int only_alone = 0;  // discordant frames: wrong alone only, or tracked only
  int only_tracked = 0;
};
WrongTilts WrongTiltsReceding(const std::string& kind,
                              double min_tilt_deg,
                              double max_tilt_deg,
                              double from_m,
                              int frames,
                              int videos,
                              uint64_t seed) {
  const MarkerSpec raw = Load(kind);
  const MarkerSpec marker = ScaledMarker(raw, EqualAreaFactor(raw, 0.01));
  const Camera camera = FrameRequest().scene.camera;
  CircleTrackerOptions each_frame_alone, nothing_carried;
  each_frame_alone.tracking = false;
  nothing_carried.max_carried_tilt_log_ratio = 0.0;
  const auto on_the_wrong_tilt = [](const TrackResult& result, const Rigid3& truth) {
    if (result.status != TrackStatus::kOk) return true;
    const Eigen::Vector3d normal = result.hypotheses.front().rotation.col(2);
    return normal.dot(truth.rotation.col(2)) < normal.dot(OtherTilt(truth).rotation.col(2));
  };
  WrongTilts wrong;
  Rng rng(seed);
  for (int video = 0; video < videos; ++video) {
    const double tilt = rng.Uniform(min_tilt_deg, max_tilt_deg), roll = rng.Uniform(0.0, 360.0);
    CircleTracker tracker, alone(each_frame_alone), uncarried(nothing_carried);
    for (int frame = 0; frame < frames; ++frame) {
      const double distance = from_m + (3.5 - from_m) * frame / (frames - 1);
      const Rigid3 truth = TiltedView(distance, tilt, roll);
      const RenderedFrame rendered = RenderMarker(marker, truth, 0.02, 0.0, 100 * video + frame);
      const Observation observation{&rendered.image, &camera, &marker};
      const bool tracked_is_wrong = on_the_wrong_tilt(tracker.Track(observation), truth);
      const bool alone_is_wrong = on_the_wrong_tilt(alone.Track(observation), truth);
      const bool uncarried_is_wrong = on_the_wrong_tilt(uncarried.Track(observation), truth);
      if (distance < 2.5) continue;
      ++wrong.far;
      wrong.tracked += tracked_is_wrong;
      wrong.alone += alone_is_wrong;
      wrong.uncarried += uncarried_is_wrong;
      wrong.only_alone += alone_is_wrong && !tracked_is_wrong;
      wrong.only_tracked += tracked_is_wrong && !alone_is_wrong;
    }
  }
  return wrong;
}

// Far away one frame hardly tells f's two tilts apart (on the paper's distance sweep its first
// hypothesis is the mirror on 14-26 % of the frames from 2.5 m on); a video carries the tilt it
// saw near. Tilted 15-30°: tracking mode, which adds each frame's 2 ln Λ between its fits on the
// two tilts to the evidence the frames before left (max_carried_tilt_log_ratio), is on the wrong
// tilt beyond 2.5 m far less often than a detection of each frame alone; without that evidence
// (0), as often. Measured on these 70 frames: 0 with it, 20 alone, 20 without it.
TEST(CircleTracker, CarriesTheTiltOfFFromNearToFar) {
  if (kSanitizedBuild) GTEST_SKIP() << "a count over 160 frames, each tracked thrice";
  const WrongTilts wrong = WrongTiltsReceding("circle_f", 15.0, 30.0, 1.2, 16, 10, 31);
  ASSERT_EQ(wrong.far, 70);
  EXPECT_GE(wrong.alone, wrong.far / 7);  // the frames are hard: each alone is often the mirror
  EXPECT_LE(wrong.tracked, wrong.far / 20);
  // McNemar's exact test on the discordant frames.
  EXPECT_LT(FairBinomialUpperTail(wrong.only_alone + wrong.only_tracked, wrong.only_alone), 0.001);
  EXPECT_GE(wrong.uncarried, wrong.far / 7);
}

// Near the camera's axis, far away, the two tilts' normals lie a few degrees apart and a frame's
// own tilt is uncertain by as much; in a smooth video tracking mode fits the pixels straight from
// the prediction (TrackOnPixels). That fit may slide to the other tilt: it must then give way to
// the search, which fits both, and not carry the slid tilt on as settled. d receding from 1.5 m
// to 3.5 m at 25 mm a frame, tilted 6-12°, 6 videos: beyond 2.5 m (246 frames) measured 18
// frames on the wrong tilt tracked, 88 alone (10 and 80 discordant); when the straight fit took
// its other tilt's distance in standard errors, squared (150-1,300), for that tilt's 2 ln Λ
// (0.1-6 between the two tilts' fits), 72 tracked (44 and 60).
TEST(CircleTracker, AStraightFitThatSlidToTheOtherTiltGivesWay) {
  if (kSanitizedBuild) GTEST_SKIP() << "a count over 486 frames, each tracked thrice";
  const WrongTilts wrong = WrongTiltsReceding("circle_d", 6.0, 12.0, 1.5, 81, 6, 42);
  ASSERT_EQ(wrong.far, 246);
  EXPECT_GE(wrong.alone, wrong.far / 5);
  EXPECT_LE(wrong.tracked, wrong.far / 8);
  EXPECT_LT(FairBinomialUpperTail(wrong.only_alone + wrong.only_tracked, wrong.only_alone), 0.001);
}

// Near the camera's axis the fits from the circle's two tilts often end on one (its other tilt
// has no minimum of its own). Where that one fit slid from a tilt the frames before favoured,
// their evidence stands against it; the merged fits after it, on the tilt now tracked, work that
// evidence off (kMergedFitLogRatio each), and tracking mode fits the pixels straight from the
// prediction again. circles_a approaching from 3 m to 0.5 m at 25 mm a frame, tilted 2-4° at any
// roll, 12 videos: within 1.5 m (492 frames) measured 122 frames taking the search, at most 23
// of a video's 41; with the merged fits counting nothing against that evidence, 183, and three
// videos took it on all or all but two of theirs.
TEST(CircleTracker, NearTheAxisMergedFitsWorkOffASlidesEvidence) {
  if (kSanitizedBuild) GTEST_SKIP() << "a count over 1,212 frames";
  const MarkerSpec raw = Load("circles_a");
  const MarkerSpec marker = ScaledMarker(raw, EqualAreaFactor(raw, 0.01));
  const Camera camera = FrameRequest().scene.camera;
  constexpr int kVideos = 12, kFrames = 101;
  Rng rng(7);
  int near = 0, searched = 0;
  for (int video = 0; video < kVideos; ++video) {
    const double tilt = rng.Uniform(2.0, 4.0), roll = rng.Uniform(0.0, 360.0);
    CircleTracker tracker;
    int searched_in_video = 0, near_in_video = 0;
    for (int frame = 0; frame < kFrames; ++frame) {
      const double distance = 3.0 - 2.5 * frame / (kFrames - 1);
      const RenderedFrame rendered =
          RenderMarker(marker, TiltedView(distance, tilt, roll), 0.02, 0.0, 1000 * video + frame);
      const TrackResult result = tracker.Track({&rendered.image, &camera, &marker});
      if (distance > 1.5) continue;
      ASSERT_EQ(result.status, TrackStatus::kOk) << video << " " << frame << " " << result.message;
      ++near_in_video;
      searched_in_video += !tracker.diagnostics().tracked_on_pixels;
    }
    EXPECT_LE(searched_in_video, 3 * near_in_video / 4) << video;
    near += near_in_video;
    searched += searched_in_video;
  }
  ASSERT_EQ(near, 492);
  EXPECT_LE(searched, near / 3);
}

// A motion carried on too far: from 1.2 m to 0.6 m (a jump the region around the first pose's
// ellipses does not match: full detection) it predicts the marker at the camera, from 2 m
// behind it. That frame, back at 0.6 m, gets full detection; the next one, the camera still,
// is tracked from its prediction again (on the pixels, from it moved onto the edges).
TEST(CircleTracker, APredictionAtOrBehindTheCameraGetsFullDetection) {
  const MarkerSpec marker = Load("circles_a");
  const Rigid3 near = TiltedView(0.6, 20.0, 30.0);
  for (const double first_m : {1.2, 2.0}) {
    SCOPED_TRACE(first_m);
    CircleTracker tracker;
    Rigid3 far = near;
    far.translation.z() = first_m;
    ASSERT_EQ(RenderAndTrack(&tracker, marker, far, 0.02, 60).result.status, TrackStatus::kOk);
    for (int frame = 1; frame <= 3; ++frame) {
      const TrackedFrame t = RenderAndTrack(&tracker, marker, near, 0.02, 60 + frame);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << frame;
      EXPECT_LE(PositionError(t.result.hypotheses.front(), near), kTiltedPositionFraction * 0.6);
      EXPECT_EQ(tracker.diagnostics().used_tracking_region, frame == 3) << frame;
      EXPECT_EQ(tracker.diagnostics().aligned_by_edge_shifts, frame == 3) << frame;
    }
  }
}

// d and e under a blur that hides their dots from the threshold (issue 21): d at 1 m and e at
// 0.8 m, blur σ 5 and σ² 0.02, where the dots (4.8 and 5.3 px in radius) peak at 0.37 and 0.42
// of their ink. The search of blurred dots finds them (without it none is detected), and the
// camera-centre error is within twice the Cramér-Rao bound's RMS for the frame (measured:
// 1.06-1.39 for d, 0.34-0.79 for e; d's errors are 2-6 % of the distance, its bound as large).
TEST(CircleTracker, FindsTheDotsOfDAndEUnderBlur) {
  const Camera camera = FrameRequest().scene.camera;
  CircleTrackerOptions without;
  without.detector.max_blurred_dot_disks = 0;
  for (const auto& [kind, distance] : {std::pair{"circle_d", 1.0}, std::pair{"circle_e", 0.8}}) {
    const MarkerSpec marker = Load(kind);
    for (int pose = 0; pose < 4; ++pose) {
      SCOPED_TRACE(std::string(kind) + " pose " + std::to_string(pose));
      const Rigid3 truth = TiltedView(distance, 10.0 + 8.0 * pose, 70.0 * pose);
      const RenderedFrame frame = RenderMarker(marker, truth, 0.02, 5.0, 40 + pose);
      const Observation observation{&frame.image, &camera, &marker};
      CircleTracker tracker;
      const TrackResult result = tracker.Track(observation);
      ASSERT_EQ(result.status, TrackStatus::kOk) << result.message;
      const double error = PositionError(result.hypotheses.front(), truth);
      const PoseBound bound = PoseCrlb(SeededFrameRequest(marker, truth, 0.02, 5.0, 40 + pose, 1));
      EXPECT_LE(error, 2.0 * bound.position_rms_m);
      CircleTracker threshold_only(without);
      EXPECT_EQ(threshold_only.Track(observation).status, TrackStatus::kNotDetected);
    }
  }
}

// circle_d on 12 poses at `distance_m` (tilt 5-38°, σ² 0.02, no blur, noise seeds from
// `first_seed`): the frames where the tracker finds it, those within 10 % of the distance, and
// the frames found by a tracker with `otherwise`.
struct FarFrames {
  int found = 0;
  int within = 0;
  int found_otherwise = 0;
};
FarFrames TrackDFarAway(double distance_m,
                        uint64_t first_seed,
                        const CircleTrackerOptions& otherwise) {
  const Camera camera = FrameRequest().scene.camera;
  const MarkerSpec marker = Load("circle_d");
  FarFrames frames;
  for (int pose = 0; pose < 12; ++pose) {
    const Rigid3 truth = TiltedView(distance_m, 5.0 + 3.0 * pose, 30.0 * pose);
    const RenderedFrame frame = RenderMarker(marker, truth, 0.02, 0.0, first_seed + pose);
    const Observation observation{&frame.image, &camera, &marker};
    CircleTracker tracker;
    const TrackResult result = tracker.Track(observation);
    if (result.status == TrackStatus::kOk) {
      ++frames.found;
      frames.within += PositionError(result.hypotheses.front(), truth) <= 0.1 * distance_m;
    }
    CircleTracker other(otherwise);
    frames.found_otherwise += other.Track(observation).status == TrackStatus::kOk;
  }
  return frames;
}

// d beyond 2 m (σ² 0.02, no blur): its feature dot, thresholded, is a blob of a few px² beside
// the disk, below the disks' min_area_px (before min_dot_area_px, d was found in no frame of the
// paper's distance sweep from 2 m on). Measured on these 12 poses at 2.3 m (tilt 5-38°): found
// on 12, within 10 % of the distance on 7 (11 and 6 by the blobs alone, without the search of
// small dots); with the dots held to the disks' minimum and no search of small dots, on none.
// The misses are the circle's other tilt (rotation errors twice the tilt), which a single disk
// and two small dots barely tell apart there: from the true pose and its mirror, the likelihood
// on the whole design (DesignLogRatios) picked the mirror on 4 of the 12 frames.
TEST(CircleTracker, FindsTheFeatureDotOfDBeyondTwoMetres) {
  CircleTrackerOptions dots_as_disks;
  dots_as_disks.detector.min_dot_area_px = dots_as_disks.detector.min_area_px;
  dots_as_disks.detector.min_dot_radius_px = dots_as_disks.detector.min_blurred_dot_radius_px;
  const FarFrames d = TrackDFarAway(2.3, 60, dots_as_disks);
  // With room for the near ties between the tilts to fall otherwise under another compiler.
  EXPECT_GE(d.found, 9);
  EXPECT_GE(d.within, 4);
  EXPECT_EQ(d.found_otherwise, 0);
}

// d from 2.5 m on (σ² 0.02, no blur): its dots, 1.2-2 px in radius, are looked for by their
// images (the threshold's blobs of a few pixels split or vanish under noise). Measured on these
// 12 poses at 3.2 m (tilt 5-38°): found on all, within 10 % of the distance on 8 (the misses: at
// 20° and 29° the circle's other tilt, rotation errors twice the tilt, as at 2.3 m; at 5° and
// 11° near-frontal poses, 14° and 17° off); without the search of small dots, on none.
TEST(CircleTracker, FindsTheSmallDotsOfDAtThreeMetres) {
  CircleTrackerOptions no_small_dots;
  no_small_dots.detector.min_dot_radius_px = no_small_dots.detector.min_blurred_dot_radius_px;
  const FarFrames d = TrackDFarAway(3.2, 80, no_small_dots);
  EXPECT_GE(d.found, 9);
  EXPECT_GE(d.within, 5);
  EXPECT_EQ(d.found_otherwise, 0);
}

// The tracker models intensities linear in the light, as the renderer draws them; cameras encode
// theirs with a gamma (sRGB: about 2.2), which bends every blurred edge. Each marker a-f on the
// same 12 frames at 0.8 m (tilt 0-40°, blur 0.5, 1.5 and 4 px, noise σ² 1e-4 and 2e-3): linear,
// encoded with 2.2, and encoded then taken back by the inverse curve (`markerbench track
// --gamma`). Located (status ok, within 1 cm) on linear / encoded / taken-back frames, measured:
// a 12/0/12, b 11/0/11, c 8/4/8, d 11/2/11, e 11/4/11, f 11/2/11. Encoded, circles_a is found on
// all 12 but centimetres off (the blurred disks' edges move, and their size gives the depth), the
// others too or rejected by their design checks (found on b 5, c 4, d 8, e 8, f 8).
TEST(CircleTracker, GammaEncodedFramesAreFoundOnceLinearized) {
  if (kSanitizedBuild) GTEST_SKIP() << "a count over 216 tracked frames (sanitized_build.h)";
  const Camera camera;
  for (const char* kind :
       {"circles_a", "circles_b", "circles_c", "circle_d", "circle_e", "circle_f"}) {
    const MarkerSpec marker = Load(kind);
    Rng rng(3);
    int linear = 0, encoded = 0, linearized = 0, encoded_found = 0;
    for (const double blur : {0.5, 1.5, 4.0}) {
      for (const double noise_var : {1e-4, 2e-3}) {
        for (uint64_t seed = 1; seed <= 2; ++seed) {
          const Rigid3 truth = RandomTiltedView(0.8, 0.0, 40.0, &rng);
          Image8 image = RenderMarker(marker, truth, noise_var, blur, seed).image;
          struct Outcome {
            bool found;    // status ok, wherever
            bool located;  // and within 1 cm
          };
          const auto track = [&] {
            CircleTracker tracker;
            const TrackResult r = tracker.Track({&image, &camera, &marker});
            const bool found = r.status == TrackStatus::kOk;
            return Outcome{found, found && PositionError(r.hypotheses.front(), truth) < 0.01};
          };
          linear += track().located;
          ApplyGammaCurve(1.0 / 2.2, &image);
          const Outcome on_encoded = track();
          encoded += on_encoded.located;
          encoded_found += on_encoded.found;
          ApplyGammaCurve(2.2, &image);
          linearized += track().located;
        }
      }
    }
    std::printf(
        "%s located on linear / encoded / taken-back frames: %d/%d/%d of 12 (encoded: "
        "found on %d)\n",
        kind,
        linear,
        encoded,
        linearized,
        encoded_found);
    EXPECT_EQ(linearized, linear) << kind;
    EXPECT_LT(encoded, linear) << kind;
  }
}

// The tracker told `marker` on 12 frames at 0.6 m (tilt 0-40°) of `printed` with noise of
// `noise_var`, encoded with `gamma` (the tracker not told): each found frame's error in mm.
std::vector<double> ErrorsMmUnderGamma(const MarkerSpec& printed,
                                       const MarkerSpec& marker,
                                       double noise_var,
                                       double gamma) {
  const Camera camera;
  Rng rng(3);
  std::vector<double> errors_mm;
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    const Rigid3 truth = RandomTiltedView(0.6, 0.0, 40.0, &rng);
    Image8 image = RenderMarker(printed, truth, noise_var, 0.0, seed).image;
    ApplyGammaCurve(1.0 / gamma, &image);
    CircleTracker tracker;
    const TrackResult r = tracker.Track({&image, &camera, &marker});
    if (r.status == TrackStatus::kOk) {
      errors_mm.push_back(1000.0 * PositionError(r.hypotheses.front(), truth));
    }
  }
  return errors_mm;
}

// f's grey wedge shows at whatever level its print or the camera's response gives it, and the
// tracker fits that level (printed_appearance.h, roll_feature.h): 12 frames at 0.6 m (tilt 0-40°,
// σ² 0.02) of f printed with its wedge at 0.35, 0.5 and 0.65 on linear frames and at 0.5 encoded
// with gamma 2.2 (the tracker not told). Measured: found on all 12 each, median errors 1.19,
// 1.12, 0.99 and 2.04 mm (the encoded frames' edges bent). Before, the design checks took the
// wedge at its printed 0.5: 0.35 was found on none, the encoded frames on none.
TEST(CircleTracker, FindsFWhereverItsGreyShows) {
  if (kSanitizedBuild) GTEST_SKIP() << "medians over 48 frames (sanitized_build.h)";
  const MarkerSpec f = Load("circle_f");
  const auto median_error_mm = [&](double grey, double gamma) {
    MarkerSpec printed = f;
    printed.layers.back().color = Rgb::Constant(grey);
    const std::vector<double> errors_mm = ErrorsMmUnderGamma(printed, f, 0.02, gamma);
    EXPECT_GE(errors_mm.size(), 11u) << "grey " << grey << ", gamma " << gamma;
    return errors_mm.empty() ? std::numeric_limits<double>::infinity() : UpperMedian(errors_mm);
  };
  const double as_designed = median_error_mm(0.5, 1.0);
  EXPECT_LE(median_error_mm(0.35, 1.0), 1.3 * as_designed);
  EXPECT_LE(median_error_mm(0.65, 1.0), 1.3 * as_designed);
  EXPECT_LE(median_error_mm(0.5, 2.2), 2.5 * as_designed);
}

// f printed white on black (a white disk with its grey wedge on black paper) under a camera's
// gamma of 2.2, the tracker not told: the wedge shows at 0.73 of the way from the darkest to the
// lightest, as on the upright f, and is read there (roll_feature.h). The poses above, σ² 1e-3.
// Measured: both found on all 12, median errors 2.16 mm (inverted) and 3.38 mm (upright; the
// encoded frames' edges bent). Before, the roll feature took the level from the disk to the
// paper (0.27) and found the inverted f on 1.
TEST(CircleTracker, FindsFPrintedWhiteOnBlackUnderACamerasGamma) {
  const MarkerSpec upright = Load("circle_f");
  MarkerSpec inverted = upright;
  inverted.background = Rgb::Zero();
  inverted.circles[0].color = inverted.layers[0].color = Rgb::Ones();
  const std::vector<double> as_printed = ErrorsMmUnderGamma(upright, upright, 1e-3, 2.2);
  const std::vector<double> white_on_black = ErrorsMmUnderGamma(inverted, inverted, 1e-3, 2.2);
  ASSERT_GE(as_printed.size(), 11u);
  ASSERT_GE(white_on_black.size(), 11u);
  EXPECT_LE(UpperMedian(white_on_black), 1.5 * UpperMedian(as_printed));
}

TEST(CircleTracker, ColourMarkerOnAGreyImageIsNotDetected) {
  const MarkerSpec marker = Load("circles_a");
  FrameRequest request;
  request.scene.marker = &marker;
  request.scene.cam_from_marker = TiltedView(0.6, 10.0, 0.0);
  const RenderedFrame frame = RenderFrame(request);  // grey
  CircleTracker tracker;
  const TrackResult r = tracker.Track({&frame.image, &request.scene.camera, &marker});
  EXPECT_EQ(r.status, TrackStatus::kNotDetected);
  EXPECT_NE(r.message.find("RGB"), std::string::npos) << r.message;
}

TEST(CircleTracker, OptionsFromYamlNameTheBadKey) {
  const std::string path =
      WriteTestFile("circle_options.yaml",
                    "good: {cost: conics, huber_px: 2.0, k_normal: false,"
                    " min_branch_angle_rad: 0.05, predict_motion: false,"
                    " max_other_tilt_log_ratio: 30, max_carried_tilt_log_ratio: 6,"
                    " min_design_radius_per_blur: 5,"
                    " max_blurred_dot_disks: 0, min_dot_area_px: 4, min_dot_radius_px: 1.5,"
                    " blurred_dot_min_significance: 8,"
                    " pixel_band_sigmas: 3, pixel_band_px: 1,"
                    " design_band_sigmas: 2, design_band_px: 0.5,"
                    " design_max_other_tilt_log_ratio: 50,"
                    " max_appearance_block_misfit: 0.3, appearance_blocks_per_side: 0,"
                    " appearance_min_significance: 5,"
                    " edge_shift_alignment: false, edge_shift_first_rays: 8, edge_shift_rays: 24,"
                    " edge_shift_max_px: 12,"
                    " edge_shift_second_max_px: 3, edge_shift_step_px: 0.5,"
                    " edge_shift_first_samples_across: 2, edge_shift_samples_across: 3,"
                    " edge_shift_min_step_per_contrast: 0.4,"
                    " edge_shift_first_min_found_fraction: 0.3,"
                    " edge_shift_min_found_fraction: 0.7, edge_shift_max_rms_px: 2}\n"
                    "bad_value: {huber_px: -1}\n"
                    "bad_cost: {cost: sampson}\n"
                    "unknown: {hubr_px: 1}\n"
                    "bad_branch: {min_branch_angle_rad: 2.0}\n"
                    "bad_radius: {min_design_radius_per_blur: -1}\n"
                    "bad_ratio: {max_other_tilt_log_ratio: -1}\n"
                    "bad_carried: {max_carried_tilt_log_ratio: -1}\n"
                    "bad_peak: {max_blurred_dot_peak: 1.5}\n"
                    "bad_dot: {min_blurred_dot_radius_px: 0}\n"
                    "bad_dot_area: {min_dot_area_px: 13}\n"
                    "bad_dot_radius: {min_dot_radius_px: -1}\n"
                    "bad_band: {pixel_band_sigmas: 0}\n"
                    "bad_margin: {pixel_band_px: -0.5}\n"
                    "bad_design_band: {design_band_sigmas: 0}\n"
                    "bad_design_margin: {design_band_px: -1}\n"
                    "bad_design_tilt: {design_max_other_tilt_log_ratio: -1}\n"
                    "bad_block_misfit: {max_appearance_block_misfit: 0}\n"
                    "bad_blocks: {appearance_blocks_per_side: -2}\n"
                    "bad_significance: {appearance_min_significance: -1}\n"
                    "bad_first_rays: {edge_shift_first_rays: 2}\n"
                    "bad_rays: {edge_shift_rays: 2}\n"
                    "bad_reach: {edge_shift_max_px: 0}\n"
                    "bad_second_reach: {edge_shift_second_max_px: -1}\n"
                    "bad_step: {edge_shift_step_px: 5}\n"
                    "bad_first_across: {edge_shift_first_samples_across: 0}\n"
                    "bad_across: {edge_shift_samples_across: 0}\n"
                    "bad_contrast: {edge_shift_min_step_per_contrast: 1.5}\n"
                    "bad_first_found: {edge_shift_first_min_found_fraction: 0}\n"
                    "bad_found: {edge_shift_min_found_fraction: 1.2}\n"
                    "bad_rms: {edge_shift_max_rms_px: 0}\n"
                    "bad_alignment: {edge_shift_alignment: maybe}\n");
  const YamlMap root = YamlMap::LoadFile(path);
  const CircleTrackerOptions good = CircleTrackerOptions::FromYaml(root.GetMap("good"));
  EXPECT_EQ(good.refinement.cost, RefinementCost::kConics);
  EXPECT_EQ(good.refinement.huber_px, 2.0);
  EXPECT_FALSE(good.analytic.k_normal);
  EXPECT_EQ(good.min_branch_angle_rad, 0.05);
  EXPECT_FALSE(good.predict_motion);
  EXPECT_EQ(good.min_design_radius_per_blur, 5.0);
  EXPECT_EQ(good.max_other_tilt_log_ratio, 30.0);
  EXPECT_EQ(good.max_carried_tilt_log_ratio, 6.0);
  EXPECT_EQ(good.detector.max_blurred_dot_disks, 0);
  EXPECT_EQ(good.detector.min_dot_area_px, 4.0);
  EXPECT_EQ(good.detector.min_dot_radius_px, 1.5);
  EXPECT_EQ(good.detector.blurred_dots.min_significance, 8.0);
  EXPECT_EQ(good.photometric_refinement.band_sigmas, 3.0);
  EXPECT_EQ(good.photometric_refinement.band_px, 1.0);
  EXPECT_EQ(good.design_refinement.band_sigmas, 2.0);
  EXPECT_EQ(good.design_refinement.band_px, 0.5);
  EXPECT_EQ(good.design_refinement.max_first_round_log_ratio, 50.0);
  EXPECT_EQ(good.appearance.max_block_misfit, 0.3);
  EXPECT_EQ(good.appearance.blocks_per_side, 0);
  EXPECT_EQ(good.appearance.min_significance, 5.0);
  EXPECT_FALSE(good.edge_shift.enabled);
  EXPECT_EQ(good.edge_shift.first.rays_per_circle, 8);
  EXPECT_EQ(good.edge_shift.second.rays_per_circle, 24);
  EXPECT_EQ(good.edge_shift.first.max_shift_px, 12.0);
  EXPECT_EQ(good.edge_shift.second.max_shift_px, 3.0);
  EXPECT_EQ(good.edge_shift.sample_step_px, 0.5);
  EXPECT_EQ(good.edge_shift.first.samples_across, 2);
  EXPECT_EQ(good.edge_shift.second.samples_across, 3);
  EXPECT_EQ(good.edge_shift.min_step_per_contrast, 0.4);
  EXPECT_EQ(good.edge_shift.first.min_found_fraction, 0.3);
  EXPECT_EQ(good.edge_shift.second.min_found_fraction, 0.7);
  EXPECT_EQ(good.edge_shift.max_rms_px, 2.0);
  for (const char* key :
       {"bad_value",        "bad_cost",        "unknown",           "bad_branch",
        "bad_radius",       "bad_ratio",       "bad_carried",       "bad_peak",
        "bad_dot",          "bad_dot_area",    "bad_dot_radius",    "bad_band",
        "bad_margin",       "bad_design_band", "bad_design_margin", "bad_design_tilt",
        "bad_block_misfit", "bad_blocks",      "bad_significance",  "bad_first_rays",
        "bad_rays",         "bad_reach",       "bad_second_reach",  "bad_step",
        "bad_first_across", "bad_across",      "bad_contrast",      "bad_first_found",
        "bad_found",        "bad_rms",         "bad_alignment"}) {
    try {
      CircleTrackerOptions::FromYaml(root.GetMap(key));
      ADD_FAILURE() << key << " was accepted";
    } catch (const ConfigError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("circle_options.yaml"), std::string::npos) << message;
      EXPECT_NE(message.find(key), std::string::npos) << message;
    }
  }
  EXPECT_TRUE(MakeTracker("circle", nullptr)->CanTrack(Load("circle_d")));
}

// The marker through a wide lens (scenarios/cameras/wide_distorted.yaml, barrel distortion)
// near the frame's side, where its pinhole image lies tens of pixels beyond the one the lens
// forms: the fit on the pixels takes those the lens forms (it had taken those within reach of
// the pinhole image, and so missed part of each edge: on these frames a median error of 2.16 mm,
// up to 10.6, better than the edge points alone on 8 of 18).
TEST(CircleTracker, FitsThePixelsOfAMarkerNearAWideLensSide) {
  const MarkerSpec marker = Load("circles_a");
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  CircleTrackerOptions edges_only;
  edges_only.photometric = false;
  std::vector<double> errors_mm;
  int better = 0;
  for (const double x_per_z : {0.7, 0.75, 0.8}) {  // the image's centre at u = 581-608 of 640
    for (int seed = 0; seed < 8; ++seed) {
      Rigid3 truth = TiltedView(0.45, 25.0, 45.0 * seed);
      truth.translation.x() = x_per_z * truth.translation.z();
      FrameRequest request = SeededFrameRequest(marker, truth, 0.02, 0.0, 100 + seed, 3);
      request.scene.camera = camera;
      const RenderedFrame frame = RenderFrame(request);
      const Observation observation{&frame.image, &camera, &marker};
      CircleTracker tracker, edge_tracker(edges_only);
      const TrackResult found = tracker.Track(observation);
      const TrackResult from_edges = edge_tracker.Track(observation);
      // Rolled so that a disk leaves the frame: neither finds the marker.
      EXPECT_EQ(found.status, from_edges.status) << x_per_z << " " << seed;
      if (found.status != TrackStatus::kOk || from_edges.status != TrackStatus::kOk) continue;
      errors_mm.push_back(1000.0 * PositionError(found.hypotheses[0], truth));
      better += errors_mm.back() < 1000.0 * PositionError(from_edges.hypotheses[0], truth);
    }
  }
  ASSERT_GE(errors_mm.size(), 15u);
  // Measured: 18 frames, median 0.77 mm (at the image's centre 0.52), largest 2.30 mm, better
  // than the edge points alone on 16 (0.90, 0.53, 2.44 and 17 with each pixel's area and the
  // blur in the pinhole's units).
  EXPECT_LT(UpperMedian(errors_mm), 1.2);
  EXPECT_LT(*std::max_element(errors_mm.begin(), errors_mm.end()), 3.0);
  EXPECT_GE(better, static_cast<int>(errors_mm.size()) - 4);
  std::printf(
      "near a wide lens's side: %zu frames, median %.2f mm, largest %.2f mm, better "
      "than the edge points on %d\n",
      errors_mm.size(),
      UpperMedian(errors_mm),
      *std::max_element(errors_mm.begin(), errors_mm.end()),
      better);
}

// Tracking through the same lens near the frame's side: the rays that move the prediction onto
// the edges, the region searched around the prediction, the ellipses the detector starts from
// and the check that the marker lies within the frame take the image the lens forms, so that a
// still marker is found by full detection, then tracked on the pixels from its pose moved onto
// the edges, then from the prediction itself; on the edge points alone (photometric: false),
// from its predicted ellipses; as at the image's centre.
TEST(CircleTracker, TracksAMarkerNearAWideLensSide) {
  const MarkerSpec marker = Load("circles_a");
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  for (const double x_per_z : {0.0, 0.7, 0.75}) {
    for (const double roll_deg : {110.0, 200.0, 290.0}) {  // disks within the frame
      for (const bool photometric : {true, false}) {
        Rigid3 truth = TiltedView(0.45, 25.0, roll_deg);
        truth.translation.x() = x_per_z * truth.translation.z();
        CircleTrackerOptions options;
        options.photometric = photometric;
        CircleTracker tracker(options);
        for (int frame = 0; frame < 3; ++frame) {
          FrameRequest request = SeededFrameRequest(
              marker, truth, 0.02, 0.0, 200 + static_cast<uint64_t>(roll_deg) + frame, 3);
          request.scene.camera = camera;
          const RenderedFrame rendered = RenderFrame(request);
          const TrackResult result = tracker.Track({&rendered.image, &camera, &marker});
          ASSERT_EQ(result.status, TrackStatus::kOk) << x_per_z << " " << roll_deg << " " << frame;
          // The edge points alone, measured: up to 5.2 mm.
          EXPECT_LT(PositionError(result.hypotheses[0], truth), photometric ? 0.003 : 0.0075)
              << x_per_z << " " << roll_deg;
          const CircleDiagnostics& d = tracker.diagnostics();
          EXPECT_EQ(d.used_tracking_region, frame > 0)
              << x_per_z << " " << roll_deg << " " << frame;
          EXPECT_EQ(d.tracked_on_pixels, photometric && frame > 0) << x_per_z << " " << roll_deg;
          EXPECT_EQ(d.aligned_by_edge_shifts, photometric && frame == 1)
              << x_per_z << " " << roll_deg;
          EXPECT_EQ(d.used_predicted_ellipses, !photometric && frame > 0)
              << x_per_z << " " << roll_deg;
        }
      }
    }
  }
}

// The designs inside e's and f's circle through the same lens, the marker near the frame's
// sides: each pixel of the window the roll is read in spans the ideal pixels the lens squeezes
// into it (about 2 there), and the design's local map is the lens's. Taken as the pinhole's,
// the design's moment came out small enough near the sides to read as no design: "the design
// inside the circle does not show" on 9 of 100 frames of a probe sweep at 0.6 m.
TEST(CircleTracker, ReadsTheDesignNearAWideLensSide) {
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  for (const char* name : {"circle_e", "circle_f"}) {
    const MarkerSpec marker = Load(name);
    std::vector<double> errors_mm;
    for (const Eigen::Vector2d& off_axis : {Eigen::Vector2d(0.7, -0.14),
                                            Eigen::Vector2d(-0.71, 0.05),
                                            Eigen::Vector2d(-0.71, 0.33),
                                            Eigen::Vector2d(0.68, -0.44)}) {
      for (const double roll_deg : {0.0, 90.0, 180.0, 270.0}) {
        Rigid3 truth = TiltedView(0.48, 30.0, roll_deg);
        truth.translation.head<2>() = off_axis * truth.translation.z();
        FrameRequest request =
            SeededFrameRequest(marker, truth, 0.02, 0.0, 300 + static_cast<uint64_t>(roll_deg), 3);
        request.scene.camera = camera;
        const RenderedFrame frame = RenderFrame(request);
        CircleTracker tracker;
        const TrackResult result = tracker.Track({&frame.image, &camera, &marker});
        ASSERT_EQ(result.status, TrackStatus::kOk)
            << name << " " << off_axis.transpose() << " " << roll_deg << ": " << result.message;
        errors_mm.push_back(1000.0 * PositionError(result.hypotheses[0], truth));
      }
    }
    EXPECT_LT(UpperMedian(errors_mm), 3.0) << name;
    std::printf("%s near a wide lens's side: median %.2f mm, largest %.2f mm\n",
                name,
                UpperMedian(errors_mm),
                *std::max_element(errors_mm.begin(), errors_mm.end()));
  }
}

}  // namespace
}  // namespace markerbench
