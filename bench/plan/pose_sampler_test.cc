#include "bench/plan/pose_sampler.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bench/plan/frame_plan.h"
#include "core/marker_yaml.h"

namespace markerbench {
namespace {

constexpr double kGeometryTol = 1e-9;

TEST(PoseSampler, FrontalWithoutOffsetLooksAtTheCentreFromTheDistance) {
  PoseSamplerOptions options;
  options.tilt_max_deg = 0.0;
  options.max_offset_px = 0.0;
  const Camera camera;
  Rng rng(1);
  const Rigid3 cam_from_center = SampleCamFromCenter(options, camera, &rng);
  const Eigen::Vector3d c = CameraCenterInMarker(cam_from_center);
  EXPECT_NEAR(c.z(), 0.6, kGeometryTol);
  EXPECT_NEAR(c.head<2>().norm(), 0.0, kGeometryTol);
  const Eigen::Vector2d px = camera.ImgFromCam(cam_from_center * Eigen::Vector3d::Zero());
  EXPECT_NEAR(px.x(), 319.5, 1e-6);
  EXPECT_NEAR(px.y(), 239.5, 1e-6);
  EXPECT_NEAR(cam_from_center.rotation.determinant(), 1.0, kGeometryTol);
}

TEST(PoseSampler, DrawsRespectTheProtocol) {
  PoseSamplerOptions options;  // 0.6 m, tilt 0..40°, offset ≤ 60 px
  const Camera camera;
  Rng rng(2);
  for (int i = 0; i < 500; ++i) {
    const Rigid3 pose = SampleCamFromCenter(options, camera, &rng);
    const Eigen::Vector3d c = CameraCenterInMarker(pose);
    EXPECT_NEAR(c.norm(), 0.6, 1e-9);
    const double tilt_deg = std::acos(c.z() / c.norm()) * 180.0 / M_PI;
    EXPECT_LE(tilt_deg, 40.0 + 1e-9);
    const Eigen::Vector2d px = camera.ImgFromCam(pose * Eigen::Vector3d::Zero());
    EXPECT_LE((px - Eigen::Vector2d(319.5, 239.5)).norm(), 60.0 + 1e-6);
  }
}

TEST(PoseSampler, PairedPoseFitsEveryMarkerAndIsDeterministic) {
  const std::vector<MarkerSpec> markers = {LoadMarkerYaml("scenarios/markers/circles_a.yaml"),
                                           LoadMarkerYaml("scenarios/markers/apriltag.yaml")};
  PoseSamplerOptions options;
  options.distance_m = 0.3;  // large in the image: some draws must be rejected
  const Camera camera;
  for (uint64_t seed = 0; seed < 50; ++seed) {
    const Rigid3 a = SamplePairedPose(options, camera, markers, seed);
    const Rigid3 b = SamplePairedPose(options, camera, markers, seed);
    EXPECT_EQ(a.rotation, b.rotation);
    EXPECT_EQ(a.translation, b.translation);
    for (const MarkerSpec& m : markers) {
      EXPECT_TRUE(MarkerFitsInImage(m, camera, CamFromMarker(a, m), options.border_px));
    }
  }
}

TEST(PoseSampler, ImpossibleFitThrows) {
  const std::vector<MarkerSpec> markers = {LoadMarkerYaml("scenarios/markers/apriltag.yaml")};
  PoseSamplerOptions options;
  options.distance_m = 0.05;
  try {
    SamplePairedPose(options, Camera(), markers, 1);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("inside the image at 0.05 m; increase distance_m"));
  }
}

TEST(FramePlan, PairsPosesAcrossMarkersAndAppliesTheSweep) {
  const Scenario s = LoadScenario("scenarios/smoke.yaml");
  const std::vector<PlannedFrame> frames = PlanFrames(s);
  ASSERT_EQ(frames.size(), s.sweep_values.size() * s.trials * s.markers.size());
  // Frames 0 and 1: the same (cell, trial), two markers, one camera pose.
  EXPECT_EQ(frames[0].cell, frames[1].cell);
  EXPECT_EQ(frames[0].trial, frames[1].trial);
  const Eigen::Vector2d c0 = s.markers[0].InkBounds().center();
  const Eigen::Vector2d c1 = s.markers[1].InkBounds().center();
  const Eigen::Vector3d cam0 =
      CameraCenterInMarker(frames[0].cam_from_marker) - Eigen::Vector3d(c0.x(), c0.y(), 0);
  const Eigen::Vector3d cam1 =
      CameraCenterInMarker(frames[1].cam_from_marker) - Eigen::Vector3d(c1.x(), c1.y(), 0);
  EXPECT_LE((cam0 - cam1).norm(), 1e-12);
  EXPECT_EQ(frames.back().degradations.noise_var, s.sweep_values.back());
  EXPECT_EQ(frames[0].channels, 3);  // circles_a has colour
  EXPECT_EQ(frames[1].channels, 1);
}

}  // namespace
}  // namespace markerbench
