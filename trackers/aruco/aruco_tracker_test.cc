#include "trackers/aruco/aruco_tracker.h"

#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>

#include "core/test_files.h"
#include "testing/square_tracker_testing.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

constexpr double kCornerBiasTolPx = 0.1;  // issue: mean corner bias under 0.1 px (SUBPIX)
// Pose tolerances over 0.3-2 m and tilt 0-60° at σ² = 0.001, measured envelope with margin.
// ArUco's subpix corners scatter by 0.2-0.3 px here (AprilTag's by < 0.1 px), so its poses
// are looser; the harness's success criterion is 10 % of the distance.
constexpr double kPositionTolFraction = 0.10;
constexpr double kRotationTolDeg = 6.0;
constexpr double kLowNoiseVar = 0.001;

class ArucoTrackerTest : public ::testing::Test {
 protected:
  MarkerSpec marker_ = LoadMarkerYaml("scenarios/markers/aruco.yaml");
};

TEST_F(ArucoTrackerTest, SubpixCornerBiasIsBelowATenthOfAPixel) {
  auto tracker = MakeTracker("aruco", nullptr);
  CornerBias bias;
  for (double tilt : {0.0, 20.0, 40.0}) {
    for (double roll : {5.0, 50.0, 130.0}) {
      const TrackedFrame t = RenderAndTrack(
          tracker.get(), marker_, marker_, TiltedView(0.5, tilt, roll), kLowNoiseVar, 1);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << tilt << " " << roll;
      bias.Add(t.result.keypoints_px, t.frame.truth.keypoints_px);
    }
  }
  EXPECT_LE(bias.Mean().norm(), kCornerBiasTolPx) << bias.Mean().transpose();
  EXPECT_LE(std::abs(bias.Inward()), kCornerBiasTolPx) << bias.Inward();
}

TEST_F(ArucoTrackerTest, PoseErrorsWithinTolerancesOverDistanceAndTilt) {
  auto tracker = MakeTracker("aruco", nullptr);
  for (double distance : {0.3, 0.8, 1.4, 2.0}) {
    for (double tilt : {0.0, 30.0, 60.0}) {
      SCOPED_TRACE("d=" + std::to_string(distance) + " tilt=" + std::to_string(tilt));
      const Rigid3 truth = TiltedView(distance, tilt, 17.0);
      const TrackedFrame t =
          RenderAndTrack(tracker.get(), marker_, marker_, truth, kLowNoiseVar, 2);
      ASSERT_EQ(t.result.status, TrackStatus::kOk);
      EXPECT_EQ(t.result.hypotheses.size(), 2u);
      if (distance == 2.0 && tilt == 0.0) {
        // 30 px and frontal: the planar-ambiguity regime (both hypotheses about 16° off at
        // this seed); the harness reports it as flips, not as a tolerance.
        continue;
      }
      const Rigid3& best = t.result.hypotheses.front();
      EXPECT_LE(PositionError(best, truth), kPositionTolFraction * distance);
      EXPECT_LE(RotationErrorDeg(best, truth), kRotationTolDeg);
    }
  }
}

TEST_F(ArucoTrackerTest, FrameAgreesUnderQuarterTurns) {
  auto tracker = MakeTracker("aruco", nullptr);
  for (double roll : {0.0, 90.0, 180.0, 270.0}) {
    const Rigid3 truth = TiltedView(0.6, 25.0, roll);
    const TrackedFrame t = RenderAndTrack(tracker.get(), marker_, marker_, truth, kLowNoiseVar, 3);
    ASSERT_EQ(t.result.status, TrackStatus::kOk) << roll;
    const Rigid3& est = t.result.hypotheses.front();
    EXPECT_GT(CameraCenterInMarker(est).z(), 0.0);
    EXPECT_GT(est.rotation.col(0).dot(truth.rotation.col(0)), 0.99) << roll;
    EXPECT_GT(est.rotation.col(1).dot(truth.rotation.col(1)), 0.99) << roll;
  }
}

TEST_F(ArucoTrackerTest, EmptyImageAndWrongId) {
  auto tracker = MakeTracker("aruco", nullptr);
  MarkerSpec blank = marker_;
  blank.layers.clear();
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), blank, marker_, TiltedView(0.5, 10, 0), 0.02, 5).result.status,
      TrackStatus::kNotDetected);
  const MarkerSpec other = LoadMarkerYaml(
      WriteTestFile("aruco_7.yaml", "kind: aruco\ndictionary: DICT_6X6_250\nid: 7\nsize_m: 0.1\n"));
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), other, marker_, TiltedView(0.5, 10, 0), 0.0, 5).result.status,
      TrackStatus::kWrongId);
}

TEST_F(ArucoTrackerTest, CornersEqualADirectLibraryCall) {
  auto tracker = MakeTracker("aruco", nullptr);
  const TrackedFrame t =
      RenderAndTrack(tracker.get(), marker_, marker_, TiltedView(0.7, 35.0, 60.0), 0.01, 6);
  ASSERT_EQ(t.result.status, TrackStatus::kOk);
  Image8 image = t.frame.image;
  const cv::Mat view(image.height, image.width, CV_8UC1, image.pixels.data());
  auto params = cv::aruco::DetectorParameters::create();
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(
      view, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_6X6_250), corners, ids, params);
  ASSERT_EQ(ids.size(), 1u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(corners[0][i].x, t.result.keypoints_px[i].x(), 1e-6);
    EXPECT_NEAR(corners[0][i].y, t.result.keypoints_px[i].y(), 1e-6);
  }
}

TEST_F(ArucoTrackerTest, CandidatesNeedMinPixelsPerCell) {
  // Frontal at 1.5 m the black square is 40 px a side, a contour of about 160 px; the floor
  // is 4 sides x 8 cells (6 bits and the border) x min_pixels_per_cell.
  const Rigid3 truth = TiltedView(1.5, 0.0, 10.0);
  for (const auto& [pixels_per_cell, status] :
       {std::pair{4.0, TrackStatus::kOk}, std::pair{6.0, TrackStatus::kNotDetected}}) {
    ArucoOptions options;
    options.min_pixels_per_cell = pixels_per_cell;
    auto tracker = MakeArucoTracker(options);
    EXPECT_EQ(RenderAndTrack(tracker.get(), marker_, marker_, truth, kLowNoiseVar, 7).result.status,
              status)
        << pixels_per_cell;
  }
}

TEST(ArucoOptions, RejectsBadValues) {
  ArucoOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.corner_refinement = "magic";
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("corner_refinement"), std::string::npos);
  options = ArucoOptions();
  options.min_pixels_per_cell = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_pixels_per_cell"), std::string::npos);
}

}  // namespace
}  // namespace markerbench
