#include "trackers/artkplus/artkplus_tracker.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "core/test_files.h"
#include "core/yaml_reader.h"
#include "testing/square_tracker_testing.h"
#include "trackers/tracker_factory.h"

namespace markerbench {
namespace {

// Issue 6: corners within 0.2 px of the projected truth in clean images.
constexpr double kCornerTolPx = 0.2;
// Pose tolerances over 0.3-2 m and tilt 0-60° in clean images: a corner error of 0.2 px on
// a 10 cm square 2 m away (30 px) is worth about 1 % of the distance and 2° of tilt near
// fronto-parallel views (the planar ambiguity), less elsewhere.
constexpr double kPositionTolFraction = 0.02;
constexpr double kRotationTolDeg = 3.0;

YamlMap OptionsYaml(const std::string& text) { return YamlMap(YAML::Load(text), "opts.yaml", ""); }

class ArtkPlusTrackerTest : public ::testing::Test {
 protected:
  MarkerSpec marker_ = LoadMarkerYaml("scenarios/markers/artkplus.yaml");
};

double MaxCornerErrorPx(const TrackedFrame& t) {
  double worst = 0.0;
  for (size_t i = 0; i < 4; ++i) {
    worst = std::max(worst, (t.result.keypoints_px[i] - t.frame.truth.keypoints_px[i]).norm());
  }
  return worst;
}

TEST_F(ArtkPlusTrackerTest, CornersAndPoseOverDistanceAndTiltInCleanImages) {
  auto tracker = MakeTracker("artkplus-improved", nullptr);
  for (double distance : {0.3, 0.6, 1.0, 1.5, 2.0}) {
    for (double tilt : {0.0, 30.0, 60.0}) {
      SCOPED_TRACE("d=" + std::to_string(distance) + " tilt=" + std::to_string(tilt));
      tracker->Reset();
      const Rigid3 truth = TiltedView(distance, tilt, 17.0);
      const TrackedFrame t = RenderAndTrack(tracker.get(), marker_, marker_, truth, 0.0, 1);
      ASSERT_EQ(t.result.status, TrackStatus::kOk);
      ASSERT_EQ(t.result.keypoints_px.size(), 4u);
      EXPECT_LE(MaxCornerErrorPx(t), kCornerTolPx);
      ASSERT_FALSE(t.result.hypotheses.empty());
      const Rigid3& best = t.result.hypotheses.front();
      EXPECT_LE(PositionError(best, truth), kPositionTolFraction * distance);
      EXPECT_LE(RotationErrorDeg(best, truth), kRotationTolDeg);
    }
  }
}

TEST_F(ArtkPlusTrackerTest, FrameAndCornerOrderAgreeUnderQuarterTurns) {
  auto tracker = MakeTracker("artkplus-improved", nullptr);
  for (double roll : {0.0, 90.0, 180.0, 270.0}) {
    SCOPED_TRACE("roll=" + std::to_string(roll));
    tracker->Reset();
    const Rigid3 truth = TiltedView(0.6, 25.0, roll + 8.0);
    const TrackedFrame t = RenderAndTrack(tracker.get(), marker_, marker_, truth, 0.0, 3);
    ASSERT_EQ(t.result.status, TrackStatus::kOk);
    EXPECT_LE(MaxCornerErrorPx(t), kCornerTolPx);  // corner k is the truth's corner k
    const Rigid3& est = t.result.hypotheses.front();
    EXPECT_GT(CameraCenterInMarker(est).z(), 0.0);
    EXPECT_GT(est.rotation.col(0).dot(truth.rotation.col(0)), 0.999);
    EXPECT_GT(est.rotation.col(1).dot(truth.rotation.col(1)), 0.999);
  }
}

// The original fits its side lines to the dark boundary pixels' centres, half a pixel inside
// the edges, so its clean poses are about 1 % too far (baselines.md: +1.1 % at 0.6 m);
// artkplus reproduces that bias and artkplus-improved (sub-pixel edges) removes it.
TEST_F(ArtkPlusTrackerTest, OriginalDepthBiasInCleanImagesAndItsRemoval) {
  for (const char* name : {"artkplus", "artkplus-improved"}) {
    SCOPED_TRACE(name);
    auto tracker = MakeTracker(name, nullptr);
    double bias_sum = 0.0;
    int frames = 0;
    for (double tilt : {0.0, 20.0, 40.0}) {
      for (double roll : {5.0, 50.0}) {
        tracker->Reset();
        const Rigid3 truth = TiltedView(0.6, tilt, roll);
        const TrackedFrame t = RenderAndTrack(tracker.get(), marker_, marker_, truth, 0.0, 7);
        ASSERT_EQ(t.result.status, TrackStatus::kOk);
        const Rigid3& best = t.result.hypotheses.front();
        bias_sum += best.translation.norm() / truth.translation.norm() - 1.0;
        ++frames;
      }
    }
    const double bias = bias_sum / frames;
    if (std::string(name) == "artkplus") {
      EXPECT_GT(bias, 0.005);
      EXPECT_LT(bias, 0.02);
    } else {
      EXPECT_LT(std::abs(bias), 0.002);
    }
  }
}

TEST_F(ArtkPlusTrackerTest, SimpleIdModeThinBorderAndClassicPose) {
  const MarkerSpec simple = LoadMarkerYaml(WriteTestFile(
      "artk_simple.yaml",
      "kind: artkplus\nmode: simple\nid: 300\nborder_fraction: 0.125\nsize_m: 0.08\n"));
  for (const char* pose : {"rpp", "classic"}) {
    SCOPED_TRACE(pose);
    const YamlMap options = OptionsYaml(std::string("pose: ") + pose + "\n");
    auto tracker = MakeTracker("artkplus-improved", &options);
    for (double tilt : {0.0, 45.0}) {
      tracker->Reset();
      const Rigid3 truth = TiltedView(0.5, tilt, 33.0);
      const TrackedFrame t = RenderAndTrack(tracker.get(), simple, simple, truth, 0.0, 4);
      ASSERT_EQ(t.result.status, TrackStatus::kOk) << tilt;
      EXPECT_LE(MaxCornerErrorPx(t), kCornerTolPx);
      const Rigid3& best = t.result.hypotheses.front();
      EXPECT_LE(PositionError(best, truth), kPositionTolFraction * 0.5) << tilt;
      EXPECT_LE(RotationErrorDeg(best, truth), kRotationTolDeg) << tilt;
    }
  }
}

TEST_F(ArtkPlusTrackerTest, WrongIdIsReported) {
  auto tracker = MakeTracker("artkplus", nullptr);
  const MarkerSpec other = LoadMarkerYaml(WriteTestFile(
      "artk_77.yaml", "kind: artkplus\nmode: bch\nid: 77\nborder_fraction: 0.25\nsize_m: 0.1\n"));
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), other, marker_, TiltedView(0.5, 10, 0), 0.0, 5).result.status,
      TrackStatus::kWrongId);
}

