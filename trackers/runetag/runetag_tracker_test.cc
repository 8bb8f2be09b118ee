#include "trackers/runetag/runetag_tracker.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "core/camera_yaml.h"
#include "core/test_files.h"
#include "testing/square_tracker_testing.h"
#include "trackers/tracker_factory.h"
#include "trackers/upper_median.h"

namespace markerbench {
namespace {

// Issue 7: a clean-image camera-centre error of about 0.5 mm or better at 0.5 m (the
// original measured about 0.2 mm).
constexpr double kCleanCenterTolM = 0.5e-3;
constexpr double kCleanRotationTolDeg = 0.1;

class RuneTagTrackerTest : public ::testing::Test {
 protected:
  MarkerSpec marker_ = LoadMarkerYaml("scenarios/markers/runetag.yaml");
};

TEST_F(RuneTagTrackerTest, CleanCameraCentresAtHalfAMetreOverTilt) {
  RuneTagTracker tracker(RuneTagOptions::Improved());
  for (double distance : {0.3, 0.5}) {
    for (double tilt : {0.0, 30.0, 60.0}) {
      SCOPED_TRACE("d=" + std::to_string(distance) + " tilt=" + std::to_string(tilt));
      const Rigid3 truth = TiltedView(distance, tilt, 17.0);
      const TrackedFrame t = RenderAndTrack(&tracker, marker_, marker_, truth, 0.0, 1);
      ASSERT_EQ(t.result.status, TrackStatus::kOk);
      ASSERT_EQ(t.result.hypotheses.size(), 1u);
      EXPECT_LE(PositionError(t.result.hypotheses[0], truth), kCleanCenterTolM);
      EXPECT_LE(RotationErrorDeg(t.result.hypotheses[0], truth), kCleanRotationTolDeg);
      EXPECT_GE(tracker.diagnostics().inliers, 40);
    }
  }
}

// Farther out the inner dots (2 mm radius) shrink to 1.6 px (0.75 m) and 0.8 px (1.5 m), 0.46
// px apart at 1.5 m: the threshold merges them, and the code is read by sweeping the slots.
// Tilted views: within 1 % of the distance and 1° (measured at most 0.65 %).
// At 60° the rings are compressed to half: with the original's code of id 8, whose outer
// dots are dense, they merge beyond 1 m.
TEST_F(RuneTagTrackerTest, TiltedMarkersDecodeOutToOneAndAHalfMetres) {
  RuneTagTracker tracker(RuneTagOptions::Improved());
  for (double distance : {0.75, 1.0, 1.25, 1.5}) {
    for (double tilt : {30.0, 60.0}) {
      if (tilt == 60.0 && distance > 1.0) continue;
      SCOPED_TRACE("d=" + std::to_string(distance) + " tilt=" + std::to_string(tilt));
      const Rigid3 truth = TiltedView(distance, tilt, 17.0);
      const TrackedFrame t = RenderAndTrack(&tracker, marker_, marker_, truth, 0.0, 3);
      ASSERT_EQ(t.result.status, TrackStatus::kOk);
      EXPECT_LE(PositionError(t.result.hypotheses[0], truth), 0.01 * distance);
      EXPECT_LE(RotationErrorDeg(t.result.hypotheses[0], truth), 1.0);
    }
  }
}

// Face-on, a marker 40-80 px across barely shows which way it is tilted (at 1.5 m a 3° tilt
// moves the outer dots by 0.04 px), so the camera centre errs sideways along the tilt:
// measured 0.3 % of the distance at 0.75 m, 3.7 % at 1.25 m and 5.6 % at 1.5 m. The sweeps'
// success criterion, 10 % of the distance (experiments.md), must hold.
TEST_F(RuneTagTrackerTest, FaceOnMarkersDecodeOutToOneAndAHalfMetres) {
  RuneTagTracker tracker(RuneTagOptions::Improved());
  for (double distance : {0.75, 1.0, 1.25, 1.5}) {
    SCOPED_TRACE("d=" + std::to_string(distance));
    const Rigid3 truth = TiltedView(distance, 0.0, 17.0);
    const TrackedFrame t = RenderAndTrack(&tracker, marker_, marker_, truth, 0.0, 3);
    ASSERT_EQ(t.result.status, TrackStatus::kOk);
    EXPECT_LE(PositionError(t.result.hypotheses[0], truth), 0.1 * distance);
  }
}

// imnoise σ² = 0.02 (the benchmark's frames) and 0.05 at 0.6 m.
TEST_F(RuneTagTrackerTest, NoisyMarkersDecode) {
  RuneTagTracker tracker(RuneTagOptions::Improved());
  for (double noise : {0.02, 0.05}) {
    for (uint64_t seed = 0; seed < 4; ++seed) {
      SCOPED_TRACE("noise=" + std::to_string(noise) + " seed=" + std::to_string(seed));
      const Rigid3 truth = TiltedView(0.6, 10.0 * static_cast<double>(seed), 40.0 * seed);
      const TrackedFrame t = RenderAndTrack(&tracker, marker_, marker_, truth, noise, seed);
      ASSERT_EQ(t.result.status, TrackStatus::kOk);
      EXPECT_LE(PositionError(t.result.hypotheses[0], truth), 0.02 * 0.6);
    }
  }
}

// The frame under in-plane rotation: the decoded rotation must carry the marker's x and y
// axes whatever the roll, including rolls between sectors.
TEST_F(RuneTagTrackerTest, FrameFollowsInPlaneRotation) {
  RuneTagTracker tracker;
  for (double roll : {0.0, 4.2, 90.0, 181.0, 270.0, 333.3}) {
    SCOPED_TRACE("roll=" + std::to_string(roll));
    const Rigid3 truth = TiltedView(0.4, 25.0, roll);
    const TrackedFrame t = RenderAndTrack(&tracker, marker_, marker_, truth, 0.0, 2);
    ASSERT_EQ(t.result.status, TrackStatus::kOk);
    const Rigid3& est = t.result.hypotheses[0];
    EXPECT_GT(est.rotation.col(0).dot(truth.rotation.col(0)), 0.9999);
    EXPECT_GT(est.rotation.col(1).dot(truth.rotation.col(1)), 0.9999);
    EXPECT_GT(CameraCenterInMarker(est).z(), 0.0);
  }
}

TEST_F(RuneTagTrackerTest, NothingInEmptyOrNoiseOnlyImagesAndWrongIdReported) {
  RuneTagTracker tracker;
  MarkerSpec blank = marker_;
  blank.layers.clear();
  for (double noise : {0.0, 0.02, 0.3}) {
    for (uint64_t seed = 0; seed < 3; ++seed) {
      EXPECT_EQ(RenderAndTrack(&tracker, blank, marker_, TiltedView(0.5, 10, 0), noise, seed)
                    .result.status,
                TrackStatus::kNotDetected)
          << noise << " " << seed;
    }
  }
  const MarkerSpec other =
      LoadMarkerYaml(WriteTestFile("rune_10.yaml", "kind: runetag\nid: 10\nradius_m: 0.053\n"));
  EXPECT_EQ(RenderAndTrack(&tracker, other, marker_, TiltedView(0.4, 10, 0), 0.0, 5).result.status,
            TrackStatus::kWrongId);
}

// Half the marker covered by a paper-coloured sheet: the unseen sectors are erasures.
TEST_F(RuneTagTrackerTest, AHalfOccludedMarkerStillDecodes) {
  MarkerSpec occluded = marker_;
  constexpr double kDeg = 3.14159265358979 / 180.0;
  PaintedShape& cover = occluded.layers.emplace_back();
  cover.shape = SectorShape{{0.0, 0.0}, 0.07, 100.0 * kDeg, 280.0 * kDeg};
  cover.color = Rgb::Ones();
  RuneTagTracker tracker(RuneTagOptions::Improved());
  const Rigid3 truth = TiltedView(0.4, 20.0, 10.0);
  const TrackedFrame t = RenderAndTrack(&tracker, occluded, marker_, truth, 0.0, 6);
  ASSERT_EQ(t.result.status, TrackStatus::kOk);
  EXPECT_GE(tracker.diagnostics().erasures, 18);
  EXPECT_LE(PositionError(t.result.hypotheses[0], truth), kCleanCenterTolM);
}

// Through a wide lens (scenarios/cameras/wide_distorted.yaml, barrel distortion), the marker at
// 0.6 m out to the frame's sides: each ring's ellipse is fitted where the pinhole would image
// its dots, as the rays it is read along are (undistort_dots). Taking the dots' pixels as a
// pinhole's, as the original's detector does, it reads fewer of these markers.
TEST_F(RuneTagTrackerTest, ReadsTheDotsThroughAWideLens) {
  const Camera camera = LoadCameraYaml("scenarios/cameras/wide_distorted.yaml");
  RuneTagOptions as_original_reads = RuneTagOptions::Improved();
  as_original_reads.rings.undistort_dots = false;
  int read = 0, read_as_original = 0, frames = 0;
  std::vector<double> errors_m;
  // The marker's centre at these (x, y) / z: the image's centre, out to a side and a corner.
  for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0.0, 0.0),
                                        Eigen::Vector2d(0.6, 0.0),
                                        Eigen::Vector2d(0.45, 0.35),
                                        Eigen::Vector2d(-0.5, -0.3)}) {
    for (const double roll_deg : {0.0, 90.0, 180.0, 270.0}) {
      Rigid3 truth = TiltedView(0.6, 25.0, roll_deg);
      truth.translation.head<2>() = offset * truth.translation.z();
      FrameRequest request = SeededFrameRequest(marker_, truth, 0.02, 0.0, 300 + frames, 1);
      request.scene.camera = camera;
      const RenderedFrame frame = RenderFrame(request);
      RuneTagTracker tracker(RuneTagOptions::Improved()), original_reading(as_original_reads);
      const TrackResult result = tracker.Track({&frame.image, &camera, &marker_});
      ++frames;
      if (original_reading.Track({&frame.image, &camera, &marker_}).status == TrackStatus::kOk) {
        ++read_as_original;
      }
      if (result.status != TrackStatus::kOk) continue;
      ++read;
      errors_m.push_back(PositionError(result.hypotheses[0], truth));
      EXPECT_LE(errors_m.back(), 0.02 * 0.6) << offset.transpose() << " " << roll_deg;
    }
  }
  std::printf("through a wide lens: %d of %d read (the dots' pixels as a pinhole's: %d)\n",
              read,
              frames,
              read_as_original);
  // Measured: all 16 read, median error 1.2 mm, largest 7.4 mm (1.2 % of the distance; at the
  // side, 90° of roll); the dots' pixels as a pinhole's read 10.
  EXPECT_EQ(read, frames);
  EXPECT_LT(read_as_original, frames);
  ASSERT_FALSE(errors_m.empty());
  EXPECT_LE(UpperMedian(errors_m), 0.002);
}

TEST(RuneTagOptions, ErrorsNameTheKey) {
  RuneTagOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.dots.block_size_px = 128;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("block_size_px"), std::string::npos);
  options = {};
  options.rings.slot_margin = 0.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_EQ(error.rfind("slot_margin=", 0), 0u);
  options = {};
  options.rings.max_dot_growth = 0.9;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_EQ(error.rfind("max_dot_growth=", 0), 0u);
  EXPECT_TRUE(
      MakeTracker("runetag", nullptr)->CanTrack(LoadMarkerYaml("scenarios/markers/runetag.yaml")));
}

}  // namespace
}  // namespace markerbench
