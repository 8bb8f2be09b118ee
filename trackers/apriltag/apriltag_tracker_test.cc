#include "trackers/apriltag/apriltag_tracker.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <gtest/gtest.h>

#include "core/marker_yaml.h"
#include "testing/square_tracker_testing.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

constexpr double kCornerBiasTolPx = 0.1;  // issue: mean corner bias under 0.1 px
// Pose tolerances over 0.3-2 m and tilt 0-60° at σ² = 0.001, measured envelope with margin:
// near-frontal far tags are the planar-ambiguity regime (2 m frontal: 4.9 % and 2.8°).
constexpr double kPositionTolFraction = 0.06;  // camera-centre error / distance
constexpr double kRotationTolDeg = 4.0;
constexpr double kLowNoiseVar = 0.001;

class AprilTagTrackerTest : public ::testing::Test {
 protected:
  MarkerSpec tag_ = LoadMarkerYaml("scenarios/markers/apriltag.yaml");
};

TEST_F(AprilTagTrackerTest, CornerBiasIsBelowATenthOfAPixel) {
  auto tracker = MakeTracker("apriltag", nullptr);
  CornerBias bias;
  for (double tilt : {0.0, 20.0, 40.0}) {
    for (double roll : {5.0, 50.0, 130.0}) {
      const TrackedFrame t =
          RenderAndTrack(tracker.get(), tag_, tag_, TiltedView(0.5, tilt, roll), kLowNoiseVar, 1);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << tilt << " " << roll;
      bias.Add(t.result.keypoints_px, t.frame.truth.keypoints_px);
    }
  }
  EXPECT_LE(bias.Mean().norm(), kCornerBiasTolPx) << bias.Mean().transpose();
  EXPECT_LE(std::abs(bias.Inward()), kCornerBiasTolPx) << bias.Inward();
}

TEST_F(AprilTagTrackerTest, PoseErrorsWithinTolerancesOverDistanceAndTilt) {
  for (const char* name : {"apriltag", "apriltag-ippe"}) {
    for (double distance : {0.3, 0.8, 1.4, 2.0}) {
      for (double tilt : {0.0, 30.0, 60.0}) {
        SCOPED_TRACE(std::string(name) + " d=" + std::to_string(distance) +
                     " tilt=" + std::to_string(tilt));
        // At 2 m and 60° the tag is 30 x 15 px: the default quad_decimate = 2 loses it.
        AprilTagOptions options;
        if (distance == 2.0 && tilt == 60.0) options.quad_decimate = 1.0;
        auto tracker = MakeAprilTagTracker(
            options, std::string(name) == "apriltag" ? AprilTagPose::kNative : AprilTagPose::kIppe);
        const Rigid3 truth = TiltedView(distance, tilt, 17.0);
        const TrackedFrame t = RenderAndTrack(tracker.get(), tag_, tag_, truth, kLowNoiseVar, 2);
        ASSERT_EQ(t.result.status, TrackStatus::kOk);
        const Rigid3& best = t.result.hypotheses.front();
        EXPECT_LE(PositionError(best, truth), kPositionTolFraction * distance);
        EXPECT_LE(RotationErrorDeg(best, truth), kRotationTolDeg);
      }
    }
  }
}

TEST_F(AprilTagTrackerTest, DefaultDecimationLosesTheSmallestObliqueTag) {
  auto tracker = MakeTracker("apriltag", nullptr);
  EXPECT_EQ(RenderAndTrack(tracker.get(), tag_, tag_, TiltedView(2.0, 60.0, 17.0), kLowNoiseVar, 2)
                .result.status,
            TrackStatus::kNotDetected);
}

TEST_F(AprilTagTrackerTest, FrameAgreesUnderQuarterTurns) {
  auto tracker = MakeTracker("apriltag", nullptr);
  for (double roll : {0.0, 90.0, 180.0, 270.0}) {
    const Rigid3 truth = TiltedView(0.6, 25.0, roll);
    const TrackedFrame t = RenderAndTrack(tracker.get(), tag_, tag_, truth, kLowNoiseVar, 3);
    ASSERT_EQ(t.result.status, TrackStatus::kOk) << roll;
    const Rigid3& est = t.result.hypotheses.front();
    EXPECT_GT(CameraCenterInMarker(est).z(), 0.0) << "camera must be on the printed side";
    // x and y of the marker frame: the estimated axes match the true ones.
    EXPECT_GT(est.rotation.col(0).dot(truth.rotation.col(0)), 0.99) << roll;
    EXPECT_GT(est.rotation.col(1).dot(truth.rotation.col(1)), 0.99) << roll;
  }
}

TEST_F(AprilTagTrackerTest, IppeReturnsBothHypothesesForASmallFrontalTag) {
  auto tracker = MakeTracker("apriltag-ippe", nullptr);
  const Rigid3 truth = TiltedView(2.0, 3.0, 40.0);
  const TrackedFrame t = RenderAndTrack(tracker.get(), tag_, tag_, truth, 0.01, 4);
  ASSERT_EQ(t.result.status, TrackStatus::kOk);
  ASSERT_EQ(t.result.hypotheses.size(), 2u);
  double best = 1e9;
  for (const Rigid3& h : t.result.hypotheses) best = std::min(best, RotationErrorDeg(h, truth));
  EXPECT_LE(best, 10.0);
}

TEST_F(AprilTagTrackerTest, EmptyImageAndWrongId) {
  auto tracker = MakeTracker("apriltag", nullptr);
  MarkerSpec blank = tag_;
  blank.layers.clear();
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), blank, tag_, TiltedView(0.5, 10, 0), 0.02, 5).result.status,
      TrackStatus::kNotDetected);
  const MarkerSpec other = LoadMarkerYaml(WriteTestTag(1));
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), other, tag_, TiltedView(0.5, 10, 0), 0.0, 5).result.status,
      TrackStatus::kWrongId);
}

TEST_F(AprilTagTrackerTest, CornersEqualADirectLibraryCallMinusHalfAPixel) {
  auto tracker = MakeTracker("apriltag", nullptr);
  const TrackedFrame t =
      RenderAndTrack(tracker.get(), tag_, tag_, TiltedView(0.7, 35.0, 60.0), 0.01, 6);
  ASSERT_EQ(t.result.status, TrackStatus::kOk);
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  apriltag_detector_add_family(detector, family);
  Image8 image = t.frame.image;
  image_u8_t view{image.width, image.height, image.width, image.pixels.data()};
  zarray_t* detections = apriltag_detector_detect(detector, &view);
  ASSERT_EQ(zarray_size(detections), 1);
  apriltag_detection_t* det;
  zarray_get(detections, 0, &det);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d direct(det->p[3 - i][0] - 0.5, det->p[3 - i][1] - 0.5);
    EXPECT_LE((direct - t.result.keypoints_px[static_cast<size_t>(i)]).norm(), 1e-9);
  }
  apriltag_detections_destroy(detections);
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
}

TEST(AprilTagOptions, RejectsBadValues) {
  AprilTagOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.quad_decimate = 0.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("quad_decimate"), std::string::npos);
}

}  // namespace
}  // namespace markerbench