// Issue 6: an empty image gives no detection; noise alone at σ² = 0.3 gives no false id.
TEST_F(ArtkPlusTrackerTest, NothingIsFoundInEmptyOrNoiseOnlyImages) {
  auto tracker = MakeTracker("artkplus", nullptr);
  MarkerSpec blank = marker_;
  blank.layers.clear();
  EXPECT_EQ(
      RenderAndTrack(tracker.get(), blank, marker_, TiltedView(0.5, 10, 0), 0.0, 6).result.status,
      TrackStatus::kNotDetected);
  for (uint64_t seed = 0; seed < 10; ++seed) {
    tracker->Reset();
    EXPECT_EQ(RenderAndTrack(tracker.get(), blank, marker_, TiltedView(0.5, 10, 0), 0.3, seed)
                  .result.status,
              TrackStatus::kNotDetected)
        << "seed " << seed;
  }
}

// On dim paper (all grey levels below 100) the fixed threshold labels the whole image dark;
// auto mode's seeded random retries find a working threshold, the same one after Reset.
TEST_F(ArtkPlusTrackerTest, AutoThresholdRetriesRecoverADimImageDeterministically) {
  FrameRequest request;
  request.scene.marker = &marker_;
  request.scene.cam_from_marker = TiltedView(0.5, 20.0, 10.0);
  request.degradations.gain = 0.3;
  const RenderedFrame frame = RenderFrame(request);
  const Observation observation{&frame.image, &request.scene.camera, &marker_};
  const YamlMap fixed = OptionsYaml("threshold_mode: fixed\n");
  EXPECT_EQ(MakeTracker("artkplus", &fixed)->Track(observation).status, TrackStatus::kNotDetected);
  const YamlMap retries = OptionsYaml("auto_threshold_retries: 8\n");
  auto tracker = MakeTracker("artkplus", &retries);
  const TrackResult first = tracker->Track(observation);
  ASSERT_EQ(first.status, TrackStatus::kOk);
  tracker->Reset();
  const TrackResult again = tracker->Track(observation);
  ASSERT_EQ(again.status, TrackStatus::kOk);
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(first.keypoints_px[k], again.keypoints_px[k]);
}

TEST(ArtkPlusOptions, ErrorsNameTheKey) {
  const auto error = [](const std::string& yaml) {
    try {
      ArtkPlusOptions::FromYaml(OptionsYaml(yaml));
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("threshold: 300\n").find("'threshold'"), std::string::npos);
  EXPECT_NE(error("pose: ippe\n").find("'pose': expected rpp or classic"), std::string::npos);
  EXPECT_NE(error("threshold_mode: otsu\n").find("'threshold_mode'"), std::string::npos);
  EXPECT_NE(error("side_trim: 0.7\n").find("'side_trim'"), std::string::npos);
  EXPECT_NE(error("treshold: 90\n").find("treshold"), std::string::npos);
  EXPECT_EQ(error("threshold: 90\nsubpixel_edges: false\n"), "");
}

}  // namespace
}  // namespace markerbench
